"""The whole course project of a linkage in steady motion (Chaika–Vasylenko §3.4) from one request: the structure,
the positions, the kinematics sheet at the real motion, the dynamics sheet with the flywheel for [δ], and the
kinetostatics at a chosen position with Zhukovsky's lever, and the balancing moment at every position three ways.

One machine (dynamics/general_machine.py: its tables of J, J′, M_c between the kinks, built once) answers the
dynamics; the kinetostatics of all N positions, and of a fine grid over the turn for the cycle's efficiency, is one
vectorised call of the groups' analysis at the real ω₁(φ), ε₁(φ).  The balancing moment M_b (on the crank's
link, positive along ω₁; group I — J₁, the rotor, the flywheel — sits on the crank's shaft, not in the groups):

    by the groups:            the crank's equilibrium (kinetostatics/groups, Chaika–Vasylenko §3.1)
    by Zhukovsky's lever:     zhukovsky.py (virtual power on the turned velocity plan)
    by the reduced equation:  M_b = J_II ε₁ + ½ J′ ω₁² − M_loads       Eremyants (1.1)–(1.5)
                              (J_II = J − J₁ − J_rotor i² − I_fly: the linkage's part, J′ its slope; M_loads the
                              reduced moment of every load and weight, positive where it drives)

and with no friction M_b + I_I ε₁ = M_д at every position (the reduced equation of motion with the constant
driving moment, Eremyants (1.13)).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..dynamics import report as dynamics_report
from ..dynamics.general_machine import general_machine
from ..dynamics.motors import Motor
from ..dynamics.reduction import Inertias
from ..dynamics.resistance import Load
from ..kinetostatics.groups.analysis import analyse
from ..kinetostatics.groups.friction import PairFriction
from ..mechanisms import GeometryError, Notice
from ..mechanisms.general import GeneralMechanism
from ..numerics import Numerics
from ..structure.masses import MassModel, with_strokes
from ..structure.reduction import reduced_inertia, reduced_loads
from . import kinetostatic_sheet as ks
from .dynamic_sheet import dynamic_sheet
from .kinematic_sheet import kinematic_sheet
from .positions import TWO_PI, stroke_positions
from .real_motion import real_motion, resistance
from .scales import FORCE_PLAN_MM, extent, standard_scale
from .zhukovsky import at_angle, difference_percent, lever

WIDTH_RATIO = 0.2          # the flywheel disk's b/D (Lecture 10 §10.6)
DENSITY = 7800.0           # steel, kg/m³
TOLERANCE = 1e-9           # ε_R of the friction equilibrium
BUDGET_S = 5.0             # wall clock of the friction solve (the forces request's bound)
EFFICIENCY_POINTS = 360    # the fine grid over the turn of the kinetostatics' efficiency (a closed grid's points)
USEFUL_FLOOR = 1e-9        # the useful loads' work over the turn below this share of ∫|M_c|: no useful load


def course_project(linkage: dict, masses: MassModel | None, inertias: Inertias, pairs: dict[str, PairFriction],
                   omega_mean: float, delta: float, count: int = 12, start: float | None = None,
                   output: str | None = None, chosen: int | None = None,
                   drawn: list[int] | None = None) -> tuple[dict, list[Notice]]:
    """The answer of the course-project endpoint (docs/course_project.md) and its notices; GeometryError names
    the field of a request the project cannot be done for."""
    mechanism = GeneralMechanism(linkage)
    positions = stroke_positions(mechanism, masses, count, start, output)
    asked = ([("chosen", chosen)] if chosen is not None else []) + [(f"drawn.{i}", k) for i, k in enumerate(drawn or [])]
    for where, k in asked:
        if not 1 <= k <= count:
            raise GeometryError(where, f"position {k} is not among the positions 1…{count}", "project_position",
                                number=k, count=count)
    if masses is None or not any(item.mass > 0 or item.inertia > 0 for item in masses.links):
        raise GeometryError("masses.links", "the dynamics and the kinetostatics need the links' masses: give at "
                            "least one moving link a mass or a moment of inertia", "project_needs_masses")
    masses = with_strokes(mechanism, masses)          # every stroke diagram's extremes, once for every part
    loaded = any(f.working > 0 for f in masses.forces) or any(m.working > 0 for m in masses.moments) or \
        any(p.magnitude > 0 for p in masses.point_forces)
    machine = general_machine(linkage, masses, inertias, Load(), Motor("constant", 0.0), pairs) if loaded else None
    resisting = resistance(machine) if loaded else None
    if not loaded or not resisting.useful_work > USEFUL_FLOOR * resisting.magnitude:
        raise GeometryError("masses.forces", "the useful loads do no work over the turn: the course project's "
                            "machine needs a useful load (a force on a slider or at a point, a moment on a link) for "
                            "its motor to drive against", "project_needs_load")
    machine = replace(machine, motor=Motor("constant", resisting.driving_moment / inertias.gear_ratio), memo={})
    flywheel, notices = dynamics_report.flywheel(machine, omega_mean, delta, True, WIDTH_RATIO, DENSITY)
    if not flywheel:
        raise GeometryError("masses", " ".join(n.text for n in notices) or "no steady cycle", "project_no_cycle")
    motion = real_motion(resisting, flywheel["flywheel_inertia"], omega_mean)
    state = motion.state(positions.phi)
    sheet = kinematic_sheet(mechanism, positions, state["omega"], state["epsilon"], masses)
    notices = notices + [Notice(n["code"], n["text"], n["context"]) for n in sheet.pop("notices")]
    kinetics = kinetostatics(mechanism, masses, pairs, motion, positions.phi, sheet["scales"]["mu_v"])
    number = chosen or int(np.argmax(np.abs(kinetics["useful"]))) + 1      # the largest useful load by default
    at_chosen, mu_f = chosen_sheet(kinetics, number - 1)
    return {
        "structure": mechanism.structure,
        "positions": positions.as_dict() | {"chosen": number, "drawn": sorted(set(drawn or [number]))},
        "scales": sheet["scales"] | {"mu_F": mu_f},
        "plan_of_positions": sheet["plan_of_positions"],
        "kinematics": sheet["kinematics"],
        "output_diagrams": sheet["output_diagrams"],
        "dynamics": dynamic_sheet(machine, flywheel, motion),
        "kinetostatics": at_chosen,
        "table": table(kinetics, positions.working),
    }, notices + kinetics["result"].notices


def useful_moment(result) -> np.ndarray:
    """The reduced moment of the useful loads alone, −Σ(F·z′ + M θ′) (N·m, positive where they resist)."""
    total = np.zeros(result.phi.shape)
    for load in result.loads:
        if load.kind == "useful":
            total = total - ((np.conj(load.force) * load.rate).real if load.force is not None
                             else load.moment * load.rate)
    return total


def kinetostatics(mechanism: GeneralMechanism, masses: MassModel, pairs: dict[str, PairFriction], motion,
                  phi: np.ndarray, mu_v: float | None) -> dict:
    """The groups' analysis at the N positions and EFFICIENCY_POINTS angles of the turn in one call, at the real
    ω₁, ε₁; the levers without and with friction; the reduced equation's balancing moment; the useful loads'
    reduced moment; the cycle's efficiency with friction."""
    fine = np.linspace(0.0, TWO_PI, EFFICIENCY_POINTS, endpoint=False)
    angles = np.concatenate([phi, fine])
    state = motion.state(angles)
    omega, epsilon = state["omega"], state["epsilon"]
    result = analyse(mechanism, masses, angles, omega, epsilon, TOLERANCE, pairs, shown=1, budget=BUDGET_S)
    mu_v = mu_v or 1.0
    linkage_part = reduced_inertia(mechanism, result.comp, masses, 0.0)
    loads = reduced_loads(mechanism, result.comp, masses)
    reduced = linkage_part.J * epsilon + 0.5 * linkage_part.dJ * omega**2 + loads.total
    return {"result": result, "crank": mechanism.linkage.crank, "omega": omega, "epsilon": epsilon,
            "useful": useful_moment(result)[:phi.size], "reduced": reduced,
            "frictionless": lever(result, omega, mu_v),
            "friction": lever(result, omega, mu_v, result.solution) if result.rough else None,
            "efficiency": cycle_efficiency(result, phi.size)}


