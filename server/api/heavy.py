"""Long computations run in a process of their own, beside the worker that serves the light requests.

An elastic time integration or a live work–precision study holds the interpreter for up to seconds
(scipy's explicit solvers step in Python); run in the worker's thread pool, it would queue every
other student's 5-ms kinematics request behind it for the lock. In a separate process it uses the
other CPU and the worker stays free. ``MDL_HEAVY_PROCESSES`` processes per worker (default 1; 0 runs
them in the worker itself, in one thread of their own). A child that dies is replaced and the computation is
tried once more.

A route awaits ``submit``: the wait holds no thread, so heavy requests never take the tokens of the thread
pool that runs the light (sync) routes — 64 waiting elastic requests cost 64 suspended coroutines, not 64 of
anyio's 40 threads. ``run`` is the blocking form for code that is not async.
"""
from __future__ import annotations

import asyncio
import multiprocessing
import multiprocessing.forkserver
import os
import signal
import threading
import weakref
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Callable, TypeVar

from ..core.warm_up import warm_up

HEAVY_PROCESSES = int(os.environ.get("MDL_HEAVY_PROCESSES", "1"))
HEAVY_NICENESS = 10            # the heavy processes' scheduling priority below the workers' (man 2 nice)
T = TypeVar("T")
_pool: ProcessPoolExecutor | None = None
_stopped: weakref.WeakSet = weakref.WeakSet()   # pools ended by shutdown(): what broke there is not retried
_lock = threading.Lock()
_in_worker: ThreadPoolExecutor | None = None   # MDL_HEAVY_PROCESSES=0: one thread, not the light routes' pool


def _current_pool() -> ProcessPoolExecutor:
    global _pool
    with _lock:
        if _pool is None:                     # forkserver: no fork of a process that runs threads
            _pool = ProcessPoolExecutor(HEAVY_PROCESSES, mp_context=multiprocessing.get_context("forkserver"),
                                        initializer=_start_heavy_process)
        return _pool


def _start_heavy_process() -> None:
    """A new heavy process yields the CPU to the workers (nice HEAVY_NICENESS) and loads the compiled kernels:
    a student's 5-ms answer is not made to wait behind seconds of a family or an elastic run."""
    os.nice(HEAVY_NICENESS)
    warm_up()


def start() -> None:
    """Start the heavy processes now (the server is starting), so that loading their compiled kernels does not
    fall on the first student's elastic request."""
    if HEAVY_PROCESSES:
        _current_pool().submit(int)


def _discard(pool: ProcessPoolExecutor) -> None:
    global _pool
    with _lock:
        if _pool is pool:
            _pool = None
    pool.shutdown(wait=False, cancel_futures=True)


def _local_threads() -> ThreadPoolExecutor:
    global _in_worker
    with _lock:
        if _in_worker is None:
            _in_worker = ThreadPoolExecutor(1, thread_name_prefix="mdl-heavy")
        return _in_worker


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
            if not _replaced(pool, attempt):
                raise
    raise AssertionError("unreachable")


async def submit(function: Callable[..., T], *args) -> T:
    """function(*args) in the heavy process, awaited without holding a thread; its exceptions come back.
    Cancelled while it waits (its client gone), it leaves the queue; one already running finishes unseen."""
    if HEAVY_PROCESSES == 0:
        return await asyncio.wrap_future(_local_threads().submit(function, *args))
    for attempt in range(2):
        pool = _current_pool()
        try:
            return await asyncio.wrap_future(pool.submit(function, *args))
        except BrokenProcessPool:
            if not _replaced(pool, attempt):
                raise
    raise AssertionError("unreachable")


def _replaced(pool: ProcessPoolExecutor, attempt: int) -> bool:
    """Whether a broken pool is replaced for one more try: not when shutdown() ended it (the server is
    stopping), nor after the second try."""
    if pool in _stopped:
        return False
    _discard(pool)
    return attempt == 0
