"""While the database cannot be used (StoreUnavailable: a full disk, PostgreSQL down — the real cases are in
tests/test_full_disk.py and tests/test_database_outage.py), the LTI background work logs one warning line per try,
never a traceback, and never raises into a submission. The store here is one whose every call raises what the real
stores raise then."""
from __future__ import annotations

import logging

from server.classroom import lti_classroom
from server.classroom.store import StoreUnavailable


class DatabaseDown:
    def __getattr__(self, name):
        def unavailable(*args, **kwargs):
            raise StoreUnavailable("PostgreSQL at 127.0.0.1:5432/mdl: connection refused")
        return unavailable


def test_the_lti_queue_logs_one_line_without_a_traceback(monkeypatch, caplog):
    monkeypatch.setattr(lti_classroom, "store", lambda: DatabaseDown())
    monkeypatch.setitem(lti_classroom._swept, "at", 0.0)
    with caplog.at_level(logging.WARNING):
        lti_classroom.submitted("WprABhAcjyY", "lti:abc")          # a submission's hook: never raises
        lti_classroom._post_due()
        lti_classroom.sweep_expired()
    records = [r for r in caplog.records if r.name == lti_classroom.log.name]
    assert len(records) == 3 and all(r.levelno == logging.WARNING and r.exc_info is None for r in records)
    assert all("waits for the database" in r.getMessage() and "connection refused" in r.getMessage()
               for r in records)
