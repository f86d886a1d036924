"""A real nginx (Debian's package) in front of app servers, for the deployment tests: bench/nginx_proxy.py's,
which renders the shipped `deploy/nginx/mdl.conf` with the test's ports only (so the test checks the shipped
config) and stops nginx afterwards, here with pytest's skip where nginx is missing (`tests/run.sh` installs
the `nginx` package then) and one worker process: its round robin hands consecutive requests to the app
servers in turn, which the tests read from the access log.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

BENCH = str(Path(__file__).resolve().parents[1] / "bench")
if BENCH not in sys.path:
    sys.path.append(BENCH)           # after the tests' own folder: bench's module names never shadow the tests'
import nginx_proxy as bench_nginx  # noqa: E402
from nginx_proxy import SITE, free_port  # noqa: E402,F401  (the deployment tests import them from here)


def nginx_binary() -> str:
    found = bench_nginx.find_nginx()
    if found is None:
        pytest.skip("nginx is not installed (tests/run.sh installs Debian's nginx)")
    return found


def nginx_proxy(directory: Path, upstream_ports: list[int]):
    """A context manager: nginx with the shipped site in front of the app servers on `upstream_ports`, one worker
    of 512 connections, its error log from `info` up; yields an Nginx (its `url`, `access_log()`, `error_log()`)."""
    return bench_nginx.nginx_proxy(directory, upstream_ports, binary=nginx_binary(), workers=1, connections=512,
                                   error_level="info")
