"""One declared Numerics: every `numerics` object in every scene's default answer (each variant, every
output the scene shows) and in the issue's friction and elastic bodies is an instance of the one response
model (server/api/schemas.py NumericsModel, extra keys forbidden), built from server/core/numerics.py."""
from __future__ import annotations

import pytest

from server.api.endpoints import compute
from server.api.schemas import NumericsModel
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

# the scenes whose answer is computed by a method with a tolerance (closed forms alone carry no numerics:
# transfer functions, reduced inertia's J(φ), wear's closed forms)
COMPUTED = {"resisting-moment", "equation-of-motion", "flywheel", "elastic-transmission", "elastic-linkage",
            "elastic-four-bar", "forces-friction", "angular-acceleration"}
# elastic-linkage/bearings asks for the modal analysis and the bearing iteration alone, elastic-linkage/dimensions
# for the compliances from dimensions (Eremyants (1.16)/(1.37)) and the modal curves: closed forms, no integration
CASES = [(scene.endpoint, scene.id, variant.id, scene_request(scene, variant, None))
         for scene in scenes().values() if scene.id in COMPUTED for variant in scene.variants
         if (scene.id, variant.id) not in {("elastic-linkage", "bearings"), ("elastic-linkage", "dimensions")}]
EXTRA = [("forces", {"params": {"l1": 0.1, "l2": 0.13}, "loads": {"force": 1000, "gravity": False, "omega": 10},
                     "pairs": {"f34": 0.8}, "n": 73}),
         ("elastic", {"model": "two_mass", "mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3},
                      "inertias": {"J1": 0.5}, "motor": {"kind": "constant", "M0": 0}, "J_motor": 0.25, "c": 10000,
                      "twist0": 0.01, "t_end": 0.2, "outputs": ["histories"]})]


def numerics_objects(tree, path=""):
    """(path, object) of every value under a key `numerics`."""
    if isinstance(tree, dict):
        for key, value in tree.items():
            if key == "numerics" and isinstance(value, dict):
                yield f"{path}.{key}", value
            else:
                yield from numerics_objects(value, f"{path}.{key}")
    elif isinstance(tree, list):
        for index, value in enumerate(tree):
            yield from numerics_objects(value, f"{path}[{index}]")


@pytest.mark.parametrize("endpoint, scene, variant, body", CASES, ids=[f"{c[1]}-{c[2]}" for c in CASES])
def test_every_numerics_of_a_scene_answer_is_the_declared_model(endpoint, scene, variant, body):
    found = list(numerics_objects(compute(endpoint, body)))
    assert found, f"{scene}/{variant}: no numerics in the answer"
    for path, numerics in found:
        NumericsModel.model_validate(numerics)          # raises, naming the field, on an undeclared key


@pytest.mark.parametrize("endpoint, body", EXTRA, ids=[e[0] for e in EXTRA])
def test_the_friction_and_elastic_answers_carry_the_declared_numerics(endpoint, body):
    found = dict(numerics_objects(compute(endpoint, body)))
    assert ".numerics" in found                          # each carries its own, at the top
    for numerics in found.values():
        model = NumericsModel.model_validate(numerics)
        assert model.method and model.runtime_ms is not None and model.error_estimate is not None
