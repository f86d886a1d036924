"""Compile (or load from numba's disk cache, `__pycache__` beside each module) every compiled kernel before the
first request, so that no student waits for the JIT: the equation of motion's RK4 in φ, the flywheel's periodic
solution and DOP853 leaving rest (server.core.dynamics.compiled), and the elastic models' right-hand sides,
DOP853 and Radau IIA (server.core.elastic.warm), the friction equilibrium of a general mechanism
(server.core.kinetostatics.groups.compiled), its tables between the kinks (server.core.dynamics.kink_table),
what a slider family's second differences do not see (server.core.interpolation_error) and the induction motor's
successive approximations (server.core.dynamics.approximations_compiled). The first compile on a
fresh machine takes tens of seconds (tests/run.sh and the Dockerfile do it once, `python3 -m
server.core.warm_up`, which compiles the parts side by side on the machine's CPUs); a process that finds the cache
loads it in about a second.
"""
from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor

from . import interpolation_error
from .dynamics import approximations_compiled as approximations
from .dynamics import compiled as dynamics
from .dynamics import kink_table
from .elastic import warm as elastic
from .kinetostatics.groups import compiled as group_friction


PARTS = {"elastic machines": elastic.warm_up, "equation of motion": dynamics.warm_up,
         "friction in a general mechanism's pairs": group_friction.warm_up,
         "a slider family's interpolation error": interpolation_error.warm_up,
         "the induction motor's successive approximations": approximations.warm_up,
         "its tables between the kinks": kink_table.warm_up}   # the longest to compile first


def warm_up() -> dict[str, float]:
    """Seconds each part took: {"elastic machines": …, "equation of motion": …}."""
    return {name: part() for name, part in PARTS.items()}


def _part(name: str) -> float:
    return PARTS[name]()


def compile_in_parallel() -> dict[str, float]:
    """The parts compiled side by side, one process per CPU (each kernel has a cache file of its own, so the
    processes never write the same one): on a fresh checkout about half warm_up's minute on two CPUs. Seconds
    each part took."""
    processes = min(len(PARTS), os.cpu_count() or 1)
    if processes == 1:
        return warm_up()
    with ProcessPoolExecutor(processes, mp_context=multiprocessing.get_context("fork")) as pool:
        return dict(zip(PARTS, pool.map(_part, PARTS)))


if __name__ == "__main__":
    print(", ".join(f"{part}: {seconds:.1f} s" for part, seconds in compile_in_parallel().items()))
