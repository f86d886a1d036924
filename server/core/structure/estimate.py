"""A first estimate of a general mechanism's masses, loads and motor, for a student's own linkage that has none
(the editor's "Masses and loads" table starts from it; every number is the student's to change).

Assumptions, stated on the page (content/i18n: editor_masses_note):

- every moving link is a uniform bar of q = 10 kg/m (BAR_DENSITY) between its origin joint and its farthest
  joint or point: l = max |w| over the joints fixed on it (w = (z − z_O) e^{−iθ}, constant over φ on the link),
  m = q·l, S at the middle of that line, w_S = w_far/2, and J_S = m l²/12 (a thin rod about its middle);
  a link with one joint only (a slider block) has m = BLOCK_MASS = 2 kg and J_S = 0;
- the crank is a bar of q about its pivot: J₁ = q l₁³/3 (m l²/3);
- the last slider on a frame guide (if any) carries the useful load P = WORKING_FORCE = 1000 N on its slow stroke
  (the stroke that takes the larger share of the turn) and k·P on the return, k = 0.1 (the textbook's 0.05…0.1);
  a linkage without one: the last link carries a load moment P·l/2 (P at half its length) the same way;
- a linear motor through a gear i = 10 whose reduced characteristic i·M(iω) = M₀ − bω carries the load from rest:
  M₀ = 1.5 × the largest static resisting moment max_φ (|P(φ) s′| + Σ m g |y′_S|) (power equality at ω → 0), and b
  such that the steady mean speed is about ω_target = 10 rad/s: M₀ − b ω_target = M_mean, M_mean = (1/2π)∮ M_useful dφ
  the useful load's mean moment over a turn (P H (1 + k)/2π for a slider of stroke H; the weights do no work over a turn); at the
  motor shaft M₀/i and b/i²;
- the rotor's J_rotor such that J_rotor i² is 5 × the links' largest reduced inertia max_φ Σ (m |z′_S|² + J_S θ′²)
  and at least A/([δ] ω_target²) with A = 2π M_mean the useful work per turn (the most the kinetic energy can swing)
  and [δ] = 0.2, and at least 10⁻³ kg·m²: the constant part of J(φ) dominates, so the fluctuation stays moderate
  (the flywheel scene then sizes a flywheel for a smaller [δ]);
- the flywheel's request: a constant motor moment M_mean/i (the work per turn balanced), ω_mean = ω_target and
  [δ] = 0.05 (machine tools, Lecture 10).

Beside them, ``load_places``: every sliding pair and moving link where the student may put a useful load, each
with a first load as above on its own slow stroke (the editor's "add a load").
"""
from __future__ import annotations

import math

import numpy as np

from ..mechanisms.general import GeneralMechanism
from .compose import compose
from .masses import MassModel, SliderForce, slider_loads
from .spec import Linkage

BAR_DENSITY = 10.0        # q, kg per metre of a link's length
BLOCK_MASS = 2.0          # kg, a link with a single joint (a slider block)
WORKING_FORCE = 1000.0    # P, N, on the last frame slider's slow stroke
RETURN_FACTOR = 0.1       # k on the return stroke
OMEGA_TARGET = 10.0       # rad/s, the mean crank speed the motor is sized for
GEAR_RATIO = 10.0        # i = ω_motor/ω_crank
DELTA_TARGET = 0.2        # δ the rotor is sized for, at most
ROTOR_SHARE = 5.0        # J_rotor i² over the links' largest reduced inertia
MOTOR_MARGIN = 1.5        # M₀ over the largest static resisting moment
GRAVITY = 9.81
FLYWHEEL_DELTA = 0.05
POINTS = 721              # 0.5° of crank angle
SAME = 1e-9               # m: a joint whose local coordinate varies less than this is fixed on the link


def _local_points(comp, link: int) -> list[complex]:
    """The local coordinates w of every joint fixed on the link (its origin at 0 included)."""
    origin, angle = comp.links[link]
    found = []
    for point in comp.joints.values():
        w = (point.z - origin.z) * np.exp(-1j * angle.th)
        finite = w[np.isfinite(w)]
        if finite.size and np.ptp(finite.real) < SAME and np.ptp(finite.imag) < SAME:
            found.append(complex(finite.mean()))
    return found


def link_bars(linkage: Linkage) -> list[dict]:
    """Every moving link but the crank as a uniform bar or a block: [{link, mass, centre [along, across],
    inertia}] in the order of the linkage's links."""
    comp = compose(linkage, np.linspace(0.0, 2 * math.pi, 9))
    rows = []
    for link in sorted(comp.links):
        if link == linkage.crank.link:
            continue
        far = max(_local_points(comp, link), key=abs, default=0j)
        length = abs(far)
        if length < SAME:
            rows.append({"link": link, "mass": BLOCK_MASS, "centre": [0.0, 0.0], "inertia": 0.0})
            continue
        mass = BAR_DENSITY * length
        rows.append({"link": link, "mass": _nice(mass, 6), "centre": [round(far.real / 2, 9), round(far.imag / 2, 9)],
                     "inertia": _nice(mass * length ** 2 / 12, 6)})
    return rows


