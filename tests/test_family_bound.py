"""The family's bound against the endpoints' exact answers on every scene (server/families/family.py): for
every slider of the scene (in each variant that brings it, and one in turn of each variant that brings none:
sliders_checked), at the defaults or with the other sliders at random values (the scene's sliders,
variant after variant, take the two in turn), the family the page
asks for (server/lessons/family_requests.py: its drawn ``fields``, packed) is interpolated by the contract's rule (linear or cubic by interval)
at random values between members, and every drawn quantity is within TOLERANCE of its span of the endpoint's
exact answer there, plus the 5 digits sent (SENT × |value|) and what packing may move a value (PACK_QUANTUM / 2
of the span). Every leaf the preview draws is checked as the page draws it (family_model.js): element by
element where it has the exact answer's shape, and where its grid differs from the exact answer's (the
nearer member's curve where the two members' lengths differ, a start-up whose steps move with the value) on a
common abscissa, the exact curve read at the drawn curve's φ or t (drawn_error). Checked where the family claims the bound: families whose interpolation_error is within the
tolerance (plus packing's), in every interval wider than a slider resolves. A family above it says where in
numerics.message (a jump, a corner, the cap) and claims nothing: there the estimates of single intervals are
not a bound either (on the elastic transmission's speed and the angular acceleration's amplitude, intervals
estimated within the tolerance are off by 1–2 %, linear and cubic alike). Families run in this process with
the time budgets lifted, so nothing depends on the machine's speed.
"""
from __future__ import annotations

import random

import numpy as np
import pytest

from server.api.endpoints import compute_answer
from server.families import family
from server.api.routers.family import WITHOUT_FAMILY
from server.lessons.family_requests import family_request
from server.lessons.requests import slider_values
from server.lessons.scenes import scenes
from test_family import SENT, TOLERANCE
from test_family_engine import unbudgeted_client
from test_family_fields import whole_members

CHECKS = 2              # random values per family


@pytest.fixture
def client():
    """In-process, no time budgets; one per test (a scene's test is a minute of work: no fixture of the module's
    keeps the scenes on one worker of the suite, tests/conftest.py)."""
    with unbudgeted_client() as made:
        yield made


def check(client, body: dict, rng: random.Random) -> int:
    """Compare the interpolated family with the exact answer at CHECKS random values; the values checked."""
    response = client.post("/api/v1/family", json=body)
    assert response.status_code == 200, response.text[:500]
    answer = response.json()
    values, log = answer["values"], body["log"]
    members = whole_members(answer)
    finest = (family.coordinate(values[-1], log) - family.coordinate(values[0], log)) * family.FINEST_FRACTION
    if answer["interpolation_error"] is None or answer["interpolation_error"] > TOLERANCE + family.PACK_QUANTUM / 2:
        return 0                    # no claim: the message says where and why
    intervals = [k for k in range(len(values) - 1) if members[k] is not None and members[k + 1] is not None
                 and family.coordinate(values[k + 1], log) - family.coordinate(values[k], log) > finest * 1.01]
    for k in rng.sample(intervals, min(CHECKS, len(intervals))):
        a, b = family.coordinate(values[k], log), family.coordinate(values[k + 1], log)
        value = family.from_coordinate(a + rng.uniform(0.05, 0.95) * (b - a), log)
        assert_drawn_within(body, answer, members, value, TOLERANCE + family.PACK_QUANTUM / 2)
    return min(CHECKS, len(intervals))


def assert_drawn_within(body: dict, answer: dict, members: list, value: float, allowed: float) -> None:
    """Every leaf the family's preview draws at ``value`` is within ``allowed`` of its span (over the members) of
    the endpoint's exact answer there, as the student sees it (drawn_error)."""
    width = family.spans(members)
    trie = family.field_trie(body["fields"]) if "fields" in body else None
    vary = [family.Vary(v["path"], v["factor"]) for v in body["vary"]]
    payload = compute_answer(body["endpoint"], family.member_body(body["request"], vary, value)).payload
    exact = family.as_tree(payload if trie is None else family.pruned(payload, trie), sent=False)
    preview = family.interpolate_family(answer["values"], members, value, body["log"], answer["orders"])
    for path, leaf in family.checked_leaves(exact):
        guess = family._leaf(preview, path)
        if guess is None:
            continue            # nothing drawn (the nearer member lacks the quantity)
        bound = allowed * width[path]
        off = drawn_error(np.asarray(guess, float), np.asarray(leaf, float), preview, exact, path, bound)
        assert off <= bound, (body["endpoint"], value, family.quantity(path), off / width[path])


