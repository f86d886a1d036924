"""The assignment store the API uses: PostgreSQL when ``MDL_DATABASE_URL=postgresql://…`` is set (several
servers behind one database), else SQLite under $MDL_DATA_DIR (default ./data in the repository).

``check()`` runs at start-up (the app's lifespan): a database the server cannot reach or write stops it
there with a message naming the database and the reason, instead of a 500 on the first submission.
"""
import logging
import os
from functools import lru_cache
from pathlib import Path

from .store import AssignmentStore, SQLiteStore, StoreUnavailable
from ..paths import default_data_dir

DATABASE_FILE = "classroom.sqlite3"
POSTGRES_SCHEMES = ("postgresql://", "postgres://")


@lru_cache(maxsize=1)
def store() -> AssignmentStore:
    url = os.environ.get("MDL_DATABASE_URL", "").strip()
    if not url:
        return SQLiteStore(Path(os.environ.get("MDL_DATA_DIR") or default_data_dir()) / DATABASE_FILE)
    if not url.startswith(POSTGRES_SCHEMES):
        raise StoreUnavailable(f"MDL_DATABASE_URL must start with postgresql:// (it starts with "
                               f"{url.split(':', 1)[0][:20]!r}); unset it for SQLite under MDL_DATA_DIR")
    try:
        from .store.postgres import PostgresStore   # psycopg is needed only here
    except ImportError as missing:
        raise StoreUnavailable(f"MDL_DATABASE_URL names a PostgreSQL database, but {missing.name or 'psycopg'} is not "
                               "installed: pip install '.[postgres]' in the checkout (or "
                               "'mechanism-dynamics-lab[postgres]'), or unset MDL_DATABASE_URL for SQLite") from None

    return PostgresStore(url)


def check() -> None:
    """Open the store and try a write; StoreUnavailable (logged, then raised: the server does not start)
    when the database cannot take one."""
    try:
        store().check()
    except StoreUnavailable as error:
        logging.getLogger("uvicorn.error").error("the server cannot start: %s", error)
        raise
