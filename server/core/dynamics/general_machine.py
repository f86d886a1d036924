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
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..mechanisms import GeometryError, Notice
from ..mechanisms.base import angle_ranges, ranges_text
from ..mechanisms.general import CHECK_POINTS, GeneralMechanism, assembly_notices
from ..kinetostatics.groups.dry_moment import dry_moment, rough
from ..kinetostatics.groups.friction import PairFriction
from ..kinetostatics.groups.pairs import crank_pair, group_pairs
from ..numerics import Numerics
from ..structure.compose import Composition, compose
from ..structure.masses import MassModel, centre_points, check_model, with_strokes
from ..structure.reduction import reduced_inertia, reduced_loads
from .machine import KINK_ITERATIONS, KINK_MERGE, KINK_SCAN, Machine, Tables
from .motors import Motor
from .reduction import Inertias
from .resistance import Load

TURN = 2 * np.pi
MEAN_POINTS = 8192       # intervals of the cycle mean M_c0 (trapezoid; the kinks make it second order)
DRY_BUDGET_S = 5.0       # wall clock of one friction solve of the dry moment (the forces request's bound), said in
                         # words where it runs out; a six-bar's 8193 angles take ~1 s


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

    def dry(self, comp: Composition) -> tuple[np.ndarray, list[Notice], np.ndarray]:
        """M_T(φ) of the pairs' dry friction on ``comp``, the notices (self-locking; the work bound), and the
        rough prismatic pairs' normal forces (R, N) (NaN where there is no equilibrium).  Each angle is solved
        once in the machine's life (``memo``: the friction equilibrium at an angle does not depend on the
        other angles solved with it; the steady cycle's levels are nested, the flywheel's nodes lie on the
        kinks' scan)."""
        if not self.rough:
            return np.zeros(comp.phi.shape), [], np.zeros((0, comp.phi.size))
        known = self.memo.setdefault("dry_by_angle", {}) if np.isfinite(comp.phi).all() else {}
        angles = comp.phi.tolist()
        missing = np.array([phi not in known for phi in angles], bool)
        rows = []
        if missing.any():
            sub = comp if missing.all() else compose(self.linkage.linkage, comp.phi[missing])
            found = dry_moment(self.linkage, sub, self.masses, dict(self.pairs), budget=DRY_BUDGET_S)
            normals = np.array(found.normals).T if found.normals else np.zeros((sub.phi.size, 0))
            rows = list(zip(found.moment.tolist(), found.locked.tolist(), found.unsettled.tolist(), normals))
            known.update(zip(sub.phi.tolist(), rows))
        if not missing.all():
            rows = [known[phi] for phi in angles]
        moment = np.array([row[0] for row in rows])
        locked, unsettled = np.array([row[1] for row in rows]), np.array([row[2] for row in rows])
        normals = np.array([row[3] for row in rows]).reshape(len(rows), -1).T
        order = np.argsort(comp.phi)             # the integrator's nodes come with its kinks at the end
        notices = []
        if locked.any():
            ranges = angle_ranges(comp.phi[order], locked[order])
            notices.append(Notice("group_self_locking", f"Self-locking for φ in {ranges_text(ranges)}: the "
                                  "equilibrium with friction ceases to exist there (the reactions it needs grow "
                                  "without bound), so no driving moment moves the mechanism.", {"ranges": ranges}))
        if unsettled.any():
            ranges = angle_ranges(comp.phi[order], unsettled[order])
            notices.append(Notice("dry_friction_work_bound", f"The equilibrium with friction was not solved within "
                                  f"the work bound ({DRY_BUDGET_S:g} s) for φ in {ranges_text(ranges)}: the "
                                  "friction moment is unknown there, no motion is computed.",
                                  {"budget": DRY_BUDGET_S, "ranges": ranges}))
        return moment, notices, normals

    def cycle(self) -> float:
        return max(TURN, self.motor.cycle())

    def jumps(self) -> list[float]:
        return []

    def kinks_key(self) -> tuple:
        """The kinks are the zeros of the loaded sliders' and links' velocity analogs, and with dry friction
        those of the rough pairs' relative motion and normal forces: they depend on the linkage and the loads,
        and with friction on the weights too."""
        return ("general", repr(self.linkage.linkage), self.masses if self.rough else
                (self.masses.forces, self.masses.moments), self.pairs, self.load, self.cycle())

    @property
    def constant_inertia(self) -> float:
        """J₁ + J_rotor i²: the crank's shaft and gears and the motor's rotor (group I)."""
        return self.inertias.J1 + self.inertias.J_rotor * self.inertias.gear_ratio**2

    def tables(self, phi: np.ndarray) -> Tables:
        comp = compose(self.linkage.linkage, np.asarray(phi, float))
        centres = centre_points(comp, self.masses)
        inertia = reduced_inertia(self.linkage, comp, self.masses, self.constant_inertia, centres)
        useful = reduced_loads(self.linkage, comp, self.masses, centres).total + self.load.crank_moment
        drive = np.full(comp.phi.shape, self.motor.M0 * self.inertias.gear_ratio) if self.motor.kind == "constant" \
            else np.zeros(comp.phi.shape)
        dry, locking, _ = self.dry(comp)
        return Tables(comp.phi, inertia.J, inertia.dJ, drive, useful, dry, self.sliding(comp),
                      locking + assembly_notices(comp))

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
        return self.dry(compose(self.linkage.linkage, np.asarray(phi, float)))[2]

    def find_kinks(self) -> np.ndarray:
        """The kinks of ``Machine.find_kinks`` (the kinematic switches), and the zeros of the rough prismatic
        pairs' normal forces (|N| has a corner there): bracketed on the same scan and refined by the Illinois
        method as there; a bracket that holds a kinematic kink is that kink (the normal force jumps there, with
        the load's or a friction's sense: no zero of its own to refine)."""
        kinks = super().find_kinks()
        cycle = self.cycle()
        phi = np.linspace(0.0, cycle, KINK_SCAN * math.ceil(cycle / TURN - 1e-9) + 1)
        values = self.normals(phi)
        with np.errstate(invalid="ignore"):
            rows, cols = np.nonzero((values[:, :-1] * values[:, 1:] < 0) | (values[:, :-1] == 0))
        low, high = phi[cols], phi[cols + 1]
        holds = ((kinks[None, :] >= low[:, None] - KINK_MERGE) & (kinks[None, :] <= high[:, None] + KINK_MERGE)).any(1)
        rows, cols, low, high = rows[~holds], cols[~holds], low[~holds], high[~holds]
        if not rows.size:
            return kinks
        found = illinois(lambda guess: self.normals(guess)[rows, np.arange(rows.size)], low, high,
                         values[rows, cols], values[rows, cols + 1])
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


