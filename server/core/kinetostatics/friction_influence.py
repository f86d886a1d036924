"""Friction's influence on the crank-slider machine: Chaika–Vasylenko §3.4, steps 18–19 of the course project
(compute the friction moment and its work, ω₁, the efficiency and the flywheel with friction, and compare them
with the frictionless machine), and the wear of §4.

One coefficient f in every pair (f₁₄ = f₁₂ = f₂₃ = f₃₄ = f), for each f of a sweep:
- the kinetostatics with friction, §3.1 (3.3)–(3.20), at the mean speed ω_m (step 17, then step 18 takes its
  reactions), for every f at once: crank_slider.motion once, equilibrium.solve on the stacked (f, φ) grid.  Each
  angle's solve is its own, so the stacked solve equals crank_slider.analyse at each f to the last bit;
- the peak |R| of each pair and of the balancing moment M_ур, and its cycle mean (the constant M_д below);
- η = A_useful/(A_useful + A_friction) over the cycle (3.38), report.efficiency;
- the equation of motion in energy form (3.31)–(3.33), J(φ)ω₁²/2 = T₀ + A(φ), with
      M_с(φ) = M_P(φ) + M_G(φ) + M_тр(φ)                                                       (3.29)
  M_P and M_G the reduced moments of the slider's load and of gravity by power equality (virtual_work), and
      M_тр = f₃₄|R₃₄||V_qB| + f₁₂|R₁₂|r₁₂|1 − u₂₁| + f₂₃|R₂₃|r₂₃|u₂₁| + f₁₄|R₁₄|r₁₄        (3.30)
  from the kinetostatic reactions; a constant driving moment M_д = A_с/(2π), so A_д = A_с over the cycle
  (3.32): the mode of §3.4 for pumps and compressors.  A(φ) = ∫(M_д − M_с)dφ by the trapezoid rule;
- δ = (ω_max − ω_min)/ω_m of the periodic solution with group I = J₁ + the flywheel given (Lecture 10 §10.4,
  flywheel.achieved_delta), and the group-I inertia that [δ] needs, found exactly (flywheel.exact), less J₁:
  the flywheel J_м needed;
- the wear of the pin, bush, piston and cylinder (§4, (4.12)–(4.21), report.wear_report) with the wear
  coefficients k = I_s/p_m (4.24) of the frictionless machine kept for every f: the materials do not change
  with f, and with k taken anew at each f, (4.24) would divide the load's growth out again.
Self-locking from the physics at each f (equilibrium.solve: the rod's line of force within the guide's friction
angle, or the friction equilibrium folding); where it locks the f has no cycle, said in words.  The f at which
it begins, by the line-of-force criterion f₃₄|tan ψ′| = 1 (equilibrium.locking_ratio), by Brent's method.
The answer the page draws is made from a Study by friction_influence_report.explorer_answer.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from ..dynamics import flywheel as fw
from ..dynamics.compiled import speed_extremes
from ..dynamics.reduction import Inertias, reduced_inertia
from ..mechanisms import GeometryError, Notice
from . import equilibrium
from .crank_slider import Approximation, ForceAnalysis, Loads, Pairs, cross, friction_loads, motion, solve_dyad
from .report import efficiency
from .wear import mean_pressure, piston_wear
from .virtual_work import reduced_moment

PAIRS = ("R12", "R23", "R34", "R41")
WEAR_PARTS = ("bush", "pin", "piston", "cylinder")
F_CEILING = 2.0          # the largest f the API takes: the onset of self-locking is sought below it
LOCKING_SCAN = 64        # f values on [0, F_CEILING] scanned for the first where the locking ratio reaches 1
BETA = np.radians(np.arange(0, 361, 5))       # the pin's and bush's surface points of report.wear_report
COS_BETA, SIN_BETA = np.cos(BETA), np.sin(BETA)
CYLINDER_POINTS = 121                          # points along the cylinder, as report.wear_report
SECANT_STEPS = 12                              # more: the flywheel needed by Brent's method (flywheel.exact)


@dataclass(frozen=True)
class WearParts:
    """The pin and piston (m), the wear intensities I_s of Table 1.1 and the service life (h) of §4.3."""

    pin_diameter: float = 0.02
    pin_length: float = 0.025
    piston_diameter: float = 0.075
    piston_length: float = 0.076
    I_pin: float = 0.6e-10
    I_bush: float = 1.0e-10
    I_piston: float = 2e-12
    I_cylinder: float = 3e-12
    hours: float = 1000.0


@dataclass(frozen=True)
class MachineSetup:
    """The crank-slider machine of the forces scene: its loads (ω is the mean speed ω_m), the journal radii (their
    f's are not used: f is swept), the closed grid of crank angles (an odd number of them: the error estimate
    halves it), ε_R of the friction equilibrium and the wear's parts (None: no wear)."""

    params: dict
    loads: Loads
    radii: Pairs
    phi: np.ndarray
    tolerance: float
    wear: WearParts | None = None


