"""Long computations run in a process of their own, beside the worker that serves the light requests.

An elastic time integration or a live work–precision study holds the interpreter for up to seconds
(scipy's explicit solvers step in Python); run in the worker's thread pool, it would queue every
other student's 5-ms kinematics request behind it for the lock. In a separate process it uses the
other CPU and the worker stays free. ``MDL_HEAVY_PROCESSES`` processes per worker (default 1; 0 runs
them in the worker itself). A child that dies is replaced and the computation is tried once more.
"""
from __future__ import annotations

import asyncio
import multiprocessing
import multiprocessing.forkserver
import os
import signal
import threading
import weakref
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Callable, TypeVar

HEAVY_PROCESSES = int(os.environ.get("MDL_HEAVY_PROCESSES", "1"))
T = TypeVar("T")
_pool: ProcessPoolExecutor | None = None
_stopped: weakref.WeakSet = weakref.WeakSet()   # pools ended by shutdown(): what broke there is not retried
_lock = threading.Lock()


def _current_pool() -> ProcessPoolExecutor:
    global _pool
    with _lock:
        if _pool is None:                     # forkserver: no fork of a process that runs threads
            _pool = ProcessPoolExecutor(HEAVY_PROCESSES, mp_context=multiprocessing.get_context("forkserver"))
        return _pool


def _discard(pool: ProcessPoolExecutor) -> None:
    global _pool
    with _lock:
        if _pool is pool:
            _pool = None
    pool.shutdown(wait=False, cancel_futures=True)


def shutdown() -> None:
    """End the heavy processes and their forkserver (the server is stopping): they are not our children
    once the forkserver has started them, so they would outlive the worker. A computation still waiting
    for its answer (its client gone) then fails instead of starting a new pool that nobody would end."""
    global _pool
    with _lock:
        pool, _pool = _pool, None
    if pool is not None:
        _stopped.add(pool)
        for process in list(getattr(pool, "_processes", {}).values()):
            process.kill()
        pool.shutdown(wait=False, cancel_futures=True)
    server = getattr(multiprocessing.forkserver, "_forkserver", None)
    pid = getattr(server, "_forkserver_pid", None)
    if pid:
        try:
            os.kill(pid, signal.SIGTERM)
        except ProcessLookupError:
            pass


def run(function: Callable[..., T], *args) -> T:
    """function(*args) in the heavy process (function and args picklable); its exceptions come back."""
    if HEAVY_PROCESSES == 0:
        return function(*args)
    for attempt in range(2):
        pool = _current_pool()
        try:
            return pool.submit(function, *args).result()
        except BrokenProcessPool:
            if pool in _stopped:               # ended by shutdown(): the server is stopping
                raise
            _discard(pool)
            if attempt:
                raise
    raise AssertionError("unreachable")


async def submit(function: Callable[..., T], *args) -> T:
    """function(*args) in the heavy process, awaited without holding a thread of the worker (a thread when
    HEAVY_PROCESSES is 0); a pool that broke is replaced and the computation tried once more, as in run()."""
    if HEAVY_PROCESSES == 0:
        return await asyncio.to_thread(function, *args)
    for attempt in range(2):
        pool = _current_pool()
        try:
            return await asyncio.wrap_future(pool.submit(function, *args))
        except BrokenProcessPool:
            if pool in _stopped:               # ended by shutdown(): the server is stopping
                raise
            _discard(pool)
            if attempt:
                raise
    raise AssertionError("unreachable")
