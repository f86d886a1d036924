"""What the reduction scenes' six-bar variants draw, link by link and load by load, checked against what it is
not computed from (content/scenes/reduced_inertia.json and resisting_moment.json, variants "shaping" and
"whitworth": the panels link_parts, link_slopes and load_parts draw /reduction's inertia.parts, inertia.slopes and
resisting.parts key by key).

tests/test_general_dynamics.py checks the totals J, dJ/dφ and M_c of every preset; here each part is checked
apart, on the answer the page gets for the scene's request (defaults and other slider values):
- the parts add up to J at every φ (rel 1e-12), the slopes to dJ/dφ, the load parts to the loads' moment
  without friction ("useful": the cutting force and the weights) and, with the pairs' dry and viscous friction,
  to M_c;
- link k's part of J is twice its own kinetic energy at unit crank speed, m_k|dz_S/dφ|² + J_Sk(dθ_k/dφ)², with
  dz_S/dφ and dθ_k/dφ from Richardson differences of the exact positions (rel 1e-7, as test_general_dynamics);
  "constant" is J₁ + J_rotor i² from the request; link k's slope is the difference of its part (rel 1e-7);
- each load's part is its own virtual work by power equality, M = −δA/δφ: the cutting force k P |δs|/δφ with δs
  the slider's displacement along the guide from differences of the joint's position, gravity g Σ m δy_S/δφ
  (rel 1e-7 of the largest part; where the slider turns, |δs/δφ| < 1e-3 m, the stroke factor is undecided and
  the angle skipped).
"""
from __future__ import annotations

import numpy as np
import pytest

from server.api.endpoints import compute_answer
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.masses import LinkMass, MassModel, SliderForce
from server.core.structure.reduction import reduced_inertia
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

from structure_checks import STENCIL
from test_general_dynamics import derivative, positions

VARIANTS = ("shaping", "whitworth")
# values of the variants' sliders besides their defaults (ids as in the scenes)
INERTIA_VALUES = ({}, {"J1": 0.9, "m3": 17.3, "m5": 7.5})
RESISTING_VALUES = ({}, {"P": 2200, "k": 0.4, "m3": 2.5})
ANGLES = 24          # answer's angles checked against differences, spread over the turn


def answer(scene_id: str, variant_id: str, values: dict) -> tuple[dict, dict]:
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    body = scene_request(scene, variant, values)
    return body, compute_answer("reduction", body).payload


def mass_model(masses: dict) -> MassModel:
    return MassModel(tuple(LinkMass(m["link"], m["mass"], tuple(m.get("centre", (0, 0))), m.get("inertia", 0.0))
                           for m in masses["links"]), masses.get("gravity", 9.81),
                     tuple(SliderForce(**f) for f in masses.get("forces", [])))


def checked_indices(phi: np.ndarray) -> np.ndarray:
    return np.linspace(0, phi.size - 1, ANGLES, endpoint=False).astype(int) + 3     # off the dead centre φ = 0


@pytest.mark.parametrize("values", INERTIA_VALUES)
@pytest.mark.parametrize("variant_id", VARIANTS)
def test_each_links_share_of_the_reduced_inertia(variant_id, values):
    body, data = answer("reduced-inertia", variant_id, values)
    inertia, phi = data["inertia"], np.asarray(data["phi"])
    parts = {key: np.asarray(value) for key, value in inertia["parts"].items()}
    slopes = {key: np.asarray(value) for key, value in inertia["slopes"].items()}
    J, dJ = np.asarray(inertia["J"]), np.asarray(inertia["dJ"])
    model = mass_model(body["masses"])
    assert sorted(parts) == sorted(slopes) == ["constant"] + [f"link {m.link}" for m in model.links]
    assert np.all(np.abs(sum(parts.values()) - J) <= 1e-12 * J)
    assert np.all(np.abs(sum(slopes.values()) - dJ) <= 1e-12 * np.abs(dJ).max())
    constant = body["inertias"]["J1"] + body["inertias"]["J_rotor"] * body["inertias"]["gear_ratio"] ** 2
    assert np.all(parts["constant"] == constant) and np.all(slopes["constant"] == 0)
    for key, value in {"J1": body["inertias"]["J1"], "m3": body["masses"]["links"][1]["mass"],
                       "m5": body["masses"]["links"][3]["mass"]}.items():
        assert value == values.get(key, value)              # the sliders' values reached the request
    linkage = GeneralMechanism(body["linkage"]).linkage
    for i in checked_indices(phi):
        _, centres, angles = positions(linkage, model, phi[i])
        v = derivative(centres)
        for row, m in enumerate(model.links):
            expected = m.mass * abs(v[row]) ** 2 + m.inertia * derivative(angles[m.link]) ** 2
            part = parts[f"link {m.link}"][i]
            assert abs(part - expected) <= 1e-7 * J[i], (m.link, phi[i], part, expected)
        # each slope against the difference of that link's part, the part evaluated on the stencil
        comp = compose(linkage, phi[i] + STENCIL)
        around = reduced_inertia(None, comp, model, constant)
        for key, values_around in around.parts.items():
            assert abs(slopes[key][i] - derivative(values_around)) <= 1e-7 * (abs(dJ).max() + J[i]), (key, phi[i])


@pytest.mark.parametrize("values", RESISTING_VALUES)
@pytest.mark.parametrize("variant_id", VARIANTS)
def test_each_loads_share_of_the_resisting_moment(variant_id, values):
    body, data = answer("resisting-moment", variant_id, values)
    resisting, phi = data["resisting"], np.asarray(data["phi"])
    parts = {key: np.asarray(value) for key, value in resisting["parts"].items()}
    total = np.asarray(resisting["total"])
    assert sorted(parts) == ["force E/ram", "gravity"]
    scale = max(np.abs(p).max() for p in parts.values())
    friction = np.asarray(resisting["dry"]) + np.asarray(resisting["viscous"])
    assert np.all(np.abs(sum(parts.values()) + friction - total) <= 1e-12 * scale)
    assert np.all(np.abs(sum(parts.values()) - np.asarray(resisting["useful"])) <= 1e-12 * scale)   # no crank load
    assert np.all(friction == 0)                            # f = 0 by default: power equality alone
    mean = np.trapezoid(total, phi) / (phi[-1] - phi[0])
    assert resisting["mean"] == pytest.approx(mean, rel=1e-4)
    force = body["masses"]["forces"][0]
    assert force["working"] == values.get("P", force["working"]) and force["k"] == values.get("k", force["k"])
    model = mass_model(body["masses"])
    linkage = GeneralMechanism(body["linkage"]).linkage
    checked = 0
    for i in checked_indices(phi):
        comp, centres, _ = positions(linkage, model, phi[i])
        gravity = model.gravity * sum(m.mass * derivative(centres[row]).imag for row, m in enumerate(model.links))
        assert abs(parts["gravity"][i] - gravity) <= 1e-7 * scale, (phi[i], parts["gravity"][i], gravity)
        joint, guide = force["joint"].split("/")
        w = (derivative(comp.joints[joint].z) * np.exp(-1j * comp.guides[guide].angle.th[0])).real
        if abs(w) < 1e-3:
            continue
        k = 1.0 if force["sense"] * w >= 0 else force["k"]
        expected = k * force["working"] * abs(w)
        assert abs(parts["force E/ram"][i] - expected) <= 1e-7 * scale, (phi[i], parts["force E/ram"][i], expected)
        checked += 1
    assert checked >= ANGLES - 2
