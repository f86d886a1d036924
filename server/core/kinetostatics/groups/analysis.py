"""Kinetostatics of a general mechanism by structural groups, with friction (Chaika–Vasylenko §3.1, (3.1)–(3.3)).

The loads (loads.py: weight, d'Alembert inertia, useful loads), then the groups in reverse order of attachment and
the crank (equilibrium.py), the textbook's successive approximations of the friction (approximation 1 without
it, then (3.3) from the previous reactions, until the relative change of the reactions is below ε_R, design step
17(d)) kept as the table the page shows, and the equilibrium with friction solved directly (friction.py) as the
answer, with self-locking decided by the physics.  Vectorised over φ.  Angles and moments counter-clockwise
internally; the balancing moment is reported along ω₁ (the crank's sense of rotation σ).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ...mechanisms.base import GeometryError, Notice, angle_ranges, ranges_text
from ..crank_slider import approximations_outcome
from ...numerics import Numerics
from ...structure.compose import Composition, compose
from ...structure.masses import MassModel, check_model, with_strokes
from . import friction as fr
from .equilibrium import Influence, solve_all
from .loads import Load, link_loads, power_moment, resultants
from .pairs import GroupPairs, KinematicPair, crank_pair, group_pairs

SHOWN_APPROXIMATIONS = 60        # rows of the textbook's table at most; the answer is the direct solve


@dataclass
class Approximation:
    """One row of the table of approximations: the friction loads it used (K, N), each group's six unknowns
    (N, 6), the frame's reaction on the crank R₀₁ (complex), the balancing moment along ω₁ and the largest
    relative change of the reactions from the previous row."""

    friction: np.ndarray
    unknowns: list[np.ndarray]
    R01: np.ndarray
    balancing: np.ndarray
    change: float | None


@dataclass
class GroupForces:
    phi: np.ndarray
    comp: Composition
    groups: list[GroupPairs]
    pairs: list[KinematicPair]             # the friction pairs: every group's three, then the crank's pivot
    coefficients: list[fr.PairFriction]
    loads: list[Load]
    influence: Influence
    crank_link: int
    sense: int
    rough_pairs: list[int]                 # the pairs with f > 0: the friction loads the solve carries
    approximations: list[Approximation] = field(default_factory=list)
    solution: Approximation | None = None
    locked: np.ndarray | None = None
    converged: np.ndarray | None = None
    ratios: np.ndarray | None = None
    ratio: float | None = None
    reduced_moment: np.ndarray | None = None   # −Σ(F·z′ + Mθ′) of the loads (power equality)
    numerics: dict | None = None
    notices: list[Notice] = field(default_factory=list)

    @property
    def rough(self) -> bool:
        return bool(self.rough_pairs)


def approximation(result: GroupForces, z: np.ndarray, change: float | None) -> Approximation:
    """The row for the friction loads z of the rough pairs (f > 0); the others' friction is zero."""
    unknowns, R01, balancing = result.influence.at(z)
    friction = np.zeros((len(result.pairs), result.phi.size))
    friction[result.rough_pairs] = z
    return Approximation(friction, unknowns, R01, result.sense * balancing, change)


def reaction_vector(row: Approximation) -> np.ndarray:
    """All the reactions of a row as one (N, 6g + 2) array (for the relative change)."""
    return np.concatenate([*row.unknowns, np.stack([row.R01.real, row.R01.imag], -1)], axis=1)


@dataclass
class Setup:
    """The friction equilibrium of a composed linkage: its groups and pairs, each pair's f and r, the loads,
    the reactions as affine functions of the friction loads, and the friction map of the rough pairs."""

    comp: Composition
    groups: list[GroupPairs]
    pairs: list[KinematicPair]
    locate: list[tuple[int, int] | None]
    coefficients: list[fr.PairFriction]
    loads: list[Load]
    influence: Influence
    rough: list[int]
    fmap: fr.FrictionMap