@dataclass(frozen=True)
class Flywheel:
    """[δ], the coefficient of speed fluctuation allowed, and the flywheel already on the crank (kg·m², 0: the
    machine as it is)."""

    delta: float
    inertia: float = 0.0


@dataclass
class Influence:
    """One f's results: its force analysis, the angles where it locks, its figures (FIGURES; None where the
    mechanism locks somewhere in the cycle, δ None where the machine stalls), the curves M_тр(φ) and ω₁(φ), and
    the largest relative change of its figures on the grid of half as many angles (0 where not checked)."""

    f: float
    analysis: ForceAnalysis
    locked: np.ndarray
    figures: dict
    friction_moment: np.ndarray | None = None
    omega: np.ndarray | None = None
    error: float = 0.0

    @property
    def runs(self) -> bool:
        return not self.locked.any()


FIGURES = (*PAIRS, "balancing_peak", "balancing_mean", "efficiency", "delta", "flywheel",
           *(f"wear_{part}" for part in WEAR_PARTS))


def forces_over_f(machine: MachineSetup, f_values: np.ndarray) -> tuple[list[ForceAnalysis], equilibrium.Equilibrium]:
    """crank_slider.analyse (table=False) at every f of f_values in one stacked solve; the equilibrium's
    per-angle decisions and errors over the stacked grid beside them."""
    phi, loads = machine.phi, machine.loads
    points, applied = motion(machine.params, loads, phi)
    count, n = len(f_values), phi.size
    stacked = lambda value: np.tile(value, (count,) + (1,) * (value.ndim - 1)) if np.ndim(value) else value
    points_all = {key: stacked(value) for key, value in points.items()}
    applied_all = {key: stacked(value) for key, value in applied.items()}
    f = np.repeat(np.asarray(f_values, float), n)
    pairs = replace(machine.radii, f14=f, f12=f, f23=f, f34=f)
    omega1_ccw = -loads.omega                                  # the crank turns clockwise (crank_slider)
    solved = equilibrium.solve(points_all, applied_all, pairs, omega1_ccw, machine.tolerance, solve_dyad)
    R12, R23, N = solve_dyad(points_all, applied_all, {"F34": solved.z[0], "M2": solved.z[1]})
    friction = friction_loads(pairs, applied_all, R12, R23, N, R12, omega1_ccw)
    R12, R23, N = solve_dyad(points_all, applied_all, friction)
    moment = -cross(points_all["A"], R12) + applied_all["M_in1"] + friction["M1"]
    analyses = []
    for k in range(count):
        part = slice(k * n, (k + 1) * n)
        locked = solved.locked[part]
        own = lambda value: np.where(locked.reshape((n,) + (1,) * (value.ndim - 1)), np.nan, value[part])
        analysis = ForceAnalysis(phi, points, applied)
        analysis.solution = Approximation(own(R12), own(R23), own(N),
                                          {key: own(value) for key, value in friction.items()}, None)
        analysis.balancing_moment = own(moment)
        analysis.R41 = analysis.solution.R12.copy()
        analysis.converged = solved.converged[part]
        analysis.guide_ratio = solved.guide_ratio[part]
        analyses.append(analysis)
    return analyses, solved


def thinned(analysis: ForceAnalysis, every: int) -> ForceAnalysis:
    """The analysis on every ``every``-th angle (the kinetostatics is exact at each angle: a coarser grid's
    analysis is the finer one's, subsampled)."""
    if every == 1:
        return analysis
    take = slice(None, None, every)
    final = analysis.final
    coarse = ForceAnalysis(analysis.phi[take], {k: v[take] for k, v in analysis.points.items()},
                           {k: v[take] if np.ndim(v) else v for k, v in analysis.applied.items()})
    coarse.solution = Approximation(final.R12[take], final.R23[take], final.N[take],
                                    {k: v[take] for k, v in final.friction.items()}, None)
    coarse.balancing_moment = analysis.balancing_moment[take]
    coarse.R41 = analysis.R41[take]
    return coarse


