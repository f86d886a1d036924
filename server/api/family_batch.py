"""The members of a family computed as a batch, through a memo of member answers (POST /api/v1/family).

``member_batch`` gives family.build its members(values, deadline): each value's body (the request with the
varied paths set), its answer from the memo when the same endpoint, body and language were computed before in
this process (a neighbouring family sharing a member; the coarse stage's members, asked again by the full
family, where both stages run in one process: with heavy processes the coarse stage runs in the lane of
answers, routers/family.py), else from endpoints.compute_answer, one body after another until the deadline has passed.
The kinematics core evaluates one parameter set per call (its special positions, harmonics and warnings are
per mechanism), so a batch is a loop over bodies, not one call over a (φ, value) grid.

Members are pruned to the request's ``fields`` (family.pruned) as they are made, so the memo keys them by
the fields too: the same body asked with other fields is another member. The endpoint is told which top-level
keys are read (endpoints.compute_answer ``reads``), so that it skips what no field reads (an elastic member's
check run at rtol/10, which only estimates the error of numerics no preview draws; the forces' crank check).

The memo is a least-recently-used store per heavy process, bounded both in members (MEMO_MEMBERS) and in the
bytes their arrays hold (MEMO_BYTES); a member cut short by a bound is not kept (a quieter moment gives it whole).
"""
from __future__ import annotations

import time
from collections import OrderedDict
from dataclasses import replace

import orjson
from pydantic import ValidationError

from ..core.mechanisms import GeometryError
from . import family
from .endpoints import compute_answer

MEMO_MEMBERS = 4096
MEMO_BYTES = 64 * 2**20


class MemberMemo:
    """Members by (endpoint, canonical body, language, fields), least recently used first out."""

    def __init__(self, entries: int = MEMO_MEMBERS, size: int = MEMO_BYTES):
        self.entries, self.size, self.held = entries, size, 0
        self.store: OrderedDict[tuple, family.Member] = OrderedDict()

    def get(self, key: tuple) -> family.Member | None:
        member = self.store.get(key)
        if member is not None:
            self.store.move_to_end(key)
        return member

    def put(self, key: tuple, member: family.Member) -> None:
        if member.partial or key in self.store:
            return
        self.store[key] = member
        self.held += member.size()
        while len(self.store) > self.entries or self.held > self.size:
            _, dropped = self.store.popitem(last=False)
            self.held -= dropped.size()


MEMO = MemberMemo()


def member_batch(endpoint: str, request: dict, vary: list[family.Vary], lang: str,
                 counts: dict | None = None, fields: list[str] | None = None) -> family.MemberBatch:
    """members(values, deadline) for family.build, each pruned to ``fields`` (None: the whole answer);
    ``counts`` (if given) gathers "computed" and "reused"."""
    counts = {} if counts is None else counts
    trie = None if fields is None else family.field_trie(fields)
    reads = None if trie is None else frozenset(trie)      # the endpoint may skip what no field reads
    named = None if fields is None else tuple(sorted(set(fields)))

    def members(values: list[float], deadline: float) -> list[family.Member]:
        found = []
        for value in values:
            body = family.member_body(request, vary, value)
            key = (endpoint, orjson.dumps(body, option=orjson.OPT_SORT_KEYS), lang, named)
            member = MEMO.get(key)
            if member is None:
                if time.perf_counter() > deadline:
                    break
                try:
                    outcome = compute_answer(endpoint, body, lang, reads)
                except (ValidationError, GeometryError) as error:
                    outcome = error
                member = family.Member.of(value, outcome, trie)
                MEMO.put(key, member)
                counts["computed"] = counts.get("computed", 0) + 1
            else:               # the same body may be another slider's member at another value
                member = replace(member, value=value)
                counts["reused"] = counts.get("reused", 0) + 1
            found.append(member)
        return found

    return members
