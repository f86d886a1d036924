"""A student's personal link never reaches a log: uvicorn's access log (server/api/access_log.py) and the shipped
nginx site (tests/test_deployment.py) write its path with the secret cut."""
from __future__ import annotations

import logging
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx

from server.api import access_log
from server.api.app import create_app

SECRET = "s3cr3t-Of-A-Student_xyz"
REPO = Path(__file__).resolve().parents[1]


def test_a_personal_links_secret_is_cut_and_every_other_path_kept():
    assert access_log.cut(f"/assignments/Ab-9/me/{SECRET}?lang=ru") == "/assignments/Ab-9/me/(secret)?lang=ru"
    assert access_log.cut(f"/assignments/Ab-9/me/{SECRET}") == "/assignments/Ab-9/me/(secret)"
    for path in ("/api/v1/assignments/Ab-9/me?lang=en", "/assignments/Ab-9?lang=uk", "/scenes/flywheel",
                 "/api/v1/kinematics?lang=ru"):
        assert access_log.cut(path) == path


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


def test_the_running_servers_log_holds_no_secret(tmp_path):
    """python3 -m server as the README starts it, its access log on stderr: a personal link is logged cut."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    log = tmp_path / "server.log"
    with log.open("w") as out:
        server = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port)], cwd=REPO, stdout=out,
                                  stderr=subprocess.STDOUT, env=os.environ | {"MDL_DATA_DIR": str(tmp_path)})
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
