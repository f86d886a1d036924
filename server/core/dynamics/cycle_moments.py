"""The reduced moments of a single-cylinder crank-slider machine over its cycle, their works, the powers and
the graphical integration (Chaika–Vasylenko §3.2 and §3.4: the course project's steps 8–10, Fig. 3.7).

Every moment is reduced to the crank by equal power and counted positive along ω₁ (Chaika–Vasylenko (3.24)):

    gas on the piston   M₃ = F₃ V_qB cos(F₃, V_B) = −F u₃₁      F ≥ 0 pushes the piston towards the crank
    gravity             M_G = Σ G_j V_qSj cos(G_j, V_qSj) = Σ m_j g⃗·V⃗_qSj,   j = 1, 2, 3    (after (3.29))

with g⃗ = g(−sin α, −cos α) in the mechanism's frame (x along the guide, α its inclination, (3.9)), S₁ at
ρ₁l₁ from O along OA, S₂ at a₂l₂ from A along AB, S₃ at B.  Two modes (§3.4):

    engine, two- or four-stroke (τ = 2, 4; cycle Φ = τπ):
        M_P = M₃; the useful resistance is constant over the cycle, M_kO = −A_P|Φ /(τπ)              (3.32)
        indicated power N_i = A_P|Φ ω₁/(τπ) (step 10); effective N_e = η_m N_i (printed "N_e = N_i/η_m")
    compressor or pump (Φ = 2π):
        M_kO = M₃ (the gas resists); M_O = M_kO + M_G; the motor's moment constant, M_P = −A_O|Φ /(2π)
        N_e = A_P|Φ ω₁/(2π) (without friction the gas's indicated power); the motor's N_дв = N_e/η_Σ (η_Σ of the
        drive from the motor to the crank); a power that does not apply to the machine is None

M_Σ = M_P + M_kO + M_G (3.25) without friction; A(φ) = ∫₀^φ M dφ (3.31); A_Σ = A_P + A_O + A_G.  Gravity does
no work over whole turns, so A_Σ|Φ = 0: the steady state (3.32).

The works are integrated by Simpson's rule on a fine uniform grid whose nodes hold the dead centres (where the
gas force changes branch and M₃ has a corner); the error is estimated as the largest change against the grid
of half as many intervals, relative to the largest |A| (conservative: between the indicator diagram's points
the monotone cubic is only once continuously differentiable).

Graphical integration (Fig. 3.7, the chord method): N intervals of Δx mm on a φ axis of L mm; the ordinate
y_k = M(φ at the interval's midpoint)/μ_M is read off the drawing (to ``reading`` mm), carried to the y-axis
and joined to the pole P at the distance K to the left of the origin; the chord over the interval is drawn
parallel to that ray, so the integral curve rises by Δy_A = y_k Δx/K, and A = y_A μ_A with

    μ_φ = Φ/L (rad/mm),   μ_M (N·m/mm, a standard drawing scale),   μ_A = μ_M μ_φ K (J/mm)

Read exactly (reading 0) this is the midpoint rule; the difference from the numeric integral is shown, with
the course project's relative error ε = |(A_an − A_gr)/A_an|·100 % of the cycle's work (§3.4).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..mechanisms import SLIDER_CRANK, Notice
from ..numerics import Numerics, cumulative_simpson
from .motors import INDICATOR_POINTS, Motor, gas_force, polytropic_diagram

MODES = ("two_stroke", "four_stroke", "compressor")
FINE_PER_TURN = 4096          # integration intervals per turn, at least (rounded up to hold the drawing's midpoints)
SHOWN_PER_TURN = 360          # plotted intervals per turn, about
DRAWING_SCALES = (1.0, 2.0, 2.5, 4.0, 5.0)     # standard drawing scales, × 10ᵏ


@dataclass(frozen=True)
class Masses:
    """The links' masses (kg) and gravity: ρ₁ = l_OS₁/l₁ of the crank (0: balanced), a₂ of the rod in the
    mechanism's params; g in m/s² at the guide's inclination α (rad, 0: horizontal guide, π/2: the cylinder
    above the crank)."""

    m1: float = 0.0
    crank_centre: float = 0.0
    m2: float = 0.0
    m3: float = 0.0
    g: float = 9.81
    guide_angle: float = 0.0


@dataclass(frozen=True)
class Cylinder:
    """The gas in the cylinder: mode (MODES); p_max, the largest pressure over the crankcase's (engine: the
    indicator diagram's peak; compressor: discharge over suction), Pa; bore D, m; the engine's indicator
    diagram (p/p_max at x/H = 0, 0.1, …, 1 from top dead centre; None: the assumed polytrope of motors.py);
    the compressor's suction pressure (absolute, Pa), relative clearance and polytropic exponent."""

    mode: str = "two_stroke"
    p_max: float = 0.0
    bore: float = 0.0
    expansion: tuple[float, ...] | None = None
    compression: tuple[float, ...] | None = None
    suction: float = 1e5
    clearance: float = 0.05
    exponent: float = 1.3

    @property
    def delivery_limit(self) -> float:
        """The compressor's largest pressure ratio p_d/p_s = ((1 + c)/c)ⁿ: beyond it the clearance gas re-expands
        over the whole suction stroke and nothing is delivered (volumetric efficiency 1 − c(π^(1/n) − 1) ≤ 0)."""
        return ((1 + self.clearance) / self.clearance) ** self.exponent

    @property
    def strokes(self) -> int:
        return 4 if self.mode == "four_stroke" else 2

    @property
    def cycle(self) -> float:
        """Φ = τπ."""
        return self.strokes * math.pi

    def indicator(self) -> Motor:
        """The diagram as the app's one indicator-diagram interface (motors.py) takes it."""
        if self.mode == "compressor":
            expansion, compression = compressor_diagram(1 + self.p_max / self.suction, self.clearance, self.exponent)
        else:
            expansion, compression = (self.expansion or polytropic_diagram()[0],
                                      self.compression or polytropic_diagram()[1])
        return Motor(kind="indicator", p_max=self.p_max, piston_diameter=self.bore, expansion=tuple(expansion),
                     compression=tuple(compression), strokes=self.strokes)


