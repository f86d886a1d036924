"""Start the server: python -m server [--host H] [--port P] [--workers N] [--forwarded-allow-ips IPS]."""
import argparse

import uvicorn


def main() -> None:
    parser = argparse.ArgumentParser(description="Mechanism Dynamics Lab")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8000)
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--forwarded-allow-ips", default="127.0.0.1",
                        help="reverse proxies whose X-Forwarded-For names the client (default: a proxy on this machine)")
    args = parser.parse_args()
    uvicorn.run("server.api.app:app", host=args.host, port=args.port, workers=args.workers,
                proxy_headers=True, forwarded_allow_ips=args.forwarded_allow_ips)


if __name__ == "__main__":
    main()
