"""Benchmark: the elastic machines, the compiled path against scipy's, and explicit against implicit solvers.

1. Each elastic scene's default request (every variant; its own outputs): the server's compute with scipy's
   solve_ivp stepping a Python right-hand side (engine "scipy", the reference path) against the compiled path
   (numba: scipy's DOP853 and Radau ported into compiled loops, engine "compiled"), side by side in one
   process; the error of the twist of both against a tight reference (compiled DOP853 at rtol 1e-11, 16
   times more steps), relative to the largest twist, beside the error estimate the answer carries.
2. Each variant's sliders swept over their ranges (9 positions each, the others at their defaults): the
   compiled request's compute time, median and p95.
3. Compile time of the compiled functions: cold (an empty numba cache) and cached (a fresh process loading
   numba's disk cache), each in a process of its own.
4. For four problems — a belt drive of moderate stiffness, a very stiff and heavily damped one (stiffness
   ratio ~1e4), an elastic crank-slider linkage and Drakunov–Tuleshova's elastic four-bar — every solve_ivp method and the two compiled solvers at
   several tolerances on the same first-order model (twists as states, analytic Jacobian for the implicit
   methods).  Error: the largest twist difference against a reference (Radau at rtol 1e-11 for the stiff
   problem, DOP853 at 1e-11 otherwise; compiled), relative to the largest twist.  The method the server picks by its
   stiffness measurement is marked.

0. (--versus OLD) Old beside new: the CPU time (time.process_time, not the wall clock: the machine is shared)
   of the server's compute and serialisation of every elastic variant's default request and of each slider's
   sweep (9 positions), each tree in processes of its own (its own ``server`` package and numba cache), the
   two trees taking turns, ROUNDS rounds, the least time of the rounds per request.

Run:  python bench/elastic.py      (writes bench/results/elastic.md; about ten minutes, mostly part 4's scipy
      rows; --quick leaves part 4 out; --positions N sweeps each slider at N values, not 9; --no-write
      prints only; --output PATH writes elsewhere)
      python bench/elastic.py --versus /tmp/elastic-old    (part 0 only, written to bench/results/elastic.md's
      first section; OLD e.g. ``mkdir /tmp/elastic-old && git archive 9b8d9d3 | tar -x -C /tmp/elastic-old``
      and ``python3 -m server.core.warm_up`` there)
"""
from __future__ import annotations

import argparse
import contextlib
import functools
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from server.lessons.scenes import scenes                                            # noqa: E402
from server.api import endpoints                                                 # noqa: E402
from server.api.endpoints import elastic_machine                          # noqa: E402
from server.lessons.requests import scene_request, slider_values               # noqa: E402
from server.api.schemas_elastic import ElasticRequest                            # noqa: E402
from server.core.dynamics.motors import Motor                                    # noqa: E402
from server.core.dynamics.reduction import Inertias                              # noqa: E402
from server.core.dynamics.resistance import Load                                 # noqa: E402
from server.core.elastic.warm import ready                                       # noqa: E402
from server.core.elastic.report import (ElasticMachine, absolute_tolerances,    # noqa: E402
                                        build, modal, no_load_speed, simulate)
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
    "Drakunov–Tuleshova elastic four-bar, b_n = 0.02": (ElasticMachine(
        "elastic_four_bar", "four_bar", FOUR_BAR, Inertias(J1=0.01, J3=0.05), Load(0.5), Motor("linear", M0=2.0, b=0.05),
        J_motor=0.02, compliances=Compliances(2e-6, 1e-9, 3e-6), b=0.02), 0.5),
}
METHODS = (("RK45", "scipy"), ("DOP853", "scipy"), ("DOP853", "compiled"), ("Radau", "scipy"),
           ("Radau", "compiled"), ("BDF", "scipy"), ("LSODA", "scipy"))
TOLERANCES = (1e-3, 1e-5, 1e-7, 1e-9)
BUDGET_S = 30.0
REFERENCE_RTOL = 1e-11


SWEEP_POSITIONS = 9


def run(machine, t_end, method, rtol, budget=BUDGET_S, engine="compiled"):
    model, y0 = build(machine)
    samples = np.linspace(0, t_end, 501)
    start = time.perf_counter()
    result = integrate(model, y0, t_end, rtol, method, samples, start + budget,
                       absolute_tolerances(machine, model, rtol), max_evaluations=5_000_000, engine=engine)
    return time.perf_counter() - start, result