def drawn_error(guess: np.ndarray, leaf: np.ndarray, preview, exact, path: tuple, allowed: float) -> float:
    """How far the drawn leaf is from the exact one, beyond the 5 digits sent (SENT × |value|), as the student
    sees it (``allowed``: the bound it is checked against). The same shape: element by element, unless a curve is drawn at other abscissae than the exact
    answer's (a start-up whose steps move with the value: node k is another φ in each), in which case, and
    wherever the shapes differ (the page draws the nearer member's curve on its own grid), the curve is read on
    a common abscissa: at each of the drawn curve's x (every sibling array of its length that increases:
    φ, t), the exact curve read there by linear interpolation on its own grid (its reading error, 1/8 of its
    largest second difference, allowed for), inside the range both cover; and the ends of what is drawn, its
    smallest and largest value, against the exact ones (a start-up that stalls where the exact one runs), but
    for an abscissa itself (φ, t of a start-up, which stops at the whole revolution where its convergence test
    is met): that is compared against the other abscissae where both curves are drawn."""
    direct = None
    if guess.shape == leaf.shape:
        direct = float(np.nanmax(np.abs(guess - leaf) - SENT * np.abs(leaf), initial=0.0))
        if direct <= allowed or guess.ndim != 1:
            return max(direct, 0.0)
    pairs = list(abscissae(family._leaf(preview, path[:-1]), family._leaf(exact, path[:-1]), path[-1],
                           guess.size, leaf.size)) if guess.ndim == 1 else []
    if direct is not None and not pairs:
        return direct
    found = 0.0
    if np.isfinite(guess).any() and np.isfinite(leaf).any() and not (family._increasing(guess)
                                                                      and family._increasing(leaf)):
        found = max(abs(np.nanmin(guess) - np.nanmin(leaf)), abs(np.nanmax(guess) - np.nanmax(leaf))) \
            - SENT * float(np.nanmax(np.abs(leaf)))
    for x_drawn, x_exact in pairs:
        inside = (x_drawn >= x_exact[0]) & (x_drawn <= x_exact[-1]) & np.isfinite(guess)
        reading = np.interp(x_drawn[inside], x_exact, leaf)
        finite = leaf[np.isfinite(leaf)]
        own = float(np.max(np.abs(np.diff(finite, 2)), initial=0.0)) / 8
        off = np.abs(guess[inside] - reading) - SENT * np.abs(reading) - own
        found = max(found, float(np.nanmax(off, initial=0.0)))
    return max(found, 0.0)


def abscissae(drawn, exact, key: str, drawn_size: int, exact_size: int):
    """(x drawn, x exact) of every sibling of ``key`` that is a curve's abscissa in both: an array of the
    leaf's length in each that increases, with no null (family._increasing)."""
    if not (isinstance(drawn, dict) and isinstance(exact, dict)):
        return
    for name, x in drawn.items():
        other = exact.get(name)
        if name == key or not (isinstance(x, np.ndarray) and isinstance(other, np.ndarray)):
            continue
        if x.shape == (drawn_size,) and other.shape == (exact_size,) and family._increasing(x) \
                and family._increasing(other):
            yield x, other


def random_values(variant, rng: random.Random) -> dict:
    """Every slider of the variant at a random value it can take."""
    return {slider.id: rng.choice(slider_values(slider)) for slider in variant.sliders}



def sliders_checked(scene):
    """(variant, the sliders whose families are checked there): every slider of the scene in the first variant
    that has it, and in a variant whose sliders all came before, one of them in turn (each variant is another
    model: its solver and its curves). A slider shared by nine variants of the equation of motion is one family
    computation per variant otherwise: 40 families against 15 on that scene, 193 against 115 on all."""
    seen, chosen = set(), []
    for variant in scene.variants:
        new = [slider for slider in variant.sliders if slider.id not in seen]
        if not new and variant.sliders:
            new = [variant.sliders[len(chosen) % len(variant.sliders)]]
        seen |= {slider.id for slider in variant.sliders}
        chosen.append((variant, new))
    return chosen


@pytest.mark.parametrize("scene_id", [s.id for s in scenes().values() if s.endpoint not in WITHOUT_FAMILY])
def test_every_slider_family_of_the_scene_is_within_the_bound_of_the_exact_answers(client, scene_id):
    scene = scenes()[scene_id]
    rng = random.Random(scene_id)
    checked = 0
    others = []                     # each slider in the setting not taken
    for variant, sliders in sliders_checked(scene):
        settings = (None, random_values(variant, rng))     # the scene's sliders take the two in turn
        for slider in sliders:
            taken = len(others) % 2
            checked += check(client, family_request(scene, variant, slider, settings[taken]), rng)
            others.append(family_request(scene, variant, slider, settings[1 - taken]))
    for body in others:             # none of those claimed: the other setting, until one does
        if checked:
            break
        checked += check(client, body, rng)
    assert checked > 0              # every scene has families within the tolerance
