"""The side-by-side benchmarks' request builders (bench/scene_sweep.py, bench/http_floor.py): what they send is
what the issue asks to measure. No timing here."""
from __future__ import annotations

import importlib.util
import json
import math
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "bench"))


def load(name: str):
    spec = importlib.util.spec_from_file_location(name, REPO / "bench" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


scene_sweep, http_floor, trees = load("scene_sweep"), load("http_floor"), load("trees")
scenes, _, slider_values, _, _ = trees.lessons()


def test_a_sweep_covers_each_slider_from_end_to_end_in_equal_steps():
    """21 values the slider can express, both ends included, each within half a step of the equally spaced
    sequence on a linear slider, within 0.5 % (the 3 significant digits a log slider shows) of the geometric
    sequence on a log one."""
    checked_log = 0
    for scene in scenes().values():
        for variant in scene.variants:
            for slider in variant.sliders:
                positions = slider_values(slider)
                values = scene_sweep.sweep_values(slider, slider_values, 21)
                assert set(values) <= set(positions) and values == sorted(values)
                assert values[0] == positions[0] and values[-1] == positions[-1]
                assert len(values) == min(21, len(positions)), (scene.id, slider.id)
                if slider.log:
                    checked_log += 1
                    assert np.allclose(values, np.geomspace(values[0], values[-1], 21), rtol=5e-3, atol=0)
                else:
                    assert np.all(np.abs(np.array(values) - np.linspace(values[0], values[-1], len(values)))
                                  <= slider.step / 2 + 1e-9), (scene.id, slider.id)
    assert checked_log >= 5


def leaves(value, path=""):
    if isinstance(value, dict):
        for key, item in value.items():
            yield from leaves(item, f"{path}.{key}")
    elif isinstance(value, list):
        for k, item in enumerate(value):
            yield from leaves(item, f"{path}[{k}]")
    else:
        yield path, value


def test_the_nudged_default_request_misses_the_response_cache_and_changes_one_value_by_1e_8():
    """k = 0 is the page's default request; k ≠ 0 changes one length or slider value (every path a slider sets)
    by the factor 1 + k·1e-8, which the server's own cache key (the validated request, its floats exact) tells
    apart from every other k."""
    from server.api.routers.cache import request_models
    from server.runtime.response_cache import validated_body
    for scene in scenes().values():
        variant = http_floor.variant_of(scene)
        default = http_floor.nudged_request(scene, variant, 0)
        assert default == trees.lessons()[1](scene, variant)
        keys = set()
        for k in (-2, -1, 0, 1, 2, 500):
            body = http_floor.nudged_request(scene, variant, k)
            changed = [(p, a, b) for (p, a), (_, b) in zip(leaves(default), leaves(body)) if a != b]
            assert bool(changed) == (k != 0), (scene.id, changed)
            for _, before, after in changed:
                assert math.isclose(after / before, 1 + k * http_floor.NUDGE, rel_tol=1e-12)
            keys.add(validated_body(json.dumps(body).encode(), request_models()[scene.endpoint]))
        assert len(keys) == 6, scene.id
