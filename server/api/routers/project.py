"""POST /api/v1/course-project: the whole course project of a linkage in one answer (docs/course_project.md), in
the heavy process (a few hundred ms: the flywheel, the real motion, the kinetostatics of every position)."""
from fastapi import APIRouter, Request

from ...runtime import heavy
from ..course_project import course_project
from ..schemas import Language
from ..schemas_project import CourseProjectRequest
from ..serialise import Precision, respond_apart
from .query import LANG, PRECISION

heavy.preload(course_project.__module__)

router = APIRouter(tags=["course project"])


@router.post("/course-project", responses={422: {"description": "invalid input: the field and the reason"}},
             summary="The course project: structure, kinematics at N positions, dynamics with the flywheel for [δ], "
                     "kinetostatics at the real motion with Zhukovsky's lever")

async def project(request: CourseProjectRequest, http: Request, lang: Language = LANG,
                  precision: Precision = PRECISION):
    return await respond_apart(http, course_project, request, lang, precision)
