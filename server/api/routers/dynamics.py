"""POST /api/v1/reduction and /api/v1/motion: the one-mass dynamic model of the machine."""
import math

import numpy as np
from fastapi import APIRouter, Query
from fastapi.responses import JSONResponse

from ...core import work_precision
from ...core.dynamics import report
from ...core.dynamics.machine import Machine
from ...core.dynamics.motors import Motor
from ...core.dynamics.reduction import Inertias
from ...core.dynamics.resistance import Load
from ...core.mechanisms import MECHANISMS, GeometryError
from .. import heavy
from ..json_safe import finite_or_none
from ..messages import localise_numerics, localise_study, translate
from ..schemas import Language
from ..schemas_dynamics import (FlywheelRequest, FlywheelResponse, MotionRequest, MotionResponse, ReductionRequest,
                                ReductionResponse)

router = APIRouter(tags=["dynamics"])
LANG = Query("en", description="language of the warnings: ru, uk or en")


def payload(result: dict, notices, lang: str) -> dict:
    """The answer's body: numerics and study in the reader's language, no NaN, the warnings once each."""
    warnings = dict.fromkeys(translate(n, lang) for n in notices)      # once each, in order
    if isinstance(result.get("study"), dict):
        result["study"] = localise_study(result["study"], lang)
    for holder in (result, result.get("startup") or {}):
        if isinstance(holder.get("numerics"), dict):
            holder["numerics"] = localise_numerics(holder["numerics"], lang)
    return finite_or_none(result) | {"warnings": list(warnings)}


def _respond(result: dict, notices, lang: str) -> JSONResponse:
    return JSONResponse(payload(result, notices, lang))


@router.post("/reduction", response_model=ReductionResponse,
             summary="Reduced moment of inertia J(φ), dJ/dφ and reduced resisting moment M_c(φ) with friction",
             responses={422: {"description": "invalid input: the field and the reason"}})
def reduction(request: ReductionRequest, lang: Language = LANG):
    result, notices = report.reduction(
        request.mechanism, request.params, Inertias(**request.inertias.model_dump()),
        Load(**request.load.model_dump()), request.n, request.omega, request.outputs, request.iteration_phi)
    return _respond(result, notices, lang)


@router.post("/motion", response_model=MotionResponse,
             summary="Equation of motion: steady cycle (ω(φ), δ, η) and start-up, with numerics",
             responses={422: {"description": "invalid input: the field and the reason"}})
def motion(request: MotionRequest, lang: Language = LANG):
    machine = _machine(request)
    result, notices = report.motion(machine, request.outputs, request.omega0, request.rtol, request.omega_mean,
                                    request.balance, request.max_cycles)
    return _respond(result, notices, lang)


@router.post("/flywheel", response_model=FlywheelResponse,
             summary="Flywheel inertia for a permissible δ by Merzalov, Gutyar, Wittenbauer and exactly; sizing",
             responses={422: {"description": "invalid input: the field and the reason"}})
def flywheel(request: FlywheelRequest, lang: Language = LANG):
    machine = _machine(request)
    if machine.speed_dependent:
        raise GeometryError("motor.kind", "the flywheel methods of the lecture need moments of φ alone: a "
                            "constant-torque motor or an indicator diagram, and no viscous friction",
                            "flywheel_needs_phi_moments")
    result, notices = report.flywheel(machine, request.omega_mean, request.delta, request.balance,
                                      request.width_ratio, request.density)
    return _respond(result, notices, lang)


@router.post("/work-precision/motion", summary="Live work–precision study of the current machine's steady cycle "
                                               "(ours against solve_ivp integrating cycles, small budget)")
def motion_work_precision(request: MotionRequest, lang: Language = LANG):
    return JSONResponse(heavy.run(motion_study_answer, request, lang))


def motion_study_answer(request: MotionRequest, lang: str) -> dict:
    """The body of /work-precision/motion (seconds of solving: run in the heavy process)."""
    machine = _machine(request)
    if not machine.speed_dependent:
        raise GeometryError("motor.kind", "the study compares steady-cycle solvers: give a motor or "
                                          "friction that depends on speed", "study_needs_speed")
    return payload({"study": work_precision.motion_study(machine)}, [], lang)


def _machine(request) -> Machine:
    """The machine of a request, checked: geometry, a piston engine only on a crank-slider, some inertia."""
    params = MECHANISMS[request.mechanism].check(request.params)
    if request.motor.kind == "indicator" and request.mechanism != "slider_crank":
        raise GeometryError("motor.kind", "an indicator diagram drives a crank-slider (piston engine) only",
                            "indicator_needs_slider")
    motor = Motor(**{**request.motor.model_dump(), "expansion": tuple(request.motor.expansion),
                     "compression": tuple(request.motor.compression)})
    machine = Machine(request.mechanism, params, Inertias(**request.inertias.model_dump()),
                      Load(**request.load.model_dump()), motor)
    _check_inertia(machine)
    return machine


def _check_inertia(machine: Machine) -> None:
    """A machine with no inertia at some angle has no equation of motion (J = 0)."""
    J = machine.tables(np.linspace(0, 2 * math.pi, 73)).J
    if J.min() <= 0:
        raise GeometryError("inertias", "the reduced moment of inertia is zero: give the crank (J1) or the motor "
                                        "rotor (J_rotor) some inertia", "zero_inertia")
