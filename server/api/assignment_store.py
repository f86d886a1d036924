"""The assignment store the API uses: SQLite under $MDL_DATA_DIR (default ./data in the repository)."""
import os
from functools import lru_cache
from pathlib import Path

from ..classroom.storage import AssignmentStore, SQLiteStore
from ..lessons.scenes import REPO_ROOT

DATABASE_FILE = "classroom.sqlite3"


@lru_cache(maxsize=1)
def store() -> AssignmentStore:
    return SQLiteStore(Path(os.environ.get("MDL_DATA_DIR") or REPO_ROOT / "data") / DATABASE_FILE)
