"""The bodies of the force endpoints: POST /forces (a crank-slider's or a general mechanism's kinetostatics, with
friction), /wear, /efficiency-chain and /friction-influence, request → core → Answer (registered in
endpoints.ENDPOINTS)."""
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
from .messages import localise_numerics, special_text, translate
from .schemas import KinematicsRequest, KinematicsResponse
from .schemas_angular import AngularRequest
from ..core.kinetostatics.friction_influence import Flywheel, MachineSetup, Study, WearParts, sweep_values

from ..core.kinetostatics.friction_influence_report import explorer_answer

from .schemas_friction_influence import FrictionInfluenceRequest
from .schemas_bearings import BearingsRequest
from .schemas_dynamics import EstimateRequest, FlywheelRequest, MotionRequest, ReductionRequest
from .schemas_elastic import ElasticRequest
from .schemas_forces import ChainRequest, ForcesRequest, WearRequest
from .schemas_motor import FlywheelAnalysisRequest, MotorCharacteristicRequest
from .serialise import Answer, serialise

def force_analysis(request: ForcesRequest, omega: float | None = None, table: bool = True,
                   tolerance: float | None = None):
    """The crank-slider's kinetostatics of a request: (params, loads, pairs, the analysis) (also the bearings')."""
    params = MECHANISMS["slider_crank"].check(request.params)
    fields = request.loads.model_dump()
    fields["gas"] = None if request.loads.gas is None else motor_of(request.loads.gas)
    if omega is not None:
        fields["omega"] = omega
    loads, pairs = Loads(**fields), Pairs(**request.pairs.model_dump())
    phi = np.linspace(0.0, 2 * np.pi, request.n)
    return params, loads, pairs, analyse(params, loads, pairs, phi, tolerance or request.tolerance, table=table)


def forces(request: ForcesRequest, lang: str, reads: Reads = None, preview: Preview = None) -> Answer:
    """The force report and the check (3.2) of the balancing moment against virtual work, with and without
    friction (without friction in the pairs, the analysis is already the frictionless one); the check, and the
    textbook's approximations with the numerics describing them, only when read (``reads``: a caller that
    reads only part of the answer). ``preview``: the friction equilibrium to preview_friction_tolerance (see
    Preview)."""
    if request.mechanism == "general":
        return _general_forces(request, lang, reads, preview)
    table = reads is None or "iteration" in reads or "numerics" in reads
    tolerance = None if preview is None else preview_friction_tolerance(request.tolerance, preview)
    params, loads, pairs, analysis = force_analysis(request, table=table, tolerance=tolerance)
    result = forces_report(analysis, pairs)
    if reads is None or "crank_check" in reads:
        rough = any((pairs.f12, pairs.f23, pairs.f34, pairs.f14))
        frictionless = analyse(params, loads, Pairs(), analysis.phi, table=False) if rough else analysis
        result["crank_check"] = crank_check(analysis, frictionless,
                                            reduced_moment(params, analysis.applied, analysis.phi))
    if (reads is None or "errata" in reads) and params["e"] == 0:     # the book's formulas are for e = 0
        result["errata"] = errata.crank_slider_kinetostatics(params["l1"], params["l2"], params["a2"] * params["l2"],
                                                             loads.omega, loads.m2)
    return answer(result, analysis.notices, lang)


def preview_friction_tolerance(tolerance: float, preview: float) -> float:
    """ε_R of a preview's friction equilibrium: PREVIEW_FRICTION × the preview's fraction, never tighter than
    the request's. ε_R bounds each reaction's error relative to the largest reaction at its angle, so a
    reaction whose span is a hundredth of that largest one is still within the preview's fraction of its
    span; Newton converges quadratically, so the error left is far below the last step that ε_R measures."""
    return max(tolerance, PREVIEW_FRICTION * preview)


PREVIEW_FRICTION = 1e-2


def _general_forces(request: ForcesRequest, lang: str, reads: Reads = None, preview: Preview = None) -> Answer:
    """A general mechanism by structural groups over one turn (core/kinetostatics/groups), its free bodies at
    ``free_body_phi``; the crank check (3.2) against the reduced moment by power equality is always in it. The
    textbook's approximations beyond the first only when their table or the numerics are read (``reads``)."""
    mechanism = GeneralMechanism(request.linkage.model_dump(exclude_none=True))
    mechanism.require_crank("the kinetostatics")
    masses = request.masses.model() if request.masses is not None else MassModel()
    pairs = {name: PairFriction(p.f, p.r, p.beta) for name, p in request.pair_friction.items()}
    table = reads is None or "iteration" in reads or "numerics" in reads
    tolerance = request.tolerance if preview is None else preview_friction_tolerance(request.tolerance, preview)
    result = analyse_groups(mechanism, masses, np.linspace(0.0, 2 * np.pi, request.n), request.loads.omega,
                            request.loads.epsilon, tolerance, pairs, **({} if table else {"shown": 1}),
                            budget=FORCES_BUDGET_S)
    report = group_forces_report(result, request.free_body_phi)
    singular = change_point_mask(mechanism.linkage, np.linspace(0.0, 2 * np.pi, request.n))
    report["reduced_moment"] = undefined_at(np.asarray(report["reduced_moment"], float), singular)
    return answer(report, [*change_point_notices(mechanism.linkage), *result.notices], lang)


