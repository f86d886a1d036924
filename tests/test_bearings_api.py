"""POST /api/v1/bearings: the load is the pair's reaction of POST /forces for the same mechanism, each check
takes the load the source's formula needs (peak for (2.3), mean heat for (2.9)/(2.12)), refusals name the
field, and an undefined load comes back in words, never as NaN."""
from __future__ import annotations

import copy
import math
from functools import partial

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.api.endpoints import compute

assert_allclose = partial(np.testing.assert_allclose, equal_nan=False)   # a NaN on either side fails

RPM = 2 * math.pi / 60
ENGINE = {"params": {"l1": 0.045, "l2": 0.18, "a2": 0.38},
          "loads": {"m2": 1.8, "m3": 1.33, "J1": 0.09, "omega": 2400 * RPM,
                    "gas": {"kind": "indicator", "p_max": 3e6, "piston_diameter": 0.075}},
          "pairs": {"f14": 0.05, "f12": 0.05, "f23": 0.05, "f34": 0.1}, "n": 181}
ALL = ["load", "checks", "sizing", "heat", "clearance", "stribeck", "film", "errata"]
REACTION = {"O": "R41", "A": "R12", "B": "R23"}


def bearing(**fields) -> dict:
    body = copy.deepcopy(ENGINE)
    body["outputs"] = ALL
    body["bearing"] = {"kind": "fluid", "material": "babbit_b83"} | fields
    return body


@pytest.fixture(scope="module")
def client():
    return TestClient(app)


@pytest.mark.parametrize("pair", ["O", "A", "B"])
def test_the_load_is_the_pairs_reaction_of_the_forces_endpoint(pair):
    """Same request, same kinetostatics: |R| of /forces and the bearing's load agree to round-off (1e-12),
    peak and mean are its maximum and its trapezoidal mean over the closed cycle."""
    forces = compute("forces", {k: ENGINE[k] for k in ("params", "loads", "pairs", "n")})
    answer = compute("bearings", bearing(pair=pair))
    force = np.array(answer["load"]["force"])
    reference = np.array(forces["magnitudes"][REACTION[pair]])
    assert_allclose(force, reference, rtol=1e-12)
    assert answer["load"]["peak"] == pytest.approx(reference.max(), rel=1e-12)
    phi = np.array(forces["phi"])
    assert answer["load"]["mean"] == pytest.approx(np.trapezoid(reference, phi) / (2 * math.pi), rel=1e-12)


def test_each_check_takes_the_load_its_formula_needs():
    """(2.3) the peak |R| over l_z·d; (2.6) the largest ω_rel·d/2; (2.9) the cycle mean of |R|·ω_rel·d/2/(l_z·d)
    (recomputed here from the answer's own curves, 1e-12)."""
    d, ratio = 0.03, 1.2
    answer = compute("bearings", bearing(pair="A", diameter=d, length_ratio=ratio))
    load, checks = answer["load"], answer["checks"]
    force, omega, phi = (np.array(load[k]) for k in ("force", "omega", "phi"))
    area = ratio * d * d
    assert checks["pressure"] == pytest.approx(force.max() / area, rel=1e-12)
    assert checks["speed"] == pytest.approx(omega.max() * d / 2, rel=1e-12)
    assert checks["pv"] == pytest.approx(np.trapezoid(force * omega * d / 2 / area, phi) / (2 * math.pi), rel=1e-12)
    rows = {row["criterion"]: row for row in checks["rows"]}
    assert rows["pressure"]["value"] == pytest.approx(checks["pressure"] / 1e6, rel=1e-12)
    assert rows["pressure"]["allowable"] == 10 and rows["temperature"]["allowable"] == 115    # Б83, Table 2.2
    assert {row["verdict"] for row in checks["rows"]} <= {"pass", "fail", "unknown"}


