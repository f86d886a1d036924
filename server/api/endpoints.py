"""Each computing endpoint's body, in one place: the validated request → the numeric core → the answer.

A body function takes the endpoint's request model and the reader's language and returns an Answer: the
payload (numpy arrays as they are, warnings translated, numerics localised) and whether a time or work bound
cut it short. The routers only parse, call and serialise (server/api/serialise.py); the classroom computes with
``parsed_answer`` (given to it when the app is made), the family endpoint with ``compute_answers``: a family's
members at once, through an endpoint's batch body (BATCHES: the kinematics over a (member, φ) grid, machines
shared by members of motion and flywheel) or one by one. Nothing is computed that the request did not ask for:
each output is computed only when it is in ``outputs``, or when what is asked is made from it.
"""
from __future__ import annotations

import math
from collections.abc import Collection

import numpy as np
import orjson
from pydantic import ValidationError

from ..core import work_precision
from ..core.angular_acceleration import CrankLaw, crank_slider, trammel
from ..core.bearings.loads import pair_load
from ..core.bearings.report import Design, bearings_report
from ..core.dynamics import report
from ..core.dynamics.cycle_moments import cycle_moments
from ..core.dynamics.flywheel_analysis import flywheel_analysis
from ..core.dynamics.general_machine import GeneralMachine, general_machine
from ..core.dynamics.general_machine import reduction as general_reduction
from ..core.dynamics.machine import Machine
from ..core.dynamics.motor_report import motor_study
from ..core.dynamics.motors import Motor
from ..core.dynamics.reduction import Inertias
from ..core.dynamics.resistance import Load
from ..core.elastic.report import (Bearing, ElasticMachine, bearing_iteration, bearing_notice, mechanism_side,
                                   modal, request_deadline, rigid, simulate)
from ..core import errata
from ..core.elastic.assemblies import OUTPUT as ASSEMBLIES, assembly_curves
from ..core.elastic.compliance import Dimensions, compliance_report
from ..core.elastic.stiffness import Compliances
from ..core.kinematics import compute_kinematics, compute_kinematics_many
from ..core.kinetostatics.crank_slider import Loads, Pairs, analyse
from ..core.kinetostatics.groups.analysis import analyse as analyse_groups
from ..core.kinetostatics.groups.friction import PairFriction
from ..core.kinetostatics.groups.report import group_forces_report
from ..core.kinetostatics.report import crank_check, forces_report, wear_report
from ..core.kinetostatics.wear_table import book_table_report, constant_load_rows, table_report
from ..core.kinetostatics.virtual_work import reduced_moment
from ..core.mechanisms import MECHANISMS, GeometryError, Notice
from ..core.mechanisms.general import GENERAL_OUTPUTS, GeneralMechanism, compute_general
from ..core.mechanisms.general import change_point_mask, change_point_notices, undefined_at
from ..core.structure.masses import MassModel
from ..core.structure.estimate import estimated_dynamics
from .answering import Preview, Reads, answer, motor_of, refused_or
from .endpoints_forces import (efficiency_chain, force_analysis, forces, friction_influence,  # noqa: F401
                               friction_influence_batch, preview_friction_tolerance, wear)
from .messages import localise_numerics, special_text, translate
from .schemas import KinematicsRequest, KinematicsResponse
from .schemas_angular import AngularRequest
from .schemas_bearings import BearingsRequest
from .schemas_dynamics import EstimateRequest, FlywheelRequest, MotionRequest, ReductionRequest
from .schemas_elastic import ElasticRequest
from .schemas_friction_influence import FrictionInfluenceRequest
from .schemas_forces import ChainRequest, ForcesRequest, WearRequest
from .schemas_motor import FlywheelAnalysisRequest, MotorCharacteristicRequest
from .serialise import Answer, serialise

def count_undefined(value) -> int:
    """Number of non-finite numbers inside an output (arrays, dicts and lists of them)."""
    if isinstance(value, dict):
        return sum(count_undefined(v) for v in value.values())
    if isinstance(value, (list, tuple)):
        return sum(count_undefined(v) for v in value)
    if isinstance(value, np.ndarray) and value.dtype.kind == "f":
        return int(np.count_nonzero(~np.isfinite(value)))
    if isinstance(value, float):
        return int(not math.isfinite(value))
    return 0


