"""Benchmark: the steady cycle of the crank-slider machine with a linear motor.

Our path (Newton shooting on the cycle map, RK4 in φ with Richardson control) against
scipy.integrate.solve_ivp (RK45, DOP853, Radau, LSODA) integrating the equation of motion
in time, J(φ)ω̇ + ½J′ω² = M_д − M_c, cycle after cycle until ω at φ = 2πk repeats to the
same tolerance.  Error: relative error of ω(φ = 0) and of δ on the steady cycle against a
reference computed by DOP853 at rtol = 1e-13 (a different method from ours).

Our path is timed twice, side by side in the same run: with the numba-compiled loops (RK4 in φ, DOP853
leaving rest: the server's path) and with the reference loops they are tested against (plain Python RK4,
scipy's DOP853): the ratio is the compiled code's speed-up. The start-up from rest (up to 80 cycles) is timed
the same way.

Run:  python bench/steady_cycle.py            (writes bench/results/steady_cycle.md)
      python bench/steady_cycle.py --paths    (only compiled against reference, printed, nothing written)
      python bench/steady_cycle.py --no-write (the whole table, printed only; --output PATH writes elsewhere)
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from server.core.dynamics import compiled, integrator    # noqa: E402
from server.core.dynamics.machine import Machine          # noqa: E402
from server.core.dynamics.motion import startup, steady_cycle  # noqa: E402
from server.core.dynamics.motors import Motor             # noqa: E402
from server.core.dynamics.reduction import Inertias       # noqa: E402
from server.core.dynamics.resistance import Load          # noqa: E402
from server.core.work_precision import cycles_until_periodic  # noqa: E402
from server.core.mechanisms import MECHANISMS             # noqa: E402

PARAMS = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.3})
MACHINE = Machine("slider_crank", PARAMS, Inertias(J1=0.5, m2=5.0, J_S2=0.05, m3=10.0, J_rotor=0.01, gear_ratio=5.0),
                  Load(2000.0, 0.2, 0.1), Motor("linear", M0=60.0, b=0.3))


def time_domain(method: str, rtol: float, omega_start: float, max_cycles: int = 400):
    """solve_ivp cycle after cycle (the server's own general path); ω(0), δ of the repeating cycle, RHS count."""
    periodic = cycles_until_periodic(MACHINE, method, rtol, omega_start, max_cycles=max_cycles)
    if periodic is None:
        raise RuntimeError(f"{method} did not settle in {max_cycles} cycles")
    last = periodic.last_cycle
    w_max, w_min = (extreme(last.sol, last.t[0], last.t_events[0][0], sign) for sign in (1, -1))
    return periodic.omega0, (w_max - w_min) / (0.5 * (w_max + w_min)), periodic.nfev, periodic.cycles


def extreme(dense, t0: float, t1: float, sign: int) -> float:
    """Largest (sign +1) or smallest (−1) ω of the dense output on [t0, t1], refined by a bounded search."""
    grid = np.linspace(t0, t1, 2001)
    k = int(np.argmax(sign * dense(grid)[1]))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    best = minimize_scalar(lambda s: -sign * dense(s)[1], bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-14 * (t1 - t0)})
    return float(dense(best.x)[1])


def timed(function, repeat=3):
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def on_path(compiled_loops: bool, function):
    """function() with integrate's loops compiled (the server's path) or the reference ones."""
    saved, integrator.COMPILED = integrator.COMPILED, compiled_loops
    try:
        return function()
    finally:
        integrator.COMPILED = saved


