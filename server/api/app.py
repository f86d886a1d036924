"""The FastAPI application: versioned JSON API under /api/v1, pages, and our own static assets."""
import json
import logging
import time
from contextlib import asynccontextmanager
from pathlib import Path

from fastapi import APIRouter, FastAPI
from fastapi.exceptions import RequestValidationError
from fastapi.middleware.gzip import GZipMiddleware

from ..paths import BENCH_RESULTS, WEB
from ..core.mechanisms import GeometryError
from ..core.warm_up import warm_up
from . import access_log
from ..classroom import answers as classroom_answers, assignment_store
from ..runtime import default_answers, heavy
from .errors import busy, geometry_error, not_found, server_error, store_unavailable, too_often, validation_error
from ..runtime.admission import AdmissionMiddleware
from .bench_pages import BenchResults
from .endpoints import ENDPOINTS, parsed_answer
from .head_requests import HeadAsGet
from .security import SecurityMiddleware
from .static_files import content_version, mount_versioned, script_version
from ..runtime.response_cache import (CACHE_AT_EXIT, GZIP_LEVEL, GZIP_MINIMUM_SIZE, ResponseCache,
                                      ResponseCacheMiddleware)
from .routers import cache as cache_stats
from .routers import lti
from .routers import friction_influence
from .routers import project as course_project
from ..classroom.refusals import Busy, NotFound, TooOften
from ..classroom.store import StoreUnavailable
from ..classroom.variants import SpecError
from .routers import (angular, assignment_pages, assignments, bearings, dynamics, editor_pages, elastic, family, motor,
                      forces, kinematics, mechanisms, pages, project_pages, scenes)

API_PREFIX = "/api/v1"
PLOTLY_DIR = WEB / "vendor" / "plotly"            # plotly.min.js, vendored: its version is fixed here
STATIC_DIR = WEB / "static"


@asynccontextmanager
async def lifespan(app: FastAPI):
    assignment_store.check()           # a database it cannot write stops the server here, with the reason
    heavy.start()                      # the heavy processes warm their kernels meanwhile
    started = time.perf_counter()      # the compiled kernels, in this worker, before its first request
    logging.getLogger("uvicorn.error").info(
        "loading the compiled numerical kernels: a second from numba's cache; on a first start, or after an update, "
        "they are compiled first (one to two minutes), then the server answers")
    parts = warm_up()
    logging.getLogger("uvicorn.error").info("compiled code ready in %.2f s (%s)", time.perf_counter() - started,
                                            ", ".join(f"{part} {seconds:.2f} s" for part, seconds in parts.items()))
    heavy.frozen_after_start()
    app.state.default_answers = default_answers.start(       # MDL_WARM_DEFAULTS: on spare CPU, after the start
        app, set(cache_stats.request_models()))
    yield
    await default_answers.stop(app.state.default_answers)
    heavy.shutdown()                   # the heavy processes end with the worker
    cache = getattr(app.state, "response_cache", None)
    if cache is not None:              # one line per worker: its counters, as GET /api/v1/cache gives them
        logging.getLogger("uvicorn.error").info("%s %s", CACHE_AT_EXIT, json.dumps(cache.stats()))


class LabApp(FastAPI):
    """The FastAPI app with SecurityMiddleware outside everything, Starlette's ServerErrorMiddleware included:
    every answer, a 500 too, carries the security headers, and bodies are checked before any layer reads them;
    inside it, HEAD is answered as GET without the body."""

    def build_middleware_stack(self):
        return SecurityMiddleware(HeadAsGet(super().build_middleware_stack()))


def create_app() -> FastAPI:
    access_log.install()                       # the access log never holds a student's secret
    classroom_answers.use_endpoints(parsed_answer)   # an assignment's answers are the endpoints' (and its heavy work's)
    app = LabApp(title="Mechanism Dynamics Lab API", version="1.0.0",
                  description="Kinematics and dynamics of planar linkages for the theory of machines and "
                              "mechanisms. SI units throughout; angles in radians.\n\n"
                              "**Precision.** The computing endpoints send every float rounded to 7 significant "
                              "digits by default (`?precision=plot`: a relative change below 5·10⁻⁷, enough for "
                              "any plot or table); `?precision=full` sends every float64 as computed. "
                              "Non-finite numbers are `null` in both.\n\n"
                              "**Partial answers.** An answer that a time or work bound cut short says so in "
                              "`numerics.message` and `warnings` and carries the header `X-Partial: 1`.",
                  openapi_url=f"{API_PREFIX}/openapi.json", docs_url=None, redoc_url=None,
                  lifespan=lifespan)
    api = APIRouter(prefix=API_PREFIX)
    for module in (mechanisms, kinematics, dynamics, motor, elastic, forces, bearings, angular, family, scenes,
                   assignments):
        api.include_router(module.router)
    api.include_router(friction_influence.router)   # POST /api/v1/friction-influence
    api.include_router(course_project.router)   # POST /api/v1/course-project
    api.include_router(cache_stats.router)  # GET /api/v1/cache
    app.include_router(api)
    app.include_router(pages.router)
    app.include_router(assignment_pages.router)
    app.include_router(editor_pages.router)     # /editor: the mechanism editor
    app.include_router(project_pages.router)    # /project: the course project and its report
    app.include_router(lti.router)              # /lti: the LTI 1.3 tool; /api/v1/lti: its registration
    app.add_exception_handler(RequestValidationError, validation_error)  # never echo NaN back
    app.add_exception_handler(GeometryError, geometry_error)
    app.add_exception_handler(SpecError, assignments.spec_error)
    app.add_exception_handler(StoreUnavailable, store_unavailable)   # 503 + Retry-After: a full disk, a server down
    app.add_exception_handler(NotFound, not_found)          # the classroom's refusals: 404,
    app.add_exception_handler(Busy, busy)                   # 503 + Retry-After (answers not to be had now),
    app.add_exception_handler(TooOften, too_often)          # 429 + Retry-After
    app.add_exception_handler(Exception, server_error)      # 500 as JSON (ServerErrorMiddleware answers it)
    app.state.response_cache = ResponseCache.from_env()  # MDL_CACHE_BYTES, default 64 MB, 0 = off
    # a share of the computing lanes per address, in turn (429 past a cap), the cookie; inside the cache: a cached
    # answer waits for no place
    app.add_middleware(AdmissionMiddleware, computing=ENDPOINTS)
    app.add_middleware(ResponseCacheMiddleware, cache=app.state.response_cache, models=cache_stats.request_models(),
                       prefix=API_PREFIX)  # inside gzip
    app.add_middleware(GZipMiddleware, minimum_size=GZIP_MINIMUM_SIZE, compresslevel=GZIP_LEVEL)
    # SecurityMiddleware (headers on every response, bodies ≤ 1 MiB and checked) wraps all of these: LabApp
    static = mount_versioned(app, "/static", STATIC_DIR, content_version(STATIC_DIR), "static")
    plotly_js = mount_versioned(app, "/vendor/plotly", PLOTLY_DIR, script_version(PLOTLY_DIR / "plotly.min.js"),
                                "plotly")
    pages.templates.env.globals.update(static=static, plotly=plotly_js)   # {{ static }}/js/api.js in templates
    app.mount("/bench-results", BenchResults(directory=BENCH_RESULTS), name="bench")
    return app


app = create_app()