def friction_moment(analysis: ForceAnalysis) -> np.ndarray:
    """M_тр(φ) (3.30): the power the pairs dissipate over ω₁, with the relative angular speeds |1 − u₂₁|ω₁ at A,
    |u₂₁|ω₁ at B and ω₁ at O, and the slider's speed |V_qB|ω₁ in the guide."""
    a, friction = analysis.applied, analysis.final.friction
    return (np.abs(friction["F34"] * a["u31"]) + friction["M_A"] * np.abs(1 - a["u21"])
            + friction["M_B"] * np.abs(a["u21"]) + friction["M_O"])


def load_moment(machine: MachineSetup, applied: dict) -> np.ndarray:
    """M_P + M_G: the moment on the crank that balances the slider's load and gravity (power equality,
    virtual_work.reduced_moment without the inertia loads: they are the equation of motion's J(φ))."""
    static = applied | {key: 0 * applied[key] for key in ("F_in2", "F_in3", "M_in2", "M_in1")}
    return reduced_moment(machine.params, static, machine.phi)


def inertia_of(machine: MachineSetup) -> np.ndarray:
    """J(φ) = J₁ + m₂V_qS2² + J_S2 u₂₁² + m₃V_qB² (3.23) on the machine's grid."""
    loads = machine.loads
    inertias = Inertias(J1=loads.J1, m2=loads.m2, J_S2=loads.J_S2, m3=loads.m3)
    return reduced_inertia("slider_crank", machine.params, inertias, machine.phi).J


def speed_and_flywheel(machine: MachineSetup, flywheel: Flywheel, phi: np.ndarray, inertia: np.ndarray,
                       resisting: np.ndarray) -> tuple[np.ndarray | None, float | None, float]:
    """ω₁(φ) and δ of the periodic solution with group I = J₁ + flywheel (None: the machine stalls in the cycle)
    and the flywheel J_м that [δ] needs: M_д constant, A(φ) = ∫(M_д − M_с)dφ by the trapezoid rule,
    ω² = 2(T₀ + A)/J with T₀ for (ω_max + ω_min)/2 = ω_m (flywheel.periodic_speed, Lecture 10)."""
    steps = np.diff(phi)
    driving = float(np.sum(steps * (resisting[1:] + resisting[:-1]) / 2)) / (phi[-1] - phi[0])
    excess = driving - resisting
    work = np.concatenate([[0.0], np.cumsum(steps * (excess[1:] + excess[:-1]) / 2)])
    work[-1] = 0.0                                  # A_д = A_с over the cycle: zero but for rounding
    group_one = machine.loads.J1
    cycle = fw.Cycle(phi, work, inertia - group_one)
    omega_mean = machine.loads.omega
    omega = fw.periodic_speed(cycle, group_one + flywheel.inertia, omega_mean)
    runs = bool(np.isfinite(omega).all())
    delta = None
    if runs:                                        # flywheel.achieved_delta of the same ω(φ)
        w_max, w_min = speed_extremes(omega)
        delta = (w_max - w_min) / (0.5 * (w_max + w_min))
    guess = fw.merzalov(cycle, omega_mean, flywheel.delta).inertia
    if guess <= 0:                                  # A and J constant: ω is, whatever the inertia
        return (omega if runs else None), delta, 0.0
    return (omega if runs else None), delta, max(needed_inertia(cycle, omega_mean, flywheel.delta, guess) - group_one,
                                                 0.0)


def needed_inertia(cycle: fw.Cycle, omega_mean: float, delta: float, guess: float) -> float:
    """flywheel.exact's group-I inertia, whose periodic solution has δ = [δ], by the secant method on
    log δ(log I) from Merzalov's ``guess`` (δ ~ 1/I: the first step takes the slope −1), stopped where a step
    is below flywheel.exact's tolerance (1e-14); 0 where group II alone keeps δ; where it does not get there in
    SECANT_STEPS, flywheel.exact itself (Brent's method on a bracket found around the guess)."""
    if cycle.inertia_ii.min() > 0 and fw.achieved_delta(cycle, 0.0, omega_mean) <= delta:
        return 0.0                                  # group II alone keeps δ (flywheel.exact's own test)

    def error(log_inertia: float) -> float:
        return float(np.log(fw.achieved_delta(cycle, float(np.exp(log_inertia)), omega_mean) / delta))
    x0 = float(np.log(guess))
    e0 = error(x0)
    x1 = x0 + e0
    for _ in range(SECANT_STEPS):
        e1 = error(x1)
        if not np.isfinite(e1) or e1 == e0:
            break
        step = -e1 * (x1 - x0) / (e1 - e0)
        x0, e0, x1 = x1, e1, x1 + step
        if abs(step) <= 1e-14 + 1e-14 * abs(x1):
            return float(np.exp(x1))
    return fw.exact(cycle, omega_mean, delta, guess).inertia


