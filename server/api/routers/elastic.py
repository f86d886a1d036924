"""POST /api/v1/elastic: elastic machine models in time, with the solver chosen by measured stiffness."""
from fastapi import APIRouter
from fastapi.responses import JSONResponse

from ...core.dynamics.motors import Motor
from ...core.dynamics.reduction import Inertias
from ...core.dynamics.resistance import Load
from ...core.elastic.report import Bearing, ElasticMachine, bearing_iteration, modal, simulate
from ...core.elastic.stiffness import Compliances
from ...core import work_precision
from ...core.mechanisms import MECHANISMS, GeometryError
from ..schemas import Language
from ..schemas_elastic import ElasticRequest
from .. import heavy
from .dynamics import LANG, payload

router = APIRouter(tags=["elastic"])


def _elastic_machine(request: ElasticRequest) -> ElasticMachine:
    if request.motor.kind == "indicator":
        raise GeometryError("motor.kind", "the elastic models take a motor with a speed characteristic or a "
                            "constant torque", "elastic_motor")
    return ElasticMachine(
        request.model, request.mechanism, MECHANISMS[request.mechanism].check(request.params),
        Inertias(**request.inertias.model_dump()), Load(**request.load.model_dump()),
        Motor(**{**request.motor.model_dump(), "expansion": tuple(request.motor.expansion),
                 "compression": tuple(request.motor.compression)}),
        request.J_motor, request.J_middle, request.c, Compliances(**request.compliances.model_dump()),
        request.b, request.b1, request.speed, request.omega0, request.twist0)


@router.post("/elastic", summary="Two- and three-mass elastic machines and elastic linkages: time histories, "
                                 "modal curves, the rigid solution, numerics",
             responses={422: {"description": "invalid input: the field and the reason"}})
def elastic(request: ElasticRequest, lang: Language = LANG):
    return JSONResponse(heavy.run(elastic_answer, request, lang))


@router.post("/work-precision/elastic", summary="Live work–precision study of the current elastic machine "
                                                "(error against run time of several solvers, small budget)")
def elastic_work_precision(request: ElasticRequest, lang: Language = LANG):
    return JSONResponse(heavy.run(study_answer, request, lang))


def elastic_answer(request: ElasticRequest, lang: str) -> dict:
    """The body of /elastic (run in the heavy process)."""
    machine = _elastic_machine(request)
    result, notices = {}, []
    if "histories" in request.outputs or "rigid" in request.outputs:
        result, notices = simulate(machine, request.t_end, request.n, request.rtol, request.method,
                                   with_rigid="rigid" in request.outputs)
    if "modal" in request.outputs:
        result["modal"] = modal(machine)
    if "bearings" in request.outputs:
        result["bearings"] = bearing_iteration(machine, Bearing(**request.bearing.model_dump()), request.t_end,
                                               request.n, request.rtol)
    return payload(result, notices, lang)


def study_answer(request: ElasticRequest, lang: str) -> dict:
    """The body of /work-precision/elastic (run in the heavy process)."""
    machine = _elastic_machine(request)
    return payload({"study": work_precision.elastic_study(machine, min(request.t_end, 0.5))}, [], lang)
