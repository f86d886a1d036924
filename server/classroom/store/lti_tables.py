"""The LTI tables (migration 6) as store methods, one SQL text for both backends.

A backend mixes ``LtiTables`` in; each method is one transaction (SQLite ``BEGIN IMMEDIATE``, PostgreSQL one
pooled connection), so servers sharing the database agree at once: a launch state or a ticket is taken by
exactly one request (``DELETE … RETURNING``), the tool's key pair is made once (``ON CONFLICT DO NOTHING``,
then the stored one read back), and a score waiting to be posted is one row per student, re-queued in place.
Queries are written with ``?``; PostgreSQL's ``%s`` is put in for it.
"""
from __future__ import annotations

import json
from dataclasses import dataclass


@dataclass(frozen=True)
class PlatformRecord:
    """A registered LMS (an LTI 1.3 platform), with what its administrator's set-up page shows."""
    id: str
    issuer: str
    client_id: str
    name: str
    auth_login_url: str
    auth_token_url: str
    key_set_url: str
    deployment_ids: tuple[str, ...]
    created_at: float


@dataclass(frozen=True)
class LearnerRecord:
    """An LMS user (platform, ``sub``) as a student of one assignment, with the grade service of their launch."""
    platform_id: str
    sub: str
    assignment_id: str
    student_key: str
    context_id: str
    ags: dict | None


@dataclass(frozen=True)
class PendingScore:
    """A student whose score is still to be posted to the LMS: queued at, tries so far, the last error."""
    assignment_id: str
    student_key: str
    queued_at: float
    tries: int
    retry_at: float
    last_error: str | None


PLATFORM_COLUMNS = ("id, issuer, client_id, name, auth_login_url, auth_token_url, key_set_url, deployment_ids, "
                    "created_at")
LEARNER_COLUMNS = "platform_id, sub, assignment_id, student_key, context_id, ags"
PENDING_COLUMNS = "assignment_id, student_key, queued_at, tries, retry_at, last_error"


def _platform(row) -> PlatformRecord:
    return PlatformRecord(row[0], row[1], row[2], row[3], row[4], row[5], row[6], tuple(json.loads(row[7])), row[8])


def _learner(row) -> LearnerRecord:
    return LearnerRecord(row[0], row[1], row[2], row[3], row[4], None if row[5] is None else json.loads(row[5]))