def wear_of(analysis: ForceAnalysis, reference: dict, parts: WearParts, cycles: float) -> dict:
    """The largest wear of the bush and pin over their surfaces, of the piston and along the cylinder (µm), with
    the frictionless machine's k = I_s/p_m (``reference``: its mean_pressures on the same grid): wear_report's
    figures (4.12)–(4.19) with p_m(0) for p_m (wear_report's answer at this f's own p_m, times p_m(f)/p_m(0),
    to rounding: tested), the pin's and bush's cosine pressure by the angle-addition formula
    (revolute_peak)."""
    final, applied, phi = analysis.final, analysis.applied, analysis.phi
    r23 = final.R23                                   # rod on the pin (link 3), as wear_report
    relative = np.abs(applied["u21"])
    rod = analysis.points["B"] - analysis.points["A"]
    revolute = 1.0 / reference["mean_pressure_23"]
    pin = revolute_peak(phi, r23, relative, np.zeros_like(phi), parts.I_pin * revolute, cycles, parts.pin_length,
                        journal=True)
    bush = revolute_peak(phi, -r23, relative, np.arctan2(rod[:, 1], rod[:, 0]), parts.I_bush * revolute, cycles,
                         parts.pin_length, journal=False)
    normal = final.N
    side = pressed_side(normal)
    prismatic = 1.0 / reference["mean_pressure_34"]
    x_b = analysis.points["B"][:, 0]
    travel = x_b.max() - x_b                          # piston crown from top dead centre
    along = np.linspace(0.0, float(travel.max()) + parts.piston_length, CYLINDER_POINTS)
    return {"wear_bush": bush, "wear_pin": pin,
            "wear_piston": piston_wear(phi, normal, applied["u31"], parts.I_piston * prismatic, cycles,
                                       parts.piston_length, parts.piston_diameter, side),
            "wear_cylinder": cylinder_peak(phi, normal, applied["u31"], travel, along, parts.I_cylinder * prismatic,
                                           cycles, parts.piston_length, parts.piston_diameter, side)}


def pressed_side(normal: np.ndarray) -> int:
    """The piston's side pressed the more over the cycle (+1 or −1), as report.wear_report (its nansum of the
    clipped normal force: the same arrays, NaN and the other side 0)."""
    return 1 if np.sum(np.where(normal > 0, normal, 0.0)) >= np.sum(np.where(normal < 0, -normal, 0.0)) else -1


def mean_pressures(analysis: ForceAnalysis, parts: WearParts) -> dict:
    """report.wear_report's p_m of the pin (pair 2–3) and of the piston's pressed side (4.23); GeometryError
    where either is zero (k = I_s/p_m (4.24) needs a pressure)."""
    p23 = mean_pressure(np.linalg.norm(analysis.final.R23, axis=1), parts.pin_length, parts.pin_diameter)
    normal = analysis.final.N
    pressed = np.where(np.sign(normal) == pressed_side(normal), np.abs(normal), 0.0)
    p34 = mean_pressure(pressed, parts.piston_length, parts.piston_diameter)
    if p23 == 0 or p34 == 0:
        raise GeometryError("loads", "nothing presses the piston pin or the piston: wear needs a load")
    return {"mean_pressure_23": p23, "mean_pressure_34": p34}


def revolute_peak(phi: np.ndarray, reaction: np.ndarray, rate: np.ndarray, link_angle: np.ndarray, k: float,
                  cycles: float, length: float, journal: bool) -> float:
    """max over the surface's points β of wear.revolute_wear's δ(β) (4.12)–(4.13), cos(θ + β − γ) written
    cos β cos(θ − γ) − sin β sin(θ − γ): two cosines per angle instead of one per (β, angle), the trapezoid
    sums over φ one matrix product (trapezoid_weights)."""
    gamma = np.arctan2(reaction[:, 1], reaction[:, 0]) + (np.pi if journal else 0.0)
    angle = link_angle - gamma
    contact = np.maximum(np.outer(COS_BETA, np.cos(angle)) - np.outer(SIN_BETA, np.sin(angle)), 0.0)
    load = trapezoid_weights(phi) * np.linalg.norm(reaction, axis=1) * rate
    return float(np.max(2e6 * k * cycles / (np.pi * length) * (contact @ load)))


