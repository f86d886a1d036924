"""Benchmark: explicit against implicit solvers on the elastic models, error against run time.

For three problems — a belt drive of moderate stiffness, a very stiff and heavily damped one
(stiffness ratio ~1e6), and seed 003's elastic four-bar — every solve_ivp method runs at
several tolerances on the same first-order model (twists as states, analytic Jacobian for the
implicit methods).  Error: the largest twist difference against a reference (Radau at rtol 1e-11
for the stiff problem, DOP853 at 1e-11 otherwise), relative to the largest twist.  The method
the server picks by its stiffness measurement is marked.

Run:  python bench/elastic.py      (writes bench/results/elastic.md)
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from server.core.dynamics.motors import Motor                                    # noqa: E402
from server.core.dynamics.reduction import Inertias                              # noqa: E402
from server.core.dynamics.resistance import Load                                 # noqa: E402
from server.core.elastic.report import (ElasticMachine, absolute_tolerances,    # noqa: E402
                                        build, no_load_speed)
from server.core.elastic.simulate import STIFF_RATIO, integrate, stiffness_ratio  # noqa: E402
from server.core.elastic.stiffness import Compliances                            # noqa: E402
from server.core.mechanisms import MECHANISMS                                    # noqa: E402

SLIDER = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.3})
FOUR_BAR = MECHANISMS["four_bar"].check({"l0": 1.0, "l1": 0.3, "l2": 1.0, "l3": 0.8})
RIG = dict(inertias=Inertias(J1=0.5, m2=5.0, J_S2=0.05, m3=10.0, gear_ratio=5.0), load=Load(2000.0, 0.2, 0.1),
           motor=Motor("linear", M0=60.0, b=0.3), J_motor=0.25)
PROBLEMS = {
    "belt drive, c = 1e5 N·m/rad, b = 30": (ElasticMachine("two_mass", "slider_crank", SLIDER, c=1e5, b=30.0, **RIG), 0.5),
    "stiff belt, c = 1e8, b = 1e5 (heavily damped)": (ElasticMachine("two_mass", "slider_crank", SLIDER, c=1e8, b=1e5,
                                                                      **RIG), 0.5),
    "elastic crank-slider linkage, c(φ) from e₁ = 1e-6, e₂ = 1e-9, b = 100": (ElasticMachine(
        "elastic_linkage", "slider_crank", SLIDER, compliances=Compliances(1e-6, 1e-9), b=100.0, **RIG), 0.5),
    "seed 003 elastic four-bar, b_n = 0.02": (ElasticMachine(
        "elastic_four_bar", "four_bar", FOUR_BAR, Inertias(J1=0.01, J3=0.05), Load(0.5), Motor("linear", M0=2.0, b=0.05),
        J_motor=0.02, compliances=Compliances(2e-6, 1e-9, 3e-6), b=0.02), 0.5),
}
METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA")
TOLERANCES = (1e-3, 1e-5, 1e-7, 1e-9)
BUDGET_S = 30.0
REFERENCE_RTOL = 1e-11


def run(machine, t_end, method, rtol, budget=BUDGET_S):
    model, y0 = build(machine)
    samples = np.linspace(0, t_end, 501)
    start = time.perf_counter()
    result = integrate(model, y0, t_end, rtol, method, samples, start + budget,
                       absolute_tolerances(machine, model, rtol), max_evaluations=5_000_000)
    return time.perf_counter() - start, result


def main() -> None:
    lines = []
    for name, (machine, t_end) in PROBLEMS.items():
        model, y0 = build(machine)
        ratio, decay, fastest = stiffness_ratio(model, y0, max(2 * np.pi / t_end, no_load_speed(machine)))
        picked = "Radau" if ratio > STIFF_RATIO else "DOP853"
        reference_method = "Radau" if picked == "Radau" else "DOP853"
        _, reference = run(machine, t_end, reference_method, REFERENCE_RTOL, budget=600.0)
        assert reference.complete, f"the reference of {name} did not finish"
        twist_ref = reference.y[2]
        lines += [f"\n### {name}\n", f"Stiffness ratio {ratio:.3g} (fastest decay {decay:.3g} 1/s, fastest |λ| "
                  f"{fastest:.3g} 1/s): the server picks **{picked}**. Reference: {reference_method} at rtol {REFERENCE_RTOL:g}.\n",
                  "| method | rtol | error | run time, ms | steps | RHS calls |", "|---|---|---:|---:|---:|---:|"]
        for method in METHODS:
            for rtol in TOLERANCES:
                times, result = [], None
                for _ in range(2):
                    seconds, result = run(machine, t_end, method, rtol)
                    times.append(seconds)
                if not result.complete or result.t.size != twist_ref.size:
                    lines.append(f"| {method} | {rtol:.0e} | did not finish in budget | {1e3 * min(times):.0f} | "
                                 f"{result.numerics['steps']} | {result.numerics['nfev']} |")
                    continue
                error = np.max(np.abs(result.y[2] - twist_ref)) / np.max(np.abs(twist_ref))
                mark = " ←" if method == picked else ""
                lines.append(f"| {method}{mark} | {rtol:.0e} | {error:.1e} | {1e3 * statistics.median(times):.0f} | "
                             f"{result.numerics['steps']} | {result.numerics['nfev']} |")
    text = "# Elastic models: error against run time\n" + "\n".join(lines) + "\n"
    print(text)
    (Path(__file__).with_name("results") / "elastic.md").write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
