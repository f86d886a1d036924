"""An assignment's correct answers, computed where they cannot starve the server, and assignments made at a
bounded rate (no expensive anonymous work).

Each variant's answers (question id → correct value, or the reason it has none) are computed in a heavy process
(server/runtime/heavy.py, the answers' lane) under a budget, and kept in the store per variant
(``variant_answers`` / ``put_variant_answers``), shared by every server: a variant is computed once for the whole
class, not once per student, per worker, per restart.

- Making an assignment checks up to CHECKED_VARIANTS variants spread over the range, within CREATE_BUDGET_S of
  one heavy process: a question without an answer for one of them refuses the assignment (SpecError naming it);
  the answers found are kept. Variants the budget did not reach are computed on their first use.
- A submission (or a page revealing a closed question) reads the variant's answers from the store, and computes
  them first, within VARIANT_BUDGET_S, only for a variant nobody has used yet. Answers the budget did not finish
  are not kept: Busy("answers_not_ready"), and the student may submit again (their attempt is not spent).
- The routes that need answers run in the worker's thread pool, which also serves the light computing routes: a
  thread waiting for the heavy process is a thread they lack. So at most ANSWER_COMPUTATIONS such waits run at
  once per worker (MDL_ANSWER_COMPUTATIONS, default 4 of the pool's 40 threads); past that the request is refused
  at once, Busy("answers_busy"), instead of queueing in a thread (answers already kept need no wait).
- One address makes at most ASSIGNMENTS_PER_HOUR assignments an hour (MDL_ASSIGNMENTS_PER_HOUR, counted in the
  store so that every worker and server sees the same count); past it, TooOften with the seconds until the oldest
  of its assignments in the window leaves it.

The refusals are the classroom's own (refusals.py); server/api/errors.py gives each its HTTP answer (503 or 429
with Retry-After).
"""
from __future__ import annotations

import os
import threading
import time
from contextlib import contextmanager

from . import turning
from .refusals import Busy, TooOften
from .variants import Plan, SpecError
from ..core.mechanisms import GeometryError
from ..runtime import heavy
from . import answers
from .answers import AnswerCutShort, Endpoints, answer_from, variant_answer
from .assignment_store import store

heavy.preload(__name__)     # answers_of_variants runs in the answers' lane

CHECKED_VARIANTS = 8            # variants whose answers are computed when the assignment is made
CREATE_BUDGET_S = 15.0          # of one heavy process, for those variants' answers
VARIANT_BUDGET_S = 15.0         # for one variant's answers on its first use
ASSIGNMENTS_PER_HOUR = int(os.environ.get("MDL_ASSIGNMENTS_PER_HOUR", "20"))     # per client address
ANSWER_COMPUTATIONS = int(os.environ.get("MDL_ANSWER_COMPUTATIONS", "4"))       # threads waiting for answers
WINDOW_S = 3600.0
RETRY_STEP_S = 60.0             # the wait a refusal names is found to this resolution
_computing = threading.BoundedSemaphore(ANSWER_COMPUTATIONS)


@contextmanager
def computing_place():
    """One of the worker's ANSWER_COMPUTATIONS places to wait for the heavy process; Busy at once when none is
    free."""
    if not _computing.acquire(blocking=False):
        raise Busy("answers_busy", "the server is computing other variants' answers; try again in a moment (no "
                                   "attempt was counted)", retry_after=2)
    try:
        yield
    finally:
        _computing.release()



def answers_of_variants(resolved: Plan, numbers: list[int], budget_s: float,
                        endpoints: Endpoints | None = None) -> dict[int, dict]:
    """In a heavy process: for each variant number in turn, every question's correct value (answers.variant_answer:
    a number, or an at_angle question's value at every angle offered) or the reason it has none, until
    `budget_s` has passed; a variant the budget cut, or whose answer an endpoint's own bound cut short
    (answers.AnswerCutShort), is left out whole (never half its answers, never a partial one). `endpoints`: what
    the worker computes with (answers.use_endpoints), handed to the heavy process with the work (None: this
    process's own)."""
    if endpoints is not None:
        answers.use_endpoints(endpoints)
    deadline = time.perf_counter() + budget_s
    found: dict[int, dict] = {}
    for number in numbers:
        values, correct = resolved.values(number), {}
        for pick in resolved.spec.questions:
            if time.perf_counter() > deadline:
                return found
            try:
                correct[pick.id] = variant_answer(resolved, values, pick.id)
            except (SpecError, GeometryError) as error:
                correct[pick.id] = getattr(error, "reason", None) or str(error)
            except AnswerCutShort:          # like the budget: the variant is left out, computed again later
                return found
        found[number] = correct
    return found