def cylinder_peak(phi: np.ndarray, normal: np.ndarray, velocity_analog: np.ndarray, travel: np.ndarray,
                  points: np.ndarray, k: float, cycles: float, length: float, diameter: float, side: int) -> float:
    """max along the cylinder of wear.cylinder_wear's δ₄(X) (4.18): its trapezoid sum over φ, linear in the
    integrand, as the weights' product with the pressed load, one matrix product over the points X."""
    pressed = np.where(np.sign(normal) == side, np.abs(normal * velocity_analog), 0.0)
    covered = (points[:, None] >= travel[None, :]) & (points[:, None] <= travel[None, :] + length)
    a = 1e6 * (4 / np.pi) * k * cycles / (length * diameter)
    return float(np.max(a * (covered @ (trapezoid_weights(phi) * pressed))))


def trapezoid_weights(phi: np.ndarray) -> np.ndarray:
    """w with Σ w_j y_j = np.trapezoid(y, phi): the trapezoid rule as weights, so that a rule applied to many
    integrands at once is one matrix product."""
    weights = np.zeros_like(phi)
    steps = 0.5 * np.diff(phi)
    weights[:-1] += steps
    weights[1:] += steps
    return weights


@dataclass
class Grid:
    """What every f shares on one grid (every ``every``-th angle): J(φ), M_P + M_G, and the wear's reference."""

    every: int
    phi: np.ndarray
    inertia: np.ndarray
    loaded: np.ndarray
    reference: dict | None


def relative_change(fine: float | None, coarse: float | None, scale: float) -> float:
    """|coarse − fine|/scale; 0 where either is missing or both are equal (no flywheel needed on either grid)."""
    if fine is None or coarse is None or fine == coarse:
        return 0.0
    return abs(coarse - fine) / scale if scale > 0 else np.inf


def figure_scale(figures: dict, key: str) -> float:
    """What a figure's change is relative to: itself, but M_ур's mean (zero in a machine without a useful load
    or friction) to M_ур's peak."""
    value = figures["balancing_peak" if key == "balancing_mean" else key]
    return 0.0 if value is None else abs(value)


