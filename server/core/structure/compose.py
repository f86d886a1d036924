"""The composition of a linkage at the crank angles with its change points found first (change_points.find):
``compose``; the composition itself (groups attached in order, change points' neighbourhoods) is composition.py."""
from __future__ import annotations

import numpy as np

from . import change_points
from .composition import Composition, compose_with
from .spec import Linkage


def compose(linkage: Linkage, phi: np.ndarray, at_change_points: str = "limit") -> Composition:
    """Positions and analogs of every joint, link, guide and slide at ``phi`` (rad), in order of attachment;
    near a group's change points the analogs are NaN (``at_change_points="null"``) or the continuing motion's
    limit (``"limit"``)."""
    return compose_with(linkage, phi, change_points.find(linkage), at_change_points)
