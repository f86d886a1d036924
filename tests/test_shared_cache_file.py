"""The slider families' file that the workers of one server share (server/runtime/shared_cache.py) lives while
the server runs and is removed when it stops: `python3 -m server --workers 2`, one request, SIGTERM."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

from test_crash_safety import free_port
from test_tcp_nodelay import LIGHT_ONLY, REPO, _connected, stop

from server.runtime.shared_cache import PREFIX, SharedStore, code_version


def test_a_server_of_two_workers_removes_its_shared_file_as_it_stops(tmp_path):
    port = free_port()
    server = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port), "--workers", "2"],
                              cwd=REPO, env={**os.environ, "MDL_DATA_DIR": str(tmp_path), **LIGHT_ONLY},
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    files = lambda: sorted(Path(tempfile.gettempdir()).glob(f"{PREFIX}{server.pid}.sqlite*"))   # noqa: E731
    try:
        _connected(port).close()                 # answered: a worker has started, and opened the file
        running = files()
    finally:
        stop(server)
    assert any(path.name == f"{PREFIX}{server.pid}.sqlite" for path in running), running
    assert files() == []


def test_a_named_file_serves_an_answer_only_to_the_code_that_computed_it(tmp_path):
    """Servers of one host name one file (MDL_SHARED_CACHE), which outlives them: an answer stored by one
    version of the code is seen by every server of that version and by no other (an update, or a server not yet
    updated beside it)."""
    path, key = tmp_path / "families.sqlite", bytes(range(32))
    old, same, updated = (SharedStore(path, 1 << 20, version=v) for v in (b"v1" * 8, b"v1" * 8, b"v2" * 8))
    old.put(key, [(b"content-type", b"application/json")], b"{}", False)
    assert same.get(key) == ([(b"content-type", b"application/json")], b"{}", False)
    assert updated.get(key) is None
    assert SharedStore(path, 1 << 20).version == code_version() and len(code_version()) == 16
