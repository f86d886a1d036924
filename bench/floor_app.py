"""The floor of an HTTP round trip: a bare Starlette app under uvicorn (the app server's defaults, as
``python3 -m server`` starts it) that reads the request body and answers with stored bytes, for
bench/http_floor.py.

    python3 bench/floor_app.py PORT DIR

Every ``DIR/<name>.body`` is answered at ``POST /<name>`` with the headers of ``DIR/<name>.json``
(content-type, content-encoding: those the app sent with the same bytes). ``GET /ready`` says it is up.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import uvicorn
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse, Response
from starlette.routing import Route


def app_for(directory: Path) -> Starlette:
    answers = {path.stem: (path.read_bytes(), json.loads(path.with_suffix(".json").read_text()))
               for path in directory.glob("*.body")}

    async def answer(request: Request) -> Response:
        await request.body()
        body, headers = answers[request.path_params["name"]]
        return Response(body, headers=headers)

    async def ready(request: Request) -> Response:
        return JSONResponse({"answers": sorted(answers)})

    return Starlette(routes=[Route("/ready", ready), Route("/{name}", answer, methods=["POST"])])


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("port", type=int, help="the loopback port to listen on")
    parser.add_argument("directory", type=Path, help="the stored answers: <name>.body and <name>.json")
    options = parser.parse_args()
    port, directory = options.port, options.directory
    uvicorn.run(app_for(directory), host="127.0.0.1", port=port, log_level="info")
