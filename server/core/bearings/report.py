"""The plain-bearing designer's answer, by output name (Chaika–Vasylenko §2): the pair's load over the cycle,
the sizing (2.4)/(2.5), the checks (2.3), (2.6), (2.9), the heat balance (2.12)/(2.13) against (2.14), the
clearance, the Stribeck curve of Fig. 2.4, the fluid-film power (2.17)/(2.19) and the book's misprints.

Which load each formula takes: the strength check (2.3) and the sizing (2.4)/(2.5) the peak of |R| over the
cycle; the speed check (2.6) the peak sliding speed; the heat criteria (2.9), (2.12), (2.13) the mean over the
cycle of p·V and of the friction power; the Stribeck characteristic λ = μω/p_m the mean load and mean speed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import errata
from ..mechanisms import GeometryError, Notice
from . import dry, film
from .loads import PairLoad
from .tables import CLEARANCE, JOURNAL_DIAMETER, LENGTH_RATIO, material

MPA = 1e6
STRIBECK_POINTS = 121
OUTPUTS = ("load", "checks", "sizing", "heat", "clearance", "stribeck", "film", "errata")


@dataclass(frozen=True)
class Design:
    """The bearing: kind (dry, semi_fluid, fluid), its material (a row of Table 2.1 or 2.2), journal diameter d
    (m), relative length l̄_z, radial clearance h₀/d, f (None: the table's), the lubricant (μ Pa·s, ρ kg/m³),
    the wrap α (rad), and the heat balance: T_B (°C), k' (W/(m²·K)), the path ("bushing" (2.12) with A_k =
    housing_area·π·d·l_z, or "shaft" (2.13) over shaft_length·d on each side for hours of work)."""

    kind: str = "dry"
    material: str = "bronze_brof"
    diameter: float = 0.04
    length_ratio: float = 1.0
    clearance_ratio: float = 0.001
    friction: float | None = None
    viscosity: float = 0.02
    density: float = 880.0
    wrap: float = 2 * math.pi
    ambient: float = 20.0
    transfer: float = 11 * dry.KCAL_PER_HOUR
    heat_path: str = "bushing"
    housing_area: float = 20.0
    shaft_length: float = 3.5
    hours: float = 8.0
    bore: float | None = None       # the cylinder's D_p, for the recommended journal diameter (§2.1)


def friction_coefficient(design: Design) -> float | None:
    """f for the heat of a dry or semi-fluid bearing: the request's, else Table 2.1's (high end); None if neither."""
    if design.friction is not None:
        return design.friction
    return material(design.kind, design.material).allowable()["friction"] if design.kind == "dry" else None


def bearings_report(load: PairLoad, design: Design, outputs) -> tuple[dict, list[Notice]]:
    """Every requested output for the pair's load; refuses (GeometryError naming the field) a dry material
    without f, and says in words when the reactions are undefined (a self-locking mechanism)."""
    row = material(design.kind, design.material)
    allowable = row.allowable()
    if not np.isfinite(load.force).all():
        return {}, [Notice("bearing_load_undefined", "The pair's reaction is undefined over part of the cycle "
                           "(the mechanism self-locks there): no bearing can be designed for it.")]
    d, ratio = design.diameter, design.length_ratio
    length, radius, h0 = ratio * d, d / 2, design.clearance_ratio * d
    mean_omega = load.cycle_mean(load.omega)
    p_mean = dry.mean_pressure(load.mean, length, d)
    lam = film.characteristic(design.viscosity, mean_omega, p_mean) if p_mean > 0 else math.inf
    f = friction_coefficient(design)
    if design.kind == "semi_fluid":
        f = float(film.stribeck(lam, h0 / radius)) if math.isfinite(lam) else None
    if design.kind == "dry" and f is None:
        raise GeometryError("bearing.friction", f"Table 2.1 gives no friction coefficient for {row.name}: "
                            "give f", "bearing_friction_needed")
    power_cycle, reynolds = film.film_power(load.omega, radius, length, h0, design.viscosity, design.wrap,
                                            design.viscosity / design.density)
    if design.kind == "fluid":
        power = load.cycle_mean(power_cycle)
    else:
        power = load.cycle_mean(dry.friction_power(f, load.force, dry.sliding_speed(load.omega, d)))
    pv = dry.cycle_pv(load.force, load.omega, length, d)
    result = {}
    if "load" in outputs:
        result["load"] = {"pair": load.pair, "phi": load.phi, "force": load.force, "omega": load.omega,
                          "peak": load.peak, "mean": load.mean, "peak_omega": float(load.omega.max()),
                          "mean_omega": mean_omega}
    heat = _heat(design, power, f, length) if "heat" in outputs or "checks" in outputs else None
    if "checks" in outputs:
        result["checks"] = _checks(load, design, allowable, pv, heat)
        result["checks"]["states"] = _states(load, design, allowable, lam, h0, reynolds, result["checks"]["verdict"])
    if "heat" in outputs:
        result["heat"] = heat
    if "sizing" in outputs:
        result["sizing"] = _sizing(load, design, allowable)
    if "clearance" in outputs:
        result["clearance"] = _clearance(design, h0)
    if "stribeck" in outputs:
        result["stribeck"] = _stribeck(lam, h0 / radius)
    if "film" in outputs:
        result["film"] = _film(load, power_cycle, reynolds)
    if "errata" in outputs:
        result["errata"] = _errata(load, design, allowable, length, f)
    return result, []


def _checks(load: PairLoad, design: Design, allowable: dict, pv: np.ndarray, heat: dict) -> dict:
    d, length = design.diameter, design.length_ratio * design.diameter
    pressure = dry.mean_pressure(load.peak, length, d)
    speed = dry.sliding_speed(float(load.omega.max()), d)
    pv_mean = load.cycle_mean(pv)
    rows = [
        ("pressure", "(2.3)", pressure / MPA, _scaled(allowable["pressure"], MPA), "MPa",
         dry.check(pressure, allowable["pressure"])),
        ("speed", "(2.6)", speed, allowable["speed"], "m_s", dry.check(speed, allowable["speed"])),
        ("pv", "(2.9)", pv_mean / MPA, _scaled(allowable["pv"], MPA), "MPa_m_s", dry.check(pv_mean, allowable["pv"])),
        ("temperature", "(2.14)", heat["temperature"], heat["allowable"], "degC", heat["verdict"]),
    ]
    table = [{"criterion": c, "equation": e, "value": v, "allowable": a, "unit": u, "verdict": k}
             for c, e, v, a, u, k in rows]
    verdicts = [row["verdict"] for row in table]
    overall = "fail" if "fail" in verdicts else ("pass" if "unknown" not in verdicts else "unknown")
    return {"rows": table, "verdict": overall, "pressure": pressure, "speed": speed, "pv": pv_mean,
            "pv_peak": float(pv.max()), "phi": load.phi, "pv_cycle_MPa_m_s": pv / MPA,
            "pv_allowable_MPa_m_s": _scaled(allowable["pv"], MPA)}


def _states(load: PairLoad, design: Design, allowable: dict, lam: float, h0: float, reynolds: np.ndarray,
            verdict: str) -> list[dict]:
    """The verdicts in words: all checks, the diameters that pass (2.3), (2.6), (2.9) together, the clearance,
    the zone of Fig. 2.4 at the operating point (lubricated bearings) and the film's flow (fluid bearings)."""
    rows = [{"quantity": "verdict", "state": verdict},
            {"quantity": "sizing", "state": "pass" if _sizing(load, design, allowable)["feasible"] else "fail"},
            {"quantity": "clearance", "state": _clearance(design, h0)["verdict"]}]
    if design.kind != "dry":
        limits = film.regime_limits(h0 / (design.diameter / 2))
        rows.append({"quantity": "stribeck", "state": film.regime(lam, limits) if math.isfinite(lam) else "fluid"})
    if design.kind == "fluid":
        turbulent = reynolds >= film.REYNOLDS_TURBULENT
        rows.append({"quantity": "film", "state": "turbulent" if turbulent.all() else (
            "laminar" if not turbulent.any() else "both")})
    return rows


