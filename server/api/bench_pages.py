"""The benchmarks' stored figures at /bench-results (bench/results/): plotly's own HTML export, which draws
its figure with two inline scripts and plotly.js from this server (/vendor/plotly/plotly.min.js).

The app's Content-Security-Policy allows no inline script, so each such page gets the policy widened by the
sha256 of exactly its own inline scripts (CSP Level 2 hash sources): no 'unsafe-inline', no 'unsafe-eval',
no other origin. Every other file there keeps the app's policy.
"""
from __future__ import annotations

import base64
import hashlib
import re
from functools import lru_cache

from starlette.staticfiles import StaticFiles

from .security import policy_with_script_hashes

INLINE_SCRIPT = re.compile(r"<script(?![^>]*\bsrc=)[^>]*>(.*?)</script>", re.S | re.I)


def inline_script_hashes(html: str) -> list[str]:
    """The base64 sha256 of each inline script's text, as the browser hashes it (the exact characters
    between the tags, UTF-8)."""
    return [base64.b64encode(hashlib.sha256(text.encode()).digest()).decode() for text in INLINE_SCRIPT.findall(html)]


@lru_cache(maxsize=64)
def _page_policy(path: str, mtime_ns: int, size: int) -> str:
    with open(path, encoding="utf-8") as page:
        return policy_with_script_hashes(inline_script_hashes(page.read()))


class BenchResults(StaticFiles):
    """StaticFiles whose HTML pages carry a policy that lets exactly their own inline scripts run."""

    def file_response(self, full_path, stat_result, scope, status_code=200):
        response = super().file_response(full_path, stat_result, scope, status_code)
        if str(full_path).endswith(".html"):
            response.headers["content-security-policy"] = _page_policy(
                str(full_path), stat_result.st_mtime_ns, stat_result.st_size)
        return response
