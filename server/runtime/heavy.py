"""Long computations run in a process of their own, beside the worker that serves the light requests.

An elastic time integration or a live work–precision study holds the interpreter for up to seconds
(scipy's explicit solvers step in Python); run in the worker's thread pool, it would queue every
other student's 5-ms kinematics request behind it for the lock. In a separate process it uses the
other CPU and the worker stays free. Three lanes (LANES), each ``MDL_HEAVY_PROCESSES`` processes per worker
(default 1, twice as many for the previews; 0 runs them in the worker itself, in one thread per lane):
- the answers a student waits for (an elastic machine, a live study, the course project);
- the previews, a slider family's coarse stage (the 9 members a student waits for while dragging);
- the refinements, a family's full stage, at a lower priority still.
An answer never waits for a preview to finish: in a class the previews' lane is rarely idle, and a 10-ms elastic
answer queued behind a 9-member preview on a busy CPU took 0.4–0.7 s (bench/results/capacity_staggered.md). A
child that dies is replaced and the computation is tried once more.

Each lane's queue is kept in the worker (LaneQueue): at most one job per heavy process is handed to the pool, so
that a job given up while it waits always leaves the queue. Jobs go oldest first, except those submitted
``newest_first`` (the refinements), which go newest first: in a class that asks for families faster than the
CPUs make them, the newest is the one a student still holds a slider for, the oldest the ones most likely given
up. A family whose client goes away (the page aborts it when the student grabs another slider, or leaves) leaves
the queue, and one already running stops before its next chunk of members (``stopped``, read by
family_batch.member_batch), so that its CPU goes to the families still wanted.

The queues say how busy the worker is (``busy``, ``crowded``): a busy worker does not start a family's
refinement (its coarse family is the answer), and while previews queue each takes fewer members.
``TIMING`` tells the request that submitted a job where the job's time went (its Server-Timing header).

A route awaits ``submit``: the wait holds no thread, so heavy requests never take the tokens of the thread
pool that runs the light (sync) routes — 64 waiting elastic requests cost 64 suspended coroutines, not 64 of
anyio's 40 threads. ``run`` is the blocking form for code that is not async.
"""
from __future__ import annotations

import asyncio
import contextvars
import gc
import importlib
import itertools
import multiprocessing
import os
import threading
import time
import weakref
from concurrent.futures import Future, ProcessPoolExecutor, ThreadPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from typing import Callable, TypeVar

from ..core.warm_up import warm_up

HEAVY_PROCESSES = int(os.environ.get("MDL_HEAVY_PROCESSES", "1"))
# Lanes of heavy work, each in processes of its own, and their scheduling priority below the workers' (man 2 nice):
# the answers a student waits for (an elastic machine, a live study) and the previews a dragging student waits for
# beside each other, before the slider families' refinements, which only make dragging smoother and so take the
# CPU that is left.
# MDL_HEAVY_NICE=0 keeps them at the worker's own priority: on a host whose CPUs other processes keep busy (a test
# run of several processes) a lane at nice 15 gets almost no CPU and its families never arrive.
LANES = {"answers": 5, "previews": 5, "families": 15}
# Processes of a lane per MDL_HEAVY_PROCESSES: two for the previews, so that one slow preview (a family whose
# members are each a slow answer, on a CPU the worker keeps busy: 0.56 CPU-s took 2.4 s) does not hold every
# preview asked after it; on a single CPU the two share it, and the short preview comes out first.
LANE_PROCESSES = {"previews": 2}
NICE = os.environ.get("MDL_HEAVY_NICE", "1") != "0"
T = TypeVar("T")
_pools: dict[str, ProcessPoolExecutor] = {}
_stopped: weakref.WeakSet = weakref.WeakSet()   # pools ended by shutdown(): what broke there is not retried
_lock = threading.Lock()
_in_worker: dict[str, ThreadPoolExecutor] = {}   # MDL_HEAVY_PROCESSES=0: one thread per lane, not the light routes' pool
STOP_SLOTS = 1024              # a stop is written to slot ticket % STOP_SLOTS, holding the ticket it stops
_tickets = itertools.count(1)
_stops = multiprocessing.RawArray("q", STOP_SLOTS)   # the worker's: what it has stopped; a heavy process gets it
_stop_flags = _stops           # read by `stopped`: in a heavy process, the array its worker writes
_running = threading.local()  # .ticket: in a heavy process (or a lane's thread in the worker), the job it runs
# Where a request's heavy job spent its time, filled in by `submit` when the request's handler set a dict here
# (admission does, for its Server-Timing header): "queue" the wait in the lane's queue, "run" the job's wall time in
# its process, "cpu" the CPU time it took there; seconds.
TIMING: contextvars.ContextVar[dict | None] = contextvars.ContextVar("mdl_heavy_timing", default=None)


