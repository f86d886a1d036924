"""What each address holds of a server's lanes, counted across its workers: one address, one share of the server.

Each worker's lanes (admission.Lane) have their own places, and without this count an address would hold its
share in every worker: a flood from one address, one light place in each of two workers, keeps both CPUs from
everyone else. The workers of one server (``--workers N``, N ≥ 2) therefore count in one table beside them what
each address (a group of admission's) holds of each lane, and while another address has asked within the last
``ACTIVE_S`` one address may hold, server-wide, what all the workers but one may hold of each lane, and of both
lanes together no more computations than the server has CPUs but one:

    places of a lane ≤ worker share × max(W − 1, 1),   places of both lanes ≤ max(C − 1, 1)

(W the workers counted in the table, C the CPUs the server may run on), so one worker's places and one CPU always
stay for the others: on two CPUs a flood from one address computes one answer at a time, light or heavy, however
many workers and heavy processes the server has. An address alone (a class behind one NAT address with the
server to itself) may hold every place: the share binds only when someone else asks.

The table: a file in the temporary folder named after the supervisor (server_files), mapped into every worker's
memory, a lock (``flock``) around each look and change (tens of microseconds). A row per address: its key (8 bytes
of BLAKE2b of the group), when it last asked (CLOCK_MONOTONIC, one clock for the machine's processes) and the
places it holds per lane and per worker. Each worker counts in a column of its own, claimed by its pid: a worker
that dies and is started again by the supervisor takes a dead one's column and clears it, so a killed worker's
places are not held for ever. Rows of addresses that hold nothing and have not asked for ``ACTIVE_S`` are cleared
when the table is full; past ``ROWS`` addresses at once (or ``WORKERS_MAX`` workers) a request is not counted,
and its worker's own lanes still share their places.
"""
from __future__ import annotations

import fcntl
import hashlib
import logging
import mmap
import os
import time
from contextlib import contextmanager

import numpy as np

from . import server_files

PREFIX = "mdl-shares-"
ROWS = 8192
WORKERS_MAX = 32
LANES = ("light", "heavy")
ACTIVE_S = 1.0                  # another address that asked this recently makes one address's share bind
ROW = np.dtype([("key", "<u8"), ("asked", "<f8"), ("held", "<i4", (len(LANES), WORKERS_MAX))])
HEADER_BYTES = 8 * WORKERS_MAX                  # the pid of each column's worker (0: none)
SIZE = HEADER_BYTES + ROWS * ROW.itemsize
log = logging.getLogger("uvicorn.error")


def key_of(group) -> int:
    """The row key of an admission group (an address, or (address, cookie) with the address cap off); never 0."""
    return int.from_bytes(hashlib.blake2b(repr(group).encode(), digest_size=8).digest(), "little") or 1


class ServerShares:
    """The table of one server's workers, seen from one of them (its column)."""

    def __init__(self, path, clock=time.monotonic, cpus: int | None = None):
        self.clock = clock
        self.cpus = max(len(os.sched_getaffinity(0)) if cpus is None else cpus, 2)   # the server's CPUs (≥ 2 counted)
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o600)    # not through a link planted there
        try:
            status = os.fstat(fd)
            if status.st_uid != os.getuid():
                raise OSError(f"{path} belongs to another user")
            if status.st_size < SIZE:
                os.ftruncate(fd, SIZE)         # zeros: no worker, no row
            self._map = mmap.mmap(fd, SIZE)
        except OSError:
            os.close(fd)
            raise
        self._fd = fd
        self._pids = np.frombuffer(self._map, "<i8", WORKERS_MAX)
        self._rows = np.frombuffer(self._map, ROW, ROWS, HEADER_BYTES)
        with self._locked():
            self.column = self._claim_column()

    @contextmanager
    def _locked(self):
        fcntl.flock(self._fd, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(self._fd, fcntl.LOCK_UN)

    def _claim_column(self) -> int:
        """This worker's column: its own, else one free or of a dead worker (its places cleared)."""
        pids = self._pids
        mine = np.flatnonzero(pids == os.getpid())
        if mine.size:
            return int(mine[0])
        for column, pid in enumerate(pids.tolist()):
            if pid == 0 or not server_files.alive(pid):
                pids[column] = os.getpid()
                self._rows["held"][:, :, column] = 0
                return column
        raise OSError(f"more than {WORKERS_MAX} workers")

    def workers(self) -> int:
        return int(np.count_nonzero(self._pids))

    def asked(self, group) -> None:
        """Note that `group` asks now (a request of its arrives)."""
        with self._locked():
            row = self._row(key_of(group))
            if row is not None:
                self._rows["asked"][row] = self.clock()

    def take(self, lane: str, group, worker_share: int) -> bool:
        """Whether `group` may take a place of `lane` (its worker has one free); if so, counted as held."""
        with self._locked():
            key = key_of(group)
            row = self._row(key)
            if row is None:
                return True                    # the table full: not counted (give_back finds no row either)
            rows, now = self._rows, self.clock()
            rows["asked"][row] = now
            lane_index = LANES.index(lane)
            held = rows["held"][row]
            if (held[lane_index].sum() >= worker_share * max(self.workers() - 1, 1)
                    or held.sum() >= self.cpus - 1) and self._others_asked(key, now):
                return False
            rows["held"][row, lane_index, self.column] += 1
            return True

    def give_back(self, lane: str, group) -> None:
        """A place of `lane` that `group` took in this worker is free."""
        with self._locked():
            rows = np.flatnonzero(self._rows["key"] == key_of(group))
            if rows.size:
                held = self._rows["held"][rows[0], LANES.index(lane)]
                held[self.column] = max(int(held[self.column]) - 1, 0)

    def held(self, lane: str, group) -> int:
        """The places of `lane` that `group` holds in all the workers."""
        with self._locked():
            rows = np.flatnonzero(self._rows["key"] == key_of(group))
            return int(self._rows["held"][rows[0], LANES.index(lane)].sum()) if rows.size else 0

    def _others_asked(self, key: int, now: float) -> bool:
        rows = self._rows
        return bool(np.any((rows["asked"] > now - ACTIVE_S) & (rows["key"] != key) & (rows["key"] != 0)))

    def _row(self, key: int) -> int | None:
        """The row of `key`, a new one if it has none (the idle rows cleared when none is free), or None."""
        keys = self._rows["key"]
        found = np.flatnonzero(keys == key)
        if found.size:
            return int(found[0])
        free = np.flatnonzero(keys == 0)
        if not free.size:
            rows = self._rows
            idle = (rows["held"].sum(axis=(1, 2)) == 0) & (rows["asked"] <= self.clock() - ACTIVE_S)
            rows[idle] = np.zeros(1, ROW)
            free = np.flatnonzero(keys == 0)
            if not free.size:
                return None
        row = int(free[0])
        self._rows[row] = np.zeros(1, ROW)
        keys[row] = key
        return row


def from_worker() -> ServerShares | None:
    """The table of this server's workers when this process is one of several (server_files), else None; None as
    well when it cannot be opened (each worker then shares only its own places)."""
    path = server_files.workers_file(PREFIX, ".table")
    if path is None:
        return None
    try:
        return ServerShares(path)
    except OSError as error:
        log.warning("server-wide shares %s not opened (%s): each worker shares its own places", path, error)
        return None


def remove_own() -> None:
    """Remove the table of this supervisor's workers (called by it once they have all stopped)."""
    server_files.remove_own(PREFIX)
