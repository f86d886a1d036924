"""Work–precision study: error against run time for every computation that uses a solver or a quadrature.

Problems: the rigid steady cycle (crank-slider, linear motor), the flywheel's exact inertia,
the elastic crank-slider linkage with c(φ), and Drakunov–Tuleshova's elastic four-bar.  For each, our method at
several tolerances against scipy's general solvers (RK45, DOP853, Radau, BDF, LSODA), errors against a
reference computed to 1e-11…1e-13 by a different method.  Writes bench/results/work_precision.md, one
interactive plot per problem (bench/results/<name>.html, plotly.js from the app's /vendor path, served
by the app at /bench-results/) and a PNG of it rendered by headless Chromium.

Run:  python bench/work_precision.py                 (writes bench/results/)
      python bench/work_precision.py --no-write      (prints the tables only; --results DIR writes elsewhere)
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import plotly.graph_objects as go
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE.parent), str(HERE)]

import elastic as elastic_bench                                          # noqa: E402
import steady_cycle as steady_bench                                       # noqa: E402
from server.core.dynamics import flywheel as fw                           # noqa: E402
from server.core.dynamics.machine import Machine                          # noqa: E402
from server.core.dynamics.motion import node_tables   # noqa: E402
from server.core.numerics import cumulative_simpson   # noqa: E402
from server.core.dynamics.motors import Motor                             # noqa: E402
from server.core.dynamics.reduction import Inertias                       # noqa: E402
from server.core.dynamics.resistance import Load                          # noqa: E402
from server.core.elastic.report import build, no_load_speed              # noqa: E402
from server.core.elastic.simulate import STIFF_RATIO, stiffness_ratio    # noqa: E402
from server.core.mechanisms import MECHANISMS                             # noqa: E402

RESULTS = HERE / "results"
METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA")


def steady_cycle_study() -> dict:
    """Rigid steady cycle: ω(0) on the cycle; ours by Newton shooting, theirs by integrating cycles."""
    from server.core.dynamics.motion import steady_cycle
    machine = steady_bench.MACHINE
    reference = steady_bench.time_domain("DOP853", 1e-13, steady_cycle(machine, 1e-10).steady.omega[0] * 0.9)[0]
    series = {"ours (Newton shooting, RK4 in φ)": []}
    for rtol in (1e-3, 1e-5, 1e-7, 1e-9, 1e-11):
        seconds, motion = steady_bench.timed(lambda: steady_cycle(machine, rtol), repeat=2)
        series["ours (Newton shooting, RK4 in φ)"].append((rtol, abs(motion.steady.omega[0] / reference - 1), seconds))
    start = reference * 0.9
    for method in ("RK45", "DOP853", "Radau", "LSODA"):
        series[f"solve_ivp {method}"] = []
        for rtol in (1e-3, 1e-5, 1e-7, 1e-9):
            seconds, (omega, _, _, _) = steady_bench.timed(lambda: steady_bench.time_domain(method, rtol, start),
                                                           repeat=1)
            series[f"solve_ivp {method}"].append((rtol, abs(omega / reference - 1), seconds))
    return {"title": "Rigid steady cycle (crank-slider, linear motor): error of ω(0)", "series": series,
            "reference": "DOP853 at rtol 1e-13 in time, cycles until periodic"}


def flywheel_cycle(steps: int):
    params = MECHANISMS["slider_crank"].check({"l1": 0.12, "l2": 0.528, "a2": 0.32008})
    machine = Machine("slider_crank", params, Inertias(J1=2.72, m2=24.2, J_S2=1.21, m3=36.2), Load(),
                      Motor("indicator", p_max=4.4e6, piston_diameter=0.1))
    tables = node_tables(machine, steps, balance=True)
    work = cumulative_simpson(tables.net_phi, float(tables.phi[2] - tables.phi[0]))
    return machine, tables, fw.Cycle(tables.phi[::2], work, tables.J[::2] - 2.72)


def flywheel_study() -> dict:
    """Exact flywheel inertia for δ = 1/80: ours (Simpson on a refined grid) against the energy ODE dT/dφ = M(φ)
    integrated by each solve_ivp method, both inside the same root finding on I_I."""
    omega, delta = 47.124, 1 / 80
    _, _, fine = flywheel_cycle(1 << 15)
    reference = fw.exact(fine, omega, delta, 40.0).inertia
    series = {"ours (Simpson on the cycle grid)": []}
    for steps in (64, 256, 1024, 4096):
        seconds, inertia = steady_bench.timed(lambda: fw.exact(flywheel_cycle(steps)[2], omega, delta, 40.0).inertia,
                                              repeat=2)
        series["ours (Simpson on the cycle grid)"].append((1.0 / steps, abs(inertia / reference - 1), seconds))
    machine, tables, _ = flywheel_cycle(4096)
    moment = lambda phi: np.interp(phi, tables.phi, tables.net_phi)
    phi = tables.phi[::2]
    for method in ("RK45", "DOP853", "Radau", "LSODA"):
        series[f"solve_ivp {method}"] = []
        for rtol in (1e-4, 1e-6, 1e-8, 1e-10):
            def run():
                solution = solve_ivp(lambda x, y: [moment(x)], (0.0, 2 * np.pi), [0.0], method=method, rtol=rtol,
                                     atol=rtol * 1e-3, t_eval=phi)
                cycle = fw.Cycle(phi, solution.y[0], tables.J[::2] - 2.72)
                return fw.exact(cycle, omega, delta, 40.0).inertia
            seconds, inertia = steady_bench.timed(run, repeat=1)
            series[f"solve_ivp {method}"].append((rtol, abs(inertia / reference - 1), seconds))
    return {"title": "Flywheel: exact inertia for δ = 1/80 (error of I_I)", "series": series,
            "reference": "ours on 32768 steps per turn", "x_note": "ours: 1/steps per turn"}


def elastic_study(name: str) -> dict:
    machine, t_end = elastic_bench.PROBLEMS[name]
    model, y0 = build(machine)
    ratio = stiffness_ratio(model, y0, max(2 * np.pi / t_end, no_load_speed(machine)))[0]
    picked = "Radau" if ratio > STIFF_RATIO else "DOP853"
    _, reference = elastic_bench.run(machine, t_end, "Radau" if picked == "DOP853" else "DOP853", 1e-11, budget=900.0)
    if not reference.complete:                     # an explicit reference cannot cross a stiff problem
        _, reference = elastic_bench.run(machine, t_end, "Radau", 1e-11, budget=900.0)
    twist = reference.y[2]
    series = {}
    for method in METHODS:
        label = f"ours (picked by stiffness ratio {ratio:.2g}): {method}" if method == picked else f"solve_ivp {method}"
        series[label] = []
        for rtol in (1e-3, 1e-5, 1e-7, 1e-9):
            seconds, result = steady_bench.timed(lambda: elastic_bench.run(machine, t_end, method, rtol)[1], repeat=1)
            if result.complete:
                error = float(np.max(np.abs(result.y[2] - twist)) / np.max(np.abs(twist)))
                series[label].append((rtol, error, seconds))
    return {"title": f"Elastic: {name} (error of the twist)", "series": series,
            "reference": "rtol 1e-11 by another method than ours"}


def figure(study: dict) -> go.Figure:
    fig = go.Figure()
    for label, points in study["series"].items():
        if points:
            fig.add_trace(go.Scatter(x=[p[2] * 1e3 for p in points], y=[max(p[1], 1e-17) for p in points],
                                     mode="lines+markers", name=label,
                                     text=[f"rtol {p[0]:.0e}" for p in points]))
    fig.update_layout(title=study["title"], xaxis_title="run time, ms", yaxis_title="relative error",
                      xaxis_type="log", yaxis_type="log", width=900, height=560, template="plotly_white")
    return fig


def render_png(fig: go.Figure, path: Path) -> None:
    """Headless Chromium renders the plot (no download of a browser: Debian's chromium)."""
    from playwright.sync_api import sync_playwright
    page_file = path.with_suffix(".render.html")
    fig.write_html(page_file, include_plotlyjs=True, full_html=True)
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox", "--disable-gpu"])
        page = browser.new_page(viewport={"width": 920, "height": 580})
        page.goto(page_file.as_uri())
        page.wait_for_selector(".main-svg")
        page.screenshot(path=str(path))
        browser.close()
    page_file.unlink()


def winner_paragraph(study: dict) -> str:
    """Which method reaches a given error fastest, in words."""
    best = {}
    for label, points in study["series"].items():
        for _, error, seconds in points:
            for target in (1e-4, 1e-6, 1e-8):
                if error <= target and seconds < best.get(target, (None, np.inf))[1]:
                    best[target] = (label, seconds)
    parts = [f"error ≤ {t:.0e}: {label} in {1e3 * s:.1f} ms" for t, (label, s) in sorted(best.items(), reverse=True)]
    return "Fastest to " + "; ".join(parts) + "." if parts else "No method reached 1e-4."


def arguments(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", type=Path, default=RESULTS,
                        help="the directory written: work_precision.md, wp_*.html, wp_*.png (default: %(default)s)")
    parser.add_argument("--no-write", action="store_true", help="print the tables only, write no file")
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> None:
    options = arguments(argv)
    results = options.results
    studies = {"steady_cycle": steady_cycle_study(), "flywheel": flywheel_study()}
    for key, name in (("elastic_belt", "belt drive, c = 1e5 N·m/rad, b = 30"),
                      ("elastic_stiff", "stiff belt, c = 1e8, b = 1e5 (heavily damped)"),
                      ("elastic_linkage", "elastic crank-slider linkage, c(φ) from e₁ = 1e-6, e₂ = 1e-9, b = 100"),
                      ("elastic_four_bar", "Drakunov–Tuleshova elastic four-bar, b_n = 0.02")):
        studies[key] = elastic_study(name)
    lines = ["# Work–precision: error against run time", ""]
    for key, study in studies.items():
        if not options.no_write:
            fig = figure(study)
            fig.write_html(results / f"wp_{key}.html", include_plotlyjs="/vendor/plotly/plotly.min.js")
            render_png(fig, results / f"wp_{key}.png")
        lines += [f"## {study['title']}", "", f"Reference: {study['reference']}. ![plot](wp_{key}.png) "
                  f"(interactive: /bench-results/wp_{key}.html)", "", winner_paragraph(study), "",
                  "| method | tolerance | error | run time, ms |", "|---|---|---:|---:|"]
        for label, points in study["series"].items():
            lines += [f"| {label} | {tol:.0e} | {err:.1e} | {1e3 * s:.1f} |" for tol, err, s in points]
        lines.append("")
    if not options.no_write:
        (results / "work_precision.md").write_text("\n".join(lines), encoding="utf-8")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
