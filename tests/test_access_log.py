"""A student's personal link and the instructor's results token never reach a log: uvicorn's access log
(server/api/access_log.py) and the shipped nginx site (here, and tests/test_deployment.py) write the path with
the secret or the token cut."""
from __future__ import annotations

import logging
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx
import pytest

from server.api import access_log
from server.api.app import create_app

SECRET = "s3cr3t-Of-A-Student_xyz"
TOKEN = "T0ken-of-the_Instructor"
REPO = Path(__file__).resolve().parents[1]


def test_a_personal_links_secret_is_cut_and_every_other_path_kept():
    assert access_log.cut(f"/assignments/Ab-9/me/{SECRET}?lang=ru") == "/assignments/Ab-9/me/(secret)?lang=ru"
    assert access_log.cut(f"/assignments/Ab-9/me/{SECRET}") == "/assignments/Ab-9/me/(secret)"
    for path in ("/api/v1/assignments/Ab-9/me?lang=en", "/assignments/Ab-9?lang=uk", "/scenes/flywheel",
                 "/api/v1/kinematics?lang=ru"):
        assert access_log.cut(path) == path


@pytest.mark.parametrize("path, logged", [
    (f"/assignments/Ab-9/results/{TOKEN}?lang=ru", "/assignments/Ab-9/results/(token)?lang=ru"),
    (f"/api/v1/assignments/Ab-9/results/{TOKEN}", "/api/v1/assignments/Ab-9/results/(token)"),
    (f"/api/v1/assignments/Ab-9/results/{TOKEN}/csv", "/api/v1/assignments/Ab-9/results/(token)/csv"),
    (f"/api/v1/assignments/Ab-9/results/{TOKEN}/links?only_new=true",
     "/api/v1/assignments/Ab-9/results/(token)/links?only_new=true"),
    (f"/api/v1/assignments/Ab-9/results/{TOKEN}/roster", "/api/v1/assignments/Ab-9/results/(token)/roster"),
    (f"/api/v1/assignments/Ab-9/results/{TOKEN}/token", "/api/v1/assignments/Ab-9/results/(token)/token"),
])
def test_the_results_token_is_cut_and_the_rest_of_the_path_kept(path, logged):
    assert access_log.cut(path) == logged


def test_uvicorns_access_record_of_a_personal_link_holds_no_secret():
    create_app()                                          # installs the filter, once however often it is made
    create_app()
    logger = logging.getLogger(access_log.ACCESS_LOGGER)
    assert sum(isinstance(f, access_log.SecretsCut) for f in logger.filters) == 1
    record = logger.makeRecord(logger.name, logging.INFO, __file__, 1, '%s - "%s %s HTTP/%s" %d',
                               ("127.0.0.1:5000", "GET", f"/assignments/Ab-9/me/{SECRET}?lang=ru", "1.1", 303),
                               None)
    assert logger.filter(record)
    assert SECRET not in record.getMessage() and "/assignments/Ab-9/me/(secret)?lang=ru" in record.getMessage()
    record = logger.makeRecord(logger.name, logging.INFO, __file__, 1, '%s - "%s %s HTTP/%s" %d',
                               ("127.0.0.1:5000", "GET", f"/api/v1/assignments/Ab-9/results/{TOKEN}/csv", "1.1", 200),
                               None)
    assert logger.filter(record)
    assert TOKEN not in record.getMessage() and "/results/(token)/csv" in record.getMessage()


def test_the_shipped_nginx_site_logs_no_results_token(tmp_path):
    """deploy/nginx/mdl.conf rendered and run (tests/nginx.py) in front of a port where nothing listens: nginx
    answers 502 and logs each request, with the token and the secret cut by map $mdl_logged_uri."""
    from nginx import free_port, nginx_proxy
    paths = [f"/assignments/Ab-9/results/{TOKEN}?lang=uk", f"/api/v1/assignments/Ab-9/results/{TOKEN}/csv",
             f"/api/v1/assignments/Ab-9/results/{TOKEN}/links?only_new=true", f"/assignments/Ab-9/me/{SECRET}"]
    with nginx_proxy(tmp_path / "nginx", [free_port()]) as proxy:
        for path in paths:
            httpx.get(f"{proxy.url}{path}", timeout=30)
        deadline = time.monotonic() + 60              # nginx logs a request after answering it: a guard, no measure
        while len(proxy.access_log()) < len(paths):
            assert time.monotonic() < deadline, proxy.access_log()
            time.sleep(0.05)
        logged = "\n".join(proxy.access_log())
    assert TOKEN not in logged and SECRET not in logged
    for kept in ("/assignments/Ab-9/results/(token)?lang=uk", "/api/v1/assignments/Ab-9/results/(token)/csv",
                 "/api/v1/assignments/Ab-9/results/(token)/links?only_new=true", "/assignments/Ab-9/me/(secret)"):
        assert kept in logged


def test_the_running_servers_log_holds_no_secret(tmp_path):
    """python3 -m server as the README starts it, its access log on stderr: a personal link is logged cut."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    log = tmp_path / "server.log"
    with log.open("w") as out:
        server = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port)], cwd=REPO, stdout=out,
                                  stderr=subprocess.STDOUT,
                                  env=os.environ | {"MDL_DATA_DIR": str(tmp_path), "MDL_HEAVY_PROCESSES": "0"})
        try:
            deadline = time.monotonic() + 120                 # a guard against a hang, not a measure of speed
            while True:
                try:
                    answer = httpx.get(f"http://127.0.0.1:{port}/assignments/nope/me/{SECRET}?lang=ru")
                    break
                except httpx.TransportError:
                    assert server.poll() is None and time.monotonic() < deadline, log.read_text()
                    time.sleep(0.2)
            assert answer.status_code == 404
            while "/me/(secret)" not in log.read_text():      # uvicorn writes the line after the answer
                assert time.monotonic() < deadline, log.read_text()
                time.sleep(0.1)
        finally:
            server.terminate()
            server.wait(timeout=60)
    text = log.read_text()
    assert SECRET not in text and "/assignments/nope/me/(secret)?lang=ru" in text
