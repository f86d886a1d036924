"""Every connection the server accepts has TCP_NODELAY, with one worker and with two (uvicorn binds the socket of
several workers with protocol 0, and asyncio then leaves Nagle's algorithm on: an answer's body waits for the
client's delayed acknowledgement of its headers).

The option is read from the running server's own socket: the server is started as the README says, a client
connects and is answered over a kept-alive connection, the server's end of that connection is found in
/proc/net/tcp (by the two ports) and among the server's processes' file descriptors (by its inode), and a copy of
that descriptor is taken with pidfd_getfd(2) to ask getsockopt. Waits are guards against a hang."""
from __future__ import annotations

import ctypes
import http.client
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from test_crash_safety import free_port

REPO = Path(__file__).resolve().parents[1]
GUARD_S = 300
SYS_PIDFD_GETFD = 438            # x86_64 and aarch64 alike
# a server that answers no heavy request starts no heavy processes (each worker's forkserver would load the
# compiled kernels: seconds of CPU that the other tests of the run need)
LIGHT_ONLY = {"MDL_HEAVY_PROCESSES": "0"}


def _connected(port: int) -> http.client.HTTPConnection:
    """A kept-alive connection that the server has accepted and answered once."""
    deadline = time.monotonic() + GUARD_S
    while True:
        connection = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
        try:
            connection.request("GET", "/api/v1/cache")
            answer = connection.getresponse()
            answer.read()
            if answer.status == 200 and not answer.will_close:
                return connection
        except OSError:
            pass
        connection.close()
        assert time.monotonic() < deadline, "the server did not start"
        time.sleep(0.5)


def _inode(local_port: int, remote_port: int) -> int:
    """The inode of the TCP socket from local_port to remote_port on loopback (/proc/net/tcp, tcp6)."""
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        for line in Path(table).read_text().splitlines()[1:]:
            fields = line.split()
            local, remote = int(fields[1].rsplit(":", 1)[1], 16), int(fields[2].rsplit(":", 1)[1], 16)
            if (local, remote) == (local_port, remote_port) and fields[3] == "01":     # ESTABLISHED
                return int(fields[9])
    raise AssertionError(f"no established connection {local_port} → {remote_port}")


def _holder(session: int, inode: int) -> tuple[int, int]:
    """(pid, fd) of the server's process that holds the socket `inode`."""
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:                   # a process of the machine's may end meanwhile (ProcessLookupError is an OSError)
            if os.getsid(int(entry.name)) != session:
                continue
            for fd in (entry / "fd").iterdir():
                if os.readlink(fd) == f"socket:[{inode}]":
                    return int(entry.name), int(fd.name)
        except OSError:
            continue
    raise AssertionError(f"no process of the server's session holds socket {inode}")


def _nodelay_of(pid: int, fd: int) -> int:
    """TCP_NODELAY of the socket `fd` of process `pid`, read on a copy of its descriptor."""
    pidfd = os.pidfd_open(pid)
    try:
        copy = ctypes.CDLL(None, use_errno=True).syscall(SYS_PIDFD_GETFD, pidfd, fd, 0)
        if copy < 0:
            pytest.skip(f"pidfd_getfd: {os.strerror(ctypes.get_errno())}")
    finally:
        os.close(pidfd)
    sock = socket.socket(fileno=copy)
    try:
        return sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY)
    finally:
        sock.close()


def stop(server: subprocess.Popen) -> None:
    """SIGTERM to the server as systemd stops it; its session killed only if it has not ended within GUARD_S."""
    server.send_signal(signal.SIGTERM)
    try:
        server.wait(timeout=GUARD_S)
    except subprocess.TimeoutExpired:
        os.killpg(server.pid, signal.SIGKILL)
        server.wait()


@pytest.mark.parametrize("workers", [1, 2])
def test_the_server_sets_nodelay_on_the_connections_it_accepts(tmp_path, workers):
    port = free_port()
    server = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port), "--workers", str(workers)],
                              cwd=REPO, env={**os.environ, "MDL_DATA_DIR": str(tmp_path), **LIGHT_ONLY},
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        connection = _connected(port)
        try:
            client_port = connection.sock.getsockname()[1]
            pid, fd = _holder(server.pid, _inode(port, client_port))
            assert _nodelay_of(pid, fd) != 0, f"TCP_NODELAY is off on the server's end ({workers} worker(s))"
        finally:
            connection.close()
    finally:
        stop(server)
        deadline = time.monotonic() + 30
        while _session(server.pid) and time.monotonic() < deadline:
            time.sleep(0.5)
        assert _session(server.pid) == [], "processes of the server's session left"


def _session(sid: int) -> list[str]:
    found = subprocess.run(["ps", "-s", str(sid), "-o", "pid=,args="], capture_output=True, text=True).stdout
    return [line.strip()[:160] for line in found.splitlines() if line.strip()]
