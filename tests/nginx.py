"""A real nginx (Debian's package) in front of app servers, for the deployment tests.

The site is the shipped `deploy/nginx/mdl.conf`, rendered with the test's ports only: the upstream's
`server` lines name the app servers' ports and `listen 80` becomes a free loopback port; every other line
(proxy headers, timeouts, retries, gzip) is the file as shipped, so the test checks the shipped config.
nginx runs in the foreground with its own prefix, pid, logs and temporary paths in a temporary directory,
and is stopped afterwards. `tests/run.sh` installs the `nginx` package when it is missing.
"""
from __future__ import annotations

import os
import re
import shutil
import signal
import socket
import subprocess
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
SITE = REPO / "deploy" / "nginx" / "mdl.conf"
UPSTREAM_SERVER = re.compile(r"^([ \t]*)server 127\.0\.0\.1:\d+ (.*\n)", re.M)
LISTEN = re.compile(r"^(\s*)listen 80;$", re.M)
ACCESS_LOG = re.compile(r"^(\s*)access_log /var/log/nginx/mdl\.access\.log mdl;$", re.M)
READY_SECONDS = 30        # nginx starts in milliseconds; a generous guard for a loaded machine

# The parts of nginx.conf that Debian's /etc/nginx/nginx.conf would give; the site is included verbatim.
MAIN = """daemon off;
master_process on;
worker_processes 1;
{user}pid {dir}/nginx.pid;
error_log {dir}/error.log info;
events {{ worker_connections 512; }}
http {{
    log_format upstream '$remote_addr "$request" $status upstream=$upstream_addr';
    access_log {dir}/access.log upstream;
    client_body_temp_path {dir}/client_body;
    proxy_temp_path {dir}/proxy;
    fastcgi_temp_path {dir}/fastcgi;
    uwsgi_temp_path {dir}/uwsgi;
    scgi_temp_path {dir}/scgi;
    include {dir}/mdl.conf;
}}
"""


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def nginx_binary() -> str:
    found = shutil.which("nginx") or shutil.which("nginx", path="/usr/sbin")     # /usr/sbin: not on every PATH
    if found is None:
        pytest.skip("nginx is not installed (tests/run.sh installs Debian's nginx)")
    return found


def render_site(upstream_ports: list[int], port: int, directory: Path) -> str:
    """deploy/nginx/mdl.conf with one upstream `server` line per app port, nginx listening on `port` and its
    access log (the shipped format) in `directory`."""
    shipped = SITE.read_text(encoding="utf-8")
    servers = UPSTREAM_SERVER.findall(shipped)
    assert servers and len(LISTEN.findall(shipped)) == 1 and len(ACCESS_LOG.findall(shipped)) == 1, \
        f"{SITE} no longer has the shape the test renders"
    shipped = ACCESS_LOG.sub(rf"\g<1>access_log {directory}/access.log mdl;", shipped)
    indent, options = servers[0]
    block = "".join(f"{indent}server 127.0.0.1:{p} {options}" for p in upstream_ports)
    first = UPSTREAM_SERVER.search(shipped).start()
    site = UPSTREAM_SERVER.sub(lambda match: block if match.start() == first else "", shipped)
    return LISTEN.sub(rf"\g<1>listen 127.0.0.1:{port};", site)


@dataclass
class Nginx:
    """A running nginx: its address, and its access log (one line per request with the upstream used)."""
    url: str
    directory: Path

    def access_log(self) -> list[str]:
        path = self.directory / "access.log"
        return path.read_text(encoding="utf-8").splitlines() if path.exists() else []

    def error_log(self) -> str:
        path = self.directory / "error.log"
        return path.read_text(encoding="utf-8") if path.exists() else ""


@contextmanager
def nginx_proxy(directory: Path, upstream_ports: list[int]):
    """Run nginx with the shipped site in front of the app servers on `upstream_ports`; yield an Nginx."""
    binary = nginx_binary()
    directory.mkdir(parents=True, exist_ok=True)
    port = free_port()
    (directory / "mdl.conf").write_text(render_site(upstream_ports, port, directory), encoding="utf-8")
    user = "user root;\n" if os.geteuid() == 0 else ""    # workers keep access to the temporary directory
    (directory / "nginx.conf").write_text(MAIN.format(dir=directory, user=user), encoding="utf-8")
    command = [binary, "-p", str(directory), "-c", str(directory / "nginx.conf"), "-e", str(directory / "error.log")]
    checked = subprocess.run([*command, "-t"], capture_output=True, text=True)
    assert checked.returncode == 0, f"nginx refuses the rendered config:\n{checked.stderr}"
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    proxy = Nginx(f"http://127.0.0.1:{port}", directory)
    try:
        deadline = time.monotonic() + READY_SECONDS
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                if process.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError(f"nginx did not start listening on port {port} within {READY_SECONDS} s "
                                       f"(exit code {process.poll()}):\n{proxy.error_log()}")
                time.sleep(0.05)
        yield proxy
    finally:
        process.send_signal(signal.SIGTERM)          # fast shutdown: the master ends its workers
        try:
            process.wait(timeout=15)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(timeout=5)