def kinematics(request: KinematicsRequest, lang: str) -> Answer:
    """Position and transfer functions; each output's undefined points (singular positions) counted in words."""
    phi = None if request.phi is None else np.asarray(request.phi, float)
    if request.mechanism == "general":
        result = compute_general(request.linkage.model_dump(exclude_none=True), request.outputs, phi, request.n,
                                 None if request.plan is None else request.plan.model_dump())
        if "special" in result.outputs:           # each special position said in the reader's language too
            result.outputs["special"] = [sp | {"text": special_text(sp, lang)} for sp in result.outputs["special"]]
        return kinematics_answer(result, GENERAL_OUTPUTS, lang)
    result = compute_kinematics(request.mechanism, request.params, request.outputs, phi=phi, n=request.n)
    return kinematics_answer(result, MECHANISMS[request.mechanism].outputs, lang)


def kinematics_answer(result, outputs, lang: str) -> Answer:
    """The answer of a kinematics result: its outputs with their units, the warnings translated, one more
    for each output's undefined points."""
    notices = list(result.warnings)
    for name, value in result.outputs.items():
        bad = count_undefined(value)
        if bad:
            notices.append(Notice("undefined_points", f"{name}: undefined at {bad} point(s), sent as null "
                                  "(singular position).", {"output": name, "count": bad}))
    units = {o.name: o.unit for o in outputs}
    body = KinematicsResponse.model_construct(     # built from checked numbers: no re-validation of the arrays
        mechanism=result.mechanism, params=result.params, cycle=result.cycle, phi=result.phi,
        outputs=result.outputs, units={name: units.get(name, "") for name in result.outputs},
        warnings=[translate(notice, lang) for notice in notices])
    return Answer(dict(body.__dict__))


def kinematics_batch(requests: list[KinematicsRequest], lang: str, reads: Reads,
                     preview: Preview = None) -> list[Answer | GeometryError]:
    """Members of one mechanism of the four (not "general") with the same outputs and angles: one
    compute_kinematics_many over their parameters (a (member, φ) grid); otherwise one by one."""
    first = requests[0] if requests else None
    shared = first is not None and first.mechanism != "general" and all(
        (r.mechanism, r.outputs, r.phi, r.n) == (first.mechanism, first.outputs, first.phi, first.n) for r in requests)
    if not shared:
        return one_by_one("kinematics")(requests, lang, reads)      # closed forms: exact in any case
    phi = None if first.phi is None else np.asarray(first.phi, float)
    results = compute_kinematics_many(first.mechanism, [r.params for r in requests], first.outputs, phi, first.n)
    outputs = MECHANISMS[first.mechanism].outputs
    return [result if isinstance(result, GeometryError) else kinematics_answer(result, outputs, lang)
            for result in results]


def reduction(request: ReductionRequest, lang: str) -> Answer:
    cycle = reduced_cycle_moments(request) if "cycle_moments" in request.outputs else None    # 422 first
    if request.mechanism == "general":
        result, notices = general_reduction(_general_machine(request, Motor()), request.n, request.omega,
                                            request.outputs)
        return answer(result, notices, lang)
    outputs = [name for name in request.outputs if name not in ("errata", "cycle_moments")]
    result, notices = report.reduction(
        request.mechanism, request.params, Inertias(**request.inertias.model_dump()),
        Load(**request.load.model_dump()), request.n, request.omega, outputs, request.iteration_phi) \
        if outputs else ({}, [])
    if "errata" in request.outputs:
        mechanism = MECHANISMS[request.mechanism]
        result["errata"] = errata.reduction(mechanism, mechanism.check(request.params), request.inertias.m3,
                                            request.omega)
    if cycle is not None:
        result["cycle_moments"], more = cycle
        notices = [*notices, *more]
    return answer(nested_numerics(result, ("cycle_moments",), lang), notices, lang)


def machine_key(request: MotionRequest | FlywheelRequest) -> bytes:
    """What the machine of a request is made of (mechanism, params, inertias, load, motor; a general mechanism's
    linkage and masses), canonically: two requests with one key have equal machines, whatever else (ω_m, δ, ω₀,
    rtol, sizing) differs."""
    return orjson.dumps(request.model_dump(include=MACHINE_FIELDS), option=orjson.OPT_SORT_KEYS)


MACHINE_FIELDS = {"mechanism", "params", "inertias", "load", "motor", "linkage", "masses", "pair_friction"}


