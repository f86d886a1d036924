"""POST /api/v1/elastic, /work-precision/elastic: elastic machine models in time (run in the heavy process)."""
from fastapi import APIRouter, Request

from .. import endpoints
from ...runtime import heavy
from ..schemas import Language
from ..schemas_elastic import ElasticRequest
from ..serialise import Precision, respond_apart
from .query import LANG, PRECISION

heavy.preload(endpoints.__name__)

router = APIRouter(tags=["elastic"])
INVALID = {422: {"description": "invalid input: the field and the reason"}}


@router.post("/elastic", responses=INVALID,
             summary="Two- and three-mass elastic machines and elastic linkages: time histories, modal curves, "
                     "the rigid solution, numerics")
async def elastic(request: ElasticRequest, http: Request, lang: Language = LANG, precision: Precision = PRECISION):
    return await respond_apart(http, endpoints.elastic, request, lang, precision)


@router.post("/work-precision/elastic", responses=INVALID,
             summary="Live work–precision study of the current elastic machine (error against run time of "
                     "several solvers, small budget)")

async def elastic_work_precision(request: ElasticRequest, http: Request, lang: Language = LANG,
                                 precision: Precision = PRECISION):
    return await respond_apart(http, endpoints.elastic_work_precision, request, lang, precision)
