"""The scenes' "own mechanism" variant (content "address", server/lessons/scene_files.py `addressed`): with the
linkage and its dynamics of an address (a hand-built six-bar and the estimate of its masses), the request the
lesson model sends is one the endpoint's pydantic model accepts, every slider's path exists in it, relative
slider ranges are multiples of the address's own values, and the endpoint computes it; a variant without a
mechanism in the address is no assignment's."""
from __future__ import annotations

import pytest

from server.api.endpoints import compute
from server.api.schemas_dynamics import FlywheelRequest, MotionRequest, ReductionRequest
from server.api.schemas_forces import ForcesRequest
from server.api.schemas_project import CourseProjectRequest
from server.classroom.spec import AssignmentSpec
from server.classroom.variants import SpecError, plan
from server.core.structure.estimate import estimated_dynamics
from server.lessons.requests import address_variant, path_value, scene_request
from server.lessons.scenes import scenes
from test_dynamics_estimate import HAND_BUILT

REQUEST_MODELS = {"motion": MotionRequest, "flywheel": FlywheelRequest, "forces": ForcesRequest,
                  "reduction": ReductionRequest, "course-project": CourseProjectRequest}
OWN = [(scene.id, variant.id) for scene in scenes().values() for variant in scene.variants if variant.address]
DOCUMENTS = {"m": HAND_BUILT, "d": estimated_dynamics(HAND_BUILT)}


def test_the_dynamics_scenes_offer_the_own_mechanism():
    """Every scene that offers a six-bar preset offers the student's own mechanism too."""
    assert sorted(scene for scene, _ in OWN) == ["course-project", "equation-of-motion", "flywheel", "forces-friction",
                                                 "reduced-inertia", "resisting-moment"]


@pytest.mark.parametrize("scene_id, variant_id", OWN)
def test_own_variant_request_from_the_address_is_accepted_and_computes(scene_id, variant_id):
    scene = scenes()[scene_id]
    variant = address_variant(next(v for v in scene.variants if v.id == variant_id), DOCUMENTS)
    body = scene_request(scene, variant)
    assert body["linkage"] == HAND_BUILT
    assert body["masses"]["links"] == DOCUMENTS["d"]["masses"]["links"]       # the address's, the scene's merged over
    if "pair_radius" in variant.address["own"].get("masses", {}):                # the scene's own, merged over
        assert body["masses"]["pair_radius"] == 0.02
    REQUEST_MODELS[scene.endpoint].model_validate(body)
    for slider in variant.sliders:
        for path in (slider.param, *slider.also):
            path_value(body, path)                                          # KeyError: a path the request lacks
        if slider.relative:                                                  # M₀, b, ω_ср: multiples of the address's
            own = path_value(variant.request, slider.param)
            for key, factor in slider.relative.items():
                assert getattr(slider, key) == pytest.approx(factor * own, rel=1e-5), (slider.id, key)
    answer = compute(scene.endpoint, body)
    assert not any("cannot" in w for w in answer["warnings"]), answer["warnings"]
    if scene.endpoint == "motion":
        assert answer["numerics"]["message"] == "" and answer["delta"] > 0


def test_the_flywheel_of_an_address_starts_from_its_delta_and_mean_speed():
    """The own flywheel's [δ] and ω_ср sliders start at the address's d.flywheel values, not the scene's."""
    scene = scenes()["flywheel"]
    documents = {"m": HAND_BUILT, "d": DOCUMENTS["d"] | {"flywheel": DOCUMENTS["d"]["flywheel"] | {
        "omega_mean": 17.0, "delta": 0.02}}}
    variant = address_variant(next(v for v in scene.variants if v.address), documents)
    body = scene_request(scene, variant)
    assert (body["omega_mean"], body["delta"]) == (17.0, 0.02)
    speed = next(s for s in variant.sliders if s.param == "omega_mean")
    assert (speed.min, speed.default, speed.max) == pytest.approx((0.2 * 17, 17, 3 * 17))


def test_an_address_without_the_dynamics_is_refused_by_name():
    scene = scenes()["equation-of-motion"]
    with pytest.raises(KeyError, match="d.masses"):
        address_variant(next(v for v in scene.variants if v.address), {"m": HAND_BUILT})


def test_an_own_variant_is_no_assignment():
    spec = AssignmentSpec.model_validate({"scene": "equation-of-motion", "variant": "own", "questions": [{"id": "delta"}]})
    with pytest.raises(SpecError, match="own mechanism"):
        plan(spec, scenes())