def machine(request: MotionRequest | FlywheelRequest) -> Machine:
    """The machine of a request, checked: geometry, a piston engine only on a crank-slider, some inertia."""
    if request.mechanism == "general":
        built = _general_machine(request, motor_of(request.motor))
    else:
        params = MECHANISMS[request.mechanism].check(request.params)
        if request.motor.kind == "indicator" and not MECHANISMS[request.mechanism].piston:
            raise GeometryError("motor.kind", "an indicator diagram drives a crank-slider (piston engine) only",
                                "indicator_needs_slider")
        built = Machine(request.mechanism, params, Inertias(**request.inertias.model_dump()),
                        Load(**request.load.model_dump()), motor_of(request.motor))
    if built.tables(np.linspace(0, 2 * math.pi, 73)).J.min() <= 0:      # J = 0 somewhere: no equation of motion
        raise GeometryError("inertias", "the reduced moment of inertia is zero: give the crank (J1) or the motor "
                                        "rotor (J_rotor) some inertia", "zero_inertia")
    return built


def _general_machine(request: ReductionRequest | MotionRequest | FlywheelRequest, motor: Motor) -> GeneralMachine:
    """A general mechanism's machine: its linkage, mass model and loads checked (GeometryError names the field)."""
    masses = request.masses.model() if request.masses is not None else MassModel()
    pairs = {name: PairFriction(p.f, p.r, p.beta) for name, p in request.pair_friction.items()}
    return general_machine(request.linkage.model_dump(exclude_none=True), masses,
                           Inertias(**request.inertias.model_dump()), Load(**request.load.model_dump()), motor, pairs)


def dynamics_estimate(request: EstimateRequest, lang: str) -> Answer:
    """A first estimate of a crank-driven general mechanism's masses, loads and motor (estimate.py)."""
    return answer(estimated_dynamics(request.linkage.model_dump(exclude_none=True)), [], lang)


def motion(request: MotionRequest, lang: str, built: Machine | None = None, preview: Preview = None) -> Answer:
    """The steady cycle and/or the start-up; ``built``: the request's machine made already (a batch);
    ``preview``: a family member's accuracy (see Preview)."""
    result, notices = report.motion(built or machine(request), request.outputs, request.omega0, request.rtol,
                                    request.omega_mean, request.balance, request.max_cycles, preview)
    return answer(result, notices, lang)


def flywheel(request: FlywheelRequest, lang: str, reads: Reads = None, built: Machine | None = None) -> Answer:
    """The flywheel study; its numerics (and their error estimate, a second exact inertia on half the grid)
    only when read (``reads``); ``built``: the request's machine made already (a batch)."""
    built = built or machine(request)
    if built.speed_dependent:
        raise GeometryError("motor.kind", "the flywheel methods of the lecture need moments of φ alone: a "
                            "constant-torque motor or an indicator diagram, and no viscous friction",
                            "flywheel_needs_phi_moments")
    result, notices = report.flywheel(built, request.omega_mean, request.delta, request.balance,
                                      request.width_ratio, request.density,
                                      with_numerics=reads is None or "numerics" in reads)
    return answer(result, notices, lang)


def motion_work_precision(request: MotionRequest, lang: str) -> Answer:
    """The live study of the steady-cycle solvers (seconds of solving: run in the heavy process)."""
    built = machine(request)
    if not built.speed_dependent:
        raise GeometryError("motor.kind", "the study compares steady-cycle solvers: give a motor or "
                                          "friction that depends on speed", "study_needs_speed")
    study = work_precision.motion_study(built)
    return answer({"study": study}, work_precision.study_notices(study), lang)


def elastic_machine(request: ElasticRequest) -> ElasticMachine:
    if request.motor.kind in ("indicator", "table"):
        raise GeometryError("motor.kind", "the elastic models take a motor with a speed characteristic or a "
                            "constant torque", "elastic_motor")
    params = MECHANISMS[request.mechanism].check(request.params)
    compliances = Compliances(**request.compliances.model_dump())
    if request.dimensions is not None:
        parts = compliance_report(_dimensions(request, params))
        compliances = Compliances(parts["e1"], parts["e2"])
    return ElasticMachine(
        request.model, request.mechanism, params,
        Inertias(**request.inertias.model_dump()), Load(**request.load.model_dump()), motor_of(request.motor),
        request.J_motor, request.J_middle, request.c, compliances,
        request.b, request.b1, request.speed, request.omega0, request.twist0)


