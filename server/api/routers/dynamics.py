"""POST /api/v1/reduction, /motion, /flywheel, /work-precision/motion: the one-mass dynamic model of the machine;
/dynamics-estimate: a first mass model for a mechanism that has none."""
from fastapi import APIRouter, Request

from .. import endpoints
from ...runtime import heavy
from ..schemas import Language
from ..schemas_dynamics import (EstimateRequest, EstimateResponse, FlywheelRequest, FlywheelResponse, MotionRequest,
                                MotionResponse, ReductionRequest, ReductionResponse)
from ..serialise import Precision, respond, respond_apart
from .query import LANG, PRECISION

heavy.preload(endpoints.__name__)

router = APIRouter(tags=["dynamics"])
INVALID = {422: {"description": "invalid input: the field and the reason"}}


@router.post("/reduction", response_model=ReductionResponse, responses=INVALID,
             summary="Reduced moment of inertia J(φ), dJ/dφ and reduced resisting moment M_c(φ) with friction")
def reduction(request: ReductionRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.reduction(request, lang), precision)


@router.post("/motion", response_model=MotionResponse, responses=INVALID,
             summary="Equation of motion: steady cycle (ω(φ), δ, η) and start-up, with numerics")
def motion(request: MotionRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.motion(request, lang), precision)


@router.post("/flywheel", response_model=FlywheelResponse, responses=INVALID,
             summary="Flywheel inertia for a permissible δ by Merzalov, Gutyar, Wittenbauer and exactly; sizing")
def flywheel(request: FlywheelRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.flywheel(request, lang), precision)


@router.post("/dynamics-estimate", response_model=EstimateResponse, responses=INVALID,
             summary="A first estimate of a general mechanism's masses, loads and motor (uniform bars, a load on "
                     "the last slider, a motor that carries it), as a preset's \"dynamics\"")
def dynamics_estimate(request: EstimateRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.dynamics_estimate(request, lang), precision)


@router.post("/work-precision/motion", responses=INVALID,
             summary="Live work–precision study of the current machine's steady cycle (ours against solve_ivp "
                     "integrating cycles, small budget)")

async def motion_work_precision(request: MotionRequest, http: Request, lang: Language = LANG,
                                precision: Precision = PRECISION):
    return await respond_apart(http, endpoints.motion_work_precision, request, lang, precision)
