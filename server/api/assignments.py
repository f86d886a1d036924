"""Assignments as the API and the pages use them: loading, enrolling a student, the state of a student's
questions and the results table. Thin glue between the store, the variants and the answers."""
from __future__ import annotations

import hashlib
import secrets
import time
from datetime import datetime, timezone

from fastapi import HTTPException

from ..classroom.spec import AssignmentSpec
from ..classroom.store import AssignmentRecord, StudentRecord
from ..classroom.variants import MAX_NAME, Plan, SpecError, plan, student_key
from . import assignment_answers
from .answers import question, tolerance
from .assignment_store import store
from ..lessons.scenes import interface_texts, scenes
from .schemas_assignments import AssignmentInfo, QuestionInfo, QuestionState, ResultRow

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
        raise HTTPException(404, "no such assignment")
    return record, plan(AssignmentSpec.model_validate(record.spec), scenes())


def check_token(record: AssignmentRecord, token: str) -> None:
    if not secrets.compare_digest(token_hash(token), record.token_hash):
        raise HTTPException(404, "no such results page")


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
                                unit=unit_text(question(resolved.scene, p.id).unit, lang), tolerance=tolerance(resolved, p.id))
                   for p in spec.questions],
        attempts=spec.attempts, deadline=None if spec.deadline is None else spec.deadline.isoformat(),
        open=is_open(resolved), variants=resolved.count)


def enrol(record: AssignmentRecord, resolved: Plan, name: str) -> StudentRecord:
    """The student (registered on first sight) with their variant."""
    name = " ".join(name.split())[:MAX_NAME]
    key = student_key(name)
    if not key:
        raise SpecError("student", "type a name or a number")
    number = resolved.number_for(record.id, key)
    stored, _ = store().register(record.id, StudentRecord(key, name, number, resolved.values(number), time.time()))
    return stored


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
            correct_value=assignment_answers.correct_value(record.id, resolved, student.variant, about.id)
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
        rows.append(ResultRow(student=student.name, variant=student.variant + 1, values=student.parameters,
                              first_seen=iso(student.first_seen), last_submission=iso(student.last_at),
                              attempts=student.attempts, score=student.solved, questions=per_question))
    return rows