def answer(request: ElasticRequest, engine: str) -> tuple[float, dict]:
    """The server's compute of the request, every output it asks for (endpoints.elastic, the body of POST
    /api/v1/elastic without the JSON), its time integration on ``engine`` and with a time budget (BUDGET_S, no
    request deadline) that a loaded machine does not reach: seconds, the answer's payload."""
    timed = functools.partial(simulate, engine=engine, budget_s=BUDGET_S)
    with patched(endpoints, simulate=timed, request_deadline=lambda: math.inf):
        start = time.perf_counter()
        result = endpoints.elastic(request, "en").payload
        return time.perf_counter() - start, result


@contextlib.contextmanager
def patched(module, **names):
    """The module's names replaced for the duration of the block."""
    saved = {name: getattr(module, name) for name in names}
    for name, value in names.items():
        setattr(module, name, value)
    try:
        yield
    finally:
        for name, value in saved.items():
            setattr(module, name, value)


def elastic_variants():
    return [(scene, variant) for scene in scenes().values() if scene.endpoint == "elastic"
            for variant in scene.variants if variant.id != "bearings"]


def scene_defaults() -> list[str]:
    """Part 1: old (scipy) and new (compiled) per default request, with errors against a tight reference."""
    lines = ["## Default requests of the elastic scenes: scipy's stepping against the compiled path\n",
             "Server compute of the request's outputs (the endpoint's body, without the JSON), median of 3 after one "
             "warm run; error: the twist against compiled DOP853 at rtol 1e-11, relative to the largest twist. A "
             "variant without time histories has no engine to compare: its compute time stands in the compiled "
             "column.\n",
             "| scene / variant | outputs | scipy, ms | compiled, ms | ratio | steps (scipy / compiled) | "
             "error scipy | error compiled | error estimate |", "|---|---|---:|---:|---:|---|---:|---:|---:|"]
    for scene, variant in elastic_variants():
        request = ElasticRequest.model_validate(scene_request(scene, variant))
        if "histories" not in request.outputs:        # nothing integrated in time: no engine to compare
            seconds = statistics.median(answer(request, "compiled")[0] for _ in range(4))
            lines.append(f"| {scene.id} / {variant.id} | {', '.join(request.outputs)} | — | {1e3 * seconds:.1f} | "
                         "— | no time integration | — | — | — |")
            continue
        times, results = {}, {}
        for engine in ("scipy", "compiled"):
            answer(request, engine)
            runs = [answer(request, engine) for _ in range(3)]
            times[engine] = statistics.median(seconds for seconds, _ in runs)
            results[engine] = runs[0][1]
        machine = elastic_machine(request)
        reference = simulate(machine, request.t_end, request.n, 1e-11, "DOP853", budget_s=120.0,
                             max_evaluations=50_000_000, with_rigid=False)[0]["twist"]
        scale = np.max(np.abs(reference))
        errors = {e: np.max(np.abs(r["twist"] - reference)) / scale for e, r in results.items()}
        numerics = {e: r["numerics"] for e, r in results.items()}
        lines.append(f"| {scene.id} / {variant.id} | {', '.join(request.outputs)} | {1e3 * times['scipy']:.0f} | "
                     f"{1e3 * times['compiled']:.1f} | {times['scipy'] / times['compiled']:.0f} | "
                     f"{numerics['scipy']['steps']} / {numerics['compiled']['steps']} | {errors['scipy']:.1e} | "
                     f"{errors['compiled']:.1e} | {numerics['compiled']['error_estimate']:.1e} |")
    return lines