def illinois(f, low: np.ndarray, high: np.ndarray, f_low: np.ndarray, f_high: np.ndarray) -> np.ndarray:
    """Zeros of f, one per bracket [low, high] with f of opposite signs at its ends, all brackets at once: the
    Illinois variant of regula falsi (Dahlquist & Björck, Numerical Methods, §6.2.3), as Machine.find_kinks,
    until a bracket or the step between two guesses is a few doubles wide (at most KINK_ITERATIONS steps)."""
    high = np.where(f_low == 0, low, high)
    previous, moved = np.full(low.size, np.inf), np.zeros(low.size)
    for _ in range(KINK_ITERATIONS):
        ulps = 4 * np.spacing(np.maximum(np.abs(low), np.abs(high)))
        open_ = (high - low > ulps) & (f_low != f_high) & np.isfinite(f_low) & np.isfinite(f_high)
        if not open_.any():
            break
        guess = np.where(open_, (low * f_high - high * f_low) / np.where(open_, f_high - f_low, 1.0), low)
        guess = np.where((guess > low) & (guess < high), guess, 0.5 * (low + high))
        settled = open_ & (np.abs(guess - previous) <= ulps)
        low, high = np.where(settled, guess, low), np.where(settled, guess, high)
        open_ &= ~settled
        previous = guess
        f_guess = f(guess)
        left = open_ & (np.sign(f_guess) == np.sign(f_low))
        right = open_ & ~left
        f_high = np.where(left & (moved > 0), 0.5 * f_high, f_high)
        f_low = np.where(right & (moved < 0), 0.5 * f_low, f_low)
        moved = np.where(left, 1.0, np.where(right, -1.0, moved))
        low, f_low = np.where(left, guess, low), np.where(left, f_guess, f_low)
        high, f_high = np.where(right, guess, high), np.where(right, f_guess, f_high)
    return 0.5 * (low + high)


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
    turn = compose(mech.linkage, np.linspace(0.0, TURN, CHECK_POINTS))
    for k, group in enumerate(turn.groups):
        if not group.closes.all():
            ranges = ranges_text(angle_ranges(turn.phi, ~group.closes))
            raise GeometryError(f"linkage.groups.{k}", f"the {group.kind} group cannot be assembled at φ = {ranges}: "
                                "the crank cannot turn fully, a machine needs the whole turn", "no_full_turn",
                                group=k)
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