def _dimensions(request: ElasticRequest, params: dict) -> Dimensions:
    """The parts of the elastic linkage: the rod is l₂ long, the motor shaft turns inertias.gear_ratio times
    as fast as the crank shaft."""
    return Dimensions(rod_length=params["l2"], ratio=request.inertias.gear_ratio, **request.dimensions.model_dump())


OTHER_ELASTIC = ("rigid", "modal", "bearings", ASSEMBLIES)   # an elastic answer's keys that are not the histories'


def elastic(request: ElasticRequest, lang: str, reads: Reads = None) -> Answer:
    """Histories (with numerics), the rigid start-up, modal curves, the bearing iteration: each only when
    asked for (and, for a caller that reads only part of the answer, ``reads``, only when read; the check run
    at rtol/10 only when the numerics or the warnings are); the rigid machine alone is sampled on the
    histories' times, t = 0 … t_end in n points, and refused where the elastic machine is (no inertia on the
    mechanism side, an undefined load)."""
    built = elastic_machine(request)
    result, notices = {}, []
    deadline = request_deadline()                  # one for every stage of this request
    asked = lambda output, *keys: output in request.outputs and (reads is None or any(k in reads for k in keys))
    wants_rigid = asked("rigid", "rigid")
    if "histories" in request.outputs and (reads is None or any(key not in OTHER_ELASTIC for key in reads)):
        result, notices = simulate(built, request.t_end, request.n, request.rtol, request.method,
                                   with_rigid=wants_rigid, deadline=deadline, check=reads is None or "numerics" in reads
                                   or "warnings" in reads)
    elif wants_rigid:
        mechanism_side(built)                      # refuses the elastic machine as its other outputs would
        result["rigid"] = rigid(built, np.linspace(0.0, request.t_end, request.n))
    if asked("modal", "modal"):
        result["modal"] = modal(built)
    if asked(ASSEMBLIES, ASSEMBLIES):
        result[ASSEMBLIES] = assembly_curves(built)
    if asked("compliance", "compliance"):
        result["compliance"] = compliance_report(_dimensions(request, built.params))
    if asked("bearings", "bearings", "warnings"):
        result["bearings"] = bearing_iteration(built, Bearing(**request.bearing.model_dump()), request.t_end,
                                               request.n, request.rtol, deadline=deadline)
        notices = [*notices, *bearing_notice(result["bearings"])]
    return answer(result, notices, lang)


def elastic_work_precision(request: ElasticRequest, lang: str) -> Answer:
    """The live study of the elastic solvers over at most 0.5 s (run in the heavy process)."""
    study = work_precision.elastic_study(elastic_machine(request), min(request.t_end, 0.5))
    return answer({"study": study}, work_precision.study_notices(study), lang)


def bearings(request: BearingsRequest, lang: str) -> Answer:
    """The plain-bearing designer on the pair's reaction over the cycle, from the same kinetostatics as /forces
    (the cylinder bore of an engine's indicator diagram gives the recommended journal diameters)."""
    _, loads, _, analysis = force_analysis(request)
    load = pair_load(analysis, request.bearing.pair, loads.omega)
    if np.isfinite(load.force).all() and load.peak <= 0:
        raise GeometryError("loads", "the pair carries no load over the cycle: give the links masses or the "
                            "slider a force", "bearing_no_load")
    fields = request.bearing.model_dump(exclude={"pair"})
    bore = request.loads.gas.piston_diameter if request.loads.gas is not None else None
    result, notices = bearings_report(load, Design(**fields, bore=bore or None), request.outputs)
    result["numerics"] = analysis.numerics          # how the reactions were solved (the formulas are closed)
    return answer(result, [*analysis.notices, *notices], lang)


def angular_acceleration(request: AngularRequest, lang: str) -> Answer:
    law = CrankLaw(request.law, request.omega0, request.epsilon0, request.amplitude, request.frequency)
    t = np.asarray(request.t, float) if request.t is not None else np.linspace(0.0, law.turn_time(), request.n)
    if request.mechanism == "trammel":
        result = trammel(request.length, law, t)
    else:
        result = crank_slider(request.lam, request.length, law, t)
    return answer(result, [], lang)


