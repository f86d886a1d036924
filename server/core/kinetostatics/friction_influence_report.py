"""The answer of the friction-influence explorer (Chaika–Vasylenko §3.4, steps 18–19): the sweep's curves over f,
the cycle at f = 0 and at f overlaid, the comparison of step 19, the onset of self-locking, the warnings and the
numerics, from a Study (friction_influence.py)."""
from __future__ import annotations

import time

import numpy as np

from ..mechanisms import Notice
from ..mechanisms.base import angle_ranges, ranges_text
from ..numerics import Numerics
from .friction_influence import FIGURES, PAIRS, WEAR_PARTS, Flywheel, Influence, Study

# The figures converge to first order in the step, irregularly: the reactions jump where the slider reverses (on a
# node: no friction and no load there), and the cylinder's wear counts the angles at which the piston covers a
# point.  Their error at 91–721 angles was at most 2× their change on the grid of half as many angles (three
# machines against 2881 angles), so the error estimate is ERROR_SAFETY times that change.
ERROR_SAFETY = 3.0


def explorer_answer(study: Study, f: float, flywheel: Flywheel, sweep: np.ndarray | None,
                    show_cycle: bool) -> tuple[dict, list[Notice]]:
    """The explorer's answer at f: the ``sweep`` (each figure over those f's) and, ``show_cycle``, the curves at
    f = 0 and f overlaid and the comparison of step 19; the onset of self-locking and the numerics.  The
    error estimate is the largest change on the grid of half as many angles at f = 0, at f and at the
    largest f of the sweep that runs (the discretisation error grows with the friction's jumps where the
    motion reverses)."""
    started = time.perf_counter()
    swept = [] if sweep is None else [study.index(value) for value in sweep]
    running = [k for k in swept if not study.locked[k].any()]
    checked = {0, study.index(f), max(running, key=lambda k: study.f_values[k], default=0)}
    shown = sorted({*swept, study.index(f), 0}, key=lambda k: study.f_values[k])
    results = {k: study.influence(k, flywheel, k in checked) for k in shown}
    answer: dict = {"f": f, "locking_onset": study.onset}
    if sweep is not None:
        answer["sweep"] = sweep_report([results[k] for k in swept])
    if show_cycle:
        frictionless, rough = results[0], results[study.index(f)]
        answer |= {"cycle": cycle_report(frictionless, rough), "comparison": comparison(frictionless, rough)}
    computed = [results[k] for k in shown]
    change = max(r.error for r in computed)
    error = max(ERROR_SAFETY * change, study.reached)
    answer["numerics"] = Numerics(
        method="the friction equilibrium at every f at once (Newton's method, safeguarded by the textbook's "
               "step); the equation of motion in energy form, A(φ) by the trapezoid rule; δ of the periodic "
               "solution and the flywheel for [δ] by Brent's method",
        code="friction_influence", rtol=study.machine.tolerance, steps=study.machine.phi.size - 1,
        runtime_ms=1e3 * (study.seconds + time.perf_counter() - started), error_estimate=error,
        message=f"the figures change by {change:.1e} (relative) on the grid of half as many angles; the error "
                f"estimate is {ERROR_SAFETY:g} times that (first-order convergence)",
        message_code="friction_influence_grid",
        message_context={"change": f"{change:.1e}", "safety": ERROR_SAFETY}).as_dict()
    top = float(study.f_values[shown[-1]])
    return answer, [*study.notices, *notices_of(computed, study.onset, top)]


def sweep_report(results: list[Influence]) -> dict:
    """The sweep's curves over f: each figure (NaN, sent as null, where that f locks or stalls), which f lock."""
    column = lambda key: np.array([np.nan if r.figures[key] is None else r.figures[key] for r in results])
    report = {"f": np.array([r.f for r in results]), "locked": [not r.runs for r in results],
              "peak": {name: column(name) for name in PAIRS},
              **{key: column(key) for key in ("balancing_peak", "balancing_mean", "efficiency", "delta", "flywheel")}}
    if any(r.figures["wear_pin"] is not None for r in results):
        report["wear"] = {part: column(f"wear_{part}") for part in WEAR_PARTS}
    return report


def reactions(result: Influence) -> dict:
    final = result.analysis.final
    return {"R12": np.linalg.norm(final.R12, axis=1), "R23": np.linalg.norm(final.R23, axis=1),
            "R34": np.abs(final.N), "R41": np.linalg.norm(result.analysis.R41, axis=1)}


def cycle_report(frictionless: Influence, rough: Influence) -> dict:
    """The cycle at f = 0 and at the chosen f, overlaid: M_ур(φ), ω₁(φ), |R| of each pair, and M_тр(φ)."""
    missing = np.full(frictionless.analysis.phi.size, np.nan)
    curve = lambda value: missing if value is None else value
    return {"phi": frictionless.analysis.phi,
            "balancing_moment": {"frictionless": frictionless.analysis.balancing_moment,
                                 "friction": rough.analysis.balancing_moment},
            "omega": {"frictionless": curve(frictionless.omega), "friction": curve(rough.omega)},
            "friction_moment": curve(rough.friction_moment),
            "reactions": {"frictionless": reactions(frictionless), "friction": reactions(rough)}}


def comparison(frictionless: Influence, rough: Influence) -> list[dict]:
    """Step 19: each figure without friction, with friction and its change in per cent (None where either is
    missing or the frictionless value is 0)."""
    rows = []
    for key in FIGURES:
        without, with_ = frictionless.figures[key], rough.figures[key]
        if key.startswith("wear_") and without is None and with_ is None:
            continue                                # no wear asked, or none computable
        change = 100 * (with_ - without) / without if None not in (without, with_) and without != 0 else None
        rows.append({"quantity": key, "frictionless": without, "friction": with_, "change": change})
    return rows


def notices_of(results: list[Influence], onset: float | None, f_top: float) -> list[Notice]:
    """Self-locking and stalls in words: the first f that locks, with its angles, and where self-locking begins
    (or that it begins beyond f_top, the largest f computed); the first f at which the machine stalls."""
    notices = []
    locked = [r for r in results if not r.runs]
    if locked:
        first = locked[0]
        ranges = angle_ranges(first.analysis.phi, first.locked)
        onset_text = "—" if onset is None else f"{onset:.4g}"
        notices.append(Notice(
            "friction_influence_self_locking",
            f"Self-locking from f = {first.f:.4g} on (by the line of force it begins at f = {onset_text}): at "
            f"f = {first.f:.4g} the rod's line of force lies within the guide's friction angle for φ in "
            f"{ranges_text(ranges)}, no driving moment moves the slider there, and the machine has no cycle; no "
            f"values from that f on.", {"f": first.f, "onset": onset_text, "ranges": ranges}))
    elif onset is not None:
        notices.append(Notice("friction_influence_locking_onset", f"Self-locking would begin at f = {onset:.4g}, "
                              f"above the largest f computed ({f_top:.4g}).",
                              {"onset": f"{onset:.4g}", "f_top": float(f_top)}))
    stalled = [r for r in results if r.runs and r.figures["delta"] is None]
    if stalled:
        notices.append(Notice(
            "friction_influence_stall", f"From f = {stalled[0].f:.4g} on the machine with the inertia it has cannot "
            f"keep its mean speed: the kinetic energy runs out within the cycle (no ω₁ and δ there; the flywheel "
            f"needed is given).", {"f": stalled[0].f}))
    return notices
