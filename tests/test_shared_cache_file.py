"""The slider families' file that the workers of one server share (server/runtime/shared_cache.py) lives while
the server runs and is removed when it stops: `python3 -m server --workers 2`, one request, SIGTERM."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

from test_crash_safety import free_port
from test_tcp_nodelay import REPO, _connected, stop

from server.runtime.shared_cache import PREFIX


def test_a_server_of_two_workers_removes_its_shared_file_as_it_stops(tmp_path):
    port = free_port()
    server = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port), "--workers", "2"],
                              cwd=REPO, env={**os.environ, "MDL_DATA_DIR": str(tmp_path)},
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    files = lambda: sorted(Path(tempfile.gettempdir()).glob(f"{PREFIX}{server.pid}.sqlite*"))   # noqa: E731
    try:
        _connected(port).close()                 # answered: a worker has started, and opened the file
        running = files()
    finally:
        stop(server)
    assert any(path.name == f"{PREFIX}{server.pid}.sqlite" for path in running), running
    assert files() == []
