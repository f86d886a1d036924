"""Run a coroutine to its end from a synchronous test, whatever the test session has running.

Playwright's sync API (the browser tests' session-wide browser) keeps an event loop running in the main
thread, where asyncio.run() refuses to start another; a thread of its own has none."""
from __future__ import annotations

import asyncio
from concurrent.futures import ThreadPoolExecutor


def run_to_end(coroutine):
    """asyncio.run(coroutine) in a thread of its own; its result, or its exception."""
    with ThreadPoolExecutor(1, thread_name_prefix="test-loop") as thread:
        return thread.submit(asyncio.run, coroutine).result()
