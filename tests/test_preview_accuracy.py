"""A family's members are computed to the preview's accuracy (server/families/family.py, Preview accuracy;
endpoints.Preview): each drawn quantity within PREVIEW = PREVIEW_FRACTION × TOLERANCE of its span of the exact
answer, decisions (stall, self-locking, refusals) the same, and exact answers untouched by it.

For every scene's variants, at the defaults and at seeded random values of every slider, the endpoint's answer
with ``preview=family.PREVIEW`` is compared with the exact answer (no preview), leaf by leaf over the leaves the
page draws (its ``fields``, server/lessons/family_requests.preview_fields), checked leaves
as the family checks them (family.checked_leaves):

- an array: |preview − exact| ≤ PREVIEW × the exact array's span (max − min), elementwise, NaN (null: a locked
  or singular angle) in the same places, the same shape;
- a number: |preview − exact| ≤ PREVIEW × |exact|: one member does not know the number's span over a family
  (the members' own error relative to the value is what the preview declares for a number);
- the answer's shape otherwise the same: the same keys, the same notices' codes (a stall, self-locking), the
  same refusals.

Where the endpoint takes no preview (closed forms: kinematics, reduction, the flywheel, wear, the angular
acceleration), the preview is the exact answer, compared bit for bit. The tolerance is the preview's own
declaration (the shooting's Newton and the friction equilibrium converge quadratically: what they leave is far
below it).
"""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from server.families import family
from server.api.endpoints import PREVIEW_AWARE, compute_answer, compute_answers
from server.api.serialise import serialise
from server.core.dynamics import report
from server.core.mechanisms import GeometryError
from server.lessons.requests import scene_request, slider_values
from server.lessons.scenes import scenes
from server.lessons.family_requests import preview_fields

DRAWS = 2               # random slider settings per variant, beside its defaults
ROUND_OFF = 1e-12       # relative: what summing the same numbers in another order may move


@pytest.fixture(autouse=True)
def no_time_budget(monkeypatch):
    """Complete answers on any machine (a motion bounded by its budget would be cut at another point)."""
    monkeypatch.setattr(report, "TIME_BUDGET_S", 1e9)


def settings(scene):
    """(variant, values) to compare: each variant at its defaults and at DRAWS seeded random slider values."""
    rng = random.Random(f"preview-{scene.id}")
    for variant in scene.variants:
        yield variant, None
        for _ in range(DRAWS):
            yield variant, {slider.id: rng.choice(slider_values(slider)) for slider in variant.sliders}


def drawn(scene, variant, payload: dict) -> dict:
    fields = preview_fields(scene, variant)
    return payload if not fields else family.pruned(payload, family.field_trie(fields))


def outcome(endpoint: str, request: dict, preview):
    try:
        return compute_answer(endpoint, request, preview=preview)
    except GeometryError as error:
        return error


def codes(answer) -> list:
    return sorted(answer.payload.get("warnings", []))


def compare(exact: dict, preview: dict, where: str) -> int:
    """Every checked leaf of the drawn answers within PREVIEW (see the module); the number of leaves compared."""
    exact_leaves = dict(family.checked_leaves(family.as_tree(exact, sent=False)))
    preview_leaves = dict(family.checked_leaves(family.as_tree(preview, sent=False)))
    assert exact_leaves.keys() == preview_leaves.keys(), (where, exact_leaves.keys() ^ preview_leaves.keys())
    for path, leaf in exact_leaves.items():
        guess = np.asarray(preview_leaves[path], float)
        leaf = np.asarray(leaf, float)
        if leaf.ndim == 0:
            bound = family.PREVIEW * abs(float(leaf)) + ROUND_OFF
        else:
            assert leaf.shape == guess.shape, (where, family.quantity(path), leaf.shape, guess.shape)
            finite = leaf[np.isfinite(leaf)]
            span = float(finite.max() - finite.min()) if finite.size else 0.0
            bound = family.PREVIEW * span + ROUND_OFF * max(float(np.max(np.abs(finite), initial=0.0)), 1e-300)
            assert np.array_equal(np.isnan(leaf), np.isnan(guess)), (where, family.quantity(path), "nulls differ")
        off = np.abs(np.nan_to_num(guess - leaf))
        assert np.all(off <= bound), (where, family.quantity(path), float(np.max(off)), bound)
    return len(exact_leaves)


