"""A family's members computed at once (endpoints.compute_answers, family_batch) are the members computed one by
one (endpoints.compute_answer): for every computing endpoint a scene's sliders reach, at seeded random values of
every slider, with members that are refused (a value past the geometry's limit: GeometryError; a value the schema
refuses: ValidationError) among them, refused alike.

Tolerances: what a batch shares (a machine and its tables, made once for members with equal machines) is the
same computation on the same numbers, so those answers are compared exactly. The kinematics of several linkages
are one numpy evaluation over a (linkage, φ) grid, the parameters broadcast as (M, 1) arrays: every operation is
the same IEEE operation on the same operands, but numpy may take another inner loop of a transcendental function
(sin, arctan2, exp) for a broadcast operand than for a contiguous one, whose last bit can differ; such answers are
compared to 1e-12 of each array's largest magnitude (a few units in the last place, amplified by the closed forms'
cancellations, far below the 7 digits sent). `runtime_ms` (wall-clock) is left out of the comparison.
"""
from __future__ import annotations

import math
import random

import numpy as np
import orjson
import pytest
from pydantic import ValidationError

from server.api import family_batch
from server.families import family
from server.api.endpoints import compute_answer, compute_answers
from server.api.routers.family import WITHOUT_FAMILY
from server.core.dynamics import report
from server.core.kinematics import compute_kinematics, compute_kinematics_many
from server.core.mechanisms import GeometryError
from server.lessons.requests import path_value, scene_request
from server.lessons.scenes import scenes

BROADCAST = 1e-12           # relative to an array's largest magnitude: the kinematics over a (linkage, φ) grid
ELASTIC_VALUES = 2          # members per elastic slider (each a time integration): the first slider per variant
VALUES = 2                  # random members per other slider


@pytest.fixture(autouse=True)
def no_time_budget(monkeypatch):
    """Complete answers on any machine (a motion bounded by its budget would be cut at another point)."""
    monkeypatch.setattr(report, "TIME_BUDGET_S", 1e9)


def slider_cases():
    for scene in (s for s in scenes().values() if s.endpoint not in WITHOUT_FAMILY):
        for variant in scene.variants:
            sliders = variant.sliders[:1] if scene.endpoint == "elastic" else variant.sliders
            for slider in sliders:
                yield pytest.param(scene.id, variant.id, slider.id, id=f"{scene.id}-{variant.id}-{slider.id}")


def request_and_vary(scene_id: str, variant_id: str, slider_id: str):
    """The scene's request at the variant's defaults and how the slider's value enters it (as the page's family)."""
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    slider = next(s for s in variant.sliders if s.id == slider_id)
    request = scene_request(scene, variant)
    if scene.kind == "kinematics":
        vary = [{"path": f"params.{slider.param}", "factor": request["params"][slider.scale] if slider.scale else 1.0}]
    else:
        scale = path_value(request, slider.scale) if slider.scale else 1.0
        vary = [{"path": path, "factor": slider.to_si * scale} for path in (slider.param, *slider.also)]
    return scene, slider, request, [family.Vary(**v) for v in vary]


def member_values(slider, rng: random.Random, count: int) -> list[float]:
    """Random values in the slider's range (log-uniform on a log slider), one of its ends, and values past them (a
    member the geometry or the schema may refuse): shuffled, so that refusals sit between computed members."""
    low, high = slider.min, slider.max
    if slider.log:
        inside = [math.exp(rng.uniform(math.log(low), math.log(high))) for _ in range(count)]
    else:
        inside = [rng.uniform(low, high) for _ in range(count)]
    span = high - low
    values = inside + [rng.choice([low, high]), low - 0.7 * span, -abs(high) * 3 - 1.0]
    rng.shuffle(values)
    return values


def plain(answer) -> object:
    """An Answer's payload as JSON data (numpy arrays as lists, non-finite numbers as None)."""
    return orjson.loads(orjson.dumps(answer.payload, option=orjson.OPT_SERIALIZE_NUMPY, default=_default))


def _default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):          # one orjson does not take as it is (not contiguous)
        return value.tolist()
    raise TypeError(type(value))


def numbers(value) -> list[float]:
    if isinstance(value, list):
        return [x for item in value for x in numbers(item)]
    return [abs(value)] if isinstance(value, (int, float)) and not isinstance(value, bool) else []


