"""Benchmark: a six-bar's dynamics requests through the general path beside the same requests on the dedicated
crank-slider, in this process (the endpoint bodies, validation included, no HTTP and no response cache),
interleaved so that both see the same machine and load.  Reports the medians and their ratio (the target of
the general pipeline: every dynamics request of a six-bar ≤ 20 ms of server compute).

  * reduction: J, dJ/dφ, M_c over 361 angles and the mean M_c0 on 8192 intervals;
  * motion: the steady cycle with a linear motor (rtol 1e-8), and the steady cycle with the start-up;
  * flywheel: Merzalov, Gutyar, Wittenbauer and the exact inertia with a constant motor, balanced.
Six-bars: the presets' own masses, loads, motors and [δ] (content/mechanisms/*.json "dynamics"); and the shaping
machine with dry friction f = 0.1 in every pair (r = 20 mm), f moved by 1e-9 for every request so that each
request solves its friction equilibria and finds its normal forces' kinks anew, as a dragged f slider does (both
are kept for an unchanged f otherwise, as is the table of M_T between the kinks that the equation of motion
reads, dynamics/kink_table.py; the kinematic kinks, the normal forces' scan setup and the table of J, J′,
M_useful and S, which do not depend on f, are kept across f: general_machine.kinematic_kinks, scan_normals,
smooth_table); and the same requests with f unchanged, as when another slider ([δ], the motor) is dragged: what
a tree keeps for an unchanged f is reused.  What a tree keeps per linkage, masses and loads (the table of J, J′,
M_useful, S) is built on the first round, untimed, as a dragged f, [δ] or motor finds it; a dragged mass builds
it anew on every request: the rows "shaping_machine, a new mass" move the first link's mass by 1e-9 per request
(the table's cost with it).

With ``--old PATH`` (another checkout, e.g. ``git worktree add --detach /tmp/old <commit>``, warmed up) the same
requests run in two worker processes, one importing this tree's server and one the other's, round by round in
turn (so both see the same load; each round's f is the same in both), and the table gives both medians, new/old
and the new one's ratio to the slider_crank's same request.

    python bench/general_dynamics.py [--repeats 15] [--old PATH]

Prints a Markdown table and writes it to bench/results/general_dynamics.md.
"""
from __future__ import annotations

import os
import platform
import statistics
import time

import side_by_side

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
ROUGH_KEPT = "shaping_machine, f = 0.1 unchanged"
MASS = "shaping_machine, a new mass"


def general(name: str, friction: float = 0.0) -> dict[str, tuple[str, dict]]:
    from server.core.structure.presets import presets
    preset = presets()[name]
    dynamics = preset["dynamics"]
    masses = dynamics["masses"] | ({"friction": friction, "pair_radius": 0.02} if friction else {})
    base = {"mechanism": "general", "linkage": preset["linkage"], "masses": masses, "inertias": dynamics["inertias"]}
    return requests(base, dynamics["motor"], dynamics["flywheel"])


def cases(repeat: int) -> dict[str, dict[str, tuple[str, dict]]]:
    """Every mechanism's requests; the rough shaping machine's f moved by 1e-9 per request (module docstring)."""
    out = {"slider_crank": requests(BASELINE, LINEAR, FLYWHEEL)} | {name: general(name) for name in SIX_BARS}
    kinds = list(out["slider_crank"])
    out[ROUGH] = {kind: general("shaping_machine", 0.1 + 1e-9 * (len(kinds) * repeat + k))[kind]
                  for k, kind in enumerate(kinds)}                # each request its own f: nothing kept for it
    out[ROUGH_KEPT] = general("shaping_machine", 0.1)             # the same f every time: what is kept for it
    out[MASS] = {kind: moved_mass(general("shaping_machine")[kind], 1e-9 * (len(kinds) * repeat + k))
                 for k, kind in enumerate(kinds)}                 # each request its own mass: nothing kept for it
    return out


def moved_mass(request: tuple[str, dict], by: float) -> tuple[str, dict]:
    """The request with its first link's mass moved by ``by`` kg."""
    endpoint, body = request
    links = [dict(link) for link in body["masses"]["links"]]
    links[0]["mass"] += by
    return endpoint, body | {"masses": body["masses"] | {"links": links}}


def one_round(repeat: int) -> dict[str, float]:
    """Seconds of each request, in order, labelled "mechanism|request"."""
    return side_by_side.timed({f"{mech}|{kind}": [request] for mech, reqs in cases(repeat).items()
                               for kind, request in reqs.items()})


def head(repeats: int, how: str) -> str:
    return (f"# General six-bar dynamics requests ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())})\n\n"
            f"Python {platform.python_version()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}, "
            f"{repeats} interleaved repeats{how}; endpoint bodies in-process (validation included, no HTTP, no "
            "cache); medians.\n\n")


def single(repeats: int) -> str:
    times = side_by_side.alone(one_round, repeats)         # interleaved: the same load for every case
    kinds = list(requests(BASELINE, LINEAR, FLYWHEEL))
    rows = ["| mechanism | " + " | ".join(f"{k}, ms (ratio)" for k in kinds) + " |", "|---|" + "---:|" * len(kinds)]
    for mech in cases(0):
        cells = []
        for kind in kinds:
            median = statistics.median(times[f"{mech}|{kind}"])
            base = statistics.median(times[f"slider_crank|{kind}"])
            cells.append(f"{1000 * median:.1f} ({median / base:.2f})")
        rows.append(f"| {mech} | " + " | ".join(cells) + " |")
    return head(repeats, "") + "ratio to the dedicated slider_crank's same request.\n\n" + "\n".join(rows) + "\n"


def compared(old: str, repeats: int) -> str:
    times = side_by_side.in_turn(__file__, old, repeats)
    rows = ["| mechanism | request | old, ms | new, ms | new/old | new p95, ms | new ratio to slider_crank |",
            "|---|---|---:|---:|---:|---:|---:|"]
    for label, old_ms, new_ms in side_by_side.medians_ms(times):
        mech, kind = label.split("|")
        p95 = 1e3 * statistics.quantiles(times["new"][label], n=20)[-1]
        base = 1e3 * statistics.median(times["new"][f"slider_crank|{kind}"])
        rows.append(f"| {mech} | {kind} | {old_ms:.1f} | {new_ms:.1f} | {new_ms / old_ms:.2f} | {p95:.1f} | "
                    f"{new_ms / base:.2f} |")
    return (head(repeats, f", old ({old}) and new (this tree) in two processes in turn") + "\n".join(rows)
            + "\n")


if __name__ == "__main__":
    side_by_side.main(__doc__, 15, "general_dynamics.md", one_round, compared, single)
