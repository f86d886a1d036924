"""Course-project variants that can be handed out: those whose crank turns fully and whose output has one
working and one idle stroke.

A variant whose linkage cannot be assembled at some crank angle, or passes a dead position, has no course
project; nor has one whose output reverses more than twice a turn (a long crank can make the shaping machine's
ram reverse four times). The check is the course project's own (core/course_project/positions.py
``stroke_positions``: ``full_turn``, the linkage composed at 0.25° steps over the turn, then the output's
reversals; the output as the request names it, else the last group's slide or link), under 10 ms a variant,
so it is made where a variant is handed out and never needs storing:

- a student's number (SHA-256 of the assignment and the name, variants.py) that does not turn is replaced by
  the next number that does (number + 1, + 2, … modulo the count), the same on every server; at most
  MAX_SKIP numbers are tried;
- an assignment is made only if some of SAMPLE variant numbers spread over the range turn (SpecError naming
  the varied slider of the linkage otherwise); the share that turns is reported with the assignment.
"""
from __future__ import annotations

from functools import lru_cache

from ..core.course_project.positions import stroke_positions
from ..core.mechanisms import GeometryError
from ..core.mechanisms.general import GeneralMechanism
from ..lessons.requests import project_body, scene_variant
from .spec import SpecError

SAMPLE = 64             # variant numbers checked when an assignment is made
MAX_SKIP = 500          # numbers tried after a student's own before giving up


def checked(plan) -> bool:
    """Whether the plan's variants must turn fully (a course-project scene)."""
    return plan.scene.kind == "project"


@lru_cache(maxsize=8192)
def _stuck(scene_id: str, variant_id: str, documents: str, values: tuple) -> tuple[str, str] | None:
    body = project_body(scene_variant(scene_id, variant_id, documents), dict(values))
    try:
        stroke_positions(GeneralMechanism(body["linkage"]), None, int(body.get("positions", 12)), body.get("start"),
                         body.get("output"))
    except GeometryError as error:
        return error.field, error.reason
    return None


def stuck(plan, number: int) -> tuple[str, str] | None:
    """Why variant `number` cannot be handed out (the field of the request and the reason), or None: it turns
    and has its two strokes."""
    if not checked(plan):
        return None
    documents = "" if plan.spec.mechanism is None else plan.spec.mechanism.documents()
    return _stuck(plan.scene.id, plan.variant.id, documents, tuple(sorted(plan.values(number).items())))


def handed_out(plan, number: int) -> int:
    """The first number from `number` on (cyclically) whose variant turns; SpecError past MAX_SKIP."""
    if not checked(plan):
        return number
    for step in range(min(plan.count, MAX_SKIP)):
        candidate = (number + step) % plan.count
        if stuck(plan, candidate) is None:
            return candidate
    raise SpecError("sliders", f"none of the {min(plan.count, MAX_SKIP)} variants from number {number + 1} on "
                               f"turns fully with two strokes")


def sample(count: int, size: int = SAMPLE) -> list[int]:
    """Up to `size` variant numbers spread evenly over 0 … count − 1, both ends included."""
    if count <= size:
        return list(range(count))
    return sorted({round(k * (count - 1) / (size - 1)) for k in range(size)})


def turning_share(plan) -> tuple[int, int] | None:
    """(variants that turn, variants checked) over the sample; None where turning is not checked."""
    if not checked(plan):
        return None
    numbers = sample(plan.count)
    return sum(stuck(plan, n) is None for n in numbers), len(numbers)


def check_some_turn(plan) -> tuple[int, int] | None:
    """The turning share; SpecError (variants.py) when no sampled variant turns, naming the varied slider that
    sets the linkage (else every varied slider) with its range and the core's reason."""
    share = turning_share(plan)
    if share is None or share[0] > 0:
        return share
    field, reason = stuck(plan, 0) or ("linkage", "")
    varied = [s for s in plan.variant.sliders if s.id in plan.varied]
    shaping = [s for s in varied if s.param.startswith("linkage.")] or varied
    ranges = ", ".join(f"{s.id} {plan.varied[s.id][0]:g} … {plan.varied[s.id][-1]:g}" for s in shaping)
    where = f"sliders.{shaping[0].id}.vary" if shaping else "sliders"
    raise SpecError(where, f"no variant of {share[1]} checked turns fully with two strokes with these ranges "
                           f"({ranges or 'none varied'}): {reason} ({field}); narrow the ranges")
