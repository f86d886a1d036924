"""Requests to the admission middleware (server/runtime/admission.py) driven by hand, as an ASGI server would:
a scope, a body to receive, the answer's messages kept, and a client that hangs up when the test says so. For
tests/test_admission.py and tests/test_fair_admission.py, which hold their apps' requests on events, never on
time."""
from __future__ import annotations

import asyncio

from server.runtime.admission import COOKIE

KINEMATICS = "/api/v1/kinematics"


class Exchange:
    """One request to the middleware: its answer's messages, and a way for its client to hang up.

    The client's id goes in the admission cookie, after `other_cookies` ("name=value; " of a browser's others);
    `label`, when given, in an x-label header for an app that tells its requests apart; `reading`, when given,
    is an event: the client reads its answer's body only once it is set; `dragging`: the request says it was asked
while a slider is dragged (X-MDL-Drag: 1)."""

    def __init__(self, middleware, path=KINEMATICS, host="10.0.0.1", client_id=None, method="POST", *,
                 label=None, other_cookies="", reading=None, dragging=False):
        self.sent: list[dict] = []
        self.reading = reading
        self.hang_up = asyncio.Event()
        self.body_read = False
        headers = [(b"x-label", label.encode())] if label is not None else []
        if dragging:                                 # asked while a slider is dragged (api.js)
            headers.append((b"x-mdl-drag", b"1"))
        if client_id:
            headers.append((b"cookie", f"{other_cookies}{COOKIE}={client_id}".encode()))
        scope = {"type": "http", "method": method, "path": path, "headers": headers, "client": (host, 5000),
                 "scheme": "http"}
        self.task = asyncio.ensure_future(middleware(scope, self._receive, self._send))

    async def _receive(self):
        if not self.body_read:
            self.body_read = True
            return {"type": "http.request", "body": b"{}", "more_body": False}
        await self.hang_up.wait()
        return {"type": "http.disconnect"}

    async def _send(self, message):
        self.sent.append(message)
        if self.reading is not None and message["type"] == "http.response.body":
            await self.reading.wait()

    @property
    def status(self):
        return self.sent[0]["status"] if self.sent else None

    def header(self, name: bytes):
        return dict(self.sent[0]["headers"]).get(name)


async def settle(turns: int = 30):
    """Let every task that can go on do so: `turns` passes of the event loop."""
    for _ in range(turns):
        await asyncio.sleep(0)