def slider_sweeps(positions: int = SWEEP_POSITIONS) -> list[str]:
    """Part 2: the compiled request's compute time over each slider's range, at ``positions`` values of it."""
    lines = ["\n## Slider sweeps, compiled path\n",
             f"Each slider at {positions} positions over its range (the others at their defaults), each request "
             "once (a fresh machine: no table shared with the previous request unless the slider leaves the "
             "mechanism's tables alone, as the damping does).\n",
             "| scene / variant | slider | requests | median, ms | p95, ms | max, ms | partial answers |",
             "|---|---|---:|---:|---:|---:|---:|"]
    for scene, variant in elastic_variants():
        for slider in variant.sliders:
            values = slider_values(slider)
            picks = [values[round(k * (len(values) - 1) / (positions - 1))] for k in range(positions)]
            times, partial = [], 0
            for value in picks:
                request = ElasticRequest.model_validate(scene_request(scene, variant, {slider.id: value}))
                seconds, result = answer(request, "compiled")
                times.append(1e3 * seconds)
                partial += bool(result.get("numerics", {}).get("message"))
            lines.append(f"| {scene.id} / {variant.id} | {slider.id} | {len(times)} | {statistics.median(times):.1f} | "
                         f"{np.percentile(times, 95):.1f} | {max(times):.1f} | {partial} |")
    return lines


def compile_times() -> list[str]:
    """Part 3: warm_up() in a fresh process, with an empty numba cache and with the disk cache."""
    code = ("import sys, time; sys.path.insert(0, %r); start = time.perf_counter(); "
            "from server.core.elastic.warm import warm_up; imported = time.perf_counter() - start; "
            "print(imported, warm_up())" % str(Path(__file__).resolve().parents[1]))
    rows = []
    with tempfile.TemporaryDirectory() as empty:
        for label, env in (("cold (empty cache)", {"NUMBA_CACHE_DIR": empty}), ("cached (the same cache, new process)",
                                                                                 {"NUMBA_CACHE_DIR": empty})):
            output = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                                    env=os.environ | env).stdout.split()
            rows.append(f"| {label} | {float(output[0]):.2f} | {float(output[1]):.2f} |")
    return ["\n## Compile time of the compiled functions (warm_up())\n",
            "| numba cache | import, s | warm_up(), s |", "|---|---:|---:|", *rows]


ROUNDS = 3
TIMER = r"""
import json, os, sys, time
os.environ["MDL_HEAVY_PROCESSES"] = "0"
sys.path.insert(0, os.getcwd())
from server.lessons.scenes import scenes
from server.lessons.requests import scene_request, slider_values
from server.api.endpoints import compute_answer
from server.api.serialise import serialise
from server.core.warm_up import warm_up
warm_up()
times = {}
for scene in scenes().values():
    if scene.endpoint != "elastic":
        continue
    for variant in scene.variants:
        points = [("(default)", {})]
        for slider in variant.sliders:
            values = slider_values(slider)
            points += [(slider.id, {slider.id: values[round(k * (len(values) - 1) / 8)]}) for k in range(9)]
        for slider, values in points:
            body = scene_request(scene, variant, values)
            start = time.process_time()
            serialise(compute_answer("elastic", body, "en").payload)
            times.setdefault(f"{scene.id}|{variant.id}|{slider}", []).append(1e3 * (time.process_time() - start))
print(json.dumps(times))
"""


def versus(old: Path) -> list[str]:
    """Part 0: CPU ms per request, old tree beside this one (see the module's docstring)."""
    trees = {"old": old.resolve(), "new": Path(__file__).resolve().parents[1]}
    best: dict = {"old": {}, "new": {}}
    for _ in range(ROUNDS):
        for name, tree in trees.items():
            output = subprocess.run([sys.executable, "-c", TIMER], cwd=tree, capture_output=True, text=True,
                                    check=True).stdout
            for key, values in json.loads(output.splitlines()[-1]).items():
                best[name][key] = [min(a, b) for a, b in zip(best[name].get(key, values), values)]
    lines = ["## Old beside new — CPU time per answer (compute + serialisation), ms\n",
             f"`python bench/elastic.py --versus {old}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
             f"load average {os.getloadavg()[0]:.1f}; least of {ROUNDS} rounds per request, each tree in its own "
             "processes taking turns, each round a fresh process (empty caches) computing the requests in order. "
             "(default): the variant's default request; a slider: 9 positions over its "
             "range, the others at their defaults.\n",
             "| scene / variant | request | old p50 | old max | new p50 | new max | p50 old/new |",
             "|---|---|---:|---:|---:|---:|---:|"]
    per_scene: dict = {}
    for key in best["new"]:
        scene, variant, slider = key.split("|")
        old_ms, new_ms = np.array(best["old"][key]), np.array(best["new"][key])
        per_scene.setdefault(scene, ([], []))[0].extend(old_ms)
        per_scene[scene][1].extend(new_ms)
        lines.append(f"| {scene} / {variant} | {slider} | {np.median(old_ms):.1f} | {old_ms.max():.1f} | "
                     f"{np.median(new_ms):.1f} | {new_ms.max():.1f} | {np.median(old_ms) / np.median(new_ms):.1f}× |")
    lines += ["\n| scene | requests | old p50 | old p95 | new p50 | new p95 | p95 old/new | new p95 ≤ 20 ms |",
              "|---|---:|---:|---:|---:|---:|---:|---|"]
    for scene, (old_ms, new_ms) in per_scene.items():
        p95_old, p95_new = np.percentile(old_ms, 95), np.percentile(new_ms, 95)
        lines.append(f"| {scene} | {len(new_ms)} | {np.median(old_ms):.1f} | {p95_old:.1f} | {np.median(new_ms):.1f} | "
                     f"{p95_new:.1f} | {p95_old / p95_new:.1f}× | {'yes' if p95_new <= 20 else '**no**'} |")
    return lines


