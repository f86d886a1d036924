"""Start the server: python -m server [--host H] [--port P] [--workers N]."""
import argparse

import uvicorn


def main() -> None:
    parser = argparse.ArgumentParser(description="Mechanism Dynamics Lab")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8000)
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    uvicorn.run("server.api.app:app", host=args.host, port=args.port, workers=args.workers)


if __name__ == "__main__":
    main()
