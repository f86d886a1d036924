"""Time integration of the elastic models: the solver chosen by the stiffness it measures, bounded work.

Stiffness ratio: the fastest decay rate max|Re λ| of the Jacobian over a turn of the mechanism,
divided by the slow rate of the motion (the crank speed, or 2π over the time span).  Fast modes
that decay (a stiff spring with damping) force an explicit method to tiny steps long after they
have died out: above STIFF_RATIO the implicit, L-stable Radau runs with the analytic Jacobian.
A fast mode that only oscillates (little damping) has to be resolved by any accurate method, and
there the explicit DOP853 is the cheaper one per step (measured in bench/elastic.py).
The span is integrated in chunks; a request that passes its work or time budget stops with the
partial result and says so.  The work bound counts right-hand-side calls, whatever the machine's speed (the check
run at rtol/10 may make twice as many): 300,000 for the Python model (seconds), 1,500,000 for the compiled one
(about 0.2 s: a call costs some 0.15 µs there).  The compiled bound lets every run the sliders reach finish: the
elastic linkage's slider-crank with little damping starts at its dead centre, where c(φ) → 0 uncouples motor and
mechanism, and the motion the model predicts there (twists of tens of radians, which the answer flags as far beyond
the linear spring) takes up to 862,000 calls at rtol 1e-6 and 1,108,000 at 1e-7 (b = 1 N·s/m, t_end = 1 s).
The error estimate is the largest difference of the twist against a run at ten times tighter tolerance (same
method, chunks of other lengths), relative to the largest twist.  The chunks differ because each chunk restarts
the step-size sequence: where the motion is sensitive to a sharp feature (the four-bar's load M₃|u₃₁| turns over
at the dead positions, exactly where c(φ) → 0 uncouples motor and mechanism), two runs that restart at the same
times can step over the feature alike and agree with each other far better than with the true motion
(Drakunov–Tuleshova's assembly 2: 1.7e-4 between rtol 1e-6 and 1e-7 with equal chunks, 7.2e-2 from an rtol 1e-12
run).

Engines: "compiled" (default) runs DOP853 and Radau as scipy's algorithms ported into numba loops
(dop853.py, radau.py) on the compiled right-hand side (compiled.py), chunk by chunk exactly as
solve_ivp is called here, so the steps are scipy's; "scipy" runs solve_ivp on the Python model, the
reference path the tests compare with and the only one for RK45, BDF and LSODA.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from . import dop853, radau
from .compiled import jac_of
from .warm import ready

STIFF_RATIO = 1e3
CHUNKS = 16
MAX_EVALUATIONS = {"scipy": 300_000, "compiled": 1_500_000}    # right-hand-side calls of one run at most
TIME_BUDGET_S = 4.0


@dataclass
class ElasticRun:
    t: np.ndarray
    y: np.ndarray
    numerics: dict = field(default_factory=dict)
    complete: bool = True


def stiffness_ratio(model, y0: np.ndarray, slow_rate: float, probes: int = 24) -> tuple[float, float, float]:
    """max|Re λ| / slow rate over a turn of the mechanism; and the largest decay rate and |λ| themselves."""
    kinematic = getattr(model, "kinematic", False)
    compiled = getattr(model, "compiled", None)
    jacobian = jac_of(compiled) if compiled is not None else model.jac
    matrices = []
    for k in range(probes):
        angle = 2 * np.pi * k / probes          # the mechanism's angle: row 0, or ωt for a kinematic drive
        y = np.array(y0, float)
        if not kinematic:
            y[0] += angle
        matrices.append(jacobian(angle / model.drive.speed if kinematic else 0.0, y))
    eigen = np.linalg.eigvals(np.array(matrices))          # all probes in one call
    fastest, decay = float(np.max(np.abs(eigen))), float(max(np.max(-eigen.real), 0.0))
    return decay / max(slow_rate, 1e-12), decay, fastest


class WorkBound(Exception):
    """The right-hand side was called past the run's evaluation or time budget."""


def bounded(rhs, evaluations: int, deadline: float):
    """rhs that raises WorkBound after `evaluations` calls or, checked every 256 calls, past `deadline`."""
    calls = 0

    def counted(t, y):
        nonlocal calls
        calls += 1
        if calls > evaluations or (calls % 256 == 0 and time.perf_counter() > deadline):
            raise WorkBound
        return rhs(t, y)
    return counted


def work_bound_message(at: float, t_end: float) -> str:
    """What a run cut short by its evaluation or time budget says (the API marks such an answer partial)."""
    return f"stopped at t = {at:.4g} s of {t_end:.4g} s: the work bound was reached; the result is partial"


def joined(pieces_t: list, pieces_y: list, size: int, numerics: dict, complete: bool) -> ElasticRun:
    """The chunks' samples as one run (no samples: empty arrays of the state's size)."""
    t = np.concatenate(pieces_t) if pieces_t else np.zeros(0)
    y = np.concatenate(pieces_y, axis=1) if pieces_y else np.zeros((size, 0))
    return ElasticRun(t, y, numerics, complete)


RK_STAGES = {"RK45": 6, "DOP853": 12}    # RHS calls per step attempt in scipy's explicit Runge–Kutta
DENSE_EXTRA = {"RK45": 0, "DOP853": 3}   # extra calls per accepted step for DOP853's dense output


COMPILED = {"DOP853": dop853.chunk, "Radau": radau.chunk}
TOO_SMALL_STEP = "Required step size is less than spacing between numbers."      # scipy's words


