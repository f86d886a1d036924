"""The elastic four-bar's two assemblies (server/core/elastic/assemblies.py): I_n, I_n′, c_n, c_n′ of
Drakunov–Tuleshova (2), (9), (10) against the exact geometry of the paper's own position solution (4)–(6),
differentiated numerically here, and against the worked values of the notes (computed there by hand and
finite differences); the API answers both assemblies whatever the request's assembly and refuses the output
where there is no elastic four-bar."""
from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.api.endpoints import elastic_machine
from server.api.schemas_elastic import ElasticRequest
from server.core.elastic.assemblies import assembly_curves
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

LENGTHS = {"l0": 1.0, "l1": 0.3, "l2": 1.0, "l3": 0.8}
NOTES_COMPLIANCES = {"e1": 2e-4, "e2": 1e-7, "e3": 3e-4}
SIGNS = {"assembly_1": +1, "assembly_2": -1}


def request(compliances=NOTES_COMPLIANCES, assembly=1, outputs=("assemblies",), **more) -> dict:
    return {"model": "elastic_four_bar", "mechanism": "four_bar", "params": LENGTHS | {"assembly": assembly},
            "inertias": {"J1": 0.01, "J3": 0.05}, "J_motor": 0.02, "motor": {"kind": "linear", "M0": 2.0, "b": 0.05},
            "compliances": compliances, "outputs": list(outputs)} | more


def machine(compliances=NOTES_COMPLIANCES):
    return elastic_machine(ElasticRequest.model_validate(request(compliances)))


def angles(phi1, sign, l0=1.0, l1=0.3, l2=1.0, l3=0.8):
    """φ₂, φ₃ by the paper's explicit solution: (4), (5) with atan2, and the reconstructed (6)."""
    gamma = np.arctan2(-l1 * np.sin(phi1), l0 - l1 * np.cos(phi1))
    l_gamma = np.hypot(l0 - l1 * np.cos(phi1), l1 * np.sin(phi1))
    phi3 = sign * np.arccos((l2**2 - l_gamma**2 - l3**2) / (2 * l_gamma * l3)) + gamma
    phi2 = np.arctan2(l3 * np.sin(phi3) - l1 * np.sin(phi1), l0 + l3 * np.cos(phi3) - l1 * np.cos(phi1))
    return phi2, phi3


def derivative(f, x, h=1e-3):
    """Five-point central difference: truncation h⁴f⁽⁵⁾/30, rounding ~1e-16·|f|/h."""
    return (f(x - 2 * h) - 8 * f(x - h) + 8 * f(x + h) - f(x + 2 * h)) / (12 * h)


def geometry(sign, e1, e2, e3, I1=0.01, I3=0.05, l1=0.3, l3=0.8):
    """I_n(φ₁) = I₁ + I₃(dφ₃/dφ₁)² and c_n(φ₁) by (2), from the exact angles alone (no transfer functions)."""
    def phi3(x):
        return np.unwrap(angles(x, sign)[1]) if np.ndim(x) else angles(x, sign)[1]

    def inertia(x):
        return I1 + I3 * derivative(phi3, x) ** 2

    def stiffness(x):
        phi2, p3 = angles(x, sign)
        n = l1**2 * np.sin(x - phi2) ** 2
        return n / (e1 * n + e2 + e3 * l3**2 * np.sin(phi2 - p3) ** 2)
    return inertia, stiffness


@pytest.mark.parametrize("compliances", [NOTES_COMPLIANCES, {"e1": 2e-6, "e2": 1e-9, "e3": 3e-6}])
def test_both_assemblies_agree_with_finite_differences_of_the_exact_geometry(compliances):
    """At 720 angles of the turn (off the nodes of any table), each curve within 1e-7 of its largest value: the
    nested five-point differences are good to about 1e-9 of it (measured: I_n′ 1.4e-9, c_n′ 1e-11; truncation
    h⁴ = 1e-12 times the derivatives, rounding 1e-16/h² = 1e-10 for the difference of a difference), so 1e-7 leaves
    a factor 70 and still catches a wrong sign of u₃₁ or a missing term of Δ′ (both change the curves by O(1))."""
    phi = np.linspace(0.01, 2 * np.pi - 0.01, 720)
    curves = assembly_curves(machine(compliances), phi)
    for name, sign in SIGNS.items():
        inertia, stiffness = geometry(sign, **compliances)
        expected = {"inertia": inertia(phi), "inertia_slope": derivative(inertia, phi),
                    "stiffness": stiffness(phi), "stiffness_slope": derivative(stiffness, phi)}
        for curve, values in expected.items():
            scale = np.max(np.abs(values))
            assert np.max(np.abs(curves[name][curve] - values)) <= 1e-7 * scale, (name, curve)