@dataclass(frozen=True)
class Drawing:
    """The drawing of Fig. 3.7: intervals per turn (12: the book's 30° positions), pole distance K (mm,
    30 … 60 in the book), φ axis per turn L (mm), the moment diagram's largest ordinate (mm), and the precision
    to which an ordinate is read off (mm; 0: exactly, so that what differs from the numeric integral is the
    method's own error; read to 0.5 mm the result jumps as a value crosses a reading)."""

    per_turn: int = 12
    pole: float = 40.0
    width: float = 180.0
    height: float = 60.0
    reading: float = 0.0


def compressor_diagram(pressure_ratio: float, clearance: float = 0.05,
                       exponent: float = 1.3) -> tuple[list[float], list[float]]:
    """A single-acting compressor's assumed diagram as (p − p_s)/(p_d − p_s) at x/H = 0, 0.1, …, 1 from top dead
    centre: the suction stroke (re-expansion of the clearance gas p_d (c/(c + x))ⁿ down to p_s, then p_s) and
    the compression stroke (p_s ((1 + c)/(c + x))ⁿ up to p_d, then discharge at p_d); ratio π = p_d/p_s."""
    x = np.linspace(0.0, 1.0, INDICATOR_POINTS)
    suction = np.maximum(pressure_ratio * (clearance / (clearance + x)) ** exponent, 1.0)
    compression = np.minimum(((1 + clearance) / (clearance + x)) ** exponent, pressure_ratio)
    span = pressure_ratio - 1.0
    return ((suction - 1) / span).round(4).tolist(), ((compression - 1) / span).round(4).tolist()


def gravity_moment(params: dict, masses: Masses, kinematics) -> np.ndarray:
    """M_G = Σ m_j g⃗·V⃗_qSj (Chaika–Vasylenko, M_jG after (3.29)), N·m; V_qS₁ = ρ₁l₁(sin φ, cos φ) for
    S₁ = ρ₁l₁(−cos φ, sin φ), V_qS₂ of the mechanism, V_qS₃ = (u₃₁, 0)."""
    phi, values = kinematics.phi, kinematics.values
    gx, gy = -masses.g * math.sin(masses.guide_angle), -masses.g * math.cos(masses.guide_angle)
    r1 = masses.crank_centre * params["l1"]
    crank = masses.m1 * r1 * (gx * np.sin(phi) + gy * np.cos(phi))
    rod = masses.m2 * (gx * values["v_s2"][:, 0] + gy * values["v_s2"][:, 1])
    return crank + rod + masses.m3 * gx * values["u31"]


