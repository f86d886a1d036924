"""The equation of motion's families against exact answers where the grids differ (a finding, not a test).

tests/test_family_bound.py compared an interpolated family with the exact answer leaf by leaf only where the
shapes agreed (it now reads every drawn curve on a common abscissa where the grids differ; this script stays as
the record of the finding, and runs on an old tree). A motion member's steady cycle and start-up are on the nodes of the level its Richardson estimate
stopped at, with every kink of the moments on a node, so a member next to the exact answer at the random value
may hold another grid (a coarser level: half the nodes), and where the kinks move with the slider, node k is
another angle in each member. Here the family (in-process, the page's body, time budgets lifted) is interpolated
at a random value of each interval (seeded), and each curve of φ (ω, t, ε; the start-up's ω and t) is compared
with the exact curve read at the interpolated φ by linear interpolation on the exact grid wherever that grid is
the finer (its own error, 1/8 of the largest second difference, added to the bound, as are the 5 digits sent
and packing's quantum). Printed: each family whose claimed interpolation error is within the tolerance but whose
curves are off by more, with the worst quantity and how far, relative to its span over the family.

    python3 bench/family_grid_check.py                 # every variant and slider of the scene at its defaults
    cd /tmp/old-tree && python3 /path/to/bench/family_grid_check.py        # the same for another tree
"""
from __future__ import annotations

import argparse
import json
import random
import sys
from pathlib import Path

import numpy as np

ROOT = Path.cwd()               # the tree whose families are checked (run from its root; an old worktree too)
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

from server.families import family  # noqa: E402
from server.api.endpoints import compute_answer  # noqa: E402
from server.api.routers import family as route  # noqa: E402
from server.core.dynamics import report  # noqa: E402
from server.lessons.scenes import scenes  # noqa: E402
from test_family import SENT, TOLERANCE  # noqa: E402
from server.lessons.family_requests import family_request  # noqa: E402
from test_family_fields import whole_members  # noqa: E402

VALUES = 3              # random values per family


def worst(body: dict, rng: random.Random) -> tuple[float, float, str]:
    """(claimed error, largest error found beyond the allowances (0 if none), where) of one family."""
    answer = json.loads(json.dumps(route.family_answer(json.loads(json.dumps(body)), "en")[0],
                                   default=lambda x: x.tolist()))
    values, log, members = answer["values"], body["log"], whole_members(answer)
    width, claim, found = family.spans(members), answer["interpolation_error"], (0.0, "")
    vary = [family.Vary(v["path"], v["factor"]) for v in body["vary"]]
    intervals = [k for k in range(len(values) - 1) if members[k] is not None and members[k + 1] is not None]
    for k in rng.sample(intervals, min(VALUES, len(intervals))):
        a, b = family.coordinate(values[k], log), family.coordinate(values[k + 1], log)
        value = family.from_coordinate(a + rng.uniform(0.05, 0.95) * (b - a), log)
        payload = compute_answer("motion", family.member_body(body["request"], vary, value)).payload
        exact = family.as_tree(family.pruned(payload, family.field_trie(body["fields"])), sent=False)
        preview = family.interpolate_family(values, members, value, log, answer["orders"])
        for holder in ((), ("startup",)):
            mine, theirs = family._leaf(preview, holder), family._leaf(exact, holder)
            if not (isinstance(mine, dict) and isinstance(theirs, dict) and "phi" in mine and "phi" in theirs):
                continue
            phi, fine_phi = np.asarray(mine["phi"], float), np.asarray(theirs["phi"], float)
            if phi.shape == fine_phi.shape or phi.size * 2 > fine_phi.size + 1:
                continue            # the same grid (test_family_bound's case), or the exact one not finer
            inside = (phi >= fine_phi[0]) & (phi <= fine_phi[-1])
            for key in ("omega", "t", "epsilon"):
                if key not in mine or key not in theirs or np.shape(mine[key]) != phi.shape:
                    continue
                fine = np.asarray(theirs[key], float)
                reading = np.interp(phi[inside], fine_phi, fine)
                span = width[(*holder, key)]
                allowed = (TOLERANCE + family.PACK_QUANTUM / 2) * span + SENT * np.abs(reading) \
                    + float(np.max(np.abs(np.diff(fine, 2)), initial=0.0)) / 8
                off = np.abs(np.asarray(mine[key], float)[inside] - reading)
                if np.any(off > allowed):
                    share = float(np.max(off) / span)
                    if share > found[0]:
                        found = (share, f"{'.'.join((*holder, key))} at {value:.5g}")
    return claim, *found


def main() -> None:
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                            formatter_class=argparse.RawDescriptionHelpFormatter,
                            epilog="Prints what it finds; writes nothing.").parse_args()
    report.TIME_BUDGET_S = family.TIME_BUDGET_S = 1e9
    scene = scenes()["equation-of-motion"]
    checked = beyond = 0
    for variant in scene.variants:
        rng = random.Random(f"grid-{variant.id}")
        for slider in variant.sliders:
            body = family_request(scene, variant, slider, None)
            claim, share, where = worst(body, rng)
            if claim is None or claim > TOLERANCE + family.PACK_QUANTUM / 2:
                continue
            checked += 1
            if share:
                beyond += 1
                print(f"{variant.id:10s} {slider.id:12s} claimed {100 * claim:.3f} %, {where} off by "
                      f"{100 * share:.2f} % of its span", flush=True)
    print(f"{beyond} of {checked} families within the tolerance by their claim are off by more somewhere")


if __name__ == "__main__":
    main()
