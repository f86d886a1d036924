"""Long computations run in a process of their own, beside the worker that serves the light requests.

An elastic time integration or a live work–precision study holds the interpreter for up to seconds
(scipy's explicit solvers step in Python); run in the worker's thread pool, it would queue every
other student's 5-ms kinematics request behind it for the lock. In a separate process it uses the
other CPU and the worker stays free. Two lanes (LANES), each ``MDL_HEAVY_PROCESSES`` processes per worker
(default 1; 0 runs them in the worker itself, in one thread of their own): the answers a student waits for,
and the slider families at a lower priority still, so that a family never delays an answer (a family's coarse
stage, the 9-member preview a student waits for, runs in the answers' lane). A child that dies is replaced and the computation is
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
# Lanes of heavy work, each in processes of its own, and their scheduling priority below the workers' (man 2 nice):
# the answers a student waits for (an elastic machine, a live study) before the slider families, which only
# make dragging smoother and so take the CPU that is left.
# MDL_HEAVY_NICE=0 keeps them at the worker's own priority: on a host whose CPUs other processes keep busy (a test
# run of several processes) a lane at nice 15 gets almost no CPU and its families never arrive.
LANES = {"answers": 5, "families": 15}
NICE = os.environ.get("MDL_HEAVY_NICE", "1") != "0"
T = TypeVar("T")
_pools: dict[str, ProcessPoolExecutor] = {}
_stopped: weakref.WeakSet = weakref.WeakSet()   # pools ended by shutdown(): what broke there is not retried
_lock = threading.Lock()
_in_worker: ThreadPoolExecutor | None = None   # MDL_HEAVY_PROCESSES=0: one thread, not the light routes' pool


def _current_pool(lane: str) -> ProcessPoolExecutor:
    with _lock:
        if lane not in _pools:                # forkserver: no fork of a process that runs threads
            _pools[lane] = ProcessPoolExecutor(HEAVY_PROCESSES, mp_context=multiprocessing.get_context("forkserver"),
                                               initializer=_start_heavy_process, initargs=(LANES[lane] if NICE else 0,))
        return _pools[lane]


def _start_heavy_process(niceness: int) -> None:
    """A new heavy process yields the CPU (nice `niceness`) and loads the compiled kernels: a student's 5-ms
    answer is not made to wait behind seconds of an elastic run, nor an elastic answer behind a family."""
    os.nice(niceness)
    warm_up()


def start() -> None:
    """Start the heavy processes now (the server is starting), so that loading their compiled kernels does not
    fall on the first student's elastic request or family."""
    if HEAVY_PROCESSES:
        for lane in LANES:
            _current_pool(lane).submit(int)


def _discard(pool: ProcessPoolExecutor) -> None:
    with _lock:
        for lane, current in list(_pools.items()):
            if current is pool:
                del _pools[lane]
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
    with _lock:
        pools = list(_pools.values())
        _pools.clear()
    for pool in pools:
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
        # wait for it and forget its address: a server started again in this process (the tests start many)
        # then starts a new forkserver instead of asking the dying one for a process (EOFError)
        forget = getattr(server, "_stop", None)
        if forget is not None:
            forget()


def run(function: Callable[..., T], *args, lane: str = "answers") -> T:
    """function(*args) in a heavy process of `lane` (function and args picklable); its exceptions come back."""
    if HEAVY_PROCESSES == 0:
        return function(*args)
    for attempt in range(2):
        pool = _current_pool(lane)
        try:
            return pool.submit(function, *args).result()
        except BrokenProcessPool:
            if not _replaced(pool, attempt):
                raise
    raise AssertionError("unreachable")


async def submit(function: Callable[..., T], *args, lane: str = "answers") -> T:
    """function(*args) in a heavy process of `lane` (LANES), awaited without holding a thread; its exceptions
    come back.
    Cancelled while it waits (its client gone), it leaves the queue; one already running finishes unseen."""
    if HEAVY_PROCESSES == 0:
        return await asyncio.wrap_future(_local_threads().submit(function, *args))
    for attempt in range(2):
        pool = _current_pool(lane)
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
