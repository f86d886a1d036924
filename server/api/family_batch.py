"""The members of a family computed as a batch, through a memo of member answers (POST /api/v1/family).

``member_batch`` gives family.build its members(values, deadline): each value's body (the request with the
varied paths set), its answer from the memo when the same endpoint, body and language were computed before in
this process (a neighbouring family sharing a member; the coarse stage's members, asked again by the full
family, where both stages run in one process: with heavy processes the coarse stage runs in the lane of
answers, routers/family.py), else computed: the members the memo lacks, in chunks of CHUNK_MEMBERS (of one
member for an endpoint without a batch body), each chunk one call of endpoints.compute_answers (what the
members share, a machine's tables, computed once for the chunk). Before each chunk the deadline is checked, and
whether the client has given the family up (heavy.stopped: the page asked for another, or left). A member is
the same whether computed alone or in a chunk (tests/test_family_members.py); the members returned are the
values' first ones, in order, up to the first one not computed by the deadline.

Members are pruned to the request's ``fields`` (family.pruned) as they are made, so the memo keys them by
the fields too: the same body asked with other fields is another member. The endpoint is told which top-level
keys are read (endpoints.compute_answers ``reads``), so that it skips what no field reads (an elastic member's
check run at rtol/10, which only estimates the error of numerics no preview draws; the forces' crank check).
Each member is computed to the preview's accuracy (family.PREVIEW, endpoints.Preview): where an endpoint's own
tolerance is far tighter than a drawn curve needs, to a small declared fraction of the family's tolerance.

The memo is a least-recently-used store per heavy process, bounded both in members (MEMO_MEMBERS) and in the
bytes their arrays hold (MEMO_BYTES); a member cut short by a bound is not kept (a quieter moment gives it whole).
"""
from __future__ import annotations

import time
from collections import OrderedDict
from dataclasses import replace

import orjson

from ..runtime import heavy
from ..families import family
from .endpoints import BATCHES, compute_answers

MEMO_MEMBERS = 4096
MEMO_BYTES = 64 * 2**20
CHUNK_MEMBERS = 8       # members computed as one batch (endpoints.compute_answers); the deadline is checked between
# chunks. An endpoint without a batch body of its own (endpoints.BATCHES) computes its members one by one anyway:
# its chunks are single members, so that the deadline is checked before each, as a long member (elastic) needs.


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
    size = CHUNK_MEMBERS if endpoint in BATCHES else 1

    def members(values: list[float], deadline: float) -> list[family.Member]:
        bodies = [family.member_body(request, vary, value) for value in values]
        keys = [(endpoint, orjson.dumps(body, option=orjson.OPT_SORT_KEYS), lang, named) for body in bodies]
        known = [MEMO.get(key) for key in keys]
        missing = [k for k, member in enumerate(known) if member is None]
        made: dict[int, family.Member] = {}
        for start in range(0, len(missing), size):
            if time.perf_counter() > deadline or heavy.stopped():     # the budget, or the client gone
                break
            chunk = missing[start:start + size]
            outcomes = compute_answers(endpoint, [bodies[k] for k in chunk], lang, reads, family.PREVIEW)
            for k, outcome in zip(chunk, outcomes):
                made[k] = family.Member.of(values[k], outcome, trie)
                MEMO.put(keys[k], made[k])             # not if a bound cut it short
                counts["computed"] = counts.get("computed", 0) + 1
        found = []
        for k, value in enumerate(values):             # the values in order, up to the first one not computed
            if known[k] is None:
                if k not in made:
                    break
                found.append(made[k])
            else:               # the same body may be another slider's member at another value
                found.append(replace(known[k], value=value))
                counts["reused"] = counts.get("reused", 0) + 1
        return found

    return members
