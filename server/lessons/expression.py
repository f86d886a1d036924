"""A quantity computed from named readouts, e.g. ``du_max / du_min`` or ``(u_max - u_min) / 2``.

A small arithmetic language, parsed by recursive descent and never by ``eval``: numbers, names of readouts,
``+ - * /`` (also ``× ÷ −``), unary signs and parentheses. Its size and nesting are bounded, so a question
spec sent by anyone cannot make the parser recurse deeply or run long.

    expression := term (("+" | "-") term)*
    term       := factor (("*" | "/") factor)*
    factor     := ("+" | "-") factor | number | name | "(" expression ")"
"""
from __future__ import annotations

import math
import re

MAX_LENGTH = 200
MAX_DEPTH = 12          # nested parentheses and signs
TOKEN = re.compile(r"\s*(?:(?P<number>\d+(?:\.\d*)?(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)"
                   r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)|(?P<operator>[-+*/()]))")
SYNONYMS = str.maketrans({"×": "*", "·": "*", "÷": "/", "−": "-"})


class ExpressionError(ValueError):
    """An expression that cannot be read or has no value; the reason in words."""


def _tokens(text: str) -> list[tuple[str, str]]:
    text = text.translate(SYNONYMS)
    found, at = [], 0
    while at < len(text):
        if text[at:].strip() == "":
            break
        match = TOKEN.match(text, at)
        if match is None:
            raise ExpressionError(f"cannot read '{text[at:].strip()[:10]}' (only numbers, names, + − × ÷ and "
                                  f"parentheses)")
        kind = match.lastgroup
        found.append((kind, match.group(kind)))
        at = match.end()
    return found


def parse(text: str, names: set[str]) -> tuple:
    """The expression as a tree of tuples: ("number", x), ("name", n), ("neg", a), (op, a, b).
    Every name must be one of `names`."""
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"longer than {MAX_LENGTH} characters")
    tokens = _tokens(text)
    if not tokens:
        raise ExpressionError("empty")
    at = 0

    def peek() -> tuple[str, str] | None:
        return tokens[at] if at < len(tokens) else None

    def take() -> tuple[str, str]:
        nonlocal at
        if at >= len(tokens):
            raise ExpressionError("ends too early")
        at += 1
        return tokens[at - 1]

    def expression(depth: int) -> tuple:
        tree = term(depth)
        while peek() in (("operator", "+"), ("operator", "-")):
            tree = (take()[1], tree, term(depth))
        return tree

    def term(depth: int) -> tuple:
        tree = factor(depth)
        while peek() in (("operator", "*"), ("operator", "/")):
            tree = (take()[1], tree, factor(depth))
        return tree

    def factor(depth: int) -> tuple:
        if depth > MAX_DEPTH:
            raise ExpressionError(f"nested deeper than {MAX_DEPTH}")
        kind, value = take()
        if (kind, value) == ("operator", "-"):
            return ("neg", factor(depth + 1))
        if (kind, value) == ("operator", "+"):
            return factor(depth + 1)
        if (kind, value) == ("operator", "("):
            tree = expression(depth + 1)
            if peek() != ("operator", ")"):
                raise ExpressionError("a parenthesis is not closed")
            take()
            return tree
        if kind == "number":
            return ("number", float(value))
        if kind == "name":
            if value not in names:
                raise ExpressionError(f"'{value}' is not a readout of this question (one of {sorted(names)})")
            return ("name", value)
        raise ExpressionError(f"unexpected '{value}'")

    tree = expression(0)
    if at != len(tokens):
        raise ExpressionError(f"unexpected '{tokens[at][1]}'")
    return tree


def names_in(tree: tuple) -> set[str]:
    if tree[0] == "name":
        return {tree[1]}
    return set().union(*(names_in(part) for part in tree[1:] if isinstance(part, tuple)))


def evaluate(tree: tuple, values: dict[str, float]) -> float:
    """The value of a parsed expression; ExpressionError on a division by zero or a non-finite result."""
    kind = tree[0]
    if kind == "number":
        return tree[1]
    if kind == "name":
        return values[tree[1]]
    if kind == "neg":
        return -evaluate(tree[1], values)
    a, b = evaluate(tree[1], values), evaluate(tree[2], values)
    if kind == "/" and b == 0:
        raise ExpressionError("division by zero")
    result = a + b if kind == "+" else a - b if kind == "-" else a * b if kind == "*" else a / b
    if not math.isfinite(result):
        raise ExpressionError("the result is not a finite number")
    return result
