"""POST /api/v1/friction-influence: friction's influence on the crank-slider machine (Chaika–Vasylenko §3.4, §4)."""
from fastapi import APIRouter

from .. import endpoints
from ..schemas import Language
from ..schemas_friction_influence import FrictionInfluenceRequest
from ..serialise import Precision, respond
from .query import LANG, PRECISION

router = APIRouter(tags=["forces"])
INVALID = {422: {"description": "invalid input: the field and the reason"}}


@router.post("/friction-influence", responses=INVALID,
             summary="Friction swept in every pair: peak reactions, balancing moment, efficiency, δ, flywheel, wear")
def friction_influence(request: FrictionInfluenceRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.friction_influence(request, lang), precision)
