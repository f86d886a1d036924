"""What the in-process side-by-side benchmarks share (bench/general_dynamics.py, bench/group_forces.py): a worker
process per tree, importing that tree's ``server`` (the tree first on sys.path), warmed up, that times one round
of requests per line it reads; two such workers, old and new, given the same round in turn so that both see the
same machine and load; and the command line: ``--repeats``, ``--old PATH`` (side by side; without it, this tree
alone), the result written to bench/results/.
"""
from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Callable

ROOT = Path(__file__).resolve().parents[1]

Round = Callable[[int], dict[str, float]]       # round number → seconds by label


def serve(root: str, one_round: Round) -> None:
    """A worker: import the server of ``root``, warm up (the compiled kernels, then one untimed round), say
    "ready", then one round per line read (its number), its times as a JSON line."""
    sys.path.insert(0, root)
    from server.core.warm_up import warm_up
    warm_up()
    one_round(0)
    print("ready", flush=True)
    for line in sys.stdin:
        print(json.dumps(one_round(int(line))), flush=True)


def in_turn(script: str, old: str, repeats: int) -> dict[str, dict[str, list[float]]]:
    """{"old"|"new": {label: [seconds, ...]}}: ``repeats`` rounds of ``script``'s workers for the tree ``old``
    and this one, in turn."""
    workers = {}
    for tag, root in (("old", old), ("new", str(ROOT))):
        workers[tag] = subprocess.Popen([sys.executable, script, "--serve", root], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, text=True)
        assert workers[tag].stdout.readline().strip() == "ready"
    times: dict[str, dict[str, list[float]]] = {tag: {} for tag in workers}
    for repeat in range(1, repeats + 1):
        for tag, worker in workers.items():
            worker.stdin.write(f"{repeat}\n")
            worker.stdin.flush()
            for label, seconds in json.loads(worker.stdout.readline()).items():
                times[tag].setdefault(label, []).append(seconds)
    for worker in workers.values():
        worker.stdin.close()
        worker.wait()
    return times


def timed(requests: dict[str, list[tuple[str, dict]]]) -> dict[str, float]:
    """Seconds by label of its requests (endpoint, body), computed in this process one after another through the
    endpoints' bodies (validation included, no HTTP, no cache): what each worker's round times."""
    from server.api.endpoints import compute_answer
    times = {}
    for label, asked in requests.items():
        start = time.perf_counter()
        for endpoint, body in asked:
            compute_answer(endpoint, body)
        times[label] = time.perf_counter() - start
    return times


def medians_ms(times: dict[str, dict[str, list[float]]]) -> list[tuple[str, float, float]]:
    """(label, old median ms, new median ms) of every label both trees timed (``in_turn``), in the new tree's
    order."""
    return [(label, 1e3 * statistics.median(times["old"][label]), 1e3 * statistics.median(values))
            for label, values in times["new"].items() if label in times["old"]]


def alone(one_round: Round, repeats: int) -> dict[str, list[float]]:
    """{label: [seconds, ...]}: ``repeats`` rounds of this tree, in this process, after the same warm-up."""
    sys.path.insert(0, str(ROOT))
    from server.core.warm_up import warm_up
    warm_up()
    one_round(0)
    times: dict[str, list[float]] = {}
    for repeat in range(1, repeats + 1):
        for label, seconds in one_round(repeat).items():
            times.setdefault(label, []).append(seconds)
    return times


def main(doc: str, repeats: int, result: str, one_round: Round,
         compared: Callable[[str, int], str], single: Callable[[int], str]) -> None:
    """The command line: a worker (``--serve``), side by side (``--old``) or this tree alone; the table printed
    and written to bench/results/``result``."""
    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=repeats)
    parser.add_argument("--old", help="another checkout to compare with, side by side")
    parser.add_argument("--serve", help=argparse.SUPPRESS)
    parser.add_argument("--no-write", action="store_true",
                        help=f"print the table only, do not write bench/results/{result}")
    args = parser.parse_args()
    if args.serve:
        serve(args.serve, one_round)
        return
    text = compared(args.old, args.repeats) if args.old else single(args.repeats)
    print(text)
    if not args.no_write:
        (ROOT / "bench" / "results" / result).write_text(text, encoding="utf-8")


if __name__ == "__main__":
    epilog = ("A module: the side-by-side benchmarks' shared code (bench/course_project.py, general_dynamics.py, "
              "group_forces.py); nothing to run by itself.")
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=epilog).parse_args()