def motor_characteristic(request: MotorCharacteristicRequest, lang: str) -> Answer:
    """The induction motor's characteristic, the operating point's stability, the successive approximations
    and the joint solution (Lecture 10 §10.9–§10.10)."""
    result, notices = motor_study(machine(request), request.outputs, request.tol)
    return answer(nested_numerics(result, ("approximations", "joint"), lang), notices, lang)


def flywheel_given(request: FlywheelAnalysisRequest, lang: str) -> Answer:
    """The analysis problem: the flywheel's I given, δ found, beside the synthesis for [δ] (Lecture 10 §10.4)."""
    built = machine(request)
    if built.speed_dependent:
        raise GeometryError("motor.kind", "the flywheel methods of the lecture need moments of φ alone: a "
                            "constant or indicator motor, no viscous load", "flywheel_needs_phi_moments")
    result, notices = flywheel_analysis(built, request.omega_mean, request.inertia, request.delta, request.balance,
                                        request.outputs)
    return answer(nested_numerics(result, ("analysis",), lang), notices, lang)


def nested_numerics(result: dict, parts: tuple[str, ...], lang: str) -> dict:
    """The numerics of each part of an answer (not at its top) in the reader's language."""
    for part in parts:
        if isinstance((result.get(part) or {}).get("numerics"), dict):
            result[part]["numerics"] = localise_numerics(result[part]["numerics"], lang)
    return result


# POST /api/v1/<name>: the request model and the body; the answer is a function of (name, lang, body) alone.
ENDPOINTS = {
    "kinematics": (KinematicsRequest, kinematics),
    "reduction": (ReductionRequest, reduction),
    "motion": (MotionRequest, motion),
    "flywheel": (FlywheelRequest, flywheel),
    "elastic": (ElasticRequest, elastic),
    "forces": (ForcesRequest, forces),
    "wear": (WearRequest, wear),
    "angular-acceleration": (AngularRequest, angular_acceleration),
    "efficiency-chain": (ChainRequest, efficiency_chain),
    "bearings": (BearingsRequest, bearings),
    "motor-characteristic": (MotorCharacteristicRequest, motor_characteristic),
    "flywheel-analysis": (FlywheelAnalysisRequest, flywheel_given),
}


# Endpoints whose body skips work whose results a caller will not read (a family pruned to its fields):
READ_AWARE = frozenset({"elastic", "forces", "flywheel"})
# ... and whose body computes a family member to the preview's accuracy when asked (Preview):
PREVIEW_AWARE = frozenset({"motion", "forces"})


def compute_answer(endpoint: str, body: dict, lang: str = "en", reads: Reads = None,
                   preview: Preview = None) -> Answer:
    """POST /api/v1/<endpoint> in-process: validates body with the endpoint's model (pydantic's
    ValidationError) and computes (the core's GeometryError) exactly where the route would answer 422.
    ``reads``: the top-level keys of the answer the caller reads (None: all); an endpoint of READ_AWARE then
    leaves out what only the others need (every key read is the same as in the whole answer); ``preview``: a
    family member's accuracy (Preview; None: the exact answer)."""
    model, body_function = ENDPOINTS[endpoint]
    return body_function(model.model_validate(body), lang, **options(endpoint, reads, preview))


Outcome = Answer | ValidationError | GeometryError     # one body's answer, or its refusal (HTTP 422)


def compute_answers(endpoint: str, bodies: list[dict], lang: str = "en", reads: Reads = None,
                    preview: Preview = None) -> list[Outcome]:
    """compute_answer over several bodies at once (a family's members: one request with its varied numbers
    changed), each entry the body's Answer or its refusal, exactly as compute_answer answers or raises it.
    Every body is validated by itself (its refusal names its own field); the valid ones go to the
    endpoint's batch body (BATCHES), which computes what they share once, or one by one. ``preview``: each
    member to that accuracy (Preview), where the endpoint is PREVIEW_AWARE."""
    model, _ = ENDPOINTS[endpoint]
    outcomes: list = []
    for body in bodies:
        try:
            outcomes.append(model.model_validate(body))
        except ValidationError as error:
            outcomes.append(error)
    valid = [k for k, outcome in enumerate(outcomes) if not isinstance(outcome, ValidationError)]
    batch = BATCHES.get(endpoint, one_by_one(endpoint))
    for k, answer_or_refusal in zip(valid, batch([outcomes[k] for k in valid], lang, reads,
                                                 preview if endpoint in PREVIEW_AWARE else None)):
        outcomes[k] = answer_or_refusal
    return outcomes


