"""A group's change point as the composition uses it: where (the crank angle), how wide its neighbourhood of
undefined analogs is, and the assembly's sign on either side (change_points.py finds them and says why)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

EQUALITY = 1e-9
SECOND_ANALOG_ERROR = 1e-6
SINGULAR_SIN = (np.finfo(float).eps / SECOND_ANALOG_ERROR) ** (1 / 3)
GRID = 721
STEPS = 60
MAX_HALF_WIDTH = np.radians(1.0)
TURN = 2 * np.pi


@dataclass(frozen=True)
class ChangePoint:
    """Group ``group`` flattens at the crank angle ``phi`` ∈ [0, 2π) while assembling on both sides; its analogs
    are undefined for |φ − phi| < ``half_width`` (|sin| < SINGULAR_SIN); ``edge`` says which: "stretched"
    (RRR, |BD| = BC + CD), "folded" (RRR, |BD| = |BC − CD|), "rod" (RRP), "slot" (RPR)."""

    group: int
    phi: float
    half_width: float
    edge: str


def offset(phi: np.ndarray, at: float) -> np.ndarray:
    """φ − at, wrapped to [−π, π)."""
    return np.mod(np.asarray(phi, float) - at + np.pi, TURN) - np.pi


def signs(points: tuple[ChangePoint, ...], k: int, phi: np.ndarray):
    """The factor of group k's branch σ along the motion: (−1)^(change points of group k passed since φ = 0),
    counting a change point at 0 once a turn (passed at 2π, not at the start); 1 without change points."""
    own = np.array([cp.phi for cp in points if cp.group == k])
    if own.size == 0:
        return 1.0
    phi = np.asarray(phi, float)
    turns = np.floor(phi / TURN)
    rest = phi - turns * TURN
    passed = turns * own.size + np.sum((own[:, None] > 0) & (own[:, None] < rest[None, :]), axis=0) \
        if phi.ndim == 1 else turns * own.size + np.sum((own > 0) & (own < rest))
    return np.where(np.mod(passed, 2) == 0, 1.0, -1.0)


def near(points: tuple[ChangePoint, ...], k: int, phi: np.ndarray) -> np.ndarray | None:
    """Where group k is within a change point's neighbourhood (None: it has none)."""
    own = [cp for cp in points if cp.group == k]
    if not own:
        return None
    return np.any([np.abs(offset(phi, cp.phi)) < cp.half_width for cp in own], axis=0)


def per_turn(points: tuple[ChangePoint, ...], k: int) -> int:
    """How many change points group k passes a turn (odd: it comes back to its start after two turns only)."""
    return sum(cp.group == k for cp in points)