def arguments(argv: list[str] | None = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="leave part 4 (the methods at several tolerances) out")
    parser.add_argument("--versus", metavar="OLD", type=Path,
                        help="part 0 only: CPU time per answer, the tree OLD beside this one")
    parser.add_argument("--output", type=Path, default=Path(__file__).with_name("results") / "elastic.md",
                        help="the Markdown file written (default: %(default)s)")
    parser.add_argument("--positions", type=int, default=SWEEP_POSITIONS,
                        help="part 2: values of each slider over its range, at least 2 (default: %(default)s)")
    parser.add_argument("--no-write", action="store_true", help="print the tables only, write no file")
    options = parser.parse_args(argv)
    if options.positions < 2:
        parser.error("--positions: at least 2 (the ends of each slider's range)")
    return options


def main(argv: list[str] | None = None) -> None:
    options = arguments(argv)
    if options.versus is not None:
        section = "\n".join(versus(options.versus)) + "\n"
        print(section)
        if options.no_write:
            return
        path = options.output
        text = path.read_text(encoding="utf-8")
        start = text.find("## Old beside new")
        rest = text[text.find("\n## ", start + 1) + 1:] if start >= 0 else text[text.find("\n## ") + 1:]
        title = text[:text.find("\n## ") + 1] if start < 0 else text[:start]
        path.write_text(title + section + "\n" + rest, encoding="utf-8")
        return
    ready()
    lines = ["# Elastic models: compiled against scipy, error against run time\n",
             f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load average {os.getloadavg()[0]:.1f}, "
             f"{os.cpu_count()} CPUs{', --quick (no part 4)' if options.quick else ''}.\n",
             *scene_defaults(), *slider_sweeps(options.positions), *compile_times()]
    if not options.quick:
        lines += ["\n## Methods at several tolerances (part 4)"] + method_study()
    text = "\n".join(lines) + "\n"
    print(text)
    if not options.no_write:
        options.output.write_text(text, encoding="utf-8")


def method_study() -> list[str]:
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
                  "| method | engine | rtol | error | run time, ms | steps | RHS calls |",
                  "|---|---|---|---:|---:|---:|---:|"]
        for method, engine in METHODS:
            for rtol in TOLERANCES:
                times, result = [], None
                for _ in range(2):
                    seconds, result = run(machine, t_end, method, rtol, engine=engine)
                    times.append(seconds)
                if not result.complete or result.t.size != twist_ref.size:
                    lines.append(f"| {method} | {engine} | {rtol:.0e} | did not finish in budget | "
                                 f"{1e3 * min(times):.0f} | {result.numerics['steps']} | {result.numerics['nfev']} |")
                    continue
                error = np.max(np.abs(result.y[2] - twist_ref)) / np.max(np.abs(twist_ref))
                mark = " ←" if method == picked else ""
                lines.append(f"| {method}{mark} | {engine} | {rtol:.0e} | {error:.1e} | "
                             f"{1e3 * statistics.median(times):.1f} | {result.numerics['steps']} | "
                             f"{result.numerics['nfev']} |")
    return lines


if __name__ == "__main__":
    main()
