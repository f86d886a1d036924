"""POST /api/v1/angular-acceleration: the two components of a coupler's angular acceleration (Kuleshova–Tokhtar (2)–(4))."""
from fastapi import APIRouter

from .. import endpoints
from ..schemas import Language
from ..schemas_angular import AngularRequest, AngularResponse
from ..serialise import Precision, respond
from .query import LANG, PRECISION

router = APIRouter(tags=["angular acceleration"])


@router.post("/angular-acceleration", response_model=AngularResponse, responses={422: {"description": "invalid input: the field and the reason"}},
             summary="ε*, ε** and ε_AB of the coupler, ω_AB, 1/AP and the points O, A, B, P")
def angular_acceleration(request: AngularRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.angular_acceleration(request, lang), precision)
