"""uvicorn's HTTP protocol with TCP_NODELAY set on every accepted TCP connection.

With several workers uvicorn binds the listening socket itself with protocol 0, and asyncio sets TCP_NODELAY on
an accepted connection only when the listening socket's protocol is IPPROTO_TCP; with one worker it does. Without
it, Nagle's algorithm holds an answer's body back until the client acknowledges the headers, which a client
delays (delayed ACK): some 40 ms on every answer over a kept-alive connection (a page's back-to-back drag values,
nginx's upstream connections). Setting the option in the protocol covers one worker and many alike.
"""
from __future__ import annotations

import socket

from uvicorn.protocols.http.auto import AutoHTTPProtocol


def set_nodelay(transport) -> None:
    """TCP_NODELAY on the transport's socket, if it is a TCP one (not a Unix socket)."""
    sock = transport.get_extra_info("socket")
    if sock is not None and sock.family in (socket.AF_INET, socket.AF_INET6) and sock.type == socket.SOCK_STREAM:
        try:
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        except OSError:          # the connection is already gone
            pass


class NoDelayHTTPProtocol(AutoHTTPProtocol):
    """uvicorn's HTTP protocol (httptools if installed, else h11) with TCP_NODELAY on its connection."""

    def connection_made(self, transport) -> None:
        set_nodelay(transport)
        super().connection_made(transport)


HTTP = f"{__name__}:{NoDelayHTTPProtocol.__qualname__}"    # uvicorn's `http` option (a worker imports it)