def piston_moment(force: np.ndarray, u31: np.ndarray) -> np.ndarray:
    """M₃ = F₃ V_qB cos(F₃, V_B) = −F u₃₁ (Chaika–Vasylenko (3.24), M_3P after (3.29)): F ≥ 0 towards the crank."""
    return -force * u31


def drawing_scale(value_per_mm: float) -> float:
    """The smallest standard drawing scale (1, 2, 2.5, 4, 5 × 10ᵏ per mm) at least value_per_mm."""
    if not value_per_mm > 0:
        return 1.0
    power = 10.0 ** math.floor(math.log10(value_per_mm))
    mantissa = value_per_mm / power
    return next((m for m in DRAWING_SCALES if m >= mantissa * (1 - 1e-12)), 10.0) * power


def graphical_integration(moment_mid: np.ndarray, peak: float, cycle: float, turns: int,
                          drawing: Drawing) -> dict:
    """Fig. 3.7 as the book draws it (module docstring): the ordinates at the N interval midpoints (N·m), the
    diagram's largest |M| (sets μ_M), the cycle Φ (rad) → the scales, the ordinates read, the chords' rises and
    the integral curve in mm and in J at the N + 1 nodes."""
    intervals = moment_mid.size
    width = drawing.width * turns
    mu_phi = cycle / width
    mu_m = drawing_scale(peak / drawing.height)
    mu_a = mu_m * mu_phi * drawing.pole
    exact = moment_mid / mu_m
    read = np.round(exact / drawing.reading) * drawing.reading if drawing.reading > 0 else exact
    step = width / intervals
    rise = read * step / drawing.pole
    curve = np.concatenate([[0.0], np.cumsum(rise)])
    return {"mu_phi": mu_phi, "mu_M": mu_m, "mu_A": mu_a, "pole": drawing.pole, "width": width, "step": step,
            "reading": drawing.reading, "ordinates": read, "rises": rise, "curve_mm": curve, "work": curve * mu_a}


def _grids(cycle: float, turns: int, drawing: Drawing) -> tuple[np.ndarray, int, int]:
    """The fine grid over the cycle and the strides to the shown grid and to the drawing's midpoints: the shown
    grid has 2r intervals per drawing interval (a midpoint on a node), the fine grid an even number per shown one
    (every shown node a Simpson step node) and a whole number per half turn (the dead centres on nodes)."""
    intervals = drawing.per_turn * turns
    r = max(1, round(SHOWN_PER_TURN / (2 * drawing.per_turn)))
    shown = 2 * r * intervals
    s = 2 * math.ceil(FINE_PER_TURN * turns / (2 * shown))
    return np.linspace(0.0, cycle, shown * s + 1), s, r


def _works(moments: dict[str, np.ndarray], h: float, stride: int) -> tuple[dict, dict, float]:
    """A(φ) of each moment by Simpson on the fine grid of spacing h (steps of 2h), at its step nodes and at the
    shown nodes (every ``stride`` fine nodes), and the same on the grid of half as many intervals; the largest
    difference relative to the largest |A|."""
    fine = {name: cumulative_simpson(m, 2 * h) for name, m in moments.items()}
    coarse = {name: cumulative_simpson(m[::2], 4 * h) for name, m in moments.items()}
    keep = stride // 2
    shown = {name: a[::keep] for name, a in fine.items()}
    error = 0.0
    for name, a in fine.items():
        scale = float(np.max(np.abs(a)))
        if scale > 0:
            error = max(error, float(np.max(np.abs(a[::2] - coarse[name]))) / scale)
    return shown, fine, error