def paths_table(omega_ref: float, delta_ref: float) -> list[str]:
    """Our steady cycle and start-up, compiled and reference loops side by side, with the ratio."""
    lines = ["| computation | rtol | reference loops, ms | compiled, ms | speed-up | error of ω(0), compiled | "
             "error of ω(0), reference |", "|---|---|---|---|---|---|---|"]
    for rtol in (1e-3, 1e-6, 1e-8, 1e-10):
        slow, old = on_path(False, lambda: timed(lambda: steady_cycle(MACHINE, rtol=rtol)))
        fast, new = on_path(True, lambda: timed(lambda: steady_cycle(MACHINE, rtol=rtol)))
        lines.append(f"| steady cycle ({new.numerics.steps} steps × {new.numerics.iterations} Newton runs) | {rtol:.0e} | "
                     f"{1e3 * slow:.1f} | {1e3 * fast:.2f} | {slow / fast:.0f}× | "
                     f"{abs(new.steady.omega[0] / omega_ref - 1):.1e} | {abs(old.steady.omega[0] / omega_ref - 1):.1e} |")
    slow, old = on_path(False, lambda: timed(lambda: startup(MACHINE, 0.0, 1e-8, 80)))
    fast, new = on_path(True, lambda: timed(lambda: startup(MACHINE, 0.0, 1e-8, 80)))
    settle = abs(new.transient.omega[-1] / old.transient.omega[-1] - 1)
    lines.append(f"| start-up from rest ({new.numerics.cycles} cycles; final ω of the paths differ by {settle:.0e}) | 1e-08 | "
                 f"{1e3 * slow:.1f} | {1e3 * fast:.2f} | {slow / fast:.0f}× | — | — |")
    return lines


def arguments(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--paths", action="store_true",
                        help="only the compiled loops against the reference loops, printed, nothing written")
    parser.add_argument("--output", type=Path, default=Path(__file__).with_name("results") / "steady_cycle.md",
                        help="the Markdown file written (default: %(default)s)")
    parser.add_argument("--no-write", action="store_true", help="print the table only, write no file")
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> None:
    options = arguments(argv)
    warm = compiled.warm_up()
    ours_ref = steady_cycle(MACHINE, rtol=1e-10).steady
    if options.paths:
        print("\n".join(paths_table(ours_ref.omega[0], ours_ref.delta)))
        return
    omega_ref, delta_ref, _, _ = time_domain("DOP853", 1e-13, ours_ref.omega[0] * 0.9)
    rows = []
    for rtol in (1e-3, 1e-4, 1e-6, 1e-8, 1e-10):
        seconds, motion = timed(lambda: steady_cycle(MACHINE, rtol=rtol))
        s = motion.steady
        rows.append(("ours: Newton shooting, RK4 in φ (compiled)", rtol, abs(s.omega[0] / omega_ref - 1),
                     abs(s.delta / delta_ref - 1), seconds,
                     f"{motion.numerics.steps} steps × {motion.numerics.iterations} Newton runs", "—"))
    start = ours_ref.omega[0] * 0.9
    for method in ("RK45", "DOP853", "Radau", "LSODA"):
        for rtol in (1e-4, 1e-6, 1e-8):
            seconds, (omega, delta, nfev, cycles) = timed(lambda: time_domain(method, rtol, start), repeat=1)
            rows.append((f"solve_ivp {method}, cycles until periodic", rtol, abs(omega / omega_ref - 1),
                         abs(delta / delta_ref - 1), seconds, f"{nfev} RHS calls", str(cycles)))
    lines = ["| method | rtol | error of ω(0) | error of δ | run time, ms | work | cycles |", "|---|---|---|---|---|---|---|"]
    lines += [f"| {m} | {r:.0e} | {e1:.1e} | {e2:.1e} | {1e3 * s:.1f} | {w} | {c} |" for m, r, e1, e2, s, w, c in rows]
    text = "\n".join(lines)
    text += ("\n\nCompiled loops (numba: RK4 in φ, DOP853 leaving rest) against the reference loops they are tested "
             f"against (plain Python RK4, scipy's DOP853), same run (compiling or loading them took {warm:.2f} s "
             "before the timings):\n\n" + "\n".join(paths_table(omega_ref, delta_ref)))
    header = (f"Crank-slider l₁ = 0.1 m, λ = 3, linear motor M = 60 − 0.3ω_m, i = 5, P_c = 2000 N, k_p = 0.2, f = 0.1.\n"
              f"Reference ω(0) = {omega_ref:.12g} rad/s, δ = {delta_ref:.10g} (DOP853, rtol 1e-13, in time). "
              f"solve_ivp starts at 0.9·ω(0) of the steady cycle.\n\n")
    print(header + text)
    if not options.no_write:
        options.output.write_text(header + text + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
