"""GET /api/v1/mechanisms: what each mechanism takes and gives."""
from dataclasses import asdict

from fastapi import APIRouter

from ...core.mechanisms import MECHANISMS
from ..schemas import MechanismInfo

router = APIRouter(tags=["mechanisms"])


@router.get("/mechanisms", response_model=list[MechanismInfo],
            summary="Mechanisms, their parameters (units, ranges, defaults), outputs and conventions")
def list_mechanisms() -> list[MechanismInfo]:
    return [MechanismInfo(name=m.name, title=m.title, conventions=m.conventions,
                          params=[asdict(p) for p in m.params], outputs=[asdict(o) for o in m.outputs])
            for m in MECHANISMS.values()]