def estimated_dynamics(raw_linkage: dict) -> dict:
    """The estimate's "masses", "inertias", "motor" and "flywheel" for the linkage's JSON (as a preset's
    "dynamics"); a slider-driven linkage, or one whose crank cannot turn fully, has no dynamics (GeometryError,
    as the dynamics endpoints answer)."""
    mechanism = GeneralMechanism(raw_linkage)
    mechanism.require_crank("the dynamics")
    mechanism.require_full_turn()
    linkage = mechanism.linkage
    bars = link_bars(linkage)
    phi = np.linspace(0.0, 2 * math.pi, POINTS)
    comp = compose(linkage, phi)
    places = load_places(linkage, comp, bars)
    forces, moments, useful = [], [], np.zeros(POINTS)
    frame_slides = [name for name in comp.slides if name.split("/")[-1] in linkage.guides]
    if frame_slides:
        force = next(f for f in places["forces"] if f["joint"] == frame_slides[-1])
        forces.append(force)
        s1 = np.nan_to_num(comp.slides[force["joint"]].d1)
        useful += np.where(force["sense"] * s1 >= 0, 1.0, RETURN_FACTOR) * WORKING_FORCE * np.abs(s1)
    elif bars:
        moment = next(m for m in places["moments"] if m["link"] == bars[-1]["link"])
        moments.append(moment)
        theta1 = np.nan_to_num(comp.links[moment["link"]][1].d1)
        useful += np.where(moment["sense"] * theta1 >= 0, 1.0, RETURN_FACTOR) * moment["working"] * np.abs(theta1)
    mean_moment = float(np.trapezoid(useful, phi) / (2 * math.pi))
    resisting = useful.copy()
    links_inertia = np.zeros(POINTS)
    for row in bars:
        origin, angle = comp.links[row["link"]]
        z1 = np.nan_to_num(origin.d1 + 1j * angle.d1 * complex(*row["centre"]) * np.exp(1j * angle.th))
        resisting += row["mass"] * GRAVITY * np.abs(z1.imag)
        links_inertia += row["mass"] * np.abs(z1) ** 2 + row["inertia"] * np.nan_to_num(angle.d1) ** 2
    crank_length = float(linkage.crank.length)
    j1 = BAR_DENSITY * crank_length ** 3 / 3
    m0 = max(MOTOR_MARGIN * float(resisting.max()), 1.0)
    b = (m0 - mean_moment) / OMEGA_TARGET
    reduced = max(ROTOR_SHARE * float(links_inertia.max()), 2 * math.pi * mean_moment / (DELTA_TARGET * OMEGA_TARGET ** 2))
    rotor = max(reduced / GEAR_RATIO ** 2, 1e-3)
    return {
        "masses": {"links": bars, "gravity": GRAVITY, "forces": forces, "moments": moments},
        "inertias": {"J1": _nice(j1, 6), "J_rotor": _nice(rotor), "gear_ratio": GEAR_RATIO},
        "motor": {"kind": "linear", "M0": _nice(m0 / GEAR_RATIO), "b": _nice(b / GEAR_RATIO ** 2)},
        "flywheel": {"motor": {"kind": "constant", "M0": _nice(max(mean_moment, 0.0) / GEAR_RATIO)},
                     "omega_mean": OMEGA_TARGET, "delta": FLYWHEEL_DELTA, "balance": True},
        "load_places": places,
    }


def load_places(linkage: Linkage, comp, bars: list[dict]) -> dict:
    """Where a useful load may stand, each place with a first load the student may add and change: every sliding
    pair (named as in ``slides``, as masses.forces.joint takes it) with P = 1000 N, and every moving link (the crank
    too) with M = P·l/2 (l its bar's length, the crank's l₁, 0.1 m for a block), both with k = 0.1 and the sense
    of the slow stroke: the one the pair's velocity analog along its guide w (as masses.py loads it) or the
    link's θ′ keeps over more of the turn."""
    mechanism_loads = slider_loads(comp, MassModel(forces=tuple(SliderForce(name, WORKING_FORCE)
                                                                for name in comp.slides)))
    forces = [{"joint": load.force.joint, "working": WORKING_FORCE, "k": RETURN_FACTOR,
               "sense": _slow_sense(np.nan_to_num(load.along))} for load in mechanism_loads]
    lengths = {row["link"]: 2 * abs(complex(*row["centre"])) for row in bars}
    lengths[linkage.crank.link] = float(linkage.crank.length)
    moments = [{"link": link, "working": _nice(WORKING_FORCE * (lengths.get(link) or 0.1) / 2), "k": RETURN_FACTOR,
                "sense": _slow_sense(np.nan_to_num(comp.links[link][1].d1))} for link in sorted(comp.links)]
    return {"forces": forces, "moments": moments}


def _slow_sense(rate: np.ndarray) -> int:
    """+1 where the output moves forward (s′ or θ′ > 0) over more of the turn than back: the slow stroke."""
    return 1 if np.count_nonzero(rate > 0) >= np.count_nonzero(rate < 0) else -1


def _nice(value: float, digits: int = 3) -> float:
    """A few significant digits (a number a student reads and types)."""
    return float(f"{value:.{digits}g}") + 0.0
