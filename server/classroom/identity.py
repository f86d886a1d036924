"""A student's personal secret: what proves, on any device, that a request comes from that student.

The secret is 32 random URL-safe characters (192 bits, ``secrets.token_urlsafe``). The store keeps only its
SHA-256 (``secret_hash``), so a copy of the database gives nobody a way in. The student holds the secret in a
cookie (set on registration, or by opening the personal link) and in the personal link itself,
``/assignments/{id}/me/{secret}``, shown once to bookmark; the instructor can make a new one, which ends the old.
"""
from __future__ import annotations

import hashlib
import re
import secrets

SECRET_BYTES = 24
SECRET_PATTERN = re.compile(r"[A-Za-z0-9_-]{32}")


def new_secret() -> str:
    return secrets.token_urlsafe(SECRET_BYTES)


def secret_hash(secret: str) -> str:
    """What the store keeps of a secret: its SHA-256, hex."""
    return hashlib.sha256(secret.encode()).hexdigest()


def well_formed(secret: str) -> bool:
    """Whether a text can be a secret at all (checked before hashing what a request sends)."""
    return SECRET_PATTERN.fullmatch(secret) is not None


def personal_path(assignment_id: str, secret: str) -> str:
    """The personal link's path: opening it on any device sets the cookie and shows the student's variant."""
    return f"/assignments/{assignment_id}/me/{secret}"