def wear(request: WearRequest, lang: str) -> Answer:
    """Wear at the request's speed over its service life (cycles = 60 · rpm · hours), from the kinetostatics or
    from the book's Table 4.3; beside it the constant-load models (4.3), (4.4), (4.14), (4.15) at the mean loads."""
    parts = request.model_dump(include={"pin_diameter", "pin_length", "piston_diameter", "piston_length",
                                        "I_pin", "I_bush", "I_piston", "I_cylinder"})
    cycles = 60 * request.rpm * request.hours
    if request.reactions == "table_4_3":
        return answer(book_table_report(parts, cycles), [], lang)
    if request.mechanism == "general":
        return _general_wear(request, parts, cycles, lang)
    if request.reactions != "kinetostatics":
        table = request.reactions
        return answer(table_report(table.columns(), parts, cycles, (table.l1, table.l2)), [], lang)
    _, _, _, analysis = force_analysis(request, omega=request.rpm * 2 * np.pi / 60, table=False)   # none read
    result = wear_report(analysis, parts, cycles)
    stroke = float(np.ptp(analysis.points["B"][:, 0]))
    mean_r23 = result["mean_pressure_23"] * np.pi * parts["pin_length"] * parts["pin_diameter"] / 4      # (4.23)
    k = {name: parts[f"I_{name}"] / result[f"mean_pressure_{pair}"]                                # (4.24)
         for name, pair in (("pin", 23), ("bush", 23), ("piston", 34), ("cylinder", 34))}
    result["coefficients"] = k
    result["constant_load"] = constant_load_rows(mean_r23, parts, k, cycles, stroke)
    return answer(result, analysis.notices, lang)


def _general_wear(request: WearRequest, parts: dict, cycles: float, lang: str) -> Answer:
    """Every pair's wear of a general mechanism (core/kinetostatics/general_wear.py) at the request's speed."""
    from ..core.kinetostatics.general_wear import general_wear
    mechanism = GeneralMechanism(request.linkage.model_dump(exclude_none=True))
    mechanism.require_crank("the kinetostatics")
    masses = request.masses.model() if request.masses is not None else MassModel()
    pairs = {name: PairFriction(p.f, p.r, p.beta) for name, p in request.pair_friction.items()}
    result = analyse_groups(mechanism, masses, np.linspace(0.0, 2 * np.pi, request.n), request.rpm * np.pi / 30,
                            request.loads.epsilon, request.tolerance, pairs, shown=1, budget=FORCES_BUDGET_S)
    return answer(general_wear(result, parts, cycles), result.notices, lang)


def efficiency_chain(request: ChainRequest, lang: str) -> Answer:
    """η of mechanisms in series, Π η_k (3.39), and in parallel, Σ A_k η_k / Σ A_k (3.40); no words to
    translate."""
    series = float(np.prod(request.efficiencies))
    if request.works is None:
        return Answer({"series": series})
    total = sum(request.works)
    parallel = sum(a * e for a, e in zip(request.works, request.efficiencies)) / total if total > 0 else None
    as_printed = errata.parallel_efficiency(request.efficiencies, request.works) if total > 0 else None
    return Answer({"series": series, "parallel": parallel, "errata": [as_printed] if as_printed else []})


def _friction_machine(request: FrictionInfluenceRequest) -> MachineSetup:
    """The request's machine, its geometry checked (GeometryError names the field)."""
    params = MECHANISMS["slider_crank"].check(request.params)
    loads = Loads(**request.loads.model_dump() | {"gas": None})
    wear_parts = None if request.wear is None else WearParts(**request.wear.model_dump())
    return MachineSetup(params, loads, Pairs(**request.pairs.model_dump()), np.linspace(0.0, 2 * np.pi, request.n),
                        request.tolerance, wear_parts)


def _friction_values(request: FrictionInfluenceRequest) -> tuple[np.ndarray | None, list[float]]:
    """The request's sweep (None when not asked for) and every f its answer needs: 0, f and the sweep's."""
    sweep = sweep_values(request.f_max, request.count) if "sweep" in request.outputs else None
    return sweep, [0.0, request.f, *([] if sweep is None else sweep)]


def friction_influence(request: FrictionInfluenceRequest, lang: str, study: Study | None = None) -> Answer:
    """The sweep over f and/or the cycle at f = 0 and f overlaid (core/kinetostatics/friction_influence*.py);
    ``study``: the kinetostatics of the request's machine at its f's made already (a batch)."""
    sweep, values = _friction_values(request)
    study = study or Study(_friction_machine(request), np.unique(values))
    result, notices = explorer_answer(study, request.f, Flywheel(request.delta, request.flywheel), sweep,
                                      "cycle" in request.outputs)
    return answer(result, notices, lang)


def friction_influence_batch(requests: list, lang: str, reads: Reads,
                             preview: Preview = None) -> list[Answer | GeometryError]:
    """Members whose requests differ only in f, [δ] or the flywheel given (a family of those sliders) share one
    Study: one stacked solve of the kinetostatics at all their f's, each f's forces and wear once (``preview`` is
    always None: the explorer is not PREVIEW_AWARE, its members are exact)."""
    groups: dict[bytes, list[int]] = {}
    for k, request in enumerate(requests):
        key = orjson.dumps(request.model_dump(exclude={"f", "delta", "flywheel"}), option=orjson.OPT_SORT_KEYS)
        groups.setdefault(key, []).append(k)
    outcomes: list = [None] * len(requests)
    for members in groups.values():
        values = np.unique([value for k in members for value in _friction_values(requests[k])[1]])
        study = refused_or(lambda: Study(_friction_machine(requests[members[0]]), values))
        for k in members:
            outcomes[k] = study if isinstance(study, GeometryError) else refused_or(
                lambda: friction_influence(requests[k], lang, study))
    return outcomes


FORCES_BUDGET_S = 5.0               # wall clock of a general mechanism's friction solve (the motion request's bound)