def reduction(machine: GeneralMachine, n: int, omega: float, outputs: list[str]) -> tuple[dict, list[Notice]]:
    """J(φ), dJ/dφ and M_c(φ) over one turn (closed grid of n points), each link's and load's part apart; the
    mean M_c0 by the trapezoid rule on MEAN_POINTS intervals, its error against half as many (with dry friction
    its jumps make the rule first order there: the estimate, the difference of the two, says so)."""
    if "friction_iteration" in outputs:
        raise GeometryError("outputs", "the textbook iterates friction forces for the sine mechanism and the "
                            "crank-slider only", "no_iteration")
    phi = np.linspace(0.0, TURN, n)
    comp = compose(machine.linkage.linkage, phi)
    result, notices = {"phi": phi}, assembly_notices(comp)
    if "inertia" in outputs:
        inertia = reduced_inertia(machine.linkage, comp, machine.masses, machine.constant_inertia)
        mean = float(np.mean(inertia.J[:-1]))
        result["inertia"] = {"J": inertia.J, "dJ": inertia.dJ, "mean": mean, "variable": inertia.J - mean,
                             "parts": inertia.parts, "slopes": inertia.slopes, "approximation": None}
    if "resisting" in outputs:
        started = time.perf_counter()
        loads = reduced_loads(machine.linkage, comp, machine.masses)
        useful = loads.total + machine.load.crank_moment
        viscous = machine.load.beta * omega * machine.sliding(comp)
        dry, locking, _ = machine.dry(comp)
        notices = locking + notices
        fine = compose(machine.linkage.linkage, np.linspace(0.0, TURN, MEAN_POINTS + 1))
        total = (reduced_loads(machine.linkage, fine, machine.masses).total + machine.load.crank_moment
                 + machine.dry(fine)[0] + machine.load.beta * omega * machine.sliding(fine))
        finite = bool(np.isfinite(total).all())
        mean = float(np.mean(total[:-1])) if finite else None
        error = abs(mean - float(np.mean(total[:-1:2]))) if finite else 0.0
        scale = float(np.mean(np.abs(total[:-1]))) if finite else 0.0
        numerics = Numerics(method="closed-form analogs of every link, power equality at each angle; M_c0 by the "
                                   "trapezoid rule on a closed uniform grid, error estimated against the grid of half "
                                   "as many points, relative to the cycle mean of |M_c|", code="closed_forms",
                            steps=MEAN_POINTS, error_estimate=error / scale if scale > 0 else 0.0,
                            runtime_ms=1e3 * (time.perf_counter() - started))
        if not finite:
            numerics.message = ("no M_c0: the moment is not finite at every angle (self-locking, or the friction "
                                "solve's work bound)")
            numerics.message_code = "no_mean_moment"
        result["numerics"] = numerics.as_dict()
        locked = ~np.isfinite(dry)
        result["resisting"] = {"total": useful + dry + viscous, "useful": useful, "dry": dry, "viscous": viscous,
                               "parts": loads.parts, "mean": mean, "means": {"consistent": mean}, "friction_angle": 0.0,
                               "self_locking": phi[locked] if locked.any() else None}
    return result, notices