def assert_same(batch, alone, rel: float, where: str = "", scale: float | None = None) -> None:
    """Equal trees; numbers within rel of their array's largest magnitude (0: exactly)."""
    if isinstance(alone, dict):
        assert isinstance(batch, dict) and batch.keys() == alone.keys(), where
        for key in alone:
            if key != "runtime_ms":
                assert_same(batch[key], alone[key], rel, f"{where}.{key}")
    elif isinstance(alone, list):
        assert isinstance(batch, list) and len(batch) == len(alone), where
        if scale is None:
            scale = max(numbers(alone), default=0.0)
        for k, (b, a) in enumerate(zip(batch, alone)):
            assert_same(b, a, rel, f"{where}[{k}]", scale)
    elif isinstance(alone, float) and isinstance(batch, float):
        bound = rel * (abs(alone) if scale is None else scale)
        assert abs(batch - alone) <= bound, f"{where}: {batch!r} vs {alone!r}"
    else:
        assert batch == alone, f"{where}: {batch!r} vs {alone!r}"


def outcome_alone(endpoint: str, body: dict, reads):
    try:
        return compute_answer(endpoint, body, "ru", reads)
    except (ValidationError, GeometryError) as error:
        return error


def assert_outcomes_agree(endpoint: str, batch: list, alone: list, rel: float) -> None:
    assert len(batch) == len(alone)
    for b, a in zip(batch, alone):
        assert type(b) is type(a)
        if isinstance(a, GeometryError):
            assert (b.field, b.code, b.reason, b.context) == (a.field, a.code, a.reason, a.context)
        elif isinstance(a, ValidationError):
            assert b.errors(include_url=False) == a.errors(include_url=False)
        else:
            assert b.partial == a.partial
            assert_same(plain(b), plain(a), rel if endpoint == "kinematics" else 0.0)


@pytest.mark.parametrize("scene_id, variant_id, slider_id", list(slider_cases()))
def test_a_batch_of_members_answers_as_each_member_alone(scene_id, variant_id, slider_id):
    """Random members of the slider (and refused ones), read in full and as the page's preview reads them
    (``reads``: the endpoint skips what no field reads, in both ways alike)."""
    scene, slider, request, vary = request_and_vary(scene_id, variant_id, slider_id)
    rng = random.Random(f"{scene_id}/{variant_id}/{slider_id}")
    count = ELASTIC_VALUES if scene.endpoint == "elastic" else VALUES
    bodies = [family.member_body(request, vary, value) for value in member_values(slider, rng, count)]
    for reads in READS.get(scene.endpoint, [None]):
        batch = compute_answers(scene.endpoint, bodies, "ru", reads)
        alone = [outcome_alone(scene.endpoint, body, reads) for body in bodies]
        assert_outcomes_agree(scene.endpoint, batch, alone, BROADCAST)
        assert any(not isinstance(a, Exception) for a in alone)        # the case computes something


# What the endpoints that skip unread work are asked to read (a page's preview), besides everything (None).
READS = {"elastic": [frozenset({"t", "omega", "twist", "modal", "warnings"})],
         "flywheel": [None, frozenset({"phi", "curves", "disk", "wittenbauer"})],
         "forces": [None, frozenset({"phi", "reactions", "magnitudes"})]}


def random_linkage(mechanism: str, rng: random.Random) -> dict:
    """Parameters that may or may not assemble: four-bars among them with change points (limiter on and off)."""
    if mechanism == "sine":
        return {"l1": rng.uniform(0.01, 1.0)}
    if mechanism == "slider_crank":
        l1 = rng.uniform(0.05, 0.2)
        return {"l1": l1, "l2": l1 * rng.uniform(0.8, 6.0), "e": l1 * rng.choice([0.0, rng.uniform(-0.5, 0.5)]),
                "a2": rng.uniform(0, 1)}
    if mechanism == "slotted_link":
        return {"l1": 0.1, "l0": 0.1 * rng.choice([1.0, rng.uniform(0.2, 3.0)])}
    l0, l1, l2 = 0.4, rng.uniform(0.05, 0.15), rng.uniform(0.2, 0.6)
    l3 = rng.choice([l0 + l1 - l2 + rng.uniform(0.0, 0.3), l2 + l0 - l1, l0 + l1 - l2])  # Q₀ = 0 or P₀ = 0: change points
    return {"l0": l0, "l1": l1, "l2": l2, "l3": abs(l3) + 1e-3 * (l3 == 0), "assembly": rng.choice([1, -1]),
            "limiter": rng.choice([0, 1]), "a2": rng.uniform(0, 1)}