def test_sizing_limits_are_where_the_checks_turn():
    """At the smallest diameter the binding check of (2.3) or (2.9) holds with equality, at the largest (2.6)
    does (1e-9: the answer's numbers at full precision, recomputed on the same grid)."""
    first = compute("bearings", bearing(pair="B", kind="dry", material="bronze_brof"))["sizing"]
    d = first["smallest_diameter"]
    at_smallest = compute("bearings", bearing(pair="B", kind="dry", material="bronze_brof", diameter=d))["checks"]
    assert max(at_smallest["pressure"] / 5e6, at_smallest["pv"] / 25e6) == pytest.approx(1, rel=1e-9)
    at_largest = compute("bearings", bearing(pair="B", kind="dry", material="bronze_brof",
                                             diameter=first["largest_diameter"]))["checks"]
    assert at_largest["speed"] == pytest.approx(1.1, rel=1e-9)
    assert first["feasible"] == (first["smallest_diameter"] <= first["largest_diameter"])


def test_recommendations_as_printed():
    """§2.1: main journal (0.35…0.65)·D_p, piston pin (0.15…0.30)·D_p for the engine's 75 mm bore;
    §2.2: dry clearance (0.0005…0.0020)·d; §2.3 semi-fluid (0.00025…0.0005)·d, rarer up to 0.001·d."""
    main = compute("bearings", bearing(pair="O"))["sizing"]
    assert (main["recommended_low"], main["recommended_high"]) == pytest.approx((0.02625, 0.04875), rel=1e-12)
    pin = compute("bearings", bearing(pair="B"))["sizing"]
    assert (pin["recommended_low"], pin["recommended_high"]) == pytest.approx((0.01125, 0.0225), rel=1e-12)
    dry = compute("bearings", bearing(kind="dry", material="textolite_dry", diameter=0.04, clearance_ratio=0.003))
    assert (dry["clearance"]["low"], dry["clearance"]["high"]) == pytest.approx((20e-6, 80e-6), rel=1e-12)
    assert dry["clearance"]["verdict"] == "fail"
    semi = compute("bearings", bearing(kind="semi_fluid", diameter=0.04, clearance_ratio=0.0008))["clearance"]
    assert semi["verdict"] == "pass" and semi["rarer_high"] == pytest.approx(40e-6, rel=1e-12)


def test_semi_fluid_friction_is_read_off_the_stribeck_curve():
    """A semi-fluid bearing heats with f of Fig. 2.4 at its operating λ = μ·ω̄/p̄_m (mean speed, mean load)."""
    d, ratio, mu = 0.02, 1.2, 0.02
    answer = compute("bearings", bearing(pair="B", kind="semi_fluid", material="bronze_brs30", diameter=d,
                                         length_ratio=ratio, viscosity=mu))
    load, stribeck = answer["load"], answer["stribeck"]
    lam = mu * load["mean_omega"] / (load["mean"] / (ratio * d * d))
    assert stribeck["lambda"] == pytest.approx(lam, rel=1e-12)
    assert answer["heat"]["friction"] == pytest.approx(stribeck["f_operating"], rel=1e-12)
    assert answer["heat"]["verdict"] == "unknown"                  # Table 2.2 has no [T] for БрС30


def test_fluid_power_switches_regime_with_reynolds():
    """A thin oil at a wide clearance makes the film turbulent over the cycle: (2.19) with k_τ > 1.835."""
    laminar = compute("bearings", bearing(pair="O"))["film"]
    turbulent = compute("bearings", bearing(pair="O", viscosity=1e-4, density=900, clearance_ratio=0.005,
                                            diameter=0.08))["film"]
    assert laminar["regime"] == "laminar" and laminar["equation"] == "(2.17)"
    assert turbulent["regime"] == "turbulent" and turbulent["equation"] == "(2.19)"
    assert turbulent["peak_reynolds"] >= 1000


def test_only_what_is_asked_is_answered():
    """Only the asked output, with the numerics of the kinetostatics that gave the load (its ε_R holds)."""
    answer = compute("bearings", bearing() | {"outputs": ["stribeck"]})
    assert set(answer) == {"stribeck", "numerics", "warnings"}
    assert answer["numerics"]["error_estimate"] <= 1e-9


