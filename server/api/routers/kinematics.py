"""POST /api/v1/kinematics: position functions and transfer functions over crank angles."""
from fastapi import APIRouter

from .. import endpoints
from ..schemas import KinematicsRequest, KinematicsResponse, Language
from ..serialise import Precision, respond
from .query import LANG, PRECISION

router = APIRouter(tags=["kinematics"])


@router.post("/kinematics", response_model=KinematicsResponse,
             summary="Position functions, u₃₁, u′₃₁, u₂₁, u′₂₁, joints and special positions",
             responses={422: {"description": "invalid input: the field and the reason"}})
def kinematics(request: KinematicsRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.kinematics(request, lang), precision)
