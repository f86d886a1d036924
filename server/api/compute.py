"""Call a computing endpoint in-process: the same validation and the same answer as over HTTP, for the
server's own use (an assignment's correct answers) without a network round trip."""
from __future__ import annotations

import json

from fastapi.responses import JSONResponse
from pydantic import BaseModel

from .routers import angular, dynamics, elastic, forces, kinematics
from .schemas import KinematicsRequest
from .schemas_dynamics import FlywheelRequest, MotionRequest, ReductionRequest
from .schemas_elastic import ElasticRequest
from .schemas_forces import ForcesRequest, WearRequest

ENDPOINTS = {
    "kinematics": (KinematicsRequest, kinematics.kinematics),
    "reduction": (ReductionRequest, dynamics.reduction),
    "motion": (MotionRequest, dynamics.motion),
    "flywheel": (FlywheelRequest, dynamics.flywheel),
    "elastic": (ElasticRequest, elastic.elastic),
    "forces": (ForcesRequest, forces.forces),
    "wear": (WearRequest, forces.wear),
    "angular-acceleration": (angular.AngularRequest, angular.angular_acceleration),
}


def compute(endpoint: str, body: dict, lang: str = "en") -> dict:
    """The JSON answer of POST /api/v1/<endpoint> for body; raises pydantic's ValidationError or the
    core's GeometryError exactly where the HTTP route would answer 422."""
    model, handler = ENDPOINTS[endpoint]
    answer = handler(model.model_validate(body), lang=lang)
    if isinstance(answer, JSONResponse):
        return json.loads(answer.body)
    if isinstance(answer, BaseModel):
        return answer.model_dump(mode="json")
    return answer
