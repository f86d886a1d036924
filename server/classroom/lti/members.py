"""Who an LMS user is here: their role (learner or instructor), their name as the LMS gives it, and the key
of the student they become in an assignment."""
from __future__ import annotations

import hashlib

from ..names import MAX_NAME, clean

ROLES_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/roles"
TEACHING_ROLES = ("#Instructor", "#Administrator", "#ContentDeveloper", "#TeachingAssistant",
                  "/Instructor", "/Administrator")           # context and institution roles, full URIs or short
KEY_PREFIX = "lti:"


def teaches(roles: list[str] | None) -> bool:
    """Whether these LTI roles may see results and choose content (Instructor, Administrator, …)."""
    return any(role.endswith(TEACHING_ROLES) or role in ("Instructor", "Administrator") for role in roles or [])


def lms_name(claims: dict) -> str:
    """The user's name from a launch or a membership: ``name``, else given and family name, else none."""
    name = clean(str(claims.get("name") or "")) or clean(
        f"{claims.get('given_name') or ''} {claims.get('family_name') or ''}")
    return name[:MAX_NAME]


def student_key(issuer: str, sub: str) -> str:
    """The key of an LMS user's student record: never a typed name's key (those have no "lti:" prefix that a
    hash follows), the same on every launch."""
    return KEY_PREFIX + hashlib.sha256(f"{issuer}\n{sub}".encode()).hexdigest()[:24]