PREVIEW_SCENES = [scene.id for scene in scenes().values() if scene.endpoint in PREVIEW_AWARE]
OTHER_SCENES = [scene.id for scene in scenes().values() if scene.endpoint not in PREVIEW_AWARE]


@pytest.mark.parametrize("scene_id", PREVIEW_SCENES)
def test_preview_members_are_within_the_declared_fraction_of_the_tolerance_of_the_exact_answers(scene_id):
    scene = scenes()[scene_id]
    compared = 0
    for variant, values in settings(scene):
        request = scene_request(scene, variant, values)
        exact, preview = outcome(scene.endpoint, request, None), outcome(scene.endpoint, request, family.PREVIEW)
        where = (scene_id, variant.id, values)
        if isinstance(exact, GeometryError):            # refused alike, for the same field
            assert isinstance(preview, GeometryError) and preview.field == exact.field, where
            continue
        assert not isinstance(preview, GeometryError), (where, preview.reason)
        assert codes(preview) == codes(exact), where     # stall, self-locking, dead positions: the same words
        compared += compare(drawn(scene, variant, exact.payload), drawn(scene, variant, preview.payload), str(where))
    assert compared > 0


@pytest.mark.parametrize("scene_id", OTHER_SCENES)
def test_an_endpoint_without_a_preview_answers_a_member_exactly(scene_id):
    scene = scenes()[scene_id]
    for variant, values in list(settings(scene))[:4]:
        request = scene_request(scene, variant, values)
        exact, preview = outcome(scene.endpoint, request, None), outcome(scene.endpoint, request, family.PREVIEW)
        if isinstance(exact, GeometryError):
            assert isinstance(preview, GeometryError) and preview.field == exact.field
            continue
        assert same(exact.payload) == same(preview.payload), (scene_id, variant.id, values)


def same(payload: dict) -> bytes:
    """The answer's JSON without its run times (wall-clock)."""
    def strip(tree):
        if isinstance(tree, dict):
            return {key: strip(value) for key, value in tree.items() if key != "runtime_ms"}
        if isinstance(tree, list):
            return [strip(value) for value in tree]
        return tree
    return serialise(strip(payload), digits=None)


@pytest.mark.parametrize("scene_id", PREVIEW_SCENES)
def test_exact_answers_are_the_same_whether_computed_alone_or_in_a_batch_without_a_preview(scene_id):
    """An exact request never takes the preview's path: compute_answer and compute_answers without a preview
    give the same answer, bit for bit (run times aside), and it differs from the preview's wherever the
    preview's tolerance is looser (the switch is not a no-op)."""
    scene = scenes()[scene_id]
    differs = False
    for variant, values in ((variant, None) for variant in scene.variants):
        request = scene_request(scene, variant, values)
        alone = outcome(scene.endpoint, request, None)
        if isinstance(alone, GeometryError):
            continue
        batch = compute_answers(scene.endpoint, [request])[0]
        assert same(alone.payload) == same(batch.payload)
        differs |= same(alone.payload) != same(compute_answer(scene.endpoint, request, preview=family.PREVIEW).payload)
    assert differs


def test_the_declared_fraction_is_a_small_part_of_the_familys_tolerance():
    assert family.PREVIEW == pytest.approx(family.PREVIEW_FRACTION * family.TOLERANCE)
    assert family.PREVIEW_FRACTION <= 1 / 50 and math.isfinite(family.PREVIEW)