def cycle_efficiency(result, first: int) -> dict:
    """η = A_useful/(A_useful + A_friction) over the turn at the real motion (Chaika–Vasylenko (3.38)), from the
    fine grid's angles (``first`` on): A_useful = ∫ of the useful loads' reduced moment, A_friction =
    ∫ Σ|z_p · relative_p| (what the pairs dissipate per unit crank angle), by the trapezoid rule on the closed
    uniform grid (the mean times 2π); its error estimated by the rule on every other point."""
    if not result.rough:
        return {"efficiency": 1.0, "work_useful": None, "work_friction": 0.0, "numerics": None}
    useful = useful_moment(result)[first:]
    lost = sum(np.abs(result.solution.friction[k, first:] * p.relative[first:]) for k, p in enumerate(result.pairs))
    if not (np.isfinite(lost).all() and np.isfinite(useful).all()):
        return {"efficiency": None, "work_useful": None, "work_friction": None, "numerics": None}
    ratio = lambda u, f: abs(u.mean()) / (abs(u.mean()) + f.mean())
    eta, coarse = ratio(useful, lost), ratio(useful[::2], lost[::2])
    numerics = Numerics(method="the trapezoid rule over the turn on a closed uniform grid of the kinetostatics with "
                               "friction at the real motion; error against the rule on every other point",
                        code="project_efficiency", steps=int(useful.size),
                        error_estimate=abs(coarse - eta) / eta if eta > 0 else None)
    return {"efficiency": float(eta), "work_useful": float(TWO_PI * useful.mean()),
            "work_friction": float(TWO_PI * lost.mean()), "numerics": numerics.as_dict()}


