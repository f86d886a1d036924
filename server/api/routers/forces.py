"""POST /api/v1/forces, /wear, /efficiency-chain: kinetostatics with friction (Chaika–Vasylenko §3, §4)."""
from fastapi import APIRouter

from .. import endpoints
from ..schemas import Language
from ..schemas_forces import ChainRequest, ForcesRequest, WearRequest
from ..serialise import Precision, respond
from .query import LANG, PRECISION

router = APIRouter(tags=["forces"])
INVALID = {422: {"description": "invalid input: the field and the reason"}}


@router.post("/forces", responses=INVALID,
             summary="Reactions, balancing moment, friction, iteration and efficiency of the crank-slider")
def forces(request: ForcesRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.forces(request, lang), precision)


@router.post("/wear", responses=INVALID,
             summary="Expected wear of the pin, bush, piston and cylinder (Chaika–Vasylenko §4)")
def wear(request: WearRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.wear(request, lang), precision)


@router.post("/efficiency-chain", responses=INVALID,
             summary="Efficiency of mechanisms in series (3.39) or parallel (3.40)")
def efficiency_chain(request: ChainRequest, lang: Language = LANG, precision: Precision = PRECISION):
    return respond(endpoints.efficiency_chain(request, lang), precision)