_preload: list[str] = []       # the modules a new heavy process imports (``preload``)


def preload(module: str) -> None:
    """A module whose functions are given to the lanes, imported by the forkserver before it forks the heavy
    processes (multiprocessing's forkserver preload, with forkserver_preload, which loads the compiled kernels),
    and again by each new heavy process, where it is then already there: the module that submits them names
    itself, ``preload(__name__)``."""
    if module not in _preload:
        _preload.append(module)


def _current_pool(lane: str) -> ProcessPoolExecutor:
    with _lock:
        if lane not in _pools:                # forkserver: no fork of a process that runs threads
            context = multiprocessing.get_context("forkserver")
            context.set_forkserver_preload([*_preload, f"{__package__}.forkserver_preload"])
            _pools[lane] = ProcessPoolExecutor(processes(lane), mp_context=context,
                                               initializer=_start_heavy_process,
                                               initargs=(LANES[lane] if NICE else 0, _stops, tuple(_preload)))
        return _pools[lane]


def processes(lane: str) -> int:
    """The heavy processes of `lane` per worker (0: its jobs run in a thread of the worker)."""
    return HEAVY_PROCESSES * LANE_PROCESSES.get(lane, 1)


def _start_heavy_process(niceness: int, stops, modules: tuple[str, ...] = ()) -> None:
    """A new heavy process yields the CPU (nice `niceness`) and loads the compiled kernels: a student's 5-ms
    answer is not made to wait behind seconds of an elastic run, nor an elastic answer behind a family. It reads
    its worker's stops from `stops` (shared memory), and imports the modules of the work it will be given
    (`modules`: those named to ``preload``). Forked by a forkserver that has loaded both (forkserver_preload), it
    finds them there and this takes milliseconds; the forkserver skips a preload that fails, and then it is here
    that they are loaded. What it
    holds then (modules, compiled code: ~185 000 objects) is frozen out of the garbage collector's reach
    (``frozen_after_start``)."""
    global _stop_flags
    _stop_flags = stops
    os.nice(niceness)
    warm_up()
    for module in modules:               # the modules of the work the lanes are given: unpickling a job imports its
        importlib.import_module(module)  # function's module, ~0.4 s on the first family
    frozen_after_start()


def frozen_after_start() -> None:
    """gc.freeze(): the objects a process holds once started (its modules, the compiled kernels, the lessons)
    live as long as it does, and a full collection no longer walks them. The family engine's members and the memo
    make many long-lived objects, and each full collection walked all of them: 59–71 ms each, 5–9 ms frozen
    (bench/results/family_engine.md)."""
    gc.collect()
    gc.freeze()


def _run_ticketed(ticket: int, function: Callable[..., T], args: tuple) -> tuple[T, float, float]:
    """function(*args) as job `ticket`, so that `stopped` can tell whether its client has given it up; with the
    wall and the CPU seconds it took (the CPU of this thread: in a heavy process, of the job alone)."""
    _running.ticket = ticket
    wall, cpu = time.perf_counter(), time.thread_time()
    try:
        return function(*args), time.perf_counter() - wall, time.thread_time() - cpu
    finally:
        _running.ticket = 0


def stopped() -> bool:
    """Whether the job running here has been given up by its client (read between chunks of work; always False
    outside a job)."""
    ticket = getattr(_running, "ticket", 0)
    return ticket != 0 and _stop_flags[ticket % STOP_SLOTS] == ticket