def chosen_sheet(kinetics: dict, k: int) -> tuple[dict, float | None]:
    """The kinetostatics at position index k: the inertia loads, the free bodies group by group and the force
    plans at μ_F (one standard scale for both analyses), the balancing moment and the lever; with friction the
    same with friction and the efficiency."""
    result, omega = kinetics["result"], kinetics["omega"]
    rows = [("frictionless", result.approximations[0])] + ([("friction", result.solution)] if result.rough else [])
    reach = [ks.group_sheets(result, row, k, 1.0)[1] for _, row in rows]        # at 1 N/mm: the plans' extent
    span = max((extent([v[end] for plan in plans for v in plan["vectors"] for end in ("from", "to")])
                for plans in reach), default=0.0)
    mu_f = standard_scale(span, FORCE_PLAN_MM)
    sheets = {}
    for name, row in rows:
        bodies, plans = ks.group_sheets(result, row, k, mu_f or 1.0)
        levered = kinetics[name]
        sheets[name] = {
            "groups": bodies, "force_plans": plans, "balancing_moment": float(row.balancing[k]),
            "zhukovsky": {"moment": float(levered.balancing[k]), "lever": at_angle(levered, k),
                          "mu_v": levered.mu_v, "pole": [0.0, 0.0],
                          "images": images(result, omega, levered.mu_v, k),
                          "balancing_force": balancing_force(kinetics["crank"], result, float(omega[k]),
                                                             levered.mu_v, float(row.balancing[k]), k),
                          "difference_percent": float(difference_percent(levered.balancing, row.balancing,
                                                                         levered.rows)[k])}}
    answer = {"number": k + 1, "phi": float(result.phi[k]), "omega1": float(omega[k]),
              "epsilon1": float(kinetics["epsilon"][k]), "inertia": ks.inertia_loads(result, k),
              **sheets["frictionless"], "reduced_moment": float(kinetics["reduced"][k]),
              "friction": None if not result.rough else sheets["friction"] | kinetics["efficiency"],
              "numerics": result.numerics}
    return answer, mu_f


def balancing_force(crank, result, omega: float, mu_v: float, moment: float, k: int) -> dict:
    """The textbook's balancing force at the crank pin A, perpendicular to OA, F_b = M_b/l₁ (its moment about O is
    M_b along ω₁), on the lever at A's image: its lever moment −M_b ω₁/μ_v balances the rows'."""
    pivot, pin = result.comp.joints[crank.pivot], result.comp.joints[crank.joint]
    along = (pin.z[k] - pivot.z[k]) / crank.length
    force = crank.sense * moment / crank.length * 1j * along
    image = 1j * pin.d1[k] * omega / mu_v
    lever_moment = float((np.conj(image) * force).imag)
    return {"joint": crank.joint, "at": ks.xy(pin.z[k]), "image": ks.xy(image), "force": ks.xy(force),
            "arm": lever_moment / abs(force) if force else 0.0, "moment": lever_moment}


def images(result, omega: np.ndarray, mu_v: float, k: int) -> dict:
    """Every joint's image on the turned velocity plan at angle index k, mm from the pole: i v/μ_v."""
    return {name: ks.xy(1j * p.d1[k] * omega[k] / mu_v) for name, p in result.comp.joints.items()}


def table(kinetics: dict, working: np.ndarray) -> list[dict]:
    """One row per position: ω₁, ε₁, the balancing moment by the groups, the lever, the reduced equation, with
    friction (by the groups and the lever), and the useful loads' reduced moment (N·m)."""
    result = kinetics["result"]
    plain, rough = kinetics["frictionless"], kinetics["friction"]
    first = result.approximations[0].balancing
    differ = difference_percent(plain.balancing, first, plain.rows)
    rows = []
    for k in range(working.size):
        rows.append({"number": k + 1, "phi": float(result.phi[k]), "working": bool(working[k]),
                     "omega1": float(kinetics["omega"][k]),
                     "epsilon1": float(kinetics["epsilon"][k]), "M_b_groups": float(first[k]),
                     "M_b_lever": float(plain.balancing[k]), "M_b_reduced": float(kinetics["reduced"][k]),
                     "difference_percent": float(differ[k]),
                     "M_b_friction": None if rough is None else float(result.solution.balancing[k]),
                     "M_b_lever_friction": None if rough is None else float(rough.balancing[k]),
                     "useful_load": float(kinetics["useful"][k])})
    return rows
