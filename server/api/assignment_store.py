"""The assignment store the API uses: SQLite under $MDL_DATA_DIR (default ./data in the repository).

``check()`` runs at start-up (the app's lifespan): a database the server cannot write stops it there with
a message naming the file and the reason, instead of a 500 on the first submission.
"""
import logging
import os
from functools import lru_cache
from pathlib import Path

from ..classroom.store import AssignmentStore, SQLiteStore, StoreUnavailable
from ..lessons.scenes import REPO_ROOT

DATABASE_FILE = "classroom.sqlite3"


@lru_cache(maxsize=1)
def store() -> AssignmentStore:
    return SQLiteStore(Path(os.environ.get("MDL_DATA_DIR") or REPO_ROOT / "data") / DATABASE_FILE)


def check() -> None:
    """Open the store and try a write; StoreUnavailable (logged, then raised: the server does not start)
    when the database cannot take one."""
    try:
        store().check()
    except StoreUnavailable as error:
        logging.getLogger("uvicorn.error").error("the server cannot start: %s", error)
        raise
