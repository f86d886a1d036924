"""A real PostgreSQL server for the tests: ``initdb`` into a temporary directory, ``postgres`` on a free port of
127.0.0.1 (its unix socket in that directory too), stopped and removed afterwards.

    url, stop = start_postgres()            # postgresql://mdl@127.0.0.1:<port>/postgres
    url_of_a_new_db = fresh_database(url)   # an empty database of its own on that server
    stop()

or the session fixture ``postgres_url`` (import it into a test module: ``from postgres import postgres_url``).
The binaries are found on PATH, under /usr/lib/postgresql/<version>/bin (Debian's layout, newest first) or in
/usr/local/bin; ``tests/run.sh`` installs Debian's ``postgresql`` when there are none. PostgreSQL refuses to
run as root, so as root the cluster belongs to the ``postgres`` user (made by Debian's package; else
``nobody``) and lives in a directory of its own under the system's temporary directory (pytest's are private
to root).
"""
from __future__ import annotations

import glob
import itertools
import os
import pwd
import shutil
import signal
import socket
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Callable

import pytest

USER = "mdl"                 # the cluster's superuser, trusted on 127.0.0.1 and the socket
READY_WITHIN_S = 120.0       # a guard against a server that never comes up, not a speed requirement
_databases = itertools.count()


def postgres_bin() -> Path | None:
    """The directory holding initdb and postgres, or None."""
    found = shutil.which("initdb")
    candidates = ([Path(found).resolve().parent] if found else []) + [
        Path(p).parent for p in sorted(glob.glob("/usr/lib/postgresql/*/bin/initdb"),
                                       key=lambda p: int(Path(p).parts[-3]) if Path(p).parts[-3].isdigit() else 0,
                                       reverse=True)] + [Path("/usr/local/bin")]
    return next((c for c in candidates if (c / "initdb").exists() and (c / "postgres").exists()), None)


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _owner() -> pwd.struct_passwd | None:
    """The unprivileged user to run the cluster as when we are root; None when we are not root."""
    if os.geteuid() != 0:
        return None
    for name in ("postgres", "nobody"):
        try:
            return pwd.getpwnam(name)
        except KeyError:
            continue
    raise RuntimeError("running as root and there is no 'postgres' or 'nobody' user to run PostgreSQL as")


def _run_as(owner, command: list[str], cwd: Path, **kwargs):
    if owner is not None:
        kwargs |= {"user": owner.pw_uid, "group": owner.pw_gid, "extra_groups": []}
    return subprocess.Popen(command, cwd=cwd, env={"PATH": os.environ.get("PATH", ""), "LC_ALL": "C"}, **kwargs)


def start_postgres(tmpdir: Path | None = None) -> tuple[str, Callable[[], None]]:
    """Start a fresh cluster; return its URL (database ``postgres``, user ``mdl``) and a function stopping
    the server and removing its directory. ``tmpdir``: where to put the cluster (as root: ignored, see above)."""
    bin_dir = postgres_bin()
    if bin_dir is None:
        raise RuntimeError("PostgreSQL is not installed (no initdb on PATH or in /usr/lib/postgresql/*/bin); "
                           "tests/run.sh installs Debian's postgresql package")
    owner = _owner()
    root = Path(tempfile.mkdtemp(prefix="mdl-postgres-", dir=None if owner else tmpdir))
    if owner is not None:
        os.chown(root, owner.pw_uid, owner.pw_gid)
    data, log_path = root / "data", root / "server.log"
    with open(root / "initdb.log", "w") as log:
        initdb = _run_as(owner, [str(bin_dir / "initdb"), "-D", str(data), "-U", USER, "--auth=trust",
                                 "--encoding=UTF8", "--no-locale", "--no-sync"], root, stdout=log, stderr=log)
        if initdb.wait(timeout=READY_WITHIN_S) != 0:
            shutil.rmtree(root, ignore_errors=True)
            raise RuntimeError(f"initdb failed: {(root / 'initdb.log').read_text()}")
    for _ in range(5):                      # another process may take the port between probing and binding
        port = free_port()
        log = open(log_path, "a")
        server = _run_as(owner, [str(bin_dir / "postgres"), "-D", str(data), "-p", str(port), "-k", str(root),
                                 "-c", "listen_addresses=127.0.0.1", "-c", "max_connections=300"],
                         root, stdout=log, stderr=subprocess.STDOUT)
        url = f"postgresql://{USER}@127.0.0.1:{port}/postgres"
        if _wait_ready(server, url):
            break
        log.close()
    else:
        shutil.rmtree(root, ignore_errors=True)
        raise RuntimeError(f"postgres did not start: {log_path.read_text()[-2000:]}")

    def stop() -> None:
        if server.poll() is None:
            server.send_signal(signal.SIGQUIT)         # immediate shutdown: the directory is thrown away anyway
            try:
                server.wait(timeout=60)
            except subprocess.TimeoutExpired:
                server.kill()
                server.wait()
        log.close()
        shutil.rmtree(root, ignore_errors=True)

    return url, stop


def _wait_ready(server: subprocess.Popen, url: str) -> bool:
    """True once the server accepts a connection; False if it exited (a taken port)."""
    import psycopg

    deadline = time.monotonic() + READY_WITHIN_S
    while time.monotonic() < deadline:
        if server.poll() is not None:
            return False
        try:
            psycopg.connect(url, connect_timeout=5).close()
            return True
        except psycopg.OperationalError:
            time.sleep(0.1)
    server.kill()
    server.wait()
    return False


def fresh_database(url: str) -> str:
    """Make an empty database on the server at ``url``; its URL."""
    import psycopg

    name = f"t{os.getpid()}_{next(_databases)}"
    with psycopg.connect(url, autocommit=True) as admin:
        admin.execute(f'CREATE DATABASE "{name}"')
    return url.rsplit("/", 1)[0] + "/" + name


@pytest.fixture(scope="session")
def postgres_url(tmp_path_factory):
    """One PostgreSQL server for the test session; its admin URL (make databases with ``fresh_database``)."""
    url, stop = start_postgres(tmp_path_factory.mktemp("postgres"))
    yield url
    stop()
