"""Serialisation of the answers (server/api/serialise.py): no NaN or infinity ever leaves, full precision is
exact, plot precision is the decimal rounding to 7 significant digits; every scene's answer at both
precisions against the standard library's json as the reference."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import create_app
from server.api.endpoints import ENDPOINTS, compute, compute_answer
from server.api.serialise import PLOT_DIGITS, serialise
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

API = "/api/v1"


def strict(raw: bytes):
    """Parse as the browser's JSON.parse: NaN, Infinity and -Infinity are errors."""
    def reject(constant):
        raise ValueError(f"non-standard JSON constant {constant}")
    return json.loads(raw, parse_constant=reject)


def reference(value):
    """The payload as the standard library sees it, non-finite numbers as None: the expected parse."""
    if isinstance(value, dict):
        return {k: reference(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [reference(v) for v in value]
    if isinstance(value, np.ndarray):
        return reference(value.tolist())
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    return value


NON_FINITE = [np.nan, np.inf, -np.inf]


@pytest.mark.parametrize("digits", [PLOT_DIGITS, None])
def test_no_non_finite_number_leaves_in_any_form(digits):
    grid = np.array([[1.5, np.nan], [np.inf, -2.0]])
    payload = {
        "array": np.array([0.1, *NON_FINITE, 2.0]), "float32": np.array([1.0, *NON_FINITE], np.float32),
        "float16": np.array([np.nan, 1.0], np.float16), "grid": grid, "column": grid[:, 1], "strided": grid.ravel()[::2],
        "scalars": [float("nan"), np.float64(np.inf), np.float32(-np.inf), -math.inf], "objects": np.array([np.nan, None]),
        "nested": {"deep": [{"x": np.array([np.nan])}, (np.inf, 1)]}, "integers": np.arange(3)[::2],
    }
    raw = serialise(payload, digits)
    assert b"NaN" not in raw and b"Infinity" not in raw
    parsed = strict(raw)
    assert parsed["array"] == [0.1, None, None, None, 2.0]
    assert parsed["float32"] == [1.0, None, None, None] and parsed["float16"] == [None, 1.0]
    assert parsed["grid"] == [[1.5, None], [None, -2.0]] and parsed["column"] == [None, -2.0]
    assert parsed["strided"] == [1.5, None] and parsed["scalars"] == [None] * 4 and parsed["objects"] == [None, None]
    assert parsed["nested"] == {"deep": [{"x": [None]}, [None, 1]]} and parsed["integers"] == [0, 2]


def test_full_precision_reads_back_every_double_exactly():
    rng = np.random.default_rng(13)
    x = rng.standard_normal(2000) * 10.0 ** rng.integers(-300, 300, 2000)
    payload = {"x": x, "tiny": np.array([5e-324, -2.2250738585072014e-308]), "scalar": float(x[0])}
    parsed = strict(serialise(payload, None))
    assert parsed == reference(payload)


def test_plot_precision_is_the_decimal_rounding_to_seven_significant_digits():
    """Against Python's decimal formatting ('.7g', correctly rounded): equal wherever the scale 10ᵏ is an
    exact double (|k| ≤ 22, here 10⁻¹⁵ ≤ |x| < 10²⁸), within one unit in the last place elsewhere."""
    rng = np.random.default_rng(7)
    exponents = rng.integers(-300, 300, 4000)
    x = rng.uniform(-10, 10, 4000) * 10.0 ** exponents
    sent = np.array(strict(serialise({"x": x}))["x"])
    decimal = np.array([float(f"{v:.7g}") for v in x])
    exact_scale = np.abs(6 - np.floor(np.log10(np.abs(x)))) <= 22
    assert np.array_equal(sent[exact_scale], decimal[exact_scale]) and exact_scale.sum() > 100
    assert np.all(np.abs(sent - decimal) <= np.spacing(np.abs(decimal)))
    assert np.all(np.abs(sent - x) <= (5e-7 + 1e-15) * np.abs(x))
    values = strict(serialise({"v": [0.1 * 3, 2 / 3, 123456789.0, -0.0, 0.0, 5e-324, 1e-310]}))["v"]
    assert values[:5] == [0.3, 0.6666667, 123456800.0, -0.0, 0.0]
    assert values[5:] == [5e-324, 1e-310]              # subnormals (10ᵏ overflows) go out as they are


def test_a_single_number_is_sent_whole_and_a_curve_rounded():
    """A field holding one number (the 4π cycle a page divides by) keeps every digit; a list or array of them
    (a curve) is rounded to plot precision."""
    cycle = 4 * np.pi
    parsed = strict(serialise({"cycle": cycle, "numerics": {"error_estimate": 1 / 3}, "phi": [cycle], "u": np.array([cycle])}))
    assert parsed["cycle"] == cycle and parsed["numerics"]["error_estimate"] == 1 / 3
    assert parsed["phi"] == parsed["u"] == [12.56637]


def test_integers_strings_and_booleans_are_left_as_they_are():
    payload = {"n": 12345678901, "flag": True, "name": "φ = 0.123456789", "counts": np.array([1, 2], np.int64)}
    assert strict(serialise(payload)) == {"n": 12345678901, "flag": True, "name": "φ = 0.123456789", "counts": [1, 2]}


def test_an_integer_beyond_64_bits_echoed_in_a_422_is_sent_as_a_number():
    client = TestClient(create_app())
    response = client.post(f"{API}/kinematics", json={"mechanism": "sine", "n": 10**30, "outputs": ["s"]})
    assert response.status_code == 422
    assert strict(response.content)["detail"][0]["input"] == 1e30


@pytest.fixture(scope="module")
def client() -> TestClient:
    return TestClient(create_app())


@pytest.mark.parametrize("scene_id", [s.id for s in scenes().values() if s.endpoint != "elastic"])
def test_every_scene_answers_at_both_precisions_as_the_standard_library_reads_them(client, scene_id):
    """The full answer is the body function's payload as the standard library reads it (exactly, run times
    aside), the plot answer is it rounded to 7 digits, leaf by leaf; both are strict JSON."""
    scene = scenes()[scene_id]
    body = scene_request(scene, scene.variants[0])
    url = f"{API}/{scene.endpoint}"
    full = client.post(url, params={"lang": "en", "precision": "full"}, json=body)
    plot = client.post(url, params={"lang": "en"}, json=body)
    assert full.status_code == plot.status_code == 200
    full_data, plot_data = strict(full.content), strict(plot.content)
    assert len(plot.content) < len(full.content)

    def close(a, b, relative, path=""):
        if isinstance(a, dict):
            assert a.keys() == b.keys(), path
            for key in a:
                if key != "runtime_ms":
                    close(a[key], b[key], relative, f"{path}.{key}")
        elif isinstance(a, list):
            assert len(a) == len(b), path
            for i, (x, y) in enumerate(zip(a, b)):
                close(x, y, relative, f"{path}[{i}]")
        elif isinstance(a, float) and isinstance(b, float):
            assert abs(a - b) <= relative * abs(b), path
        else:
            assert a == b, path
    close(full_data, reference(compute_answer(scene.endpoint, body, "en").payload), 0.0)
    close(plot_data, full_data, 5e-7 + 1e-15)
    assert compute(scene.endpoint, body, "en").keys() == full_data.keys()


def test_every_computing_endpoint_documents_its_precision_parameter(client):
    schema = client.get(f"{API}/openapi.json").json()
    for name in ENDPOINTS:
        parameters = {p["name"]: p for p in schema["paths"][f"{API}/{name}"]["post"]["parameters"]}
        precision = parameters["precision"]
        assert precision["schema"]["enum"] == ["plot", "full"] and "7 significant digits" in precision["description"]
    assert "X-Partial" in schema["info"]["description"]


def _without_run_times(value):
    if isinstance(value, dict):
        return {key: _without_run_times(item) for key, item in value.items() if key != "runtime_ms"}
    if isinstance(value, list):
        return [_without_run_times(item) for item in value]
    return value


def test_a_heavy_answer_is_serialised_and_compressed_in_its_process_as_the_worker_would_send_it(client):
    """An elastic machine's answer is computed, serialised and gzip-compressed in the heavy process
    (serialise.respond_apart): compressed for a client that takes gzip, plain for one that does not, and in both
    the endpoint's payload at the precision asked for (run times aside)."""
    scene = scenes()["elastic-four-bar"]
    body = scene_request(scene, scene.variants[0])
    url = f"{API}/elastic"
    packed = client.post(url, params={"lang": "en"}, json=body, headers={"Accept-Encoding": "gzip"})
    plain = client.post(url, params={"lang": "en", "precision": "full"}, json=body,
                        headers={"Accept-Encoding": "identity"})
    assert packed.status_code == plain.status_code == 200
    assert packed.headers["content-encoding"] == "gzip" and "content-encoding" not in plain.headers
    payload = compute_answer("elastic", body, "en").payload
    for answer, digits in ((packed, PLOT_DIGITS), (plain, None)):
        assert _without_run_times(strict(answer.content)) == _without_run_times(strict(serialise(payload, digits)))