def cycle_moments(params: dict, masses: Masses, cylinder: Cylinder, omega: float, efficiency: float,
                  drawing: Drawing) -> tuple[dict, list[Notice]]:
    """Steps 8–10 of the course project for the crank-slider ``params`` (l1, l2, e, a2 in m) at the crank speed
    ω₁ (rad/s): the moments and works over the cycle (shown grid), the constant moment that balances the cycle,
    the powers, the graphical integration beside the numeric one, and the numerics."""
    started = time.perf_counter()
    mechanism = SLIDER_CRANK
    p = mechanism.check(params)
    cycle, turns = cylinder.cycle, cylinder.strokes // 2
    phi, stride, r = _grids(cycle, turns, drawing)
    kinematics = mechanism.evaluate(p, phi, set())
    gas = piston_moment(gas_force(cylinder.indicator(), mechanism, p, phi, kinematics), kinematics.values["u31"])
    gravity = gravity_moment(p, masses, kinematics)
    engine = cylinder.mode != "compressor"
    integrated = gas if engine else gas + gravity          # A_P of the engine (step 9), A_O of the compressor
    shown, fine, error = _works({"gas": gas, "gravity": gravity, "integrated": integrated},
                                float(phi[1] - phi[0]), stride)
    cycle_work = float(fine["gas"][-1])                  # A₃|Φ: A_P of the engine, A_kO of the compressor
    balancing = -cycle_work / cycle                      # the constant M_kO (engine) or M_P (compressor), (3.32)
    nodes = phi[::stride]
    constant = np.full_like(nodes, balancing)
    variable, gravity_shown = gas[::stride], gravity[::stride]
    moments = {"P": variable if engine else constant, "kO": constant if engine else variable,
               "G": gravity_shown, "sum": variable + gravity_shown + constant}
    works = {"P": shown["gas"] if engine else balancing * nodes, "kO": balancing * nodes if engine else shown["gas"],
             "G": shown["gravity"]}
    works["O"] = works["kO"] + works["G"]
    works["sum"] = works["P"] + works["kO"] + works["G"]
    moments["O"] = moments["kO"] + moments["G"]
    driving = cycle_work if engine else -cycle_work     # A_P|Φ = |A_O|Φ| (3.32)
    power = driving * omega / cycle
    powers = ({"indicated": power, "effective": efficiency * power, "effective_printed": power / efficiency,
               "motor": None} if engine else
              {"indicated": power, "effective": power, "effective_printed": None, "motor": power / efficiency})
    graphical = _drawing(phi, integrated, fine["integrated"], stride, r, cylinder, drawing)
    graphical["integrated"] = "P" if engine else "O"
    notices = []
    if driving == 0:
        notices.append(Notice("cycle_no_work", "The gas does no work over the cycle (p_max = 0): nothing to "
                              "balance, the powers are zero and the relative error ε of the graphical integration "
                              "is not defined."))
    elif not engine and 1 + cylinder.p_max / cylinder.suction >= cylinder.delivery_limit:
        ratio = 1 + cylinder.p_max / cylinder.suction
        notices.append(Notice("compressor_no_delivery", f"The pressure ratio p_d/p_s = {ratio:.3g} is at least "
                              f"((1 + c)/c)ⁿ = {cylinder.delivery_limit:.3g}: the clearance gas re-expands over the "
                              "whole suction stroke, the compressor delivers nothing and its diagram (a polytrope "
                              "there and back through 11 points) is no longer a working cycle.",
                              {"ratio": ratio, "limit": cylinder.delivery_limit}))
    elif driving < 0:
        notices.append(Notice("cycle_work_reversed", f"Over the cycle the gas does {driving:.4g} J on the "
                              "driving side: the diagram takes more work on compression than it gives on "
                              "expansion, so the constant moment that balances the cycle drives instead of "
                              "resisting.", {"work": driving}))
    numerics = Numerics(
        method="M₃ = −F u₃₁ and M_G = Σ m g⃗·V⃗_qS in closed form at each angle; the works by Simpson's rule on a "
               "uniform grid with the dead centres on its nodes, error estimated against the grid of half as many "
               "intervals, relative to the largest |A|", code="cycle_works_simpson",
        steps=int(phi.size - 1), runtime_ms=1e3 * (time.perf_counter() - started), error_estimate=error)
    result = {"mode": cylinder.mode, "strokes": cylinder.strokes, "cycle": cycle, "phi": nodes,
              "moments": moments, "works": works, "cycle_work": driving, "balancing_moment": balancing,
              "powers": powers, "graphical": graphical, "numerics": numerics.as_dict()}
    return result, notices


