"""Assignments as the API and the pages use them: loading, registering a student (a name and a personal
secret), the state of a student's questions, the results table and the instructor's roster. Thin glue
between the store, the names, the variants and the answers."""
from __future__ import annotations

import hashlib
import os
import secrets
import time
from datetime import datetime, timezone

from . import identity, turning
from .refusals import NotFound
from .names import NameRefused, check_new, normalise, resembles, roster_names
from .spec import AssignmentSpec
from .store import AssignmentRecord, StudentRecord
from .variants import Plan, plan
from . import assignment_answers
from .answers import question, question_kind, tolerance
from .assignment_models import AssignmentInfo, QuestionInfo, QuestionState, ResultRow, RosterOutcome
from .assignment_store import store
from ..lessons.scenes import interface_texts, scenes

REGISTRATION_WINDOW_S = 3600


def registrations_per_hour() -> int:
    """New students one address may register per hour (``MDL_REGISTRATIONS_PER_HOUR``, 120 unless set: a class
    behind one address, a university's NAT, registers well under it; a script making up students stops there)."""
    return int(os.environ.get("MDL_REGISTRATIONS_PER_HOUR", "120"))


def token_hash(token: str) -> str:
    return hashlib.sha256(token.encode()).hexdigest()


def iso(at: float | None) -> str | None:
    return None if at is None else datetime.fromtimestamp(at, timezone.utc).isoformat(timespec="seconds")


def create(spec: AssignmentSpec, client: str = "") -> tuple[AssignmentRecord, Plan, str]:
    """Check the spec, make sure every question has an answer across the checked variants (computed in a heavy
    process, assignment_answers), store it with the answers found."""
    resolved = plan(spec, scenes())
    found = assignment_answers.check_new(resolved)
    token = secrets.token_urlsafe(18)
    record = AssignmentRecord(secrets.token_urlsafe(8), token_hash(token), time.time(), spec.model_dump(mode="json"),
                              client=client)
    store().create(record)
    assignment_answers.keep(record.id, found)
    return record, resolved, token


def load(assignment_id: str) -> tuple[AssignmentRecord, Plan]:
    record = store().assignment(assignment_id) if len(assignment_id) <= 40 else None
    if record is None:
        raise NotFound("no such assignment")
    return record, plan(AssignmentSpec.model_validate(record.spec), scenes())


def check_token(record: AssignmentRecord, token: str) -> None:
    if not secrets.compare_digest(token_hash(token), record.token_hash):
        raise NotFound("no such results page")


def replace_token(record: AssignmentRecord, token: str) -> str:
    """A new results token in place of ``token`` (a leaked link): the old one stops working at once."""
    check_token(record, token)
    new = secrets.token_urlsafe(18)
    if not store().replace_token(record.id, record.token_hash, token_hash(new)):
        raise NotFound("no such results page")             # replaced a moment ago by another request
    return new


def results_url(base: str, record: AssignmentRecord, token: str, lang: str) -> str:
    return f"{base}/assignments/{record.id}/results/{token}?lang={lang}"


def is_open(resolved: Plan, now: float | None = None) -> bool:
    deadline = resolved.spec.deadline
    return deadline is None or (now or time.time()) <= deadline.timestamp()


def unit_text(unit: str, lang: str) -> str:
    """A question's unit in the reader's language ("kg_m2" → "кг·м²"), from content/i18n's units_<unit>."""
    return interface_texts(lang).get(f"units_{unit}", unit) if unit else ""


def info(record: AssignmentRecord, resolved: Plan, lang: str) -> AssignmentInfo:
    spec = resolved.spec
    return AssignmentInfo(
        id=record.id, title=spec.title or resolved.scene.title[lang], scene=spec.scene,
        scene_title=resolved.scene.title[lang], variant=spec.variant,
        questions=[QuestionInfo(id=p.id, label=question(resolved.scene, p.id).label[lang],
                                unit=unit_text(question(resolved.scene, p.id).unit, lang), tolerance=tolerance(resolved, p.id),
                                **question_kind(resolved, p.id))
                   for p in spec.questions],
        attempts=spec.attempts, deadline=None if spec.deadline is None else spec.deadline.isoformat(),
        open=is_open(resolved), variants=resolved.count, turning=turning_info(resolved))


