"""The dry-friction moment of a general mechanism reduced to its crank, for the equation of motion.

The crank-slider's friction moment is the limit of the textbook's successive approximations of the friction
loads under the useful load (Eremyants (3.24)–(3.28): M_c = k P_c |u₃₁|/(1 − f|tan ψ|)); generalised, it is the
group kinetostatics with friction (3.3) under the static loads (the useful loads and the weights, ω₁ = ε₁ = 0,
analysis.setup), its successive approximations summed by the direct solve (friction.solve):

    M_T(φ) = M_b,f(φ) − M_b,0(φ),

the balancing moment with friction minus the one without (the reduced moment of the loads by power equality,
loads.power_moment).  By power equality M_T = Σ_p |z_p| |rel_p|, the power the pairs dissipate per unit crank
speed (z_p a pair's friction load, rel_p its relative velocity analog).  The inertia loads' share of the
friction is left out, as the crank-slider's model leaves it out: it depends on ω and ε, the equation of motion
tabulates what depends on φ alone.

M_T has a corner where a rough pair's relative motion reverses (its friction changes sense) and where a rough
prismatic pair's normal force changes sign (|N| has a corner): ``switches``.  Where the equilibrium with
friction ceases to exist (self-locking, decided by the physics in friction.solve) or a group stands at a dead
position, M_T is NaN and ``locked`` says where; so it is where the solve's work bound (``budget``) ran out
first (``unsettled``: said in words by the caller, never decided locked).  Where the normal forces' signs are
proved without solving (``normal_signs``), their zeros are bracketed without the solve.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...structure.compose import Composition
from ...structure.masses import MassModel
from . import friction as fr
from .analysis import Setup, setup
from .compiled import certified_normals
from .loads import power_moment

TOLERANCE = 1e-12        # ε_R of the friction solve: far below any integrator tolerance the dynamics offers


@dataclass
class DryMoment:
    moment: np.ndarray          # M_T(φ), N·m, positive against the crank; NaN where ``locked``
    locked: np.ndarray          # (N,) the equilibrium with friction does not exist (self-locking)
    singular: np.ndarray        # (N,) a group at a dead position
    error: np.ndarray           # (N,) relative error of the reactions the solve reached
    unsettled: np.ndarray       # (N,) neither solved to the tolerance nor locked: the work bound ran out
    switches: list[np.ndarray]  # the rough pairs' relative motions: M_T has a corner or a jump at their zeros
    normals: list[np.ndarray]   # the rough prismatic pairs' normal forces (NaN where blank): a corner at a zero


def rough(model: MassModel, pairs: dict[str, fr.PairFriction] | None) -> bool:
    """Whether any pair has friction."""
    return model.friction > 0 or any(p.f > 0 for p in (pairs or {}).values())


def dry_moment(mechanism, comp: Composition, model: MassModel, pairs: dict[str, fr.PairFriction] | None = None,
               tolerance: float = TOLERANCE, budget: float | None = None, jams: bool = True) -> DryMoment:
    """M_T(φ) at the angles of ``comp`` (module docstring); ``pairs``: f and r by pair name, else the model's;
    ``budget``, ``jams``: as friction.solve's."""
    s = setup(mechanism, comp, model, 0.0, 0.0, pairs)
    solved = fr.solve(s.fmap, tolerance, budget, jams, ratios=False)
    z = s.fmap.apply(solved.z)
    _, _, balancing = s.influence.at(z)
    moment = mechanism.linkage.crank.sense * balancing - power_moment(s.loads)
    unsettled = ~solved.converged & ~solved.locked & ~s.influence.singular
    blank = solved.locked | s.influence.singular | unsettled
    reactions = s.fmap.reactions(solved.z)
    switches = [s.pairs[index].relative for index in s.rough]
    normals = [np.where(blank, np.nan, reactions[row, :, 0])     # none where there is no equilibrium
               for row, index in enumerate(s.rough) if s.pairs[index].kind == "P"]
    return DryMoment(np.where(blank, np.nan, moment), solved.locked, s.influence.singular, solved.error, unsettled,
                     switches, normals)


def normal_signs(mechanism, comp: Composition, model: MassModel,
                 pairs: dict[str, fr.PairFriction] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The rough prismatic pairs' normal forces without friction (R, N) and where each has, proved without the
    friction solve, the sign of the normal force with friction (N,) (compiled.certified_normals: there the
    equilibrium with friction exists, is unique and does not lock).  The corners of M_T at the normal forces'
    zeros are bracketed from these signs, solving only where they are not proved."""
    return proved_signs(setup(mechanism, comp, model, 0.0, 0.0, pairs))


def proved_signs(s: Setup) -> tuple[np.ndarray, np.ndarray]:
    """``normal_signs`` of a setup (analysis.with_friction gives a kept one new coefficients)."""
    rows = [row for row, index in enumerate(s.rough) if s.pairs[index].kind == "P"]
    normals = s.fmap.base[rows, :, 0]
    if not rows:
        return normals, np.ones(s.comp.phi.size, bool)
    proved = certified_normals(np.ascontiguousarray(s.fmap.base.transpose(1, 0, 2)), s.fmap.lever,
                               np.ascontiguousarray(s.fmap.coefficient.T), np.array(rows, np.int64))
    return normals, proved
