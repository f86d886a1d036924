"""One address, one share of the server, however many workers (server/runtime/server_shares.py).

The table's rule in real processes (each its own column, as the workers are), with clocks the test sets; then a
server of two real workers flooded from one address with invented cookies while another address asks: the
table, read under its lock as the server runs, never shows the flood take a place beyond its share while the
other address has asked within ACTIVE_S (a rule of the order of events, not of their speed)."""
from __future__ import annotations

import fcntl
import http.client
import json
import mmap
import multiprocessing
import os
import secrets
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from test_crash_safety import free_port
from test_tcp_nodelay import GUARD_S, LIGHT_ONLY, REPO, _connected, stop

from server.lessons.requests import scene_request
from server.lessons.scenes import scenes
from server.runtime.server_shares import ACTIVE_S, HEADER_BYTES, PREFIX, ROW, ROWS, ServerShares, key_of

FLOOD, STUDENT = "127.0.0.2", "127.0.0.1"
PAIRS_WANTED = 50               # consecutive samples with the other address active throughout


def _worker(path: str, cpus: int, commands, answers) -> None:
    """A process standing for a worker: its own column of the table at `path`, its clock set by each command."""
    now = [0.0]
    shares = ServerShares(path, clock=lambda: now[0], cpus=cpus)
    answers.put(shares.column)
    while (command := commands.get()) is not None:
        name, at, *args = command
        now[0] = at
        answers.put(getattr(shares, name)(*args))


class Worker:
    def __init__(self, path: Path, cpus: int = 8):
        context = multiprocessing.get_context("fork")
        self.commands, self.answers = context.Queue(), context.Queue()
        self.process = context.Process(target=_worker, args=(str(path), cpus, self.commands, self.answers))
        self.process.start()
        self.column = self.answers.get(timeout=GUARD_S)

    def __call__(self, name: str, at: float, *args):
        self.commands.put((name, at, *args))
        return self.answers.get(timeout=GUARD_S)

    def end(self, kill: bool = False) -> None:
        if kill:
            self.process.kill()
        else:
            self.commands.put(None)
        self.process.join(GUARD_S)


def test_an_address_holds_what_all_workers_but_one_may_hold_while_another_asks(tmp_path):
    path = tmp_path / "shares.table"
    first, second = Worker(path), Worker(path)
    try:
        assert first.column != second.column and first("workers", 0.0) == 2
        # alone, an address takes a place in each worker (a class behind one address has the server to itself)
        assert first("take", 100.0, "light", "A", 1) and second("take", 100.0, "light", "A", 1)
        assert first("held", 100.0, "light", "A") == 2
        first("give_back", 100.0, "light", "A")
        second("give_back", 100.0, "light", "A")
        assert first("held", 100.0, "light", "A") == 0
        # another address asks: A may hold 1 × (2 − 1) light place, and B its own
        first("asked", 100.0, "B")
        assert first("take", 100.2, "light", "A", 1)
        assert not second("take", 100.4, "light", "A", 1)
        assert second("take", 100.4, "light", "B", 1)
        assert second("take", 100.4, "heavy", "A", 1)            # each lane its own share
        assert not first("take", 100.4, "heavy", "A", 1)
        # B has not asked for ACTIVE_S: A's share binds no longer (B's own ask at 100.4 counts too)
        assert second("take", 100.4 + ACTIVE_S + 0.1, "light", "A", 1)
        assert second("held", 102.0, "light", "A") == 2
        # a worker killed holding places: the worker started in its stead clears its column
        second.end(kill=True)
        third = Worker(path)
        try:
            assert third.column == second.column and third("workers", 0.0) == 2
            assert third("held", 102.0, "light", "A") == 1 and third("held", 102.0, "heavy", "A") == 0
            third("give_back", 102.0, "light", "A")                       # not its place: nothing to give back
            assert third("held", 102.0, "light", "A") == 1
        finally:
            third.end()
    finally:
        first.end()
        second.end()


def test_on_two_cpus_an_address_computes_one_answer_light_or_heavy_while_another_asks(tmp_path):
    path = tmp_path / "shares.table"
    first, second = Worker(path, cpus=2), Worker(path, cpus=2)
    try:
        first("asked", 50.0, "B")
        assert first("take", 50.1, "light", "A", 1)
        assert not second("take", 50.1, "heavy", "A", 1)      # its one computation is the light one
        assert second("take", 50.1, "heavy", "B", 1)
        first("give_back", 50.2, "light", "A")
        assert second("take", 50.2, "heavy", "A", 1)          # now its heavy one
        assert not first("take", 50.2, "light", "A", 1)
        assert first("take", 50.2 + ACTIVE_S, "light", "A", 1)   # B has not asked since 50.1: no one else asks
    finally:
        first.end()
        second.end()


def test_with_three_workers_an_address_may_hold_two_places_while_another_asks(tmp_path):
    path = tmp_path / "shares.table"
    workers = [Worker(path) for _ in range(3)]
    try:
        workers[0]("asked", 10.0, "B")
        assert [w("take", 10.1, "light", "A", 1) for w in workers] == [True, True, False]
    finally:
        for worker in workers:
            worker.end()


