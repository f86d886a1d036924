"""POST /api/v1/motor-characteristic and /flywheel-analysis: Lecture 10's induction motor (its static
characteristic, stability, successive approximations) and the flywheel's analysis problem (I given, δ found)."""
from fastapi import APIRouter

from .. import endpoints
from ..schemas import Language
from ..schemas_motor import FlywheelAnalysisRequest, MotorCharacteristicRequest
from ..serialise import Precision, respond
from .query import LANG, PRECISION

router = APIRouter(tags=["dynamics"])
INVALID = {422: {"description": "invalid input: the field and the reason"}}


@router.post("/motor-characteristic", responses=INVALID,
             summary="Induction motor: static characteristic M_д(ω) with its branches, the operating point's "
                     "stability, successive approximations beside the joint solution")
def motor_characteristic(request: MotorCharacteristicRequest, lang: Language = LANG,
                         precision: Precision = PRECISION):
    return respond(endpoints.motor_characteristic(request, lang), precision)


@router.post("/flywheel-analysis", responses=INVALID,
             summary="The flywheel's I given: the δ it gives (Merzalov and exact), ω(φ), beside the I that [δ] needs")
def flywheel_analysis(request: FlywheelAnalysisRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.flywheel_given(request, lang), precision)
