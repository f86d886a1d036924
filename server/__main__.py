"""Start the server: python -m server [--host H] [--port P] [--workers N] [--forwarded-allow-ips IPS].

Proxy headers (X-Forwarded-For, X-Forwarded-Proto) are read only from the reverse proxies named by
``--forwarded-allow-ips`` or ``MDL_FORWARDED_ALLOW_IPS`` (comma-separated addresses or networks). By default
none is trusted: any local process could otherwise name itself a new client in X-Forwarded-For and so
escape the per-address limits (submissions per minute, computations in flight).

Every accepted connection has TCP_NODELAY (server/runtime/nodelay.py), with one worker and with several.
"""
import argparse
import os

import uvicorn

from .runtime import server_shares, shared_cache
from .runtime.nodelay import HTTP


KEEP_ALIVE_S = 5     # an idle connection is closed after this long (uvicorn's default; nginx's upstream keeps it
                     # shorter: deploy/nginx/mdl.conf)


def uvicorn_options(argv: list[str] | None = None) -> dict:
    """The keyword arguments of uvicorn.run for these command-line arguments and the environment."""
    parser = argparse.ArgumentParser(prog="python3 -m server", description="Mechanism Dynamics Lab")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8000)
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--forwarded-allow-ips", default=os.environ.get("MDL_FORWARDED_ALLOW_IPS", ""),
                        help="the reverse proxies whose X-Forwarded-For names the client, e.g. 127.0.0.1 for an "
                             "nginx on this machine (default: $MDL_FORWARDED_ALLOW_IPS, else none)")
    args = parser.parse_args(argv)
    trusted = args.forwarded_allow_ips.strip()
    return {"host": args.host, "port": args.port, "workers": args.workers,
            "proxy_headers": bool(trusted), "forwarded_allow_ips": trusted or None, "http": HTTP,
            "timeout_keep_alive": KEEP_ALIVE_S}


def main() -> None:
    try:
        uvicorn.run("server.api.app:app", **uvicorn_options())
    finally:
        shared_cache.remove_own()          # the workers' shared families and shares, once they have all stopped
        server_shares.remove_own()


if __name__ == "__main__":
    main()