def _scaled(value: float | None, scale: float) -> float | None:
    return None if value is None else value / scale


def _heat(design: Design, power: float, friction: float | None, length: float) -> dict:
    d, row = design.diameter, material(design.kind, design.material)
    limit = row.allowable()["temperature"]
    if design.heat_path == "shaft":
        part = dry.shaft(d, design.shaft_length)
        t = dry.shaft_temperature(power, design.ambient, design.transfer, part["mass"], part["area"], design.hours)
        area, mass = part["area"], part["mass"]
        printed = None if friction is None else dry.shaft_temperature_as_printed(
            length, d, friction, design.ambient, design.transfer, mass, area, design.hours)
        equation = "(2.13)"
    else:
        area, mass, printed = design.housing_area * math.pi * d * length, None, None
        t = dry.bushing_temperature(power, design.ambient, design.transfer, area)
        equation = "(2.12)"
    return {"temperature": t, "allowable": limit, "verdict": dry.check(t, limit), "power": power,
            "friction": friction, "area": area, "shaft_mass": mass, "equation": equation,
            "printed_temperature": printed}


def _sizing(load: PairLoad, design: Design, allowable: dict) -> dict:
    by_formula = dry.size(load.peak, allowable["pressure"], design.length_ratio)
    heat_load = load.cycle_mean(load.force * load.omega)
    limits = dry.feasible_diameters(load.peak, heat_load, float(load.omega.max()), allowable, design.length_ratio)
    bore = JOURNAL_DIAMETER[load.pair]
    lengths = LENGTH_RATIO[design.kind]
    return {"diameter": by_formula["diameter"], "length": by_formula["length"], "smallest_diameter":
            limits["smallest"], "largest_diameter": limits["speed"], "heat_diameter": limits["heat"],
            "feasible": limits["feasible"],
            "recommended_low": None if design.bore is None else bore[0] * design.bore,
            "recommended_high": None if design.bore is None else bore[1] * design.bore,
            "length_ratio_low": None if lengths is None else lengths[0],
            "length_ratio_high": None if lengths is None else lengths[1]}