def start() -> None:
    """Start the heavy processes now (the server is starting), so that loading their compiled kernels does not
    fall on the first student's elastic request or family."""
    if HEAVY_PROCESSES:
        for lane in LANES:
            for _ in range(processes(lane)):    # submitted while none is idle yet: each starts a process
                _current_pool(lane).submit(int)


def _discard(pool: ProcessPoolExecutor) -> None:
    with _lock:
        for lane, current in list(_pools.items()):
            if current is pool:
                del _pools[lane]
    pool.shutdown(wait=False, cancel_futures=True)


def _local_thread(lane: str) -> ThreadPoolExecutor:
    with _lock:
        if lane not in _in_worker:
            _in_worker[lane] = ThreadPoolExecutor(1, thread_name_prefix=f"mdl-heavy-{lane}")
        return _in_worker[lane]


def shutdown() -> None:
    """End the heavy processes (the server is stopping): they are not our children once the forkserver has
    started them, so they would outlive the worker. A computation still waiting for its answer (its client gone)
    then fails instead of starting a new pool that nobody would end. The forkserver is left running: it ends with
    this process (it reads the end of the pipe that this process holds open), so it never outlives the worker,
    and an app started again in the same process (the tests start app after app) forks its heavy processes from
    it without loading the compiled kernels again (~3 CPU-s)."""
    with _lock:
        pools = list(_pools.values())
        _pools.clear()
    for pool in pools:
        _stopped.add(pool)
        for process in list(getattr(pool, "_processes", {}).values()):
            process.kill()
        # with its processes gone the pool's manager ends at once; waiting for it lets the pool close its queues,
        # whose named semaphores are then released (else: "resource_tracker: … leaked semaphore objects")
        pool.shutdown(wait=True, cancel_futures=True)


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


async def submit(function: Callable[..., T], *args, lane: str = "answers", newest_first: bool = False) -> T:
    """function(*args) in a heavy process of `lane` (LANES), awaited without holding a thread; its exceptions
    come back. `newest_first`: a refinement (a slider's full family) that waits behind the lane's other jobs and
    before the refinements asked before it (LaneQueue).
    Cancelled while it waits (its client gone), it leaves the lane's queue (LaneQueue); one already running is
    told so by `stopped` (a family reads it between chunks of members; other work finishes unseen)."""
    return await _queues[lane].submit(function, args, newest_first)


def busy() -> bool:
    """Whether this worker's heavy lanes have no CPU to spare for a family's refinement: an answer or a preview
    waits for its lane's process (taken, and more queued behind it), or the families' lane holds a job (running
    or waiting). A refinement then is not started: the grab gets its coarse family only
    (routers/family.py), and the CPU goes to the exact answers and the first previews. Read from the lanes'
    queues in this worker (each worker has its own lanes), so it says the same for the same sequence of
    requests whatever the machine's speed."""
    return (_queues["answers"].pressure() > 0 or _queues["previews"].pressure() > 0
            or _queues["families"].occupied() > 0)


def crowded() -> bool:
    """Whether previews queue in their lane: as many wait there as it has processes, or more. A first preview
    then takes fewer members (family.LEAN_MEMBERS), so that the queue drains sooner."""
    return _queues["previews"].pressure() >= _queues["previews"].capacity()


def _replaced(pool: ProcessPoolExecutor, attempt: int) -> bool:
    """Whether a broken pool is replaced for one more try: not when shutdown() ended it (the server is
    stopping), nor after the second try."""
    if pool in _stopped:
        return False
    _discard(pool)
    return attempt == 0


@dataclass(eq=False)
class _Job:
    function: Callable
    args: tuple
    loop: asyncio.AbstractEventLoop
    done: asyncio.Future
    newest_first: bool
    ticket: int = field(default_factory=lambda: next(_tickets))
    tries: int = 0
    running: bool = False
    queued: float = field(default_factory=time.perf_counter)   # when it joined the queue
    queue_s: float = 0.0                                       # its wait there, once it ran