def test_the_notes_worked_values_at_phi_0_7():
    """The notes' oracle table (l = 1, 0.3, 1, 0.8 m; I₁ = 0.01, I₃ = 0.05 kg·m²; e = 2e-4, 1e-7, 3e-4) printed to 6–7
    digits: rel 1e-5 (I_n′ of assembly 2 is printed to 6 digits, −0.0124528)."""
    curves = assembly_curves(machine(), np.array([0.7]))
    printed = {"assembly_1": (0.01002747, 0.00144285, 1.829090, 96.03744),
               "assembly_2": (0.02082885, -0.0124528, 630.3633, -633.2681)}
    for name, values in printed.items():
        got = [curves[name][c][0] for c in ("inertia", "inertia_slope", "stiffness", "stiffness_slope")]
        assert got == pytest.approx(values, rel=1e-5), name


def test_the_stiffness_vanishes_at_the_dead_positions_of_each_assembly():
    """c_n = 0 where crank and coupler are collinear (sin(φ₁ − φ₂) = 0, the notes §6): A, B, C on a line with
    AC = l₂ ± l₁, so the angle α± of AC from AD is fixed by the triangle ACD, and φ₁ = ±α₊ (stretched) or π ± α₋
    (folded); each assembly is dead at two of these four, the mirror images about AD of the other's."""
    l0, l1, l2, l3 = LENGTHS.values()
    alpha = {s: np.arccos((l0**2 + (l2 + s * l1) ** 2 - l3**2) / (2 * l0 * (l2 + s * l1))) for s in (+1, -1)}
    candidates = np.mod([alpha[1], -alpha[1], np.pi + alpha[-1], np.pi - alpha[-1]], 2 * np.pi)
    curves = assembly_curves(machine(), candidates)
    dead = {name: set(np.flatnonzero(np.abs(curves[name]["stiffness"]) < 1e-9)) for name in SIGNS}
    assert dead["assembly_1"] | dead["assembly_2"] == {0, 1, 2, 3}
    assert len(dead["assembly_1"]) == len(dead["assembly_2"]) == 2


def test_the_api_answers_both_assemblies_whichever_the_request_computes():
    client = TestClient(app)
    answers = [client.post("/api/v1/elastic", json=request(assembly=a)).json()["assemblies"] for a in (1, -1)]
    assert answers[0] == answers[1] and len(answers[0]["phi"]) == 361
    assert answers[0]["assembly_1"]["stiffness"] != answers[0]["assembly_2"]["stiffness"]


def test_the_output_is_refused_where_there_is_no_elastic_four_bar():
    client = TestClient(app)
    body = request() | {"model": "two_mass", "c": 100.0}
    body.pop("compliances")
    refused = client.post("/api/v1/elastic", json=body)
    assert refused.status_code == 422 and "assemblies: the two assemblies" in refused.text


def test_every_input_of_the_paper_is_a_control_of_the_scene():
    """Drakunov–Tuleshova's inputs: l₀…l₃, I_d, I₁, I₃, e₁–e₃, b_n, M_d, M₃ (sliders) and the assembly (toggle); each
    slider's range holds its default, and every combination of the lengths' extremes is a Grashof crank-rocker (the
    crank turns fully, so no slider position is refused)."""
    scene = scenes()["elastic-four-bar"]
    variant = scene.variants[0]
    params = {s.param: s for s in variant.sliders}
    assert set(params) == {"params.l0", "params.l1", "params.l2", "params.l3", "J_motor", "inertias.J1", "inertias.J3",
                           "compliances.e1", "compliances.e2", "compliances.e3", "b", "motor.M0", "load.force"}
    assert [(t.param, t.options) for t in variant.toggles] == [("params.assembly", [1, -1])]
    assert all(s.min <= s.default <= s.max for s in variant.sliders)
    ranges = [(params[f"params.l{k}"].min, params[f"params.l{k}"].max) for k in range(4)]
    for corner in np.array(np.meshgrid(*ranges)).reshape(4, -1).T:
        l0, l1, l2, l3 = corner
        assert l1 == min(corner) and l1 + max(corner) < sum(corner) - l1 - max(corner), corner
    body = scene_request(scene, variant, {"assembly": -1})
    assert body["params"]["assembly"] == -1 and "assemblies" in body["outputs"]