class LtiTables:
    """Store methods of the LTI tables; the backend supplies ``_transaction`` (SQLite) or ``_pool`` (PostgreSQL)."""

    def _lti(self, query: str, args: tuple = ()) -> tuple[list[tuple], int]:
        """Run one statement in its own transaction: the rows it returns and the count of rows it changed."""
        pool = getattr(self, "_pool", None)
        if pool is not None:
            with pool.connection() as connection:
                cursor = connection.execute(query.replace("?", "%s"), args)
                return (cursor.fetchall() if cursor.description else []), cursor.rowcount
        with self._transaction() as connection:
            cursor = connection.execute(query, args)
            rows = cursor.fetchall()
            return rows, cursor.rowcount

    # the platforms
    def lti_add_platform(self, platform: PlatformRecord) -> bool:
        """Register a platform; False when one with this issuer and client id is registered already."""
        _, count = self._lti(
            f"INSERT INTO lti_platforms ({PLATFORM_COLUMNS}) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?) "
            "ON CONFLICT (issuer, client_id) DO NOTHING",
            (platform.id, platform.issuer, platform.client_id, platform.name, platform.auth_login_url,
             platform.auth_token_url, platform.key_set_url, json.dumps(list(platform.deployment_ids)),
             platform.created_at))
        return count == 1

    def lti_platforms(self, issuer: str | None = None) -> list[PlatformRecord]:
        """Every registered platform (of one issuer when given), oldest first."""
        where, args = ("WHERE issuer = ?", (issuer,)) if issuer is not None else ("", ())
        rows, _ = self._lti(f"SELECT {PLATFORM_COLUMNS} FROM lti_platforms {where} ORDER BY created_at, id", args)
        return [_platform(row) for row in rows]

    def lti_platform(self, platform_id: str) -> PlatformRecord | None:
        rows, _ = self._lti(f"SELECT {PLATFORM_COLUMNS} FROM lti_platforms WHERE id = ?", (platform_id,))
        return _platform(rows[0]) if rows else None

    # the tool's key pair
    def lti_tool_key(self, kid: str, private_pem: str, at: float) -> tuple[str, str]:
        """The tool's key pair (kid, private key PEM): the stored one, or this one stored first if there is none
        (of two servers making one at once, both get the same)."""
        self._lti("INSERT INTO lti_tool_keys (slot, kid, private_pem, created_at) VALUES (1, ?, ?, ?) "
                  "ON CONFLICT (slot) DO NOTHING", (kid, private_pem, at))
        rows, _ = self._lti("SELECT kid, private_pem FROM lti_tool_keys WHERE slot = 1")
        return rows[0][0], rows[0][1]

    def lti_stored_tool_key(self) -> tuple[str, str] | None:
        rows, _ = self._lti("SELECT kid, private_pem FROM lti_tool_keys WHERE slot = 1")
        return (rows[0][0], rows[0][1]) if rows else None

    # launch state: OIDC state and nonce, launch data, tickets, the platforms' key sets (JSON, with an expiry)
    def lti_put(self, key: str, value, expires_at: float) -> None:
        self._lti("INSERT INTO lti_launch_state (key, value, expires_at) VALUES (?, ?, ?) "
                  "ON CONFLICT (key) DO UPDATE SET value = excluded.value, expires_at = excluded.expires_at",
                  (key, json.dumps(value), expires_at))

    def lti_get(self, key: str, now: float):
        rows, _ = self._lti("SELECT value FROM lti_launch_state WHERE key = ? AND expires_at > ?", (key, now))
        return json.loads(rows[0][0]) if rows else None

    def lti_take(self, key: str, now: float):
        """The value, removed in the same statement: of two requests taking one key, one gets it, the other None."""
        rows, _ = self._lti("DELETE FROM lti_launch_state WHERE key = ? RETURNING value, expires_at", (key,))
        return json.loads(rows[0][0]) if rows and rows[0][1] > now else None

    def lti_forget_expired(self, now: float) -> int:
        return self._lti("DELETE FROM lti_launch_state WHERE expires_at <= ?", (now,))[1]

    # LMS users as students
    def lti_link_learner(self, learner: LearnerRecord) -> None:
        """Record (or update) which student an LMS user is in an assignment, and their launch's grade service
        (kept when this launch brings none)."""
        self._lti(f"INSERT INTO lti_learners ({LEARNER_COLUMNS}) VALUES (?, ?, ?, ?, ?, ?) "
                  "ON CONFLICT (platform_id, sub, assignment_id) DO UPDATE SET student_key = excluded.student_key, "
                  "context_id = excluded.context_id, ags = COALESCE(excluded.ags, lti_learners.ags)",
                  (learner.platform_id, learner.sub, learner.assignment_id, learner.student_key, learner.context_id,
                   None if learner.ags is None else json.dumps(learner.ags)))

    def lti_learner(self, platform_id: str, sub: str, assignment_id: str) -> LearnerRecord | None:
        rows, _ = self._lti(f"SELECT {LEARNER_COLUMNS} FROM lti_learners WHERE platform_id = ? AND sub = ? "
                            "AND assignment_id = ?", (platform_id, sub, assignment_id))
        return _learner(rows[0]) if rows else None

    def lti_learners_of(self, assignment_id: str, student_key: str | None = None) -> list[LearnerRecord]:
        """The LMS users behind an assignment's students (one student, when given)."""
        query = f"SELECT {LEARNER_COLUMNS} FROM lti_learners WHERE assignment_id = ?"
        args: tuple = (assignment_id,)
        if student_key is not None:
            query, args = query + " AND student_key = ?", (assignment_id, student_key)
        return [_learner(row) for row in self._lti(query + " ORDER BY platform_id, sub", args)[0]]

    # assignments placed in an LMS course (a deep link, or a launch), and their line items
    def lti_place(self, platform_id: str, context_id: str, assignment_id: str, title: str, at: float) -> None:
        self._lti("INSERT INTO lti_placements (platform_id, context_id, assignment_id, title, placed_at) "
                  "VALUES (?, ?, ?, ?, ?) ON CONFLICT (platform_id, context_id, assignment_id) DO NOTHING",
                  (platform_id, context_id, assignment_id, title, at))

    def lti_placed(self, platform_id: str, context_id: str) -> list[tuple[str, str]]:
        """(assignment id, title) of the assignments placed in this course, newest first."""
        rows, _ = self._lti("SELECT assignment_id, title FROM lti_placements WHERE platform_id = ? AND "
                            "context_id = ? ORDER BY placed_at DESC", (platform_id, context_id))
        return [(row[0], row[1]) for row in rows]

    def lti_placements_of(self, assignment_id: str) -> list[tuple[str, str]]:
        """(platform id, context id) of every course the assignment is placed in."""
        rows, _ = self._lti("SELECT platform_id, context_id FROM lti_placements WHERE assignment_id = ?",
                            (assignment_id,))
        return [(row[0], row[1]) for row in rows]

    def lti_unplaced_by_client(self, client: str, since: float) -> list[tuple[str, dict]]:
        """(id, spec) of the assignments made from this address since then that no course has placed yet."""
        rows, _ = self._lti("SELECT id, spec FROM assignments WHERE client = ? AND created_at >= ? AND id NOT IN "
                            "(SELECT assignment_id FROM lti_placements) ORDER BY created_at DESC LIMIT 50",
                            (client, since))
        return [(row[0], json.loads(row[1])) for row in rows]

    def lti_line_item(self, platform_id: str, context_id: str, assignment_id: str) -> str | None:
        rows, _ = self._lti("SELECT url FROM lti_line_items WHERE platform_id = ? AND context_id = ? AND "
                            "assignment_id = ?", (platform_id, context_id, assignment_id))
        return rows[0][0] if rows else None

    def lti_keep_line_item(self, platform_id: str, context_id: str, assignment_id: str, url: str) -> None:
        self._lti("INSERT INTO lti_line_items (platform_id, context_id, assignment_id, url) VALUES (?, ?, ?, ?) "
                  "ON CONFLICT (platform_id, context_id, assignment_id) DO UPDATE SET url = excluded.url",
                  (platform_id, context_id, assignment_id, url))

    # scores still to post
    def lti_queue_score(self, assignment_id: str, student_key: str, at: float) -> None:
        """The student's score is to be posted (again): one row per student, due now."""
        self._lti(f"INSERT INTO lti_passbacks ({PENDING_COLUMNS}) VALUES (?, ?, ?, 0, ?, NULL) "
                  "ON CONFLICT (assignment_id, student_key) DO UPDATE SET queued_at = excluded.queued_at, "
                  "retry_at = excluded.retry_at", (assignment_id, student_key, at, at))

    def lti_due_scores(self, now: float, limit: int = 50) -> list[PendingScore]:
        rows, _ = self._lti(f"SELECT {PENDING_COLUMNS} FROM lti_passbacks WHERE retry_at <= ? "
                            "ORDER BY retry_at LIMIT ?", (now, limit))
        return [PendingScore(*row) for row in rows]

    def lti_pending_scores(self) -> list[PendingScore]:
        rows, _ = self._lti(f"SELECT {PENDING_COLUMNS} FROM lti_passbacks ORDER BY retry_at")
        return [PendingScore(*row) for row in rows]

    def lti_claim_score(self, pending: PendingScore, until: float) -> bool:
        """Take a due score for posting (its retry moved to ``until``); False when another server took it."""
        return self._lti("UPDATE lti_passbacks SET retry_at = ? WHERE assignment_id = ? AND student_key = ? "
                         "AND retry_at = ? AND queued_at = ?", (until, pending.assignment_id, pending.student_key,
                                                                pending.retry_at, pending.queued_at))[1] == 1

    def lti_score_posted(self, pending: PendingScore) -> None:
        """Posted: the row goes, unless the score was queued again meanwhile (then it is posted once more)."""
        self._lti("DELETE FROM lti_passbacks WHERE assignment_id = ? AND student_key = ? AND queued_at = ?",
                  (pending.assignment_id, pending.student_key, pending.queued_at))

    def lti_score_failed(self, pending: PendingScore, error: str, retry_at: float) -> None:
        self._lti("UPDATE lti_passbacks SET tries = tries + 1, last_error = ?, retry_at = ? "
                  "WHERE assignment_id = ? AND student_key = ? AND queued_at = ?",
                  (error[:500], retry_at, pending.assignment_id, pending.student_key, pending.queued_at))
