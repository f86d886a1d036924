"""The whole suite: run in parallel worker processes by pytest-xdist (`tests/run.sh`: `-n 3 --dist loadgroup`).

What the workers must not share, and how they don't:
- a module's own fixtures (its servers, nginx, a PostgreSQL) start once per module: every test of a module that
  uses a module- or class-scoped fixture goes to one worker (the group is the module's path);
- the session fixtures (the browser tests' app server and Chromium, tests/postgres.py's server) start at most
  once per worker, each on a free port, with their data in a temporary directory of their own;
- the app's SQLite store: a test that builds the app without naming `MDL_DATA_DIR` would use the repository's
  `data/`, shared by every worker and every earlier run; here it gets a temporary directory per process.
The numba disk cache is filled by `python3 -m server.core.warm_up` before pytest starts, so the workers only
read it. No Hypothesis example has a deadline (its default is 200 ms): the suite may not depend on the machine's
speed, and a parallel run on a loaded 2-CPU machine takes longer than that for an example now and then.
"""
from __future__ import annotations

import os
import shutil
import tempfile

import pytest
from hypothesis import settings

settings.register_profile("suite", deadline=None)
settings.load_profile("suite")

_DATA_DIR: str | None = None


def pytest_configure(config):
    global _DATA_DIR
    if not os.environ.get("MDL_DATA_DIR"):
        _DATA_DIR = tempfile.mkdtemp(prefix="mdl-tests-data-")
        os.environ["MDL_DATA_DIR"] = _DATA_DIR


def pytest_unconfigure(config):
    if _DATA_DIR is not None:
        os.environ.pop("MDL_DATA_DIR", None)
        shutil.rmtree(_DATA_DIR, ignore_errors=True)


@pytest.hookimpl(tryfirst=True)          # before xdist reads the groups (--dist loadgroup)
def pytest_collection_modifyitems(config, items):
    """Keep the tests sharing a module's (or class's) own fixture on one worker, so it starts once."""
    for item in items:
        info = getattr(item, "_fixtureinfo", None)
        if info is None or any(True for _ in item.iter_markers("xdist_group")):
            continue
        if any(definition.scope in ("module", "class", "package")
               for definitions in info.name2fixturedefs.values() for definition in definitions):
            item.add_marker(pytest.mark.xdist_group(item.nodeid.split("::", 1)[0]))