def setup(mechanism, comp: Composition, model: MassModel, omega: float, epsilon: float,
          pairs: dict[str, fr.PairFriction] | None = None) -> Setup:
    """Everything the friction solve needs on ``comp`` (GeometryError names an unknown pair of ``pairs``)."""
    linkage = mechanism.linkage
    groups = group_pairs(linkage, comp)
    pivot = crank_pair(linkage, comp)
    friction_pairs = [p for g in groups for p in g.pairs] + [pivot]
    for name in pairs or {}:
        if name not in {p.name for p in friction_pairs}:
            known = ", ".join(sorted({p.name for p in friction_pairs}))
            raise GeometryError(f"pair_friction.{name}", f"no pair '{name}' in this linkage (pairs: {known})",
                                "unknown_pair", pair=name)
    locate = [(g.index, k) for g in groups for k in range(3)] + [None]
    default = fr.PairFriction(model.friction, model.pair_radius)
    coefficients = [(pairs or {}).get(p.name, default) for p in friction_pairs]
    loads = link_loads(mechanism, comp, model, omega, epsilon)
    force, moment = resultants(loads, comp.links, comp.phi.size)
    rough = [k for k, c in enumerate(coefficients) if c.f > 0]
    influence = solve_all(groups, linkage.crank.link, pivot, force, moment, [friction_pairs[k] for k in rough])
    fmap = fr.friction_map(influence, [locate[k] for k in rough], [friction_pairs[k] for k in rough],
                           [coefficients[k] for k in rough])
    return Setup(comp, groups, friction_pairs, locate, coefficients, loads, influence, rough, fmap)


def rough_pairs(pairs: list[KinematicPair], model: MassModel,
                pairs_friction: dict[str, fr.PairFriction] | None = None) -> tuple[bool, ...]:
    """Which of the friction pairs ``pairs`` have f > 0 (the friction loads the solve carries)."""
    default = fr.PairFriction(model.friction, model.pair_radius)
    return tuple((pairs_friction or {}).get(p.name, default).f > 0 for p in pairs)


def with_friction(s: Setup, model: MassModel, pairs: dict[str, fr.PairFriction] | None = None) -> Setup:
    """``s`` with the f and r of ``model`` and ``pairs``, the same pairs rough (rough_pairs): the loads and the
    reactions as affine functions of the friction loads do not depend on f or r, only the coefficients
    −sgn(relative) f ρ of (3.3) do (friction.friction_coefficients)."""
    default = fr.PairFriction(model.friction, model.pair_radius)
    coefficients = [(pairs or {}).get(p.name, default) for p in s.pairs]
    if [k for k, c in enumerate(coefficients) if c.f > 0] != s.rough:
        raise ValueError("with_friction keeps the rough pairs: set up anew where they change")
    if not s.rough:
        return replace(s, coefficients=coefficients)
    fmap = fr.FrictionMap(s.fmap.base, s.fmap.lever, fr.friction_coefficients([s.pairs[k] for k in s.rough],
                                                                              [coefficients[k] for k in s.rough]))
    return replace(s, coefficients=coefficients, fmap=fmap)


def require_full_turn(comp: Composition) -> None:
    """Refuse a linkage one of whose groups does not close at every angle of ``comp``."""
    for k, group in enumerate(comp.groups):
        if not group.closes.all():
            ranges = ranges_text(angle_ranges(comp.phi, ~group.closes))
            raise GeometryError(f"linkage.groups.{k}", f"the {group.kind} group cannot be assembled at φ = {ranges}: "
                                "the crank cannot turn fully; the forces are computed over the whole turn",
                                "group_forces_no_full_turn", group=k)


def analyse(mechanism, model: MassModel, phi: np.ndarray, omega: float = 10.0, epsilon: float = 0.0,
            tolerance: float = 1e-9, pairs: dict[str, fr.PairFriction] | None = None,
            shown: int = SHOWN_APPROXIMATIONS, budget: float | None = None) -> GroupForces:
    """The reactions in every pair and the balancing moment at the crank angles ``phi`` (rad).

    ``omega`` > 0: the crank's speed along its rotation, ``epsilon`` its angular acceleration (rad/s, rad/s²);
    friction f and journal radius r of every pair from the model (``friction``, ``pair_radius``), or per pair
    by name (``pairs``: joint names for revolute pairs, guide names for prismatic, the slide of an RPR, B/slot);
    ``budget``: a wall-clock bound of the friction solve, s (the server's; None: none)."""
    clock = time.perf_counter()
    phi = np.asarray(phi, float)
    linkage = mechanism.linkage
    comp = compose(linkage, phi)
    require_full_turn(comp)
    model = with_strokes(mechanism, model)
    check_model(comp, model)
    s = setup(mechanism, comp, model, omega, epsilon, pairs)
    result = GroupForces(phi, comp, s.groups, s.pairs, s.coefficients, s.loads, s.influence, linkage.crank.link,
                         linkage.crank.sense, s.rough)
    result.reduced_moment = power_moment(s.loads)
    fmap = s.fmap
    solved = fr.solve(fmap, tolerance, budget)
    result.locked = solved.locked
    result.approximations = textbook_approximations(result, fmap, tolerance, shown if result.rough else 1)
    final = fmap.apply(solved.z)                 # friction from the solved reactions (3.3), and the
    result.solution = approximation(result, final, None)   # reactions in equilibrium with it
    result.converged = solved.converged
    result.ratios = np.where(solved.locked, np.nan, solved.ratio)
    free = ~solved.locked & np.isfinite(solved.ratio)
    result.ratio = float(np.max(solved.ratio[free])) if result.rough and free.any() else None
    blank(result, solved.locked | s.influence.singular)
    say(result, solved, tolerance)
    result.numerics = numerics(result, solved, tolerance, time.perf_counter() - clock)
    return result


