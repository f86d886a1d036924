"""Where assignments and submissions live: the ``AssignmentStore`` interface (``records``), its numbered
schema (``migrations``) and two backends, SQLite (``sqlite``, the embedded default) and PostgreSQL
(``postgres``, for several servers behind one database; imported only when used, so psycopg is needed
only there)."""
from .records import (AssignmentRecord, AssignmentStore, AttemptRefused, StoreUnavailable, StudentRecord,
                      Submission)
from .sqlite import SQLiteStore

__all__ = ["AssignmentRecord", "AssignmentStore", "AttemptRefused", "SQLiteStore", "StoreUnavailable",
           "StudentRecord", "Submission"]
