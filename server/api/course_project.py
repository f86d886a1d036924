"""POST /api/v1/course-project's body: the request → core/course_project/report.py → the answer, its numerics and
warnings in the reader's language (registered in endpoints.ENDPOINTS, run in the heavy process: a few hundred ms)."""
from __future__ import annotations

from ..core.course_project.report import course_project as project
from ..core.dynamics.reduction import Inertias
from ..core.kinetostatics.groups.friction import PairFriction
from ..core.mechanisms import GeometryError
from .answering import answer
from .messages import localise_numerics
from .schemas_project import CourseProjectRequest
from .serialise import Answer


def course_project(request: CourseProjectRequest, lang: str) -> Answer:
    """The whole project of the request (docs/course_project.md); GeometryError (422) names the field."""
    for name, pair in request.pair_friction.items():
        if pair.beta > 0:
            raise GeometryError(f"pair_friction.{name}.beta", "the flywheel of the course project needs moments of "
                                "the crank angle alone: no viscous friction", "flywheel_needs_phi_moments")
    inertias = Inertias(J1=request.inertias.J1, J_rotor=request.inertias.J_rotor,
                        gear_ratio=request.inertias.gear_ratio)
    pairs = {name: PairFriction(p.f, p.r) for name, p in request.pair_friction.items()}
    result, notices = project(request.linkage.model_dump(exclude_none=True), request.masses.model(), inertias, pairs,
                              request.omega_mean, request.delta, request.positions, request.start, request.output,
                              request.chosen, request.drawn)
    result["title"] = request.title.model_dump()
    local = lambda holder: holder | {"numerics": localise_numerics(holder["numerics"], lang)} \
        if isinstance((holder or {}).get("numerics"), dict) else holder
    dynamics, kinetics = result["dynamics"], result["kinetostatics"]
    dynamics["flywheel"] = local(dynamics["flywheel"])
    result["dynamics"], result["kinetostatics"] = local(dynamics), local(kinetics)
    kinetics = result["kinetostatics"]
    kinetics["friction"] = local(kinetics["friction"])
    return answer(result, notices, lang)