def one_by_one(endpoint: str):
    """The batch body of an endpoint without one of its own: each request by itself."""
    _, body_function = ENDPOINTS[endpoint]

    def batch(requests: list, lang: str, reads: Reads, preview: Preview = None) -> list[Answer | GeometryError]:
        extra = options(endpoint, reads, preview)
        return [refused_or(lambda: body_function(request, lang, **extra)) for request in requests]
    return batch


def options(endpoint: str, reads: Reads, preview: Preview) -> dict:
    """The keyword arguments of an endpoint's body for what a family reads and the preview's accuracy, those
    it takes (READ_AWARE, PREVIEW_AWARE); none for an exact answer."""
    return ({"reads": reads} if reads is not None and endpoint in READ_AWARE else {}) | \
        ({"preview": preview} if preview is not None and endpoint in PREVIEW_AWARE else {})


def machine_batch(endpoint: str):
    """The batch body of an endpoint of a machine (motion, flywheel): members with equal machines (machine_key:
    a slider of ω_m, δ, ω₀ or the flywheel's sizing) share one Machine, so its tables (the flywheel's nodes and
    their error estimate's, the steady cycle's levels and kinks: Machine.memo) are computed once, and so is
    the machine's check; each member's own answer is then computed as compute_answer computes it."""
    _, body_function = ENDPOINTS[endpoint]

    def batch(requests: list, lang: str, reads: Reads, preview: Preview = None) -> list[Answer | GeometryError]:
        extra = options(endpoint, reads, preview)
        machines: dict[bytes, Machine | GeometryError] = {}
        outcomes = []
        for request in requests:
            key = machine_key(request)
            if key not in machines:
                machines[key] = refused_or(lambda: machine(request))
            built = machines[key]
            outcomes.append(built if isinstance(built, GeometryError)
                            else refused_or(lambda: body_function(request, lang, built=built, **extra)))
        return outcomes
    return batch


BATCHES = {"kinematics": kinematics_batch, "motion": machine_batch("motion"), "flywheel": machine_batch("flywheel")}


def parsed_answer(endpoint: str, body: dict, lang: str = "en") -> Answer:
    """compute_answer's Answer with its payload as a client parses the JSON of POST
    /api/v1/<endpoint>?precision=full: lists and numbers, null (None) for every non-finite number. What the
    classroom computes its answers with (server/classroom/answers.py, given when the app is made)."""
    answer = compute_answer(endpoint, body, lang)
    return Answer(orjson.loads(serialise(answer.payload, digits=None)), answer.partial)


def compute(endpoint: str, body: dict, lang: str = "en") -> dict:
    """The JSON answer of POST /api/v1/<endpoint>?precision=full as Python data (parsed_answer's payload)."""
    return parsed_answer(endpoint, body, lang).payload


# POST /api/v1/friction-influence: friction swept in every pair of the crank-slider machine (Chaika–Vasylenko §3.4,
# steps 18–19, and §4); its body is in endpoints_forces.py.
ENDPOINTS["friction-influence"] = (FrictionInfluenceRequest, friction_influence)
BATCHES["friction-influence"] = friction_influence_batch


def reduced_cycle_moments(request: ReductionRequest) -> tuple[dict, list[Notice]]:
    """Steps 8–10 of Chaika–Vasylenko's course project for the crank-slider: M_P, M_kO, M_G, M_Σ and their works
    over the engine's or the compressor's cycle, the powers, and the graphical integration (Fig. 3.7)."""
    if request.mechanism != "slider_crank" or request.cycle is None:
        raise GeometryError("cycle", "the moments over a cylinder's cycle need the crank-slider and `cycle`",
                            "cycle_needs_cylinder")
    cycle = request.cycle
    return cycle_moments(request.params, cycle.masses(request.inertias.m2, request.inertias.m3), cycle.cylinder(),
                         request.omega, cycle.efficiency, cycle.drawing.core())


# POST /api/v1/course-project: the whole course project of a linkage (server/api/course_project.py, its body).
from .course_project import course_project  # noqa: E402
from .schemas_project import CourseProjectRequest  # noqa: E402

ENDPOINTS["course-project"] = (CourseProjectRequest, course_project)
