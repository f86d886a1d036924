"""An RPR group whose block joint B lies on the lever's pivot D (Chaika–Vasylenko §3.1, the slotted link with
e = 0): there the slot through D may point any way, so the closure B = D + s e_j does not determine the lever's
angle θ_j = arg(B − D), which would be the argument of round-off noise.

- B ≡ D at every crank angle (B a point fixed on a link exactly over D): refused, 422 naming the group and the
  reason in words, in the reader's language;
- B passes over D at one angle (the inverted crank-slider whose crank pin runs through the lever's pivot,
  |OD| = l₁): that angle is singular (determinant 0, the lever's angle and analogs null), every other angle is
  as the closed form θ_j = arg(A − D) (to 1e-12: the same formula evaluated apart from the group module).
"""
from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.mechanisms.base import GeometryError
from server.core.mechanisms.general import compute_general
from server.core.structure.compose import compose
from server.core.structure.spec import parse
from server.lessons.scenes import interface_texts

COINCIDENT = {"frame": {"joints": {"O": [0, 0], "E": [0.3, 0]}},
              "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.1},
              "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "E"], "inner": "C", "lengths": [0.3, 0.25],
                          "points": {"Q": {"link": 3, "along": 0.25}}},       # Q on link 3 exactly over C
                         {"kind": "RPR", "links": [4, 5], "outer": ["Q", "C"], "offset": 0}]}
PASS = np.pi / 3                      # the crank pin A passes over the lever's pivot D here
THROUGH = {"frame": {"joints": {"O": [0, 0], "D": [0.1 * np.cos(PASS), 0.1 * np.sin(PASS)]}},
           "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.1},
           "groups": [{"kind": "RPR", "links": [2, 3], "outer": ["A", "D"], "offset": 0}]}


def test_block_on_the_pivot_everywhere_is_refused():
    with pytest.raises(GeometryError) as refused:
        compute_general(COINCIDENT, ["angles"], n=37)
    assert refused.value.field == "linkage.groups.1" and refused.value.code == "rpr_block_on_pivot"


def test_the_refusal_names_the_group_in_words():
    """422 with the field, the English reason, and the code and context the pages fill each language's
    template with (content/i18n err_rpr_block_on_pivot)."""
    with TestClient(app) as client:
        answer = client.post("/api/v1/kinematics",
                             json={"mechanism": "general", "linkage": COINCIDENT, "outputs": ["angles"], "n": 37})
    assert answer.status_code == 422, answer.text[:300]
    detail = answer.json()["detail"][0]
    assert detail["loc"][:4] == ["body", "linkage", "groups", "1"] and "lever's pivot C" in detail["msg"], detail
    context = detail["ctx"]
    assert context["code"] == "rpr_block_on_pivot", detail
    for lang, words in (("en", "lever's pivot C"), ("ru", "с осью кулисы C"), ("uk", "з віссю куліси C")):
        assert words in interface_texts(lang)["err_rpr_block_on_pivot"].format(**context)


def test_block_passing_over_the_pivot_is_singular_there_only():
    phi = np.linspace(0, 2 * np.pi, 13)              # PASS = phi[2]
    comp = compose(parse(THROUGH), phi)
    group, lever = comp.groups[0], comp.links[3][1]
    assert group.undetermined[2] and group.undetermined.sum() == 1 and group.determinant[2] == 0
    assert np.isnan(lever.th[2]) and np.isnan(lever.d1[2]) and np.isnan(lever.d2[2])
    a = 0.1 * np.exp(1j * phi)
    d = 0.1 * np.exp(1j * PASS)
    others = np.arange(13) != 2
    expected = np.angle(a - d)[others]
    assert np.max(np.abs(np.angle(np.exp(1j * (lever.th[others] - expected))))) <= 1e-12
    result = compute_general(THROUGH, ["angles_d1"], phi=phi)
    assert [n.code for n in result.warnings] == ["group_dead_position"]
    assert result.warnings[0].context["mu"] == 0.0 and result.warnings[0].context["phi"] == pytest.approx(60.0)