OUTPUTS = {"sine": ["s", "u31", "du31", "u21", "du21", "chi21", "v_s2", "a_s2", "joints", "special", "info", "harmonics"],
           "slider_crank": ["s", "u31", "du31", "s2", "u21", "du21", "chi21", "v_s2", "a_s2", "joints", "special",
                            "info", "harmonics", "u31_approx", "du31_approx", "u21_approx", "du21_approx", "approx_error"],
           "slotted_link": ["s", "u31", "du31", "s2", "u21", "du21", "chi21", "v_s2", "a_s2", "joints", "special",
                            "info", "harmonics"],
           "four_bar": ["s", "u31", "du31", "s2", "u21", "du21", "chi21", "v_s2", "a_s2", "mu", "joints", "special",
                        "info", "harmonics"]}


@pytest.mark.parametrize("mechanism", list(OUTPUTS))
@pytest.mark.parametrize("seed", range(3))
def test_the_kinematics_of_linkages_at_once_are_each_linkage_alone(mechanism, seed):
    """compute_kinematics_many over random linkages of mixed branches (four-bars with change points, limiter on
    and off, both assemblies; slotted links with λ = 1 among them) and on a grid of 361 points or at given
    angles: each result that of compute_kinematics (to BROADCAST), refusals the same."""
    rng = random.Random(f"{mechanism}/{seed}")
    linkages = [random_linkage(mechanism, rng) for _ in range(8)]
    phi = None if seed else np.sort(np.array([rng.uniform(0, 2 * np.pi) for _ in range(50)] + [np.pi]))
    many = compute_kinematics_many(mechanism, linkages, OUTPUTS[mechanism], phi, 361)
    computed = 0
    for linkage, result in zip(linkages, many):
        try:
            alone = compute_kinematics(mechanism, linkage, OUTPUTS[mechanism], phi, 361)
        except GeometryError as error:
            assert isinstance(result, GeometryError) and (result.field, result.code) == (error.field, error.code)
            continue
        computed += 1
        assert result.warnings == alone.warnings and result.cycle == alone.cycle and result.params == alone.params
        as_json = lambda r: orjson.loads(orjson.dumps({"phi": r.phi, "outputs": r.outputs},
                                                      option=orjson.OPT_SERIALIZE_NUMPY, default=_default))
        assert_same(as_json(result), as_json(alone), BROADCAST)
    assert computed >= 2


def test_members_past_the_deadline_are_not_computed_and_the_known_ones_come_in_order():
    """family_batch: before the deadline every member is computed (in chunks) and kept; after it only the values'
    first members the memo holds come back, up to the first one it lacks."""
    family_batch.MEMO.store.clear()
    family_batch.MEMO.held = 0
    _, _, request, vary = request_and_vary("transfer-functions", "slider_crank", "lambda")
    counts: dict = {}
    members = family_batch.member_batch("kinematics", request, vary, "en", counts)
    values = [2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5, 7.0]      # more than one chunk
    first = members(values, math.inf)
    assert [m.value for m in first] == values and counts == {"computed": len(values)}
    later = members([2.0, 2.5, 2.25, 3.0], -math.inf)                    # 2.25 is not in the memo
    assert [m.value for m in later] == [2.0, 2.5] and counts["computed"] == len(values)
    for kept, again in zip(first, later):
        assert again.answer is kept.answer
    assert members([2.25], -math.inf) == []


def test_a_family_given_up_by_its_client_computes_no_further_chunk(monkeypatch):
    """family_batch: once heavy.stopped() says the client has given the family up (the page aborted it), no
    further chunk is computed; the members before it come back, in order, and stay in the memo."""
    from server.runtime import heavy
    family_batch.MEMO.store.clear()
    family_batch.MEMO.held = 0
    _, _, request, vary = request_and_vary("transfer-functions", "slider_crank", "lambda")
    counts: dict = {}
    members = family_batch.member_batch("kinematics", request, vary, "en", counts)
    asked = []
    monkeypatch.setattr(heavy, "stopped", lambda: asked.append(counts.get("computed", 0)) or len(asked) > 1)
    values = [2.0 + 0.25 * k for k in range(2 * family_batch.CHUNK_MEMBERS + 1)]      # three chunks
    first = members(values, math.inf)
    assert asked == [0, family_batch.CHUNK_MEMBERS]          # asked before each chunk; the second was not computed
    assert [m.value for m in first] == values[:family_batch.CHUNK_MEMBERS]
    assert counts == {"computed": family_batch.CHUNK_MEMBERS}
    monkeypatch.setattr(heavy, "stopped", lambda: False)
    assert [m.value for m in members(values, math.inf)] == values and counts["computed"] == len(values)