@pytest.mark.parametrize("change, loc", [
    ({"bearing": {"kind": "fluid", "material": "bronze_brof"}}, ["body", "bearing", "material"]),
    ({"bearing": {"diameter": -0.01}}, ["body", "bearing", "diameter"]),
    ({"bearing": {"kind": "wet"}}, ["body", "bearing", "kind"]),
    ({"bearing": {"pair": "C"}}, ["body", "bearing", "pair"]),
    ({"outputs": ["everything"]}, ["body", "outputs", 0]),
    ({"bearing": {"kind": "dry", "material": "nylon"}}, ["body", "bearing", "friction"]),
    ({"loads": {"omega": 10.0}, "params": {"l1": 0.1, "l2": 0.4}}, ["body", "loads"]),
])
def test_bad_input_is_refused_naming_the_field(client, change, loc):
    body = bearing()
    for key, value in change.items():
        body[key] = value if key != "loads" else {**value, "gravity": False}
    response = client.post("/api/v1/bearings", json=body)
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"] == loc


def test_non_finite_input_is_refused(client):
    text = '{"bearing": {"diameter": NaN}}'
    response = client.post("/api/v1/bearings", content=text, headers={"content-type": "application/json"})
    assert response.status_code == 422 and response.json()["detail"][0]["loc"] == ["body", "bearing", "diameter"]


def test_a_self_locking_mechanism_is_said_in_words_never_nan(client):
    """Short rod and a rough guide: f₃₄·|tan ψ′| ≥ 1 over part of the cycle, so no reaction there."""
    body = {"params": {"l1": 0.1, "l2": 0.12}, "loads": {"m2": 1, "m3": 1, "force": 1000, "omega": 10},
            "pairs": {"f34": 0.9}, "outputs": ALL, "bearing": {"kind": "dry"}}
    response = client.post("/api/v1/bearings?lang=ru", json=body)
    assert response.status_code == 200
    assert "NaN" not in response.text and "Infinity" not in response.text
    answer = response.json()
    assert "checks" not in answer
    assert any("подшипник" in text for text in answer["warnings"])


def test_the_errata_are_rows_of_the_common_format_with_the_printed_values_by_hand():
    """The misprints of §2 in the rows every scene's errata panel shows (server/core/errata.py): (2.4) as
    printed, l_z = √(F_e·l_z/[p_m]), solves to F_e/[p_m] = l_z²/l̄_z of the corrected l_z (an area); (2.16)
    without the arm gives the film power over r; (2.13) is there for a dry bearing.  Words in three languages.
    Only rounding differs: rel 1e-12."""
    import json
    from pathlib import Path
    from server.core.errata import row
    d, ratio = 0.03, 1.2
    answer = compute("bearings", {**bearing(), "bearing": {"kind": "dry", "diameter": d, "length_ratio": ratio}})
    rows = {r["key"]: r for r in answer["errata"]}
    assert list(rows) == ["bearing_size", "bearing_shaft_heat", "bearing_film_arm"]
    assert all(set(r) == set(row("k", "s", "e", 0, 0, "u")) and r["source"] == "chaika_vasylenko" for r in rows.values())
    size, film = rows["bearing_size"], rows["bearing_film_arm"]
    assert size["printed_value"] == pytest.approx(size["corrected_value"] ** 2 / ratio, rel=1e-12)
    assert (size["printed_unit"], size["unit"]) == ("m2_area", "m")
    assert film["printed_value"] * d / 2 == pytest.approx(film["corrected_value"], rel=1e-12)
    texts = {lang: json.loads((Path(__file__).parents[1] / "content" / "i18n" / f"{lang}.json").read_text("utf-8"))
             for lang in ("ru", "uk", "en")}
    for lang, t in texts.items():
        for r in rows.values():
            assert {f"erratum_why_{r['key']}", f"erratum_printed_{r['key']}", f"erratum_corrected_{r['key']}",
                    f"erratum_unit_{r['unit']}", f"erratum_unit_{r['printed_unit']}", f"source_{r['source']}"} <= set(t)
