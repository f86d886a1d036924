"""Benchmark: the whole course project of a six-bar in one request, beside the separate requests a student
would otherwise send for the same sheets, in this process (the endpoint bodies, validation included, no HTTP and
no response cache), interleaved so that both see the same machine and load.

The project (POST /api/v1/course-project): 24 positions, dry friction f = 0.1 in every pair (r = 20 mm), the
preset's masses, loads and [δ]; each request's first link's mass moved by 1e-9 kg so that nothing a tree keeps
per machine is reused (a student editing the design data), and once more with the machine unchanged and [δ]
moved (a student trying another [δ]).  The separate requests for the same content: the kinematics over the turn
(361 angles, every joint's analogs and the special positions), the velocity and acceleration plans at each of
the 24 positions (one /kinematics request each, `plan`), the reduction (J, M_c), the flywheel for [δ] and the
forces by groups with friction (at a constant ω₁ₘ, as /forces takes it); their sum is the baseline.  Target:
the project ≤ 500 ms of server compute.

    python bench/course_project.py [--repeats 15] [--old PATH]

Prints a Markdown table and writes it to bench/results/course_project.md.
"""
from __future__ import annotations

import math
import os
import platform
import statistics
import time

import side_by_side

MACHINES = ("shaping_machine", "jaw_crusher")
POSITIONS = 24
FRICTION = {"friction": 0.1, "pair_radius": 0.02}


def design(name: str, by: float) -> tuple[dict, dict]:
    """The preset's linkage and its design data with friction, the first link's mass moved by ``by`` kg."""
    from server.core.structure.presets import presets
    preset = presets()[name]
    dynamics = preset["dynamics"]
    links = [dict(link) for link in dynamics["masses"]["links"]]
    links[0]["mass"] += by
    return preset["linkage"], dynamics | {"masses": dynamics["masses"] | FRICTION | {"links": links}}


def project(name: str, by: float, delta_by: float = 0.0) -> tuple[str, dict]:
    linkage, dynamics = design(name, by)
    flywheel = dynamics["flywheel"]
    return "course-project", {"linkage": linkage, "masses": dynamics["masses"], "inertias": dynamics["inertias"],
                              "omega_mean": flywheel["omega_mean"], "delta": flywheel["delta"] + delta_by,
                              "positions": POSITIONS}


def separate(name: str, by: float) -> list[tuple[str, dict]]:
    """The requests that give the same sheets one by one (module docstring)."""
    linkage, dynamics = design(name, by)
    flywheel, omega = dynamics["flywheel"], dynamics["flywheel"]["omega_mean"]
    general = {"mechanism": "general", "linkage": linkage}
    machine = general | {"masses": dynamics["masses"], "inertias": dynamics["inertias"]}
    turn = [("kinematics", general | {"n": 361, "outputs": ["joints", "joints_d1", "joints_d2", "angles",
                                                            "angles_d1", "angles_d2", "slides", "slides_d1",
                                                            "slides_d2", "structure", "special"]})]
    plans = [("kinematics", general | {"outputs": ["plan"], "phi": [0.0],
                                       "plan": {"phi": 2 * math.pi * k / POSITIONS, "omega1": omega, "epsilon1": 0.0}})
             for k in range(POSITIONS)]
    dynamics_requests = [("reduction", machine | {"outputs": ["inertia", "resisting"], "n": 361}),
                         ("flywheel", machine | flywheel),
                         ("forces", general | {"masses": dynamics["masses"], "n": 361, "free_body_phi": 1.0,
                                              "loads": {"omega": omega, "epsilon": 0.0}})]
    return turn + plans + dynamics_requests


def one_round(repeat: int) -> dict[str, float]:
    """Seconds of each case, labelled "machine|case"."""
    requests = {}
    for k, name in enumerate(MACHINES):
        by = 1e-9 * (repeat * len(MACHINES) + k + 1)
        requests |= {f"{name}|project": [project(name, by)],
                     f"{name}|project, another [δ]": [project(name, 0.0, by * 1e3)],
                     f"{name}|separate requests": separate(name, by)}
    return side_by_side.timed(requests)


def head(repeats: int, how: str) -> str:
    return (f"# The course project in one request ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())})\n\n"
            f"Python {platform.python_version()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}, "
            f"{repeats} interleaved repeats{how}; endpoint bodies in-process (validation included, no HTTP, no "
            f"cache); {POSITIONS} positions, f = 0.1 in every pair; medians and p95.\n\n")


def single(repeats: int) -> str:
    times = side_by_side.alone(one_round, repeats)
    rows = ["| machine | project, ms (p95) | project with another [δ], ms | separate requests, ms | "
            "project / separate |", "|---|---:|---:|---:|---:|"]
    for name in MACHINES:
        values = times[f"{name}|project"]
        whole = statistics.median(values)
        again = statistics.median(times[f"{name}|project, another [δ]"])
        parts = statistics.median(times[f"{name}|separate requests"])
        p95 = statistics.quantiles(values, n=20)[-1]
        rows.append(f"| {name} | {1e3 * whole:.0f} ({1e3 * p95:.0f}) | {1e3 * again:.0f} | {1e3 * parts:.0f} | "
                    f"{whole / parts:.2f} |")
    return head(repeats, "") + "\n".join(rows) + "\n"


def compared(old: str, repeats: int) -> str:
    times = side_by_side.in_turn(__file__, old, repeats)
    rows = ["| machine | case | old, ms | new, ms | new/old |", "|---|---|---:|---:|---:|"]
    for label, old_ms, new_ms in side_by_side.medians_ms(times):
        name, case = label.split("|")
        rows.append(f"| {name} | {case} | {old_ms:.0f} | {new_ms:.0f} | {new_ms / old_ms:.2f} |")
    return head(repeats, f", old ({old}) and new (this tree) in two processes in turn") + "\n".join(rows) + "\n"


if __name__ == "__main__":
    side_by_side.main(__doc__, 15, "course_project.md", one_round, compared, single)
