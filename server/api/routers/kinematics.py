"""POST /api/v1/kinematics: position functions and transfer functions over crank angles."""
import numpy as np
from fastapi import APIRouter, Query
from fastapi.responses import JSONResponse

from ...core.kinematics import compute_kinematics
from ...core.mechanisms import MECHANISMS, Notice
from ..json_safe import count_undefined, finite_or_none
from ..messages import translate
from ..schemas import KinematicsRequest, KinematicsResponse, Language

router = APIRouter(tags=["kinematics"])


@router.post("/kinematics", response_model=KinematicsResponse,
             summary="Position functions, u₃₁, u′₃₁, u₂₁, u′₂₁, joints and special positions",
             responses={422: {"description": "invalid input: the field and the reason"}})
def kinematics(request: KinematicsRequest,
               lang: Language = Query("en", description="language of the warnings: ru, uk or en")) -> KinematicsResponse:
    result = compute_kinematics(request.mechanism, request.params, request.outputs,
                                phi=None if request.phi is None else np.asarray(request.phi, float), n=request.n)
    notices = list(result.warnings)
    for name, value in result.outputs.items():
        bad = count_undefined(value)
        if bad:
            notices.append(Notice("undefined_points", f"{name}: undefined at {bad} point(s), sent as null "
                                  "(singular position).", {"output": name, "count": bad}))
    units = {o.name: o.unit for o in MECHANISMS[request.mechanism].outputs}
    body = KinematicsResponse.model_construct(
        mechanism=result.mechanism, params=result.params, cycle=result.cycle,
        phi=finite_or_none(result.phi), outputs=finite_or_none(result.outputs),
        units={name: units.get(name, "") for name in result.outputs},
        warnings=[translate(notice, lang) for notice in notices])
    # Built from checked numbers: skip re-validating thousands of floats, refuse NaN on the way out.
    return JSONResponse(body.__dict__)
