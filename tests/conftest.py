"""The whole suite: run in parallel worker processes by pytest-xdist (`tests/run.sh`: `-n 4 --dist loadgroup`).

What the workers must not share, and how they don't:
- a module's own fixtures (its servers, nginx, a PostgreSQL) start once per module: every test of a module that
  has a module- or class-scoped fixture goes to one worker, in file order (the group is the module's path;
  schemathesis's items do not take it: tests/run.sh runs test_schemathesis_api.py in a process of its own);
- the session fixtures (the browser tests' app server and Chromium, tests/postgres.py's server) start at most
  once per worker, each on a free port, with their data in a temporary directory of their own;
- the warming of the response cache after a start (MDL_WARM_DEFAULTS, on by default): off unless a test asks;
- the app's SQLite store: a test that builds the app without naming `MDL_DATA_DIR` would use the repository's
  `data/`, shared by every worker and every earlier run; here it gets a temporary directory per process.
The numba disk cache is filled by `python3 -m server.core.warm_up` before pytest starts, so the workers only
read it. No Hypothesis example has a deadline (its default is 200 ms): the suite may not depend on the machine's
speed, and a parallel run on a loaded 2-CPU machine takes longer than that for an example now and then.
"""
from __future__ import annotations

import collections
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
    # the app warms its cache with every scene's default answers after each start unless told not to: the suite
    # starts about a hundred servers, and only tests/test_default_answers_warming.py wants that work done
    os.environ.setdefault("MDL_WARM_DEFAULTS", "0")
    if not os.environ.get("MDL_DATA_DIR"):
        _DATA_DIR = tempfile.mkdtemp(prefix="mdl-tests-data-")
        os.environ["MDL_DATA_DIR"] = _DATA_DIR


def pytest_unconfigure(config):
    if _DATA_DIR is not None:
        os.environ.pop("MDL_DATA_DIR", None)
        shutil.rmtree(_DATA_DIR, ignore_errors=True)


def _rename(item, nodeid: str) -> None:
    """Give a test another node id (pytest 9 keeps it in `_id`; xdist's own loadgroup renaming, which sets
    `_nodeid`, no longer takes effect there)."""
    if hasattr(item, "_id"):
        from _pytest.nodes import coerce_node_id
        item._id = coerce_node_id(nodeid)
    else:
        item._nodeid = nodeid


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Keep every test of a module that has a module- (or class-) scoped fixture on one worker, in file order:
    the fixture starts once, and a test may count what the module's earlier tests did
    (test_schemathesis_api's test_enough_cases_were_sent). Every test gets a node id of its own first: xdist
    hands out tests by node id."""
    named = collections.Counter(item.nodeid for item in items)
    for item in items:            # schemathesis gives each operation's test the same node id; xdist runs one only
        if named[item.nodeid] > 1:
            _rename(item, f"{item.nodeid.rsplit('::', 1)[0]}::{item.name}")
    assert len({item.nodeid for item in items}) == len(items), "two tests share a node id"
    if getattr(config.option, "dist", "no") != "loadgroup" and not getattr(config.option, "loadgroup", False):
        return                    # (an xdist worker, which collects, has dist "no" and loadgroup True instead)
    shared = {item.path for item in items if any(
        definition.scope in ("module", "class", "package") for definitions in
        getattr(getattr(item, "_fixtureinfo", None), "name2fixturedefs", {}).values() for definition in definitions)}
    for item in items:            # xdist's loadgroup sends the tests whose node ids end in the same "@group" together
        if item.path in shared and "@" not in item.nodeid.rsplit("]", 1)[-1]:
            _rename(item, f"{item.nodeid}@{item.nodeid.split('::', 1)[0]}")
