"""The small arithmetic language of combination questions (server/lessons/expression.py): the same value as
Python's own arithmetic on the same text (the reference: the expressions generated here hold only numbers,
names bound to numbers, + − × ÷ and parentheses), and refusals in words for everything else."""
from __future__ import annotations

import math

import pytest
from hypothesis import given, settings, strategies as st

from server.lessons.expression import MAX_DEPTH, ExpressionError, evaluate, names_in, parse

VALUES = {"a": 2.5, "b": -4.0, "du_max": 0.13, "du_min": -0.07}

leaf = st.one_of(st.sampled_from(sorted(VALUES)), st.integers(1, 99).map(str),
                 st.floats(0.01, 100, allow_nan=False).map(lambda x: f"{x:.3f}"))
expressions = st.recursive(leaf, lambda inner: st.one_of(
    st.tuples(inner, st.sampled_from(["+", "-", "*", "/"]), inner).map(lambda t: f"{t[0]} {t[1]} {t[2]}"),
    inner.map(lambda e: f"({e})"), inner.map(lambda e: f"-{e}")), max_leaves=8)


@settings(max_examples=300, deadline=None)
@given(expressions)
def test_the_value_is_pythons_arithmetic_on_the_same_text(text):
    try:
        reference = eval(text, {"__builtins__": {}}, dict(VALUES))     # noqa: S307 (the reference, in a test)
    except ZeroDivisionError:
        with pytest.raises(ExpressionError):
            evaluate(parse(text, set(VALUES)), VALUES)
        return
    tree = parse(text, set(VALUES))
    if not math.isfinite(reference):
        with pytest.raises(ExpressionError):
            evaluate(tree, VALUES)
        return
    assert evaluate(tree, VALUES) == pytest.approx(reference, rel=1e-12, abs=1e-300)


def test_precedence_signs_and_the_typographic_operators():
    assert evaluate(parse("1 + 2 × 3", set()), {}) == 7
    assert evaluate(parse("(1 + 2) * 3", set()), {}) == 9
    assert evaluate(parse("8 ÷ 2 ÷ 2", set()), {}) == 2
    assert evaluate(parse("2 − −3", set()), {}) == 5
    assert evaluate(parse("du_max / du_min", set(VALUES)), VALUES) == pytest.approx(0.13 / -0.07)
    assert names_in(parse("(a - b) / a", set(VALUES))) == {"a", "b"}


@pytest.mark.parametrize("text, reason", [
    ("", "empty"), ("a +", "ends too early"), ("(a", "not closed"), ("a b", "unexpected 'b'"),
    ("a ** 2", "unexpected '*'"), ("c", "'c' is not a readout"), ("a.real", "cannot read"),
    ("__import__('os').system('x')", "cannot read"), ("a; b", "cannot read"),
    ("-" * (MAX_DEPTH + 2) + "a", "deeper"), ("(" * (MAX_DEPTH + 2) + "a" + ")" * (MAX_DEPTH + 2), "deeper"),
    ("a + " * 60 + "a", "longer than 200"),
])
def test_what_is_not_arithmetic_over_the_readouts_is_refused_in_words(text, reason):
    with pytest.raises(ExpressionError, match=reason):
        parse(text, set(VALUES))


def test_a_division_by_zero_or_an_overflow_has_no_value():
    with pytest.raises(ExpressionError, match="division by zero"):
        evaluate(parse("a / (b + 4)", set(VALUES)), VALUES)
    with pytest.raises(ExpressionError, match="not a finite number"):
        evaluate(parse("1e200 * 1e200", set()), {})
