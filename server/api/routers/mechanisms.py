"""GET /api/v1/mechanisms: what each mechanism takes and gives; GET /api/v1/mechanisms/general: the JSON of a
mechanism composed of structural groups, with an example request and the presets."""
from dataclasses import asdict

from fastapi import APIRouter

from ...core.mechanisms import MECHANISMS
from ...core.mechanisms.general import GENERAL_OUTPUTS
from ...core.structure import spec
from ...core.structure.presets import presets
from ..schemas import LinkageModel, MechanismInfo

router = APIRouter(tags=["mechanisms"])


@router.get("/mechanisms", response_model=list[MechanismInfo],
            summary="Mechanisms, their parameters (units, ranges, defaults), outputs and conventions")
def list_mechanisms() -> list[MechanismInfo]:
    return [MechanismInfo(name=m.name, title=m.title, conventions=m.conventions,
                          params=[asdict(p) for p in m.params], outputs=[asdict(o) for o in m.outputs])
            for m in MECHANISMS.values()]


@router.get("/mechanisms/general",
            summary="A general mechanism as data (frame, input crank or slider, class-II groups): its JSON, examples, the presets")
def general_mechanism() -> dict:
    example = presets()["shaping_machine"]["linkage"]
    return {"description": spec.__doc__, "schema": LinkageModel.model_json_schema(),
            "outputs": [asdict(o) for o in GENERAL_OUTPUTS],
            "example": {"mechanism": "general", "linkage": example, "n": 361,
                        "outputs": ["structure", "joints", "joints_d1", "angles_d1", "slides_d1", "special", "plan"],
                        "plan": {"phi": 0.5, "omega1": 10.0, "epsilon1": 0.0}},
            "example_slider_input": {"mechanism": "general", "linkage": presets()["slider_driven_crank"]["linkage"],
                                     "n": 141, "outputs": ["structure", "joints", "angles", "angles_d1", "special"]},
            "presets": list(presets().values())}