def turning_info(resolved: Plan) -> dict[str, int] | None:
    """A course project's share of variants that turn fully (classroom/turning.py), else None."""
    share = turning.turning_share(resolved)
    return None if share is None else {"turn": share[0], "checked": share[1]}


def student_id(assignment_id: str, key: str) -> str:
    """The handle of a student in the instructor's API (no name in a URL): 16 hex digits of SHA-256."""
    return hashlib.sha256(f"{assignment_id}\n{key}".encode()).hexdigest()[:16]


def new_student(record: AssignmentRecord, resolved: Plan, name: str, secret_hash: str | None,
                on_roster: bool = False) -> StudentRecord:
    """The record of a student not yet stored: the key, the variant that follows from it, the values."""
    key = normalise(name)
    number = resolved.number_for(record.id, key)
    return StudentRecord(key, name, number, resolved.values(number), time.time(), secret_hash=secret_hash,
                         on_roster=on_roster)


def identify(record: AssignmentRecord, secret: str | None) -> StudentRecord | None:
    """The student whose personal secret this is, or None."""
    if not secret or not identity.well_formed(secret):
        return None
    return store().student_by_secret(record.id, identity.secret_hash(secret))


def needs_link(name: str) -> NameRefused:
    return NameRefused("roster_name_needs_link", f"the name '{name}' is on the instructor's list: open the personal "
                                                 f"link the instructor gave you", name=name)


def register(record: AssignmentRecord, resolved: Plan, name: str, current: StudentRecord | None,
             client: str = "") -> tuple[StudentRecord, str | None]:
    """Register a name typed by ``client`` (an address): the student and their new secret (None when the request
    already is this student).

    A name on the instructor's roster is entered only with the personal link the instructor hands out, never by
    typing it, nor by typing a name that looks like it: NameRefused("roster_name_needs_link"). A new name must
    pass ``names.check_new`` (one alphabet per word, not a look-alike of a registered name), be on the roster
    once the instructor has locked registration, and come from an address that has registered fewer than
    ``registrations_per_hour()`` students in the last hour. A registered name off the roster that has no secret
    yet (registered before secrets existed) is claimed by its first registration; one that has a secret
    belongs to whoever holds it: NameRefused("name_taken")."""
    key = normalise(name)
    if current is not None and current.key == key:
        return current, None
    existing = store().students(record.id)
    same = next((s for s in existing if s.key == key), None)
    if same is None:
        shown = check_new(name, [])                      # empty, too long, a word in two alphabets
        on_roster = resembles(shown, [s.name for s in existing if s.on_roster])
        if on_roster is not None:
            raise needs_link(on_roster)
        check_new(shown, [s.name for s in existing])
        if record.roster_locked:
            raise NameRefused("roster_locked", "registration is open only to the names on the instructor's roster; "
                                               "check how your name is written there, or ask the instructor")
        limit = registrations_per_hour()
        if client and store().recent_registrations_by_client(client, time.time() - REGISTRATION_WINDOW_S) >= limit:
            raise NameRefused("too_many_registrations", f"at most {limit} new students per hour from one address "
                                                        f"(MDL_REGISTRATIONS_PER_HOUR); try again later, or ask the "
                                                        f"instructor for a personal link", limit=str(limit))
        secret = identity.new_secret()
        stored, created = store().register(record.id, new_student(record, resolved, shown,
                                                                  identity.secret_hash(secret)), client)
        if created:
            return stored, secret
        same = stored                                    # registered by someone else a moment ago
    if same.on_roster:
        raise needs_link(same.name)
    if same.secret_hash is None:
        secret = identity.new_secret()
        if store().claim_secret(record.id, same.key, identity.secret_hash(secret)):     # the first claim only
            return store().student(record.id, same.key), secret
    raise NameRefused("name_taken", f"the name '{same.name}' is already registered; if it is yours, open your "
                                    f"personal link, or ask the instructor for a new one", name=same.name)