class Study:
    """The machine's kinetostatics at a set of f's (one stacked solve: forces_over_f) and each f's figures on
    demand, those of the forces and the wear once per f and grid, those of the motion once per f, grid and
    flywheel: the members of a slider's family over f or [δ] share the rest.  f_values[0] must be 0 (the
    frictionless machine is the wear's reference)."""

    def __init__(self, machine: MachineSetup, f_values: np.ndarray):
        started = time.perf_counter()
        self.machine, self.f_values = machine, np.asarray(f_values, float)
        self.analyses, solved = forces_over_f(machine, self.f_values)
        self.locked = [~np.isfinite(analysis.balancing_moment) for analysis in self.analyses]
        self.reached = float(np.max(solved.error[~solved.locked], initial=0.0))   # ε of the reactions left
        self.onset = locking_onset(machine, self.analyses[0])
        self.notices: list[Notice] = []
        self.cycles = None if machine.wear is None else 3600 * machine.loads.omega / (2 * np.pi) * machine.wear.hours
        inertia, loaded = inertia_of(machine), load_moment(machine, self.analyses[0].applied)
        self.grids = [Grid(every, machine.phi[::every], inertia[::every], loaded[::every], self.reference(every))
                      for every in (1, 2)]
        self.memo: dict = {}
        self.seconds = time.perf_counter() - started              # the shared part's run time

    def reference(self, every: int) -> dict | None:
        """The frictionless machine's mean pressures p_m of the pin and the piston (4.23), those of its
        wear_report, or None with the reason said (nothing presses)."""
        if self.cycles is None:
            return None
        try:
            return mean_pressures(thinned(self.analyses[0], every), self.machine.wear)
        except GeometryError:                 # k = I_s/p_m (4.24) needs a pressure
            if every == 1:
                self.notices.append(Notice("friction_influence_no_wear", "No wear: nothing presses the piston pin "
                                           "or the piston on the cylinder (wear needs a load: the slider's force "
                                           "or the masses)."))
            return None

    def index(self, f: float) -> int:
        return int(np.nonzero(self.f_values == f)[0][0])

    def forces_figures(self, k: int, grid: Grid) -> tuple[dict, np.ndarray]:
        """Peaks, M_ур's peak and mean, η and the wear of f_values[k] on the grid, and M_тр(φ) there."""
        key = (k, grid.every)
        if key not in self.memo:
            analysis = thinned(self.analyses[k], grid.every)
            final, balancing = analysis.final, analysis.balancing_moment
            magnitudes = {"R12": np.linalg.norm(final.R12, axis=1), "R23": np.linalg.norm(final.R23, axis=1),
                          "R34": np.abs(final.N), "R41": np.linalg.norm(analysis.R41, axis=1)}
            figures = {name: float(np.max(value)) for name, value in magnitudes.items()} | {
                "balancing_peak": float(np.max(np.abs(balancing))),
                "balancing_mean": float(np.trapezoid(balancing, grid.phi)) / (grid.phi[-1] - grid.phi[0]),
                "efficiency": efficiency(analysis)["efficiency"]}
            if grid.reference is not None:
                figures |= wear_of(analysis, grid.reference, self.machine.wear, self.cycles)
            self.memo[key] = figures, friction_moment(analysis)
        return self.memo[key]

    def figures(self, k: int, flywheel: Flywheel, grid: Grid) -> tuple[dict, np.ndarray, np.ndarray | None]:
        """Every figure of f_values[k] on the grid, M_тр(φ) and ω₁(φ) there."""
        key = (k, grid.every, flywheel)
        if key not in self.memo:
            figures, lost = self.forces_figures(k, grid)
            omega, delta, needed = speed_and_flywheel(self.machine, flywheel, grid.phi, grid.inertia,
                                                      grid.loaded + lost)
            self.memo[key] = figures | {"delta": delta, "flywheel": needed}, lost, omega
        return self.memo[key]

    def influence(self, k: int, flywheel: Flywheel, checked: bool) -> Influence:
        """f_values[k]'s results; ``checked``: with the change of its figures on the grid of half as many angles."""
        f, analysis, locked = float(self.f_values[k]), self.analyses[k], self.locked[k]
        if locked.any():
            return Influence(f, analysis, locked, dict.fromkeys(FIGURES))
        fine, lost, omega = self.figures(k, flywheel, self.grids[0])
        error = 0.0
        if checked:
            coarse = self.figures(k, flywheel, self.grids[1])[0]
            error = max(relative_change(fine[key], coarse.get(key), figure_scale(fine, key)) for key in fine)
        return Influence(f, analysis, locked, dict.fromkeys(FIGURES) | fine, lost, omega, error)


def locking_onset(machine: MachineSetup, analysis: ForceAnalysis) -> float | None:
    """The smallest f (in every pair) below F_CEILING at which the rod's line of force, tangent to the friction
    circles, reaches the guide's friction angle somewhere in the cycle: max_φ f₃₄|tan ψ′| = 1
    (equilibrium.locking_ratio; ``analysis``: any f's, for the positions and loads); scanned on LOCKING_SCAN
    values at once, refined by Brent's method in the first bracket.  Without the journals' friction circles it
    is 1/max|tan ψ|: √(λ² − 1) for the central crank-slider (λ = l₂/l₁)."""
    dyad = equilibrium.dyad(analysis.points, analysis.applied, -machine.loads.omega)
    n = machine.phi.size

    def excess(f_values: np.ndarray) -> np.ndarray:        # clipped: where the circles wedge the rod it is ∞
        f = np.repeat(f_values, n)
        tiled = equilibrium.Dyad(**{key: np.tile(value, f_values.size) for key, value in vars(dyad).items()})
        ratio = equilibrium.locking_ratio(replace(machine.radii, f14=f, f12=f, f23=f, f34=f), tiled)
        return np.minimum(ratio.reshape(f_values.size, n).max(axis=1), 2.0) - 1.0
    scan = np.linspace(0.0, F_CEILING, LOCKING_SCAN + 1)
    reached = np.nonzero(excess(scan) >= 0)[0]
    if not reached.size:
        return None
    first = int(reached[0])
    return float(brentq(lambda f: excess(np.array([f]))[0], scan[first - 1], scan[first], xtol=1e-9, rtol=1e-9))


def sweep_values(f_max: float, count: int) -> np.ndarray:
    """The sweep's f's: 0 … f_max in count equal steps."""
    return np.linspace(0.0, f_max, count)
