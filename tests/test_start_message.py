"""What the server says while it starts."""
from __future__ import annotations

from fastapi.testclient import TestClient

from server.api.app import app


def test_the_start_says_it_is_compiling_before_it_waits(caplog):
    """A first start compiles for a minute or two: the log says so before, and when the code is ready."""
    with caplog.at_level("INFO", logger="uvicorn.error"), TestClient(app):
        pass
    messages = [record.getMessage() for record in caplog.records if record.name == "uvicorn.error"]
    loading = next(i for i, m in enumerate(messages) if m.startswith("loading the compiled numerical kernels"))
    ready = next(i for i, m in enumerate(messages) if m.startswith("compiled code ready in"))
    assert loading < ready and "compiled first" in messages[loading]
