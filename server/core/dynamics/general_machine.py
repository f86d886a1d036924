"""A machine whose mechanism is a general linkage of class-II groups (server/core/structure/): motor →
transmission ratio i → the linkage with its mass model and loads (structure/masses.py).

It is a ``Machine``: the equation of motion, the steady cycle, the start-up, the flywheel and the live study
ask it the same things (``tables``, ``switching``, ``kinks``, ``cycle``), answered from the composed linkage:
J(φ), dJ/dφ by kinetic-energy equality and M_c(φ) by power equality (structure/reduction.py, Eremyants
(1.1)–(1.5)), load diagrams on sliders (structure/masses.py), dry friction in the pairs as the friction moment of the static loads by the group kinetostatics
(kinetostatics/groups/dry_moment.py: the crank-slider's (3.24)–(3.28) generalised), viscous friction β ω Σ s′²
over every prismatic pair (Eremyants (3.15)–(3.17)) and β_p of single pairs: the viscous moment is β ω S(φ) with

    β S(φ) = β_P Σ_prismatic s′² + Σ_p β_p rel_p²,

rel_p the pair's relative angular (revolute) or sliding (prismatic) velocity analog (kinetostatics/groups/
pairs.py): the power β_p (rel_p ω)² the pair dissipates, reduced to the crank.  β is the request's β_P, or 1
where only single pairs have one.

The equation of motion reads J, J′, M_useful and S from their table between the kinks (``smooth_table``: piecewise
Chebyshev interpolants to SMOOTH_TOLERANCE, dynamics/kink_table.py), built once per linkage, masses and loads (a
dragged f, [δ] or motor finds it), a few compositions of the groups instead of twenty-odd per answer, and M_T
from its own table (``dry_table``: to the friction solve's own ε_R), a few hundred solves a turn instead of one
per node; /reduction shows and integrates the composed and solved moments themselves.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..mechanisms import GeometryError, Notice
from ..mechanisms.base import angle_ranges, ranges_text
from ..mechanisms.general import (GeneralMechanism, assembly_notices, change_point_mask, change_point_notices,
                                  undefined_at)
from ..kinetostatics.groups.analysis import setup, with_friction
from ..kinetostatics.groups.dry_moment import TOLERANCE as DRY_TOLERANCE, dry_moment, proved_signs, rough
from ..kinetostatics.groups.friction import PairFriction
from ..kinetostatics.groups.pairs import crank_pair, group_pairs
from ..numerics import Numerics
from ..structure.compose import Composition, compose
from ..structure.masses import MassModel, centre_points, check_model, with_strokes
from ..structure.reduction import reduced_inertia, reduced_loads
from .kink_table import KinkTable, build as build_table
from .kept import Kept
from .brackets import own_rows, refine_zeros
from .machine import KINK_MERGE, KINK_SCAN, KINKS_KEPT, Machine, Tables, read_only
from .motors import Motor, table_moment
from .reduction import Inertias
from .resistance import Load

TURN = 2 * np.pi
MEAN_ORDER = 8           # Gauss–Legendre nodes per segment of M_c0's coarse rule (the fine rule: twice as many)
MEAN_TOLERANCE = 1e-11   # a segment's |fine − coarse| accepted below this share of the cycle mean of |M_c|
MEAN_HALVINGS = 30       # a segment above it is halved at most this often (≥ 2π/2³⁰ wide): its error is then
                         # bounded by its width times the range of M_c on its nodes (a jump the kinks missed)
MEAN_ANGLES = 16384      # or once the rule has used this many angles (the work bound: a steep stretch near
                         # self-locking halves many segments), the segments left bounded so
DRY_BUDGET_S = 5.0       # wall clock of one friction solve of the dry moment (the forces request's bound), said in
                         # words where it runs out; a six-bar's 8193 angles take ~0.1 s
_switches_found = Kept(KINKS_KEPT)                  # GeneralMachine.kinematic_kinks, by what they depend on
DRY_KEPT = 16            # machines whose dry-friction solves are kept (GeneralMachine.dry; ≲ 0.5 MB each)
_dry_solved = Kept(DRY_KEPT)                        # (linkage, masses, pairs) → (sorted angles, their rows)
_dry_tables = Kept(DRY_KEPT)                        # (linkage, masses, pairs, kinks) → KinkTable of M_T
DRY_ORDERS = (32, 64, 128)  # degrees tried on each segment of M_T's table
SMOOTH_TOLERANCE = 1e-13    # of each function's largest magnitude: the estimate of J, J′, M_useful, S's table
SMOOTH_ORDERS = (32, 64, 128, 256)   # degrees tried on each segment of their table
SMOOTH_KEPT = 64            # machines whose table of J, J′, M_useful, S is kept (≲ 40 kB each)
_smooth_tables = Kept(SMOOTH_KEPT)                  # (linkage, masses but f and r, inertias, loads, β) → KinkTable
NORMAL_SECTIONS = 8      # points per bracket and pass refining a normal force's zero (~9 µs each, ~1 ms a call)
SCAN_KEPT = 4            # setups of the normal forces' kink scan kept (GeneralMachine.scan_normals; ~12 MB each)
_scan_setups = Kept(SCAN_KEPT)                      # (linkage, masses but f and r, rough pairs, scan) → Setup


@dataclass(frozen=True)
class GeneralMachine(Machine):
    linkage: GeneralMechanism | None = field(default=None, compare=False, repr=False)
    masses: MassModel = field(default_factory=MassModel)
    pairs: tuple[tuple[str, PairFriction], ...] = ()      # f and r of single pairs by name (else the model's)
    prismatic_beta: float = 0.0                            # β_P of every prismatic pair (load.beta is β)

    @property
    def rough(self) -> bool:
        """Whether a pair has dry friction."""
        return rough(self.masses, dict(self.pairs))

    @property
    def lossless(self) -> bool:
        """No friction: none in the load, none viscous, and no pair with dry friction."""
        return super().lossless and not self.rough

    def dry(self, comp: Composition) -> tuple[np.ndarray, list[Notice], np.ndarray]:
        """M_T(φ) of the pairs' dry friction on ``comp``, the notices (self-locking; the work bound), and the
        rough prismatic pairs' normal forces (R, N) (NaN where there is no equilibrium), solved at every angle
        (``solved``)."""
        moment, locked, unsettled, normals = self.solved(comp.phi, comp)
        return moment, dry_notices(comp.phi, locked, unsettled), normals

    def solved(self, phi: np.ndarray, comp: Composition | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                                               np.ndarray]:
        """M_T, where the equilibrium locks, where the work bound left it, and the normal forces at the angles
        ``phi`` (``comp``: the linkage composed there, if it is; else composed where an angle is not kept).
        Each angle is solved once for the linkage, masses and pairs (kept for the last DRY_KEPT of them: the
        friction equilibrium at an angle does not depend on the other angles solved with it, nor on the motor,
        ω or [δ]; the steady cycle's levels are nested, the flywheel's nodes lie on the kinks' scan, which lies
        on the reduction's grid of its mean), but where the work bound left it."""
        phi = np.asarray(phi, float)
        if not self.rough:
            empty = np.zeros(phi.shape, bool)
            return np.zeros(phi.shape), empty, empty, np.zeros((0, phi.size))
        finite = bool(np.isfinite(phi).all())
        key = (repr(self.linkage.linkage), self.masses, self.pairs)
        known_phi, known = _dry_solved.get(key, (np.zeros(0), None)) if finite else (np.zeros(0), None)
        at = np.minimum(np.searchsorted(known_phi, phi), max(known_phi.size - 1, 0))
        hit = (known_phi[at] == phi) if known_phi.size else np.zeros(phi.size, bool)
        table = None
        if not hit.all():
            sub = comp if comp is not None and not hit.any() else compose(self.linkage.linkage, phi[~hit])
            found = dry_moment(self.linkage, sub, self.masses, dict(self.pairs), budget=DRY_BUDGET_S)
            rows = np.column_stack([found.moment, found.locked, found.unsettled, *found.normals])
            table = np.empty((phi.size, rows.shape[1]))
            table[~hit] = rows
            settled = ~found.unsettled            # the work bound's angles are tried again next time
            if finite and settled.any():          # the angles solved so far, sorted, one row each
                angles, first = np.unique(np.concatenate([known_phi, sub.phi[settled]]), return_index=True)
                both = rows[settled] if known is None else np.concatenate([known, rows[settled]])
                _dry_solved.put(key, (angles, both[first]))
        if hit.any():
            table = known[at] if hit.all() else np.where(hit[:, None], known[at], table)
        return table[:, 0], table[:, 1] > 0, table[:, 2] > 0, table[:, 3:].T

    def dry_table(self) -> KinkTable:
        """M_T between the machine's kinks as piecewise Chebyshev interpolants (kink_table.py) to the friction
        solve's ε_R, kept for the last DRY_KEPT linkages, masses, pairs and kinks (a dragged [δ] or motor finds
        it)."""
        kinks = np.asarray(self.kinks())
        key = (repr(self.linkage.linkage), self.masses, self.pairs, kinks.tobytes())
        return _dry_tables.kept(key, lambda: build_table(lambda phi: self.solved(phi)[0][None], kinks,
                                                         DRY_TOLERANCE, DRY_ORDERS))

    def smooth_table(self) -> tuple[KinkTable, list[Notice]]:
        """J, J′, M_useful and S (``smooth_columns``) between the kinematic kinks (the loads' reversals and diagram
        points: M_useful's corners; the rough pairs' reversals) as piecewise Chebyshev interpolants to
        SMOOTH_TOLERANCE (kink_table.py), and the assembly notices over the turn (a group near a dead position,
        on KINK_SCAN angles).  None of them depends on f, r, the motor or [δ]: kept for the last SMOOTH_KEPT
        linkages, masses, inertias and loads (and in the machine's memo)."""
        if "smooth_table" in self.memo:
            return self.memo["smooth_table"]
        key = (repr(self.linkage.linkage), replace(self.masses, friction=0.0, pair_radius=0.0), self.inertias,
               self.load, self.prismatic_beta, tuple((name, p.beta) for name, p in self.pairs), self.cycle(),
               self.rough_flags())
        found = _smooth_tables.kept(key, lambda: (
            build_table(self.smooth_columns, self.kinematic_kinks(), SMOOTH_TOLERANCE, SMOOTH_ORDERS),
            assembly_notices(compose(self.linkage.linkage, np.linspace(0.0, TURN, KINK_SCAN + 1)),
                             self.linkage.linkage, integrated=True)))
        self.memo["smooth_table"] = found
        return found

    def smooth_columns(self, phi: np.ndarray, comp: Composition | None = None) -> np.ndarray:
        """Rows J, J′ (Eremyants (1.3)), M_useful (power equality, (1.5), with the crank's own moment) and S at
        the angles ``phi`` from the linkage composed there (``comp``, if it is)."""
        comp = compose(self.linkage.linkage, np.asarray(phi, float)) if comp is None else comp
        centres = centre_points(comp, self.masses)
        inertia = reduced_inertia(self.linkage, comp, self.masses, self.constant_inertia, centres)
        useful = reduced_loads(self.linkage, comp, self.masses, centres).total + self.load.crank_moment
        return np.stack([inertia.J, inertia.dJ, useful + np.zeros(comp.phi.shape), self.sliding(comp)])

    def dry_moment(self, phi: np.ndarray) -> tuple[np.ndarray, list[Notice]]:
        """M_T at the angles ``phi`` for the equation of motion: from ``dry_table`` between the kinks, solved
        directly where the table leaves it (within KINK_SIDE of a kink, a segment it does not interpolate), and
        the notices of those angles (an interpolated segment neither locks nor leaves the work bound)."""
        if not self.rough:
            return np.zeros(phi.shape), []
        values, direct = self.dry_table().at(phi)
        moment = values[0]
        locked, unsettled = np.zeros(phi.shape, bool), np.zeros(phi.shape, bool)
        if direct.any():
            moment[direct], locked[direct], unsettled[direct], _ = self.solved(phi[direct])
        return moment, dry_notices(phi, locked, unsettled)

    def cycle(self) -> float:
        return max(TURN, self.motor.cycle())

    def linkage_notices(self) -> list[Notice]:
        """The change points passed (angle, branch kept) and that the motion integrates their limit."""
        return change_point_notices(self.linkage.linkage, integrated=True)

    def jumps(self) -> list[float]:
        return []

    def kinks_key(self) -> tuple:
        """The kinks are the zeros of the loaded sliders', points' and links' velocity analogs and the loads'
        diagrams' breaks, and with dry friction those of the rough pairs' relative motion and normal forces: they
        depend on the linkage and the loads, and with friction on the weights too."""
        return ("general", repr(self.linkage.linkage), self.masses if self.rough else
                (self.masses.forces, self.masses.moments, self.masses.point_forces), self.pairs, self.load,
                self.cycle())

    @property
    def constant_inertia(self) -> float:
        """J₁ + J_rotor i²: the crank's shaft and gears and the motor's rotor (group I)."""
        return self.inertias.J1 + self.inertias.J_rotor * self.inertias.gear_ratio**2

    def tables(self, phi: np.ndarray) -> Tables:
        """J, J′, M_useful, S from ``smooth_table`` (composed directly within KINK_SIDE of a kinematic kink, or on
        a segment the table leaves), M_T from ``dry_table``, the constant motor's moment or a free law M_P(φ₁)."""
        phi = np.asarray(phi, float)
        table, notices = self.smooth_table()
        columns, direct = table.at(phi)
        if direct.any():
            columns[:, direct] = self.smooth_columns(phi[direct])
        drive = np.full(phi.shape, self.motor.M0 * self.inertias.gear_ratio) if self.motor.kind == "constant" \
            else table_moment(self.motor, phi) if self.motor.kind == "table" else np.zeros(phi.shape)
        dry, locking = self.dry_moment(phi)
        return Tables(phi, columns[0], columns[1], drive, columns[2], dry, columns[3], locking + notices)

    def switching(self, phi: np.ndarray) -> np.ndarray:
        """The loads' switches and the rough pairs' relative motions: kinematics alone (the normal forces'
        zeros, which need the friction solve, are found apart: ``find_kinks``)."""
        comp = compose(self.linkage.linkage, np.asarray(phi, float))
        rows = reduced_loads(self.linkage, comp, self.masses).switches + self.relative_motions(comp)
        return np.array(rows) if rows else np.zeros((0, comp.phi.size))

    def relative_motions(self, comp: Composition) -> list[np.ndarray]:
        """The relative velocity analog of every pair with dry friction."""
        if not self.rough:
            return []
        named = dict(self.pairs)
        default = self.masses.friction
        return [relative for name, relative in pair_motions(self.linkage, comp)
                if named.get(name, PairFriction(default)).f > 0]

    def normals(self, phi: np.ndarray) -> np.ndarray:
        """(R, N): the normal force of every rough prismatic pair at φ, NaN where there is no equilibrium."""
        return self.solved(phi)[3]

    def scan_normals(self, phi: np.ndarray) -> np.ndarray:
        """``normals`` where their signs are not proved without the friction solve (dry_moment.normal_signs),
        the normal forces without friction, which have those signs, elsewhere: for bracketing their zeros.  The
        setup on the scan (the loads, the groups' pass, the reactions affine in the friction loads) does not
        depend on f or r: kept for the last SCAN_KEPT linkages, masses and rough pairs, only the coefficients of
        (3.3) made anew (analysis.with_friction), so a dragged f proves the signs with the same arithmetic."""
        phi = np.asarray(phi, float)
        key = (repr(self.linkage.linkage), replace(self.masses, friction=0.0, pair_radius=0.0), self.rough_flags(),
               phi.tobytes())
        kept = _scan_setups.kept(key, lambda: setup(self.linkage, compose(self.linkage.linkage, phi), self.masses,
                                                    0.0, 0.0, dict(self.pairs)))
        comp = kept.comp
        values, proved = proved_signs(with_friction(kept, self.masses, dict(self.pairs)))
        if not proved.all():
            values[:, ~proved] = self.normals(comp.phi[~proved])
        return values

    def rough_flags(self) -> tuple[bool, ...]:
        """Which pairs have dry friction, in the order of ``pair_motions`` (kept in the machine's memo)."""
        if "rough_flags" not in self.memo:
            named = dict(self.pairs)
            self.memo["rough_flags"] = tuple(
                named.get(name, PairFriction(self.masses.friction)).f > 0
                for name, _ in pair_motions(self.linkage, compose(self.linkage.linkage, np.zeros(1))))
        return self.memo["rough_flags"]

    def kinematic_kinks(self) -> np.ndarray:
        """The kinks of ``Machine.find_kinks`` (the loads' switches and the rough pairs' relative motions). They
        depend on the linkage, the loads and which pairs are rough, not on f or r: a dragged f finds them kept
        (the last KINKS_KEPT, as Machine.kinks keeps a machine's)."""
        key = (repr(self.linkage.linkage), self.masses.forces, self.masses.moments, self.masses.point_forces,
               self.load, self.cycle(), self.rough_flags())
        switches = super().find_kinks
        return _switches_found.kept(key, lambda: read_only(switches()))

    def find_kinks(self) -> np.ndarray:
        """The kinks of ``Machine.find_kinks`` (the kinematic switches, ``kinematic_kinks``), and the zeros of the
        rough prismatic pairs' normal forces (|N| has a corner there): bracketed on the same scan (their signs
        proved without the friction solve where they can be, ``scan_normals``) and refined as there
        (brackets.refine_zeros) from the solved values at the brackets' ends; a bracket that holds a kinematic kink is that kink (the normal force jumps there, with
        the load's or a friction's sense: no zero of its own to refine)."""
        kinks = self.kinematic_kinks()
        cycle = self.cycle()
        phi = np.linspace(0.0, cycle, KINK_SCAN * math.ceil(cycle / TURN - 1e-9) + 1)
        values = self.scan_normals(phi)
        with np.errstate(invalid="ignore"):
            rows, cols = np.nonzero((values[:, :-1] * values[:, 1:] < 0) | (values[:, :-1] == 0))
        low, high = phi[cols], phi[cols + 1]
        holds = ((kinks[None, :] >= low[:, None] - KINK_MERGE) & (kinks[None, :] <= high[:, None] + KINK_MERGE)).any(1)
        rows, cols, low, high = rows[~holds], cols[~holds], low[~holds], high[~holds]
        if not rows.size:
            return kinks
        ends = self.normals(np.concatenate([low, high]))           # the brackets' ends with friction, solved
        count = np.arange(rows.size)
        found = refine_zeros(lambda index, at: own_rows(self.normals(at.ravel()), rows[index], at.shape),
                             low, high, ends[rows, count], ends[rows, rows.size + count], sections=NORMAL_SECTIONS)
        found = np.where((found <= KINK_MERGE) | (found >= cycle - KINK_MERGE), 0.0, found)
        found = np.sort(np.concatenate([kinks, found]))
        return found[np.append(True, np.diff(found) > KINK_MERGE)]


    def sliding(self, comp: Composition) -> np.ndarray:
        """S(φ) of the viscous moment β ω S(φ) (module docstring)."""
        beta = self.load.beta
        if not beta:
            return np.zeros(comp.phi.shape)
        total = (self.prismatic_beta / beta) * sliding_squares(comp)
        viscous = {name: p.beta for name, p in self.pairs if p.beta > 0}
        if viscous:
            total = total + sum((viscous[name] / beta) * relative**2
                                for name, relative in pair_motions(self.linkage, comp) if name in viscous)
        return total


def dry_notices(phi: np.ndarray, locked: np.ndarray, unsettled: np.ndarray) -> list[Notice]:
    """Self-locking and the friction solve's work bound, as sentences with the ranges of φ."""
    order = np.argsort(phi)             # the integrator's nodes come with its kinks at the end
    notices = []
    if locked.any():
        ranges = angle_ranges(phi[order], locked[order])
        notices.append(Notice("group_self_locking", f"Self-locking for φ in {ranges_text(ranges)}: the "
                              "equilibrium with friction ceases to exist there (the reactions it needs grow "
                              "without bound), so no driving moment moves the mechanism.", {"ranges": ranges}))
    if unsettled.any():
        ranges = angle_ranges(phi[order], unsettled[order])
        notices.append(Notice("dry_friction_work_bound", f"The equilibrium with friction was not solved within "
                              f"the work bound ({DRY_BUDGET_S:g} s) for φ in {ranges_text(ranges)}: the "
                              "friction moment is unknown there, no motion is computed.",
                              {"budget": DRY_BUDGET_S, "ranges": ranges}))
    return notices


def pair_motions(mechanism: GeneralMechanism, comp: Composition) -> list[tuple[str, np.ndarray]]:
    """Every pair's name and relative velocity analog: θ′_b − θ′_a (revolute), the sliding analog (prismatic).
    A joint that joins three links is two revolute pairs of one name (a pair's f, r, β by name are both's)."""
    pairs = [p for g in group_pairs(mechanism.linkage, comp) for p in g.pairs]
    return [(p.name, p.relative) for p in pairs + [crank_pair(mechanism.linkage, comp)]]


def sliding_squares(comp: Composition) -> np.ndarray:
    """S(φ) = Σ s′² over the prismatic pairs: the viscous moment is β ω S(φ) (Eremyants (3.15)–(3.17))."""
    return sum((s.d1**2 for s in comp.slides.values()), np.zeros(comp.phi.shape))


def general_machine(linkage: dict, masses: MassModel, inertias: Inertias, load: Load, motor: Motor,
                    pairs: dict[str, PairFriction] | None = None) -> GeneralMachine:
    """The machine of a request, checked: the linkage assembles over the whole turn, the mass model names its
    links and sliders, the loads are the general mechanism's (GeometryError names the field)."""
    mech = GeneralMechanism(linkage)
    mech.require_crank("the dynamics")
    turn = mech.require_full_turn()
    mech.require_even_change_points()
    masses = with_strokes(mech, masses)
    check_model(turn, masses)
    known = {name for name, _ in pair_motions(mech, compose(mech.linkage, np.zeros(1)))}
    for name in pairs or {}:
        if name not in known:
            raise GeometryError(f"pair_friction.{name}", f"no pair '{name}' in this linkage (pairs: "
                                f"{', '.join(sorted(known))})", "unknown_pair", pair=name)
    if motor.kind == "indicator":
        raise GeometryError("motor.kind", "an indicator diagram drives a crank-slider (piston engine) only",
                            "indicator_needs_slider")
    refused = {"load.force": load.force, "load.f": load.f, "inertias.m2": inertias.m2,
               "inertias.J_S2": inertias.J_S2, "inertias.m3": inertias.m3,
               "inertias.J3": inertias.J3}
    for where, value in refused.items():
        if value:
            raise GeometryError(where, "a general mechanism takes its link masses and loads in `masses` (links, "
                                "forces, moments) and the dry friction of its pairs in `masses.friction`, "
                                "`masses.pair_radius` and `pair_friction`", "general_loads")
    if load.convention != "consistent":
        raise GeometryError("load.convention", "the textbook's printed formulas are for the four fixed mechanisms",
                            "general_masses")
    single = any(p.beta > 0 for p in (pairs or {}).values())
    beta = load.beta if load.beta > 0 or not single else 1.0
    return GeneralMachine("general", {}, inertias, replace(load, beta=beta), motor, linkage=mech, masses=masses,
                          pairs=tuple(sorted((pairs or {}).items())), prismatic_beta=load.beta)


@dataclass
class CycleMean:
    mean: float | None          # M_c0, N·m; None where M_c is not finite somewhere (self-locking, the work bound)
    error: float                # its error estimate relative to the cycle mean of |M_c|
    angles: int                 # the angles at which M_c was computed


def resisting_total(machine: GeneralMachine, phi: np.ndarray, omega: float) -> np.ndarray:
    """M_c(φ) = M_useful + M_T + β ω S at the angles ``phi`` (the reduction's total)."""
    comp = compose(machine.linkage.linkage, phi)
    return (reduced_loads(machine.linkage, comp, machine.masses).total + machine.load.crank_moment
            + machine.dry(comp)[0] + machine.load.beta * omega * machine.sliding(comp))


def cycle_mean(machine: GeneralMachine, omega: float) -> CycleMean:
    """M_c0 = (1/2π) ∫₀²π M_c dφ (Eremyants (3.11)) by composite Gauss–Legendre quadrature between the machine's
    kinks (``find_kinks``: M_c is analytic between them, so the rule converges geometrically on each segment;
    Davis & Rabinowitz, Methods of Numerical Integration, §2.7): on each segment the rules of MEAN_ORDER and
    2·MEAN_ORDER nodes; the fine one's error is far below their difference (geometric convergence), which is
    the segment's error estimate.  A segment whose difference exceeds MEAN_TOLERANCE of the cycle mean of |M_c|
    (its share by width) is halved (a corner the kinks did not name, a steep stretch near self-locking), at most
    MEAN_HALVINGS times; two halves are accepted together, their estimate the sum of their differences and of
    the change of the fine rule from the whole to the halves (so that the two orders agreeing by chance on a
    corner does not pass); at the last halving a segment's error is bounded by its width times the range of M_c
    on its nodes (a jump the kinks missed is no smooth stretch).  The estimate adds the friction solve's ε_R (M_T is solved to it) and the rounding
    of the sums."""
    kinks = np.asarray(machine.kinks())
    edges = np.unique(np.concatenate([[0.0], kinks[(kinks > 0) & (kinks < TURN)], [TURN]]))
    low, high, parent = edges[:-1], edges[1:], None       # parent: the fine rule on the whole of two halves
    coarse_t, coarse_w = np.polynomial.legendre.leggauss(MEAN_ORDER)
    fine_t, fine_w = np.polynomial.legendre.leggauss(2 * MEAN_ORDER)
    t, w = np.concatenate([coarse_t, fine_t]), np.concatenate([coarse_w, -fine_w])    # coarse − fine at once
    integral = difference = absolute = 0.0
    angles, scale, depth = 0, 0.0, 0
    while low.size:
        half, mid = 0.5 * (high - low), 0.5 * (high + low)
        values = resisting_total(machine, (mid[:, None] + half[:, None] * t[None, :]).ravel(), omega)
        angles += values.size
        if not np.isfinite(values).all():
            return CycleMean(None, 0.0, angles)
        values = values.reshape(low.size, t.size)
        fine = half * (values[:, MEAN_ORDER:] @ fine_w)
        differ = np.abs(half * (values @ w))
        size = half * (np.abs(values[:, MEAN_ORDER:]) @ fine_w)
        if parent is None:                      # the first pass spans the cycle: the cycle mean of |M_c|
            scale = float(size.sum()) / TURN
            width = 2 * half
        else:                                   # halves k and k + n of one segment, taken together
            n = low.size // 2
            fine, size, width = fine[:n] + fine[n:], size[:n] + size[n:], 4 * half[:n]
            differ = differ[:n] + differ[n:] + np.abs(fine - parent)
        last = depth >= MEAN_HALVINGS or angles >= MEAN_ANGLES
        if last:                                # no longer smooth by assumption: bounded by the values' range
            spread = np.ptp(values, axis=1)
            differ = np.maximum(differ, width * (spread if parent is None else np.maximum(spread[:n], spread[n:])))
        done = (differ <= MEAN_TOLERANCE * scale * width) | last
        integral += float(fine[done].sum())
        difference += float(differ[done].sum())
        absolute += float(size[done].sum())
        if parent is not None:                  # the halves of the segments not done are halved again
            keep = np.concatenate([~done, ~done])
            low, high, parent = low[keep], high[keep], (half * (values[:, MEAN_ORDER:] @ fine_w))[keep]
        else:
            low, high, parent = low[~done], high[~done], fine[~done]
        split = 0.5 * (low + high)
        low, high, parent = np.concatenate([low, split]), np.concatenate([split, high]), parent
        depth += 1
    rough_part = DRY_TOLERANCE if machine.rough else 0.0
    rounding = 64 * np.finfo(float).eps * absolute
    error = (difference + rounding) / (TURN * scale) + rough_part if scale > 0 else 0.0
    return CycleMean(integral / TURN, error, angles)


def reduction(machine: GeneralMachine, n: int, omega: float, outputs: list[str]) -> tuple[dict, list[Notice]]:
    """J(φ), dJ/dφ and M_c(φ) over one turn (closed grid of n points), each link's and load's part apart; the
    mean M_c0 by Gauss–Legendre quadrature between the kinks with its error estimate (``cycle_mean``)."""
    if "friction_iteration" in outputs:
        raise GeometryError("outputs", "the textbook iterates friction forces for the sine mechanism and the "
                            "crank-slider only", "no_iteration")
    phi = np.linspace(0.0, TURN, n)
    linkage = machine.linkage.linkage
    comp = compose(linkage, phi)            # the limit at change points: the means integrate the continuing motion
    result, notices = {"phi": phi}, assembly_notices(comp, linkage, integrated=True)
    singular = change_point_mask(linkage, phi)
    if "inertia" in outputs:
        inertia = reduced_inertia(machine.linkage, comp, machine.masses, machine.constant_inertia)
        mean = float(np.mean(inertia.J[:-1]))
        result["inertia"] = undefined_at({"J": inertia.J, "dJ": inertia.dJ, "variable": inertia.J - mean,
                                          "parts": inertia.parts, "slopes": inertia.slopes}, singular) \
            | {"mean": mean, "approximation": None}
    if "resisting" in outputs:
        started = time.perf_counter()
        loads = reduced_loads(machine.linkage, comp, machine.masses)
        useful = loads.total + machine.load.crank_moment
        viscous = machine.load.beta * omega * machine.sliding(comp)
        dry, locking, _ = machine.dry(comp)
        notices = locking + notices
        found = cycle_mean(machine, omega)
        mean = found.mean if np.isfinite(dry).all() else None     # a locked range between the rule's nodes
        numerics = Numerics(method="closed-form analogs of every link, power equality at each angle; M_c0 by "
                                   "composite Gauss–Legendre quadrature between the kinks of M_c, error estimated "
                                   f"by the difference of the rules of {MEAN_ORDER} and {2 * MEAN_ORDER} nodes on "
                                   "each segment (halved where it is large), relative to the cycle mean of |M_c|", code="closed_forms",
                            steps=found.angles, error_estimate=found.error,
                            runtime_ms=1e3 * (time.perf_counter() - started))
        if mean is None:
            numerics.message = ("no M_c0: the moment is not finite at every angle (self-locking, or the friction "
                                "solve's work bound)")
            numerics.message_code = "no_mean_moment"
        result["numerics"] = numerics.as_dict()
        locked = ~np.isfinite(dry)
        result["resisting"] = undefined_at({"total": useful + dry + viscous, "useful": useful, "dry": dry,
                                            "viscous": viscous, "parts": loads.parts}, singular) \
            | {"mean": mean, "means": {"consistent": mean}, "friction_angle": 0.0,
               "self_locking": phi[locked] if locked.any() else None}
    return result, notices
