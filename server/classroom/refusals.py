"""What the classroom refuses, in its own words: something a request names that is not there, answers that cannot
be computed just now, and a client that has done something too often. server/api/errors.py answers each with its
HTTP status, body and Retry-After; the classroom knows nothing of HTTP."""
from __future__ import annotations


class NotFound(Exception):
    """No such assignment, results page (a wrong token) or student: ``what`` says which, in words."""

    def __init__(self, what: str):
        super().__init__(what)
        self.what = what


class Busy(Exception):
    """The correct answers cannot be had now (every place to wait for them is taken, or their budget ran out):
    nothing was counted, and the same request may be made again in ``retry_after`` seconds. ``code`` names the
    case (answers_busy, answers_not_ready), ``reason`` says it in words."""

    def __init__(self, code: str, reason: str, retry_after: int):
        super().__init__(reason)
        self.code, self.reason, self.retry_after = code, reason, retry_after


class TooOften(Exception):
    """A client has done something ``limit`` times within its window: the next one is possible in ``retry_after``
    seconds. ``code`` names what is limited (rate_limited), ``reason`` says it in words."""

    def __init__(self, code: str, reason: str, retry_after: int, limit: int):
        super().__init__(reason)
        self.code, self.reason, self.retry_after, self.limit = code, reason, retry_after, limit
