"""POST /api/v1/forces, /api/v1/wear, /api/v1/efficiency-chain: kinetostatics with friction (seed 002)."""
import numpy as np
from fastapi import APIRouter

from ...core.dynamics.motors import Motor
from ...core.kinetostatics.crank_slider import Loads, Pairs, analyse
from ...core.kinetostatics.report import crank_check, forces_report, wear_report
from ...core.kinetostatics.virtual_work import reduced_moment
from ...core.mechanisms import MECHANISMS
from ..schemas import Language
from ..schemas_forces import ChainRequest, ForcesRequest, WearRequest
from .dynamics import LANG, _respond

router = APIRouter(tags=["forces"])


def _analyses(request: ForcesRequest, omega: float | None = None):
    params = MECHANISMS["slider_crank"].check(request.params)
    fields = request.loads.model_dump()
    gas = request.loads.gas
    fields["gas"] = None if gas is None else Motor(**{**gas.model_dump(), "expansion": tuple(gas.expansion),
                                                        "compression": tuple(gas.compression)})
    if omega is not None:
        fields["omega"] = omega
    loads = Loads(**fields)
    pairs = Pairs(**request.pairs.model_dump())
    phi = np.linspace(0.0, 2 * np.pi, request.n)
    analysis = analyse(params, loads, pairs, phi, request.tolerance)
    frictionless = analyse(params, loads, Pairs(), phi)
    return params, pairs, analysis, frictionless


@router.post("/forces", summary="Reactions, balancing moment, friction, iteration and efficiency of the crank-slider",
             responses={422: {"description": "invalid input: the field and the reason"}})
def forces(request: ForcesRequest, lang: Language = LANG):
    params, pairs, analysis, frictionless = _analyses(request)
    result = forces_report(analysis, pairs)
    result["crank_check"] = crank_check(analysis, frictionless, reduced_moment(params, analysis.applied, analysis.phi))
    return _respond(result, analysis.notices, lang)


@router.post("/wear", summary="Expected wear of the pin, bush, piston and cylinder (seed 002 §4)",
             responses={422: {"description": "invalid input: the field and the reason"}})
def wear(request: WearRequest, lang: Language = LANG):
    _, _, analysis, _ = _analyses(request, omega=request.rpm * 2 * np.pi / 60)
    parts = request.model_dump(include={"pin_diameter", "pin_length", "piston_diameter", "piston_length",
                                        "I_pin", "I_bush", "I_piston", "I_cylinder"})
    return _respond(wear_report(analysis, parts, 60 * request.rpm * request.hours), analysis.notices, lang)


@router.post("/efficiency-chain", summary="Efficiency of mechanisms in series (3.39) or parallel (3.40)")
def efficiency_chain(request: ChainRequest):
    series = float(np.prod(request.efficiencies))
    if request.works is None:
        return {"series": series}
    total = sum(request.works)
    parallel = sum(a * e for a, e in zip(request.works, request.efficiencies)) / total if total > 0 else None
    return {"series": series, "parallel": parallel}