def _drawing(phi: np.ndarray, moment: np.ndarray, work: np.ndarray, stride: int, r: int, cylinder: Cylinder,
             drawing: Drawing) -> dict:
    """Fig. 3.7 on the cycle's grids (``_grids``): the moment integrated and its numeric work (at the fine grid's
    step nodes) → the construction, its comparison, and what the plots draw on the shown grid (the moment, the
    numeric curve, the chords, their ends and the midpoint ordinates; NaN between the marks)."""
    per_interval = 2 * r * stride                         # fine nodes per drawing interval
    node_index = np.arange(0, phi.size, per_interval)
    midpoints = node_index[:-1] + per_interval // 2
    graphical = graphical_integration(moment[midpoints], float(np.max(np.abs(moment))), cylinder.cycle,
                                      cylinder.strokes // 2, drawing)
    graphical |= _comparison(graphical, work[node_index // 2], phi[node_index], phi[midpoints], moment[midpoints])
    nodes = phi[::stride]
    chords = np.interp(nodes, phi[node_index], graphical["work"])
    index = np.arange(nodes.size) % (2 * r)
    return graphical | {"moment": moment[::stride], "numeric_curve": work[::stride // 2], "chords": chords,
                        "node_marks": np.where(index == 0, chords, np.nan),
                        "midpoint_marks": np.where(index == r, moment[::stride], np.nan),
                        "sheet": _sheet(graphical, nodes, moment[::stride], phi[midpoints])}


def _sheet(graphical: dict, phi: np.ndarray, moment: np.ndarray, midpoints: np.ndarray) -> dict:
    """Fig. 3.7 on the drawing sheet, in mm, as one abscissa ``x`` and one ordinate per element, NaN outside its
    own stretch (a plot draws every element against the same x): the moment diagram M/μ_M over φ/μ_φ; each
    ordinate y_k carried from the interval's midpoint to the y-axis; the ray from the pole P(−K, 0) to (0, y_k);
    the integral curve y_A, whose chord over interval k is parallel to ray k (rise y_k Δx/K over Δx)."""
    mu_phi, pole, y = graphical["mu_phi"], graphical["pole"], graphical["ordinates"]
    gap = np.full(y.size, np.nan)
    carried = np.column_stack([midpoints / mu_phi, 0 * y, gap]).ravel()
    rays = np.column_stack([np.full(y.size, -pole), 0 * y, gap]).ravel()
    ends = np.column_stack([y, y, gap]).ravel()
    ray_y = np.column_stack([0 * y, y, gap]).ravel()
    nodes = np.arange(graphical["curve_mm"].size) * graphical["step"]
    parts = [(phi / mu_phi, moment / graphical["mu_M"]), (carried, ends), (rays, ray_y), (nodes, graphical["curve_mm"])]
    x = np.concatenate([part[0] for part in parts])
    elements = {}
    start = 0
    for name, (xs, ys) in zip(("diagram", "carried", "rays", "integral"), parts):
        column = np.full(x.size, np.nan)
        column[start:start + xs.size] = ys
        elements[name] = column
        start += xs.size
    return {"x": x} | elements


def _comparison(graphical: dict, numeric: np.ndarray, nodes: np.ndarray, midpoints: np.ndarray,
                moment_mid: np.ndarray) -> dict:
    """The graphical integral beside the numeric one at the nodes, their difference, the steps as a table, and
    ε = |(A_an − A_gr)/A_an| of the cycle's work (None where the numeric work over the cycle is zero)."""
    work = graphical["work"]
    total = float(numeric[-1])
    epsilon = abs((total - float(work[-1])) / total) if total != 0 else None
    rows = [{"k": k + 1, "phi_mid": float(midpoints[k]), "M_mid": float(moment_mid[k]),
             "y_mid": float(graphical["ordinates"][k]), "rise": float(graphical["rises"][k]),
             "y_A": float(graphical["curve_mm"][k + 1]), "A_graphical": float(work[k + 1]),
             "A_numeric": float(numeric[k + 1]), "difference": float(work[k + 1] - numeric[k + 1])}
            for k in range(midpoints.size)]
    return {"numeric": numeric, "difference": work - numeric, "epsilon": epsilon, "rows": rows}
