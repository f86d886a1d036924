"""POST /api/v1/kinematics: position functions and transfer functions over crank angles.

A page's question (a few hundred angles, ~1 ms of numpy) is answered on the event loop: handing it to a
thread costs more than the work. A long table (up to kinematics.MAX_POINTS angles, tens of ms) goes to the
thread pool, so that it never holds the event loop for everyone else."""
from fastapi import APIRouter
from starlette.concurrency import run_in_threadpool

from .. import endpoints
from ..schemas import KinematicsRequest, KinematicsResponse, Language
from ..serialise import Precision, respond
from .query import LANG, PRECISION

router = APIRouter(tags=["kinematics"])
INLINE_POINTS = 1441            # 0.25° over a turn: a page's table; longer ones run in a thread


@router.post("/kinematics", response_model=KinematicsResponse,
             summary="Position functions, u₃₁, u′₃₁, u₂₁, u′₂₁, joints and special positions",
             responses={422: {"description": "invalid input: the field and the reason"}})
async def kinematics(request: KinematicsRequest, lang: Language = LANG, precision: Precision = PRECISION):
    points = len(request.phi) if request.phi is not None else request.n or 0
    if points <= INLINE_POINTS:
        return respond(endpoints.kinematics(request, lang), precision)
    return await run_in_threadpool(lambda: respond(endpoints.kinematics(request, lang), precision))
