"""One entry point for the kinematics of any mechanism: validated parameters in, requested outputs out.

The result holds only what was asked for.  Values that are undefined at a singular
position (NaN) are kept as NaN here; :func:`finite_or_none` at the edge turns them
into nulls, and the result carries a warning saying where and why.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .harmonics import harmonic_grid, harmonics
from .mechanisms import MECHANISMS, GeometryError, Notice
from .mechanisms.base import Evaluation

MAX_POINTS = 10001
ARRAY_OUTPUTS_2D = ("v_s2", "a_s2")


@dataclass
class KinematicsResult:
    """Crank angles, the requested outputs (SI units) and warnings in words."""

    mechanism: str
    params: dict[str, float]
    cycle: float
    phi: np.ndarray
    outputs: dict[str, object] = field(default_factory=dict)
    warnings: list[Notice] = field(default_factory=list)


def crank_angles(cycle: float, n: int) -> np.ndarray:
    """n equally spaced angles over one closed cycle, both ends included: 0, …, cycle."""
    return np.linspace(0.0, cycle, n)


def compute_kinematics(mechanism: str, params: dict[str, float], outputs: list[str],
                       phi: np.ndarray | None = None, n: int | None = None) -> KinematicsResult:
    """Evaluate ``outputs`` of ``mechanism`` at ``phi`` (rad) or on ``n`` points over one cycle.

    Raises GeometryError (field, reason) for unknown outputs, bad sizes and geometry
    that cannot be assembled.
    """
    result, = compute_kinematics_many(mechanism, [params], outputs, phi, n)
    if isinstance(result, GeometryError):
        raise result
    return result


POINT_OUTPUTS = ARRAY_OUTPUTS_2D        # evaluate's outputs of points (…, N, 2); the others (…, N)


def compute_kinematics_many(mechanism: str, params: list[dict[str, float]], outputs: list[str],
                            phi: np.ndarray | None = None, n: int | None = None) -> list[KinematicsResult | GeometryError]:
    """compute_kinematics for several parameter sets of one mechanism (a family's members), each entry its
    result or the GeometryError compute_kinematics would raise for it. The sets that share a cycle and a
    ``branch`` are evaluated in one numpy call over a (linkage, φ) grid, their parameters broadcast as
    arrays of shape (M, 1), and so are the harmonics on their grid; special positions, descriptions and
    warnings are per linkage (closed forms), and a group whose evaluation warns is evaluated linkage by
    linkage (the warning is then each one's own)."""
    mech = MECHANISMS[mechanism]
    results: list = []
    for p in params:
        try:
            results.append(_checked(mech, mechanism, p, outputs, phi, n))
        except GeometryError as error:
            results.append(error)
    groups: dict[tuple, list[int]] = {}
    for k, result in enumerate(results):
        if isinstance(result, KinematicsResult):
            groups.setdefault((result.cycle, mech.branch(result.params)), []).append(k)
    wanted = set(outputs)
    for members in groups.values():
        linkages = [results[k].params for k in members]
        phi_k = results[members[0]].phi
        evaluations = _evaluate_many(mech, linkages, phi_k, wanted)
        spectra = None
        if "harmonics" in wanted:
            grid = harmonic_grid(results[members[0]].cycle)
            spectra = [ev.values["u31"] for ev in _evaluate_many(mech, linkages, grid, set())]
        special = None if "special" not in wanted else (
            mech.special_positions_many(linkages) if len(linkages) > 1 else [mech.special_positions(linkages[0])])
        for m, k in enumerate(members):
            _fill(mech, mechanism, results[k], evaluations[m], outputs,
                  None if spectra is None else spectra[m], None if special is None else special[m])
    return results


def _checked(mech, mechanism, params, outputs, phi, n) -> KinematicsResult:
    """compute_kinematics' checks, in its order: the outputs, the parameters, the angles."""
    known = {o.name for o in mech.outputs} | {"harmonics", "harmonics_du31", "info"}
    for i, name in enumerate(outputs):
        if name not in known:
            raise GeometryError(f"outputs.{i}", f"'{name}' is not an output of {mechanism}; "
                                                f"available: {', '.join(sorted(known))}")
    p = mech.check(params)
    cycle = mech.cycle(p)
    if phi is None:
        if n is None or not 2 <= n <= MAX_POINTS:
            raise GeometryError("n", f"give between 2 and {MAX_POINTS} points")
        phi = crank_angles(cycle, n)
    elif not 1 <= phi.size <= MAX_POINTS:
        raise GeometryError("phi", f"give between 1 and {MAX_POINTS} angles")
    return KinematicsResult(mechanism, p, cycle, phi)


def _evaluate_many(mech, linkages: list[dict], phi: np.ndarray, wanted: set[str]) -> list:
    """Each linkage's Evaluation at phi, from one evaluation of them all (parameters (M, 1)), split by linkage
    and completed by per_linkage; one by one where there is one linkage or the evaluation warns."""
    if len(linkages) == 1:
        return [mech.evaluate(linkages[0], phi, wanted)]
    stacked = {name: np.array([p[name] for p in linkages], float)[:, None] for name in linkages[0]}
    together = mech.evaluate(stacked, phi, wanted)
    if together.warnings:
        return [mech.evaluate(p, phi, wanted) for p in linkages]
    evaluations = []
    for m, p in enumerate(linkages):
        ev = Evaluation(phi)
        ev.values = {name: _row(value, m, name in POINT_OUTPUTS) for name, value in together.values.items()}
        ev.joints = {name: _row(value, m, True) for name, value in together.joints.items()}
        mech.per_linkage(p, ev, wanted)
        evaluations.append(ev)
    return evaluations


def _row(value: np.ndarray, m: int, points: bool) -> np.ndarray:
    """Linkage m's part of an output evaluated for several at once (an output the parameters do not change,
    such as a fixed pivot, is one array for all: a copy of it)."""
    return value[m].copy() if value.ndim == (3 if points else 2) else value.copy()


def _fill(mech, mechanism: str, result: KinematicsResult, ev: Evaluation, outputs: list[str],
          spectrum: np.ndarray | None, special: list | None) -> None:
    """compute_kinematics' outputs and warnings from the linkage's evaluation (and its u₃₁ on the harmonic grid,
    its special positions)."""
    p = result.params
    result.warnings.extend(ev.warnings)
    for name in outputs:
        if name == "joints":
            result.outputs[name] = ev.joints
        elif name == "special":
            result.outputs[name] = [sp.as_dict() for sp in special]
        elif name == "harmonics":
            result.outputs[name] = harmonics(mech, p, "u31", values=spectrum)
        elif name == "harmonics_du31":
            result.outputs[name] = harmonics(mech, p, "du31")
            claim = mech.harmonic_claim(p, result.outputs[name])
            if claim is not None:
                result.outputs[name]["claim"] = claim
        elif name == "info":
            result.outputs[name] = mech.describe(p)
        else:
            result.outputs[name] = ev.values[name]
    result.warnings.extend(mech.proximity_warnings(p))

