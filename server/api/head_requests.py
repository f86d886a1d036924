"""HEAD answered as GET without the body (RFC 9110 §9.3.2): the same status and headers, Content-Length included.

FastAPI routes a path for the methods it declares, so HEAD of a page or a GET route of the API would be 405;
uptime monitors and link checkers send HEAD. A HEAD of a path with no GET stays 405, as GET would be.
"""
from __future__ import annotations


class HeadAsGet:
    """ASGI middleware: a HEAD request runs as GET; the body the app sends is dropped."""

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http" or scope["method"] != "HEAD":
            await self.app(scope, receive, send)
            return

        async def without_body(message):
            if message["type"] == "http.response.body":
                message = {**message, "body": b""}
            await send(message)

        await self.app({**scope, "method": "GET"}, receive, without_body)