def test_a_link_planted_where_the_table_goes_is_not_followed(tmp_path):
    """The table's name in the temporary folder is predictable: a link another user plants there is not opened
    (the server's workers then share only their own places), and the file it names is left as it was."""
    kept = tmp_path / "kept"
    kept.write_bytes(b"another file")
    (tmp_path / "shares.table").symlink_to(kept)
    with pytest.raises(OSError):
        ServerShares(tmp_path / "shares.table")
    assert kept.read_bytes() == b"another file"


class Table:
    """The server's table, read under its lock as the workers take it."""

    def __init__(self, path: Path):
        self.fd = os.open(path, os.O_RDONLY)
        self.map = mmap.mmap(self.fd, HEADER_BYTES + ROWS * ROW.itemsize, prot=mmap.PROT_READ)
        self.rows = np.frombuffer(self.map, ROW, ROWS, HEADER_BYTES)

    def sample(self, *groups) -> tuple[float, list[tuple[int, float]]]:
        """(now, per group (its light places in all the workers, when it last asked))."""
        found = []
        fcntl.flock(self.fd, fcntl.LOCK_EX)
        try:
            now = time.monotonic()
            for group in groups:
                row = np.flatnonzero(self.rows["key"] == key_of(group))
                found.append((int(self.rows["held"][row[0], 0].sum()), float(self.rows["asked"][row[0]]))
                             if row.size else (0, -np.inf))
        finally:
            fcntl.flock(self.fd, fcntl.LOCK_UN)
        return now, found

    def close(self) -> None:
        del self.rows
        self.map.close()
        os.close(self.fd)


def _light_request() -> tuple[str, bytes]:
    scene = scenes()["transfer-functions"]
    return "/api/v1/kinematics?lang=en", json.dumps(scene_request(scene, scene.variants[0])).encode()


def _asking(port: int, source: str, stop_asking: threading.Event, statuses: list, fresh_connections: bool) -> None:
    """Light requests one after another from `source` (a cookie of its own) until told to stop."""
    path, body = _light_request()
    headers = {"Content-Type": "application/json", "Cookie": f"mdl_client={secrets.token_urlsafe(16)}"}
    connection = None
    while not stop_asking.is_set():
        if connection is None:
            connection = http.client.HTTPConnection("127.0.0.1", port, timeout=GUARD_S, source_address=(source, 0))
        try:
            connection.request("POST", path, body=body, headers=headers)
            answer = connection.getresponse()
            answer.read()
            statuses.append(answer.status)
            if answer.status == 429:
                stop_asking.wait(float(answer.getheader("retry-after") or 1))
        except (OSError, http.client.HTTPException) as error:
            statuses.append(repr(error))
            connection.close()
            connection = None
        if fresh_connections and connection is not None:   # each its own connection: the workers share them
            connection.close()
            connection = None
    if connection is not None:
        connection.close()


def test_a_flood_of_invented_cookies_holds_one_share_of_two_workers_while_a_student_asks(tmp_path):
    port = free_port()
    server = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port), "--workers", "2"],
                              cwd=REPO, env={**os.environ, "MDL_DATA_DIR": str(tmp_path), "MDL_CACHE_BYTES": "0",
                                             "MDL_WARM_DEFAULTS": "0", **LIGHT_ONLY},
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    stop_flood, stop_student, threads = threading.Event(), threading.Event(), []
    flood_statuses, student_statuses = [], []
    table = None
    try:
        _connected(port).close()
        table = Table(Path(tempfile.gettempdir()) / f"{PREFIX}{server.pid}.table")
        for _ in range(12):
            threads.append(threading.Thread(target=_asking, args=(port, FLOOD, stop_flood, flood_statuses, True)))
            threads[-1].start()
        # the flood alone takes both workers' light places (no one else asks)
        deadline = time.monotonic() + GUARD_S
        while table.sample(FLOOD)[1][0][0] < 2:
            assert time.monotonic() < deadline, "the flood never held a place in both workers"
            time.sleep(0.001)
        student = threading.Thread(target=_asking, args=(port, STUDENT, stop_student, student_statuses, False))
        student.start()
        threads.append(student)
        pairs, flood_served, previous, deadline = 0, False, None, time.monotonic() + GUARD_S
        while pairs < PAIRS_WANTED:
            assert time.monotonic() < deadline, f"only {pairs} samples with the student asking throughout"
            now, ((flood_held, _), (_, student_asked)) = table.sample(FLOOD, STUDENT)
            if previous is not None and student_asked > now - ACTIVE_S and previous[2] > now - ACTIVE_S:
                # the student had asked within ACTIVE_S all the time from the previous sample to this one
                pairs += 1
                assert not (previous[1] <= 1 < flood_held), "the flood took a second place while the student asked"
                flood_served |= flood_held == 1
            previous = (now, flood_held, student_asked)
            time.sleep(0.001)
        assert flood_served                      # its share, served
    finally:
        stop_flood.set()
        stop_student.set()
        for thread in threads:
            thread.join(GUARD_S)
        if table is not None:
            table.close()
        stop(server)
    assert student_statuses and set(student_statuses) == {200}, student_statuses[:5]
    assert set(flood_statuses) <= {200, 429} and 200 in flood_statuses