def textbook_approximations(result: GroupForces, fmap: fr.FrictionMap, tolerance: float,
                            shown: int) -> list[Approximation]:
    """Approximation 1 without friction, then the friction of (3.3) from the previous reactions, until the
    largest relative change of the reactions over the angles that neither lock nor stand at a dead position is
    below ε_R, or ``shown`` rows stand in the table, or the table has visibly run away (series' ratio ≥ 1)."""
    K, n = fmap.coefficient.shape
    free = ~result.locked & ~result.influence.singular
    z = np.zeros((K, n))
    table, previous = [], None
    with np.errstate(over="ignore", invalid="ignore"):
        while len(table) < shown:
            row = approximation(result, z, None)
            now = reaction_vector(row)[free]
            if previous is not None:
                scale = np.maximum(np.abs(now).max(axis=1), 1e-300)
                row.change = float(np.max(np.abs(now - previous).max(axis=1) / scale, initial=0.0))
            table.append(row)
            if row.change is not None and (row.change < tolerance or not row.change < 1e12):
                break
            previous = now
            z = fmap.apply(z)
    return table


def blank(result: GroupForces, where: np.ndarray) -> None:
    """No reaction and no friction where the mechanism locks or a group stands at a dead position: NaN."""
    if not where.any():
        return
    for row in (*result.approximations, result.solution):
        for x in row.unknowns:
            x[where] = np.nan
        row.friction[:, where] = np.nan
        row.R01[where] = np.nan
        row.balancing[where] = np.nan


def say(result: GroupForces, solved: fr.Solved, tolerance: float) -> None:
    phi = result.phi
    if solved.locked.any():
        ranges = angle_ranges(phi, solved.locked)
        result.notices.append(Notice(
            "group_self_locking", f"Self-locking for φ in {ranges_text(ranges)}: the equilibrium with friction, "
            "followed as the friction grows from zero, ceases to exist there (the reactions it needs grow without "
            "bound), so no driving moment moves the mechanism.", {"ranges": ranges}))
    if result.influence.singular.any():
        ranges = angle_ranges(phi, result.influence.singular)
        result.notices.append(Notice(
            "group_forces_dead_position", f"For φ in {ranges_text(ranges)} a group stands at a dead position (its links "
            "or guides in line): its equilibrium equations do not determine the reactions there.",
            {"ranges": ranges}))
    unconverged = ~solved.locked & ~result.influence.singular & ~solved.converged
    if unconverged.any():
        ranges = angle_ranges(phi, unconverged)
        reached = float(np.max(solved.error[unconverged]))
        result.notices.append(Notice(
            "kinetostatics_not_converged", f"The equilibrium with friction reached a relative error of "
            f"{reached:.2g}, not ε_R = {tolerance:.2g}, for φ in {ranges_text(ranges)}: rounding or the work bound "
            f"stopped it; the values there carry that error.",
            {"reached": reached, "tolerance": float(tolerance), "ranges": ranges}))


def numerics(result: GroupForces, solved: fr.Solved, tolerance: float, seconds: float) -> dict:
    """As the crank-slider's: the direct solve, its error, how much of the textbook's series the table shows."""
    free = ~solved.locked & ~result.influence.singular
    error = float(np.max(solved.error[free], initial=0.0))
    code, context, message = approximations_outcome(result.approximations, result.ratio, tolerance,
                                                     result.rough)
    return Numerics(
        method="Newton's method on the friction equilibrium of all the groups and the crank (the friction of "
               "(3.3) as unknowns), safeguarded by the textbook's step; the textbook's successive approximations "
               "shown beside it", rtol=float(tolerance), code="group_kinetostatics_newton", message_code=code,
        message_context=context, iterations=solved.iterations, runtime_ms=1e3 * seconds,
        error_estimate=error if result.rough else 0.0, message=message).as_dict()
