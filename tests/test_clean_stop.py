"""A server of two workers stopped as systemd stops it (SIGTERM) after heavy computations: it ends, with its heavy
processes and their forkservers, and without "resource_tracker: … leaked semaphore objects" (the pools' queues
are closed before the workers exit). Waits are guards against a hang, with a message."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import httpx

from server.lessons.requests import scene_request
from server.lessons.scenes import scenes
from test_crash_safety import free_port

REPO = Path(__file__).resolve().parents[1]
GUARD_S = 300


def test_sigterm_after_heavy_work_stops_everything_cleanly(tmp_path):
    port = free_port()
    env = {**os.environ, "MDL_DATA_DIR": str(tmp_path)}
    server = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port), "--workers", "2"], cwd=REPO,
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                              start_new_session=True)
    try:
        scene = scenes()["elastic-transmission"]
        body = scene_request(scene, scene.variants[0])
        deadline = time.monotonic() + GUARD_S
        with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=120) as client:
            while True:
                try:
                    if client.get("/").status_code == 200:
                        break
                except httpx.TransportError:
                    pass
                assert time.monotonic() < deadline, "the server did not start"
                time.sleep(0.5)
            for stiffness in (1.0e4, 1.1e4, 1.2e4, 1.3e4):    # distinct requests: none answered by the cache
                answer = client.post("/api/v1/elastic", json=body | {"c": stiffness})
                assert answer.status_code == 200, answer.text[:300]
        server.send_signal(signal.SIGTERM)
        _, stderr = server.communicate(timeout=GUARD_S)
    finally:
        if server.poll() is None:
            os.killpg(server.pid, signal.SIGKILL)
            server.wait()
    assert server.returncode == 0, stderr[-3000:]
    assert "leaked semaphore" not in stderr and "Traceback" not in stderr, stderr[-3000:]
    deadline = time.monotonic() + 30                      # the last helpers see their pipes close and end
    while (left := _session(server.pid)) and time.monotonic() < deadline:
        time.sleep(0.5)
    assert left == [], f"processes of the server's session left: {left}"


def _session(sid: int) -> list[str]:
    found = subprocess.run(["ps", "-s", str(sid), "-o", "pid=,args="], capture_output=True, text=True).stdout
    return [line.strip()[:160] for line in found.splitlines() if line.strip()]