def _clearance(design: Design, h0: float) -> dict:
    ranges = CLEARANCE[design.kind]
    d = design.diameter
    if ranges is None:
        return {"clearance": h0, "low": None, "high": None, "rarer_low": None, "rarer_high": None, "verdict": "unknown"}
    usual, rarer = ranges
    inside = usual[0] <= design.clearance_ratio <= usual[1] or (
        rarer is not None and rarer[0] <= design.clearance_ratio <= rarer[1])
    return {"clearance": h0, "low": usual[0] * d, "high": usual[1] * d,
            "rarer_low": None if rarer is None else rarer[0] * d, "rarer_high": None if rarer is None else rarer[1] * d,
            "verdict": "pass" if inside else "fail"}


def _stribeck(lam: float, relative_clearance: float) -> dict:
    """The curve against lg(λ/λ_t) from −2 to 2 (widened to half a decade around the operating point), in its
    three zones; each zone's curve reaches the next zone's first point, so the curve is drawn without gaps."""
    limits = film.regime_limits(relative_clearance)
    low, high = -2.0, 2.0
    if math.isfinite(lam) and lam > 0:
        where = math.log10(lam / film.TRANSITION)
        low, high = min(low, where - 0.5), max(high, where + 0.5)
    log_ratio = np.linspace(low, high, STRIBECK_POINTS)
    lam_grid = film.TRANSITION * 10**log_ratio
    f = film.stribeck(lam_grid, relative_clearance)
    zones = np.array([film.regime(value, limits) for value in lam_grid])
    joined = {name: np.where(zones == name, f, np.nan) for name in ("boundary", "mixed", "fluid")}
    for a, b in (("boundary", "mixed"), ("mixed", "fluid")):
        first = np.flatnonzero(zones == b)
        if first.size and first[0] > 0:
            joined[a][first[0]] = f[first[0]]
    finite = math.isfinite(lam)
    return {"log_ratio": log_ratio, "lambda_grid": lam_grid, "f": f,
            **{f"f_{name}": value for name, value in joined.items()},
            "lambda": lam if finite else None, "f_operating": float(film.stribeck(lam, relative_clearance)) if finite else None,
            "regime": film.regime(lam, limits) if finite else "fluid",
            "boundary_end": limits[0], "fluid_start": limits[1], "transition": film.TRANSITION}


def _film(load: PairLoad, power: np.ndarray, reynolds: np.ndarray) -> dict:
    turbulent = reynolds >= film.REYNOLDS_TURBULENT
    share = load.cycle_mean(turbulent.astype(float))
    regime = "turbulent" if turbulent.all() else ("laminar" if not turbulent.any() else "both")
    return {"phi": load.phi, "power": power, "reynolds": reynolds, "mean_power": load.cycle_mean(power),
            "peak_reynolds": float(reynolds.max()), "regime": regime, "turbulent_share": share,
            "equation": "(2.17)" if regime == "laminar" else "(2.19)"}


def _errata(load: PairLoad, design: Design, allowable: dict, length: float, friction: float | None) -> list[dict]:
    """The misprints of §2 that change a number, each printed beside corrected with the value each gives (the
    rows of errata.row): (2.4) read as printed solves to l_z = F_e/[p_m], an area; (2.13) without p_m·V_s;
    (2.16) without the arm r, a power per metre."""
    sized = dry.size(load.peak, allowable["pressure"], design.length_ratio)
    rows = [errata.row("bearing_size", "chaika_vasylenko", "(2.4)", load.peak / allowable["pressure"],
                       sized["length"], "m", printed_unit="m2_area")]
    part = dry.shaft(design.diameter, design.shaft_length)
    if friction is not None:
        args = (design.ambient, design.transfer, part["mass"], part["area"], design.hours)
        power = load.cycle_mean(dry.friction_power(friction, load.force, dry.sliding_speed(load.omega, design.diameter)))
        rows.append(errata.row("bearing_shaft_heat", "chaika_vasylenko", "(2.13)",
                               dry.shaft_temperature_as_printed(length, design.diameter, friction, *args),
                               dry.shaft_temperature(power, *args), "degC"))
    radius, h0 = design.diameter / 2, design.clearance_ratio * design.diameter
    power, _ = film.film_power(load.omega, radius, length, h0, design.viscosity, design.wrap,
                               design.viscosity / design.density)
    rows.append(errata.row("bearing_film_arm", "chaika_vasylenko", "(2.16)", load.cycle_mean(power) / radius,
                           load.cycle_mean(power), "W", printed_unit="W_m"))
    return rows