class LaneQueue:
    """A lane's queue in the worker: at most `capacity()` jobs handed to the lane's pool (one per process, so that
    none waits in the pool's own queue, out of reach). Next goes the oldest job waiting, else the newest of those
    submitted `newest_first` (the refinements). A job whose awaiting coroutine is cancelled leaves the queue, or,
    running, has its stop written for `stopped` to read."""

    def __init__(self, lane: str):
        self.lane = lane
        self.waiting: list[_Job] = []
        self.running = 0
        self.lock = threading.Lock()

    def capacity(self) -> int:
        """Jobs it runs at once: its processes (one thread in the worker when MDL_HEAVY_PROCESSES is 0)."""
        return max(processes(self.lane), 1)

    def pressure(self) -> int:
        """Jobs waiting for a process of this lane (not yet handed to its pool)."""
        with self.lock:
            return len(self.waiting)

    def occupied(self) -> int:
        """Jobs this lane holds: running and waiting."""
        with self.lock:
            return self.running + len(self.waiting)

    async def submit(self, function: Callable[..., T], args: tuple, newest_first: bool = False) -> T:
        loop = asyncio.get_running_loop()
        job = _Job(function, args, loop, loop.create_future(), newest_first)
        with self.lock:
            self.waiting.append(job)
        self._dispatch()
        try:
            result, run_s, cpu_s = await job.done
            if (timing := TIMING.get()) is not None:
                timing.update(queue=job.queue_s, run=run_s, cpu=cpu_s)
            return result
        except asyncio.CancelledError:
            with self.lock:
                if job in self.waiting:
                    self.waiting.remove(job)
                elif job.running:
                    _stops[job.ticket % STOP_SLOTS] = job.ticket
            raise

    def _next(self) -> int:
        """The index of the job to run next: the oldest answer, else the newest preview (under the lock)."""
        return next((k for k, job in enumerate(self.waiting) if not job.newest_first), len(self.waiting) - 1)

    def _dispatch(self) -> None:
        """Hand the next waiting jobs (_next) to the pool while it has a process free (any thread)."""
        while True:
            with self.lock:
                if self.running >= self.capacity() or not self.waiting:
                    return
                job = self.waiting.pop(self._next())
                self.running += 1
                job.running = True
                job.queue_s = time.perf_counter() - job.queued
            pool = None
            try:
                if HEAVY_PROCESSES == 0:
                    future = _local_thread(self.lane).submit(_run_ticketed, job.ticket, job.function, job.args)
                else:
                    pool = _current_pool(self.lane)
                    future = pool.submit(_run_ticketed, job.ticket, job.function, job.args)
            except Exception as error:        # the pool is shut down or broken: the job fails, the lane goes on
                self._finished(job, None, error)
                continue
            future.add_done_callback(lambda done, job=job, pool=pool: self._finished(job, pool, done))

    def _finished(self, job: _Job, pool: ProcessPoolExecutor | None, outcome: Future | Exception) -> None:
        """A job's pool call ended (any thread): a broken pool is replaced and the job tried once more; else its
        outcome goes to its coroutine (cancelled when shutdown() cancelled the call); then the next job goes."""
        cancelled = isinstance(outcome, Future) and outcome.cancelled()
        error = outcome if isinstance(outcome, Exception) else None if cancelled else outcome.exception()
        retry = (isinstance(error, BrokenProcessPool) and pool is not None and not job.done.cancelled()
                 and _replaced(pool, job.tries))        # outside the lock: replacing ends calls, whose callbacks lock
        with self.lock:
            self.running -= 1
            job.running = False
            if retry:                         # next, whatever the order
                job.tries += 1
                self.waiting.insert(len(self.waiting) if job.newest_first else 0, job)
        if not retry:
            _settle(job, cancelled, error, None if cancelled or error is not None else outcome.result())
        self._dispatch()


def _settle(job: _Job, cancelled: bool, error: BaseException | None, result) -> None:
    """Resolve the job's future in its event loop (a closed loop: nobody waits for it)."""
    def settle():
        if job.done.done():
            return
        if cancelled:
            job.done.cancel()
        elif error is not None:
            job.done.set_exception(error)
        else:
            job.done.set_result(result)
    try:
        job.loop.call_soon_threadsafe(settle)
    except RuntimeError:
        pass


_queues = {lane: LaneQueue(lane) for lane in LANES}