def runs_compiled(model, method: str, engine: str) -> bool:
    """Whether integrate() runs the compiled loop: asked for, the model packed, the method ported."""
    return engine == "compiled" and getattr(model, "compiled", None) is not None and method in COMPILED


def work_bound(model, method: str, engine: str) -> int:
    """The right-hand-side calls a run of this engine may make (MAX_EVALUATIONS)."""
    return MAX_EVALUATIONS["compiled" if runs_compiled(model, method, engine) else "scipy"]


def integrate(model, y0: np.ndarray, t_end: float, rtol: float, method: str, samples: np.ndarray,
              deadline: float, atol: np.ndarray | float = 1e-12, max_evaluations: int | None = None,
              engine: str = "compiled", chunks: int = CHUNKS) -> ElasticRun:
    """The run in `chunks` equal chunks, compiled where the model and method allow, else solve_ivp; stops at
    the work bound (by default that of the engine that runs, work_bound) with the partial result and a message."""
    max_evaluations = max_evaluations or work_bound(model, method, engine)
    if runs_compiled(model, method, engine):
        return integrate_compiled(model.compiled, y0, t_end, rtol, method, samples, deadline, atol,
                                  max_evaluations, chunks)
    edges = np.linspace(0.0, t_end, chunks + 1)
    implicit = {"jac": model.jac} if method in ("Radau", "BDF", "LSODA") else {}
    pieces_t, pieces_y = [], []
    stats = {"steps": 0, "rejected": 0 if method in RK_STAGES else None, "nfev": 0, "njev": 0, "nlu": 0}
    y, complete, message = np.asarray(y0, float), True, ""
    for a, b in zip(edges[:-1], edges[1:]):
        rhs = bounded(model.rhs, max_evaluations - stats["nfev"], deadline)
        try:
            with np.errstate(all="ignore"):          # a diverging explicit run is caught below and reported
                solution = solve_ivp(rhs, (a, b), y, method=method, rtol=rtol, atol=atol, dense_output=True,
                                     **implicit)
        except WorkBound:                            # the bound is also kept inside a chunk (a very stiff spring)
            complete = False
            message = work_bound_message(a, t_end)
            break
        accepted = solution.t.size - 1
        stats["steps"] += accepted
        stats["nfev"] += solution.nfev
        stats["njev"] += solution.njev
        stats["nlu"] += solution.nlu
        if method in RK_STAGES:        # two calls start each chunk; every attempt costs one call per stage
            attempts = (solution.nfev - 2 - DENSE_EXTRA[method] * accepted) / RK_STAGES[method]
            stats["rejected"] += max(round(attempts) - accepted, 0)
        if not solution.success or not np.isfinite(solution.y[:, -1]).all():
            complete = False
            message = f"the solver stopped at t = {a:.4g} s: {solution.message if not solution.success else 'the state diverged'}"
            break
        inside = samples[(samples >= a) & ((samples < b) | (b == t_end))]
        pieces_t.append(inside)
        pieces_y.append(solution.sol(inside) if inside.size else np.zeros((len(y), 0)))
        y = solution.y[:, -1]
        if stats["nfev"] > max_evaluations or time.perf_counter() > deadline:
            if b < t_end:
                complete = False
                message = work_bound_message(b, t_end)
            break
    return joined(pieces_t, pieces_y, len(y0), stats | {"message": message}, complete)


def integrate_compiled(compiled, y0: np.ndarray, t_end: float, rtol: float, method: str, samples: np.ndarray,
                       deadline: float, atol: np.ndarray | float, max_evaluations: int,
                       chunks: int = CHUNKS) -> ElasticRun:
    """integrate() with each chunk one call of the compiled DOP853 or Radau: the same chunks, samples, counts
    and messages as the solve_ivp path; the evaluation bound is kept inside the compiled loop."""
    ready()
    edges = np.linspace(0.0, t_end, chunks + 1)
    atol = np.array(np.broadcast_to(np.asarray(atol, float), (compiled.size,)))    # writable, C: warm_up's types
    samples = np.array(samples, dtype=float)
    pieces_t, pieces_y = [], []
    stats = {"steps": 0, "rejected": 0, "nfev": 0, "njev": 0, "nlu": 0}
    y, complete, message = np.array(y0, dtype=float), True, ""
    for a, b in zip(edges[:-1], edges[1:]):
        inside = samples[(samples >= a) & ((samples < b) | (b == t_end))]
        out = np.empty((compiled.size, inside.size))
        answer = COMPILED[method](compiled.kind, compiled.p, compiled.tab, float(a), float(b), y, float(rtol), atol,
                                  inside, out, max_evaluations - stats["nfev"])
        status, y_end, accepted, rejected, nfev = answer[:5]
        stats["steps"] += accepted
        stats["rejected"] += rejected
        stats["nfev"] += nfev
        if method == "Radau":
            stats["njev"] += answer[5]
            stats["nlu"] += answer[6]
        if status == dop853.WORK_BOUND:
            complete = False
            message = work_bound_message(a, t_end)
            break
        if status != dop853.FINISHED or not np.isfinite(y_end).all():
            complete = False
            reason = TOO_SMALL_STEP if status == dop853.TOO_SMALL_STEP else "the state diverged"
            message = f"the solver stopped at t = {a:.4g} s: {reason}"
            break
        pieces_t.append(inside)
        pieces_y.append(out)
        y = y_end
        if stats["nfev"] > max_evaluations or time.perf_counter() > deadline:
            if b < t_end:
                complete = False
                message = work_bound_message(b, t_end)
            break
    return joined(pieces_t, pieces_y, len(y0), stats | {"message": message}, complete)
