"""A real nginx (Debian's package) in front of app servers, running the shipped site: for the benchmarks, and
(through tests/nginx.py, which adds pytest's skip where nginx is missing) for the deployment tests.

The site is `deploy/nginx/mdl.conf` rendered with the run's ports only: the upstream's `server` lines name the
app servers' ports, `listen 80` becomes a free loopback port and the access log goes to a temporary folder;
every other line (proxy headers, keep-alive to the upstream, timeouts, retries, gzip off) is the file as shipped.
The main configuration is Debian's /etc/nginx/nginx.conf in what matters here (`worker_processes auto`) with
`worker_connections` raised from Debian's 768 to 4096, so that the proxy's connection table never limits a class
(each simulated student keeps two connections to nginx, and nginx up to two to the app servers); the tests ask
for one worker, whose round robin hands consecutive requests to the app servers in turn.

nginx runs in the foreground, in a session of its own, in its temporary folder with its own prefix, pid, logs and
temporary paths; it is stopped with SIGTERM to its master (fast shutdown), then SIGKILL to its whole process group
if anything is left.
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import signal
import socket
import subprocess
import time
from collections import Counter
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "deploy" / "nginx" / "mdl.conf"
UPSTREAM_SERVER = re.compile(r"^([ \t]*)server 127\.0\.0\.1:\d+ (.*\n)", re.M)
LISTEN = re.compile(r"^(\s*)listen 80;$", re.M)
ACCESS_LOG = re.compile(r"^(\s*)access_log /var/log/nginx/mdl\.access\.log mdl;$", re.M)
UPSTREAM_IN_LOG = re.compile(r"upstream=(\S+)$")
READY_S = 30            # nginx starts in milliseconds; a guard for a loaded machine
STOP_S = 15

MAIN = """daemon off;
master_process on;
worker_processes {workers};
{user}pid {dir}/nginx.pid;
error_log {dir}/error.log {level};
events {{ worker_connections {connections}; }}
http {{
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


def find_nginx() -> str | None:
    """The nginx binary, or None where it is not installed."""
    return shutil.which("nginx") or shutil.which("nginx", path="/usr/sbin")     # /usr/sbin: not on every PATH


def nginx_binary() -> str:
    found = find_nginx()
    if found is None:
        raise SystemExit("nginx is not installed (apt-get install nginx)")
    return found


def render_site(upstream_ports: list[int], port: int, directory: Path) -> str:
    """deploy/nginx/mdl.conf with one upstream `server` line per app port, nginx listening on `port` and its
    access log (the shipped format) in `directory`."""
    shipped = SITE.read_text(encoding="utf-8")
    servers = UPSTREAM_SERVER.findall(shipped)
    if not servers or len(LISTEN.findall(shipped)) != 1 or len(ACCESS_LOG.findall(shipped)) != 1:
        raise RuntimeError(f"{SITE} no longer has the shape that render_site renders")
    shipped = ACCESS_LOG.sub(rf"\g<1>access_log {directory}/access.log mdl;", shipped)
    indent, options = servers[0]
    block = "".join(f"{indent}server 127.0.0.1:{p} {options}" for p in upstream_ports)
    first = UPSTREAM_SERVER.search(shipped).start()
    site = UPSTREAM_SERVER.sub(lambda match: block if match.start() == first else "", shipped)
    return LISTEN.sub(rf"\g<1>listen 127.0.0.1:{port};", site)


@dataclass
class Nginx:
    """A running nginx: its port, folder, command and process (the master, leader of its own session)."""
    port: int
    directory: Path
    command: list[str]
    process: subprocess.Popen

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def access_log(self) -> list[str]:
        """The access log's lines so far (the shipped format: one a request, ending with upstream=…)."""
        path = self.directory / "access.log"
        return path.read_text(encoding="utf-8", errors="replace").splitlines() if path.exists() else []

    def upstreams(self) -> Counter:
        """Requests per app server so far, from the access log."""
        return Counter(match[1] for line in self.access_log() if (match := UPSTREAM_IN_LOG.search(line)))

    def error_log(self) -> str:
        path = self.directory / "error.log"
        return path.read_text(encoding="utf-8", errors="replace") if path.exists() else ""


def stop_group(process: subprocess.Popen, wait_s: float = STOP_S) -> None:
    """SIGTERM to the process; once it has ended (or after wait_s), SIGKILL to whatever is left of its process
    group (it leads a session of its own)."""
    if process.poll() is None:
        process.send_signal(signal.SIGTERM)
        try:
            process.wait(timeout=wait_s)
        except subprocess.TimeoutExpired:
            pass
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    process.wait()


@contextmanager
def nginx_proxy(directory: Path, upstream_ports: list[int], binary: str | None = None, workers: int | str = "auto",
                connections: int = 4096, error_level: str = "warn"):
    """Run nginx (`binary`, else the installed one) with the shipped site in front of the app servers on
    `upstream_ports`, with `workers` worker processes of `connections` connections each and its error log from
    `error_level` up; yield an Nginx."""
    binary = binary or nginx_binary()
    directory.mkdir(parents=True, exist_ok=True)
    port = free_port()
    (directory / "mdl.conf").write_text(render_site(upstream_ports, port, directory), encoding="utf-8")
    user = "user root;\n" if os.geteuid() == 0 else ""    # workers keep access to the temporary directory
    main = MAIN.format(dir=directory, user=user, workers=workers, connections=connections, level=error_level)
    (directory / "nginx.conf").write_text(main, encoding="utf-8")
    command = [binary, "-p", str(directory), "-c", str(directory / "nginx.conf"), "-e", str(directory / "error.log")]
    checked = subprocess.run([*command, "-t"], capture_output=True, text=True)
    if checked.returncode != 0:
        raise RuntimeError(f"nginx refuses the rendered config:\n{checked.stderr}")
    process = subprocess.Popen(command, cwd=directory, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               start_new_session=True)
    proxy = Nginx(port, directory, command, process)
    try:
        deadline = time.monotonic() + READY_S
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                if process.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError(f"nginx did not start listening on port {port} within {READY_S} s "
                                       f"(exit code {process.poll()}):\n{proxy.error_log()}")
                time.sleep(0.05)
        yield proxy
    finally:
        stop_group(process)


if __name__ == "__main__":
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                            epilog="A module: nginx for the bench scripts and the deployment tests; nothing to run "
                                   "by itself.").parse_args()