def checked_numbers(count: int) -> list[int]:
    """CHECKED_VARIANTS variant numbers spread evenly over 0 … count − 1, both ends included."""
    return sorted({round(k * (count - 1) / (CHECKED_VARIANTS - 1)) for k in range(CHECKED_VARIANTS)})


def check_new(resolved: Plan) -> dict[int, dict]:
    """The answers of the checked variants (those the budget reached; a course project's: the variants handed out
    in their place, turning.py); SpecError naming the first question that has no answer for one of them, or the
    slider ranges when no sampled course-project variant turns fully."""
    turning.check_some_turn(resolved)
    numbers = sorted({turning.handed_out(resolved, n) for n in checked_numbers(resolved.count)})
    with computing_place():
        found = heavy.run(answers_of_variants, resolved, numbers, CREATE_BUDGET_S, answers.compute_answer)
    for number, correct in sorted(found.items()):
        for question_id, value in correct.items():
            if isinstance(value, str):
                shown = ", ".join(f"{k} = {v}" for k, v in resolved.values(number).items())
                raise SpecError("sliders", f"question '{question_id}' has no answer for the variant {shown}: {value}")
    return found


def keep(assignment_id: str, found: dict[int, dict]) -> None:
    """Store the answers computed while the assignment was made, for every server to read."""
    for number, values in found.items():
        store().put_variant_answers(assignment_id, number, values)


def variant_answers(assignment_id: str, resolved: Plan, number: int) -> dict:
    """The variant's answers from the store, computed (heavy process, VARIANT_BUDGET_S) and kept on first use;
    Busy when the budget ran out first."""
    kept = store().variant_answers(assignment_id, number)
    if kept is not None and all(p.id in kept for p in resolved.spec.questions):
        return kept
    with computing_place():
        found = heavy.run(answers_of_variants, resolved, [number], VARIANT_BUDGET_S, answers.compute_answer)
    if number not in found:
        raise Busy("answers_not_ready", "the correct answers of this variant took longer than the time allowed; "
                                        "submit again in a moment (no attempt was counted)", retry_after=10)
    store().put_variant_answers(assignment_id, number, found[number])
    return found[number]


def correct_value(assignment_id: str, resolved: Plan, number: int, question_id: str,
                  angle: float | None = None) -> float:
    """The correct value of a question for variant `number` (an at_angle question: at the student's `angle`,
    answers.answer_from); SpecError when it has none."""
    value = variant_answers(assignment_id, resolved, number)[question_id]
    if isinstance(value, str):
        raise SpecError("questions", value)
    return answer_from(resolved, question_id, value, angle)


def limit_creation(client: str, now: float | None = None) -> None:
    """TooOften when `client` has made ASSIGNMENTS_PER_HOUR assignments in the last hour (retry_after: the seconds
    until the oldest of them leaves the window, to RETRY_STEP_S)."""
    now = time.time() if now is None else now
    recent = store().recent_assignments_by_client
    if recent(client, now - WINDOW_S) < ASSIGNMENTS_PER_HOUR:
        return
    low, high = 0, int(WINDOW_S // RETRY_STEP_S)          # the count in (now − WINDOW + s, now] falls as s grows
    while low < high:
        middle = (low + high) // 2
        if recent(client, now - WINDOW_S + middle * RETRY_STEP_S) < ASSIGNMENTS_PER_HOUR:
            high = middle
        else:
            low = middle + 1
    wait = max(int(low * RETRY_STEP_S), 1)
    raise TooOften("rate_limited", f"this address has made {ASSIGNMENTS_PER_HOUR} assignments in the last hour; the "
                                   f"next one is possible in {wait} s", retry_after=wait, limit=ASSIGNMENTS_PER_HOUR)
