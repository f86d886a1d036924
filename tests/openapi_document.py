"""The app's OpenAPI document, built once per test process: building it takes about a second, and test_fuzz,
test_hostile_input and test_schemathesis_api read it while the tests are collected, which every test process
does. Each caller gets a copy of its own."""
from __future__ import annotations

import copy
import functools

from server.api.app import create_app


@functools.cache
def _document() -> dict:
    return create_app().openapi()


def openapi_document() -> dict:
    """create_app().openapi(), as a fresh copy."""
    return copy.deepcopy(_document())
