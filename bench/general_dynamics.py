"""Benchmark: a six-bar's dynamics requests through the general path beside the same requests on the dedicated
crank-slider, in this process (the endpoint bodies, validation included, no HTTP and no response cache),
interleaved so that both see the same machine and load.  Reports the medians and their ratio (the target of
the general pipeline: every dynamics request of a six-bar ≤ 20 ms of server compute).

  * reduction: J, dJ/dφ, M_c over 361 angles and the mean M_c0 on 8192 intervals;
  * motion: the steady cycle with a linear motor (rtol 1e-8), and the steady cycle with the start-up;
  * flywheel: Merzalov, Gutyar, Wittenbauer and the exact inertia with a constant motor, balanced.
Six-bars: the presets' own masses, loads, motors and [δ] (content/mechanisms/*.json "dynamics"); and the shaping
machine with dry friction f = 0.1 in every pair (r = 20 mm), f moved by 1e-9 at every repeat so that each
request finds its kinks anew, as a dragged f slider does (the kinks are kept per machine otherwise).

    python bench/general_dynamics.py [--repeats 15]

Prints a Markdown table and writes it to bench/results/general_dynamics.md.
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from server.api.endpoints import compute_answer  # noqa: E402
from server.core.dynamics import compiled  # noqa: E402
from server.core.structure.presets import presets  # noqa: E402

SIX_BARS = ("shaping_machine", "jaw_crusher", "v_engine")
BASELINE = {"mechanism": "slider_crank", "inertias": {"J1": 0.05, "m2": 2.0, "J_S2": 0.02, "m3": 3.0,
                                                      "J_rotor": 0.01, "gear_ratio": 3.0},
            "load": {"force": 500.0, "return_factor": 0.2}}
LINEAR = {"kind": "linear", "M0": 60.0, "b": 1.0}
FLYWHEEL = {"motor": {"kind": "constant", "M0": 30.0}, "omega_mean": 12.0, "delta": 0.04, "balance": True}


def requests(base: dict, motor: dict, flywheel: dict) -> dict[str, tuple[str, dict]]:
    return {"reduction": ("reduction", base | {"outputs": ["inertia", "resisting"], "n": 361}),
            "motion steady": ("motion", base | {"motor": motor, "outputs": ["steady"]}),
            "motion steady + start-up": ("motion", base | {"motor": motor, "outputs": ["steady", "startup"]}),
            "flywheel": ("flywheel", base | flywheel)}


ROUGH = "shaping_machine, f = 0.1"


def general(name: str, friction: float = 0.0) -> dict[str, tuple[str, dict]]:
    preset = presets()[name]
    dynamics = preset["dynamics"]
    masses = dynamics["masses"] | ({"friction": friction, "pair_radius": 0.02} if friction else {})
    base = {"mechanism": "general", "linkage": preset["linkage"], "masses": masses, "inertias": dynamics["inertias"]}
    return requests(base, dynamics["motor"], dynamics["flywheel"])


def timed(endpoint: str, body: dict) -> float:
    start = time.perf_counter()
    compute_answer(endpoint, body)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()
    compiled.warm_up()
    cases = {"slider_crank": requests(BASELINE, LINEAR, FLYWHEEL)} | {name: general(name) for name in SIX_BARS}
    cases[ROUGH] = general("shaping_machine", 0.1)
    times = {(mech, kind): [] for mech, reqs in cases.items() for kind in reqs}
    for mech, reqs in cases.items():                      # warm-up
        for endpoint, body in reqs.values():
            compute_answer(endpoint, body)
    for repeat in range(args.repeats):                    # interleaved: the same load for every case
        cases[ROUGH] = general("shaping_machine", 0.1 + 1e-9 * (repeat + 1))
        for mech, reqs in cases.items():
            for kind, (endpoint, body) in reqs.items():
                times[mech, kind].append(timed(endpoint, body))
    kinds = list(cases["slider_crank"])
    rows = ["| mechanism | " + " | ".join(f"{k}, ms (ratio)" for k in kinds) + " |",
            "|---|" + "---:|" * len(kinds)]
    for mech in cases:
        cells = []
        for kind in kinds:
            median = statistics.median(times[mech, kind])
            base = statistics.median(times["slider_crank", kind])
            cells.append(f"{1000 * median:.1f} ({median / base:.2f})")
        rows.append(f"| {mech} | " + " | ".join(cells) + " |")
    head = (f"# General six-bar dynamics requests ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())})\n\n"
            f"Python {platform.python_version()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}, "
            f"{args.repeats} interleaved repeats; endpoint bodies in-process (validation included, no HTTP, no "
            "cache); medians, ratio to the dedicated slider_crank's same request.\n\n")
    text = head + "\n".join(rows) + "\n"
    print(text)
    (ROOT / "bench" / "results" / "general_dynamics.md").write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