def personal_url(base: str, record: AssignmentRecord, resolved: Plan, secret: str) -> str:
    """The student's personal link, in the assignment's language."""
    return f"{base}{identity.personal_path(record.id, secret)}?lang={resolved.spec.lang}"


def find_student(record: AssignmentRecord, handle: str) -> StudentRecord:
    """The student with this handle (``student_id``); NotFound if there is none."""
    found = next((s for s in store().students(record.id) if student_id(record.id, s.key) == handle), None)
    if found is None:
        raise NotFound("no such student")
    return found


def new_link(record: AssignmentRecord, student: StudentRecord) -> str:
    """A new personal secret for the student (the old link and cookies stop working); the secret."""
    secret = identity.new_secret()
    if not store().set_secret(record.id, student.key, identity.secret_hash(secret)):
        raise NotFound("no such student")
    return secret


def add_roster(record: AssignmentRecord, resolved: Plan, text: str) -> RosterOutcome:
    """Put the roster's names on the assignment (each with their variant, no secret yet): the names added,
    those already registered, and the lines refused with the reason (no name, a name in two alphabets, a
    look-alike of another name)."""
    roster = roster_names(text)
    existing = store().students(record.id)
    known = {s.key: s.name for s in existing}
    shown_names = [s.name for s in existing]
    outcome = RosterOutcome(refused=[{"line": line, "reason": reason} for line, reason in roster.refused])
    for name in roster.names:
        if normalise(name) in known:
            outcome.already.append(known[normalise(name)])
            continue
        try:
            shown = check_new(name, shown_names)
        except NameRefused as refused:
            outcome.refused.append({"line": name, "reason": refused.reason})
            continue
        stored, created = store().register(record.id, new_student(record, resolved, shown, None, on_roster=True))
        (outcome.added if created else outcome.already).append(stored.name)
        known[stored.key] = stored.name
        shown_names.append(stored.name)
    return outcome


def question_states(record: AssignmentRecord, resolved: Plan, student: StudentRecord,
                    lang: str) -> list[QuestionState]:
    tried = store().submissions(record.id, student.key)
    states = []
    for about in info(record, resolved, lang).questions:
        mine = [s for s in tried if s.question == about.id]
        right = any(s.correct for s in mine)
        left = 0 if right else resolved.spec.attempts - len(mine)
        states.append(QuestionState(
            **about.model_dump(), attempts_used=len(mine), attempts_left=left, right=right,
            answers=[s.answer for s in mine],
            correct_value=mine[-1].correct_value
            if resolved.spec.reveal_answers and (right or left == 0) else None))
    return states


def result_rows(record: AssignmentRecord, resolved: Plan) -> list[ResultRow]:
    tried = store().submissions(record.id)
    rows = []
    for student in store().students(record.id):
        mine = [s for s in tried if s.student_key == student.key]
        per_question = {}
        for pick in resolved.spec.questions:
            answers = [s for s in mine if s.question == pick.id]
            per_question[pick.id] = {"attempts": len(answers), "right": any(s.correct for s in answers),
                                     "answer": answers[-1].answer if answers else None,
                                     "correct": answers[-1].correct_value if answers else None}
        rows.append(ResultRow(id=student_id(record.id, student.key), student=student.name,
                              on_roster=student.on_roster, has_link=student.secret_hash is not None,
                              variant=student.variant + 1, values=student.parameters,
                              first_seen=iso(student.first_seen), last_submission=iso(student.last_at),
                              attempts=student.attempts, score=student.solved, questions=per_question))
    return rows
