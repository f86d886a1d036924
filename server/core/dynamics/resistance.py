"""Reduced moment of the resisting forces M_c(φ, ω) of a named mechanism: its kinematics, the stroke factor, the
builder of its kind (resisting_forces.py: the load, the answer and each mechanism's moment, Eremyants chapter 3)
and the viscous friction's sliding analogs."""
from __future__ import annotations

import numpy as np

from ..mechanisms import MECHANISMS
# the load, the answer and the cycle mean, read from here by the machine, the reports and the tests
from .resisting_forces import CONVENTIONS, Load, ResistingMoment, mean_over_cycle, stroke_factor  # noqa: F401


def resisting_moment(mechanism: str, params: dict[str, float], load: Load, phi: np.ndarray,
                     omega: np.ndarray | float = 0.0, kinematics=None) -> ResistingMoment:
    """M_c(φ, ω) reduced to the crank shaft, Eremyants (3.5)–(3.53) by mechanism (module docstring);
    ω (rad/s) enters only through viscous friction
    (``kinematics``: the mechanism already evaluated at phi, to share one evaluation)."""
    kinematics = kinematics or MECHANISMS[mechanism].evaluate(params, phi, set())
    values = kinematics.values
    u31 = values["u31"]
    k = stroke_factor(u31, load.return_factor)
    result = MECHANISMS[mechanism].resisting(params, load, phi, values, k)     # the builder below of its kind
    result.notices = kinematics.warnings + result.notices     # singular positions of the linkage itself
    sliding = MECHANISMS[mechanism].sliding_squares(params, kinematics)     # finite at removable singularities
    result.viscous = load.beta * np.asarray(omega) * sliding
    result.useful = result.useful + load.crank_moment
    result.switches = [u31] + result.switches           # the stroke factor k and |u₃₁|
    return result
