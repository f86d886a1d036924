"""POST /api/v1/bearings: the plain-bearing designer (Chaika–Vasylenko §2) on a pair of the crank-slider."""
from fastapi import APIRouter

from .. import endpoints
from ..schemas import Language
from ..schemas_bearings import BearingsRequest
from ..serialise import Precision, respond
from .query import LANG, PRECISION

router = APIRouter(tags=["bearings"])
INVALID = {422: {"description": "invalid input: the field and the reason"}}


@router.post("/bearings", responses=INVALID,
             summary="Plain radial bearing of a crank-slider pair: sizing, checks, heat, Stribeck curve, film power")
def bearings(request: BearingsRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.bearings(request, lang), precision)
