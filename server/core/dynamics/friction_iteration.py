"""The textbook's successive approximations of the friction forces, step by step (Eremyants §3.1, §3.2).

Sine mechanism, yoke 3 (Fig. 3.1): (R₂₃)₀ = P_c; then F_T2 = f R₂₃ (block in the slot),
R₀₃ = F_T2, F_T3 = f R₀₃ (yoke in its guide), R₂₃ = P_c + F_T3, so
(R₂₃)_n = P_c Σ_{i=0}^{n} f^{2i} → P_c/(1 − f²); the ratio of the series is f².
Crank-slider, group 2–3 (Fig. 3.3): (R₀₃)₀ = P_c tan ψ; F_T = f R₀₃;
R₀₃ = (P_c + F_T) tan ψ, so (F_T)_k = P_c Σ_{i=1}^{k} (f tan ψ)^i (3.24) → P_c f tan ψ/(1 − f tan ψ);
the ratio is f|tan ψ|.  A ratio ≥ 1 means the series diverges: self-locking.

The ratio test decides, not the number of steps: the series converges exactly when its ratio is below 1,
and its limit is the closed form above.  The steps are the table the page shows; they run until the
relative change is below ``tolerance`` or ``max_steps`` rows stand (a display bound: with ratio q the
series needs about log(tolerance)/log(q) terms, ``needed``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..mechanisms import MECHANISMS
from ..mechanisms.base import DIVERGED  # noqa: F401  (friction_iteration.DIVERGED)



@dataclass
class IterationLog:
    """Each approximation's forces (N), the relative change, and whether the series converges."""

    ratio: float
    steps: list[dict] = field(default_factory=list)
    converged: bool = False          # the series converges: ratio < 1
    limit: dict = field(default_factory=dict)
    needed: int | None = None        # terms the series needs for the tolerance (None when it diverges)
    truncated: bool = False          # the table stops before the tolerance is reached


def friction_iteration(mechanism: str, params: dict[str, float], phi: float, force: float, f: float,
                       tolerance: float = 1e-6, max_steps: int = 200) -> IterationLog:
    """The approximations at crank angle φ (rad), their ratio, and the limit in closed form where it exists."""
    ratio, steps, limit = MECHANISMS[mechanism].friction_steps(params, phi, force, f, tolerance, max_steps)
    log = IterationLog(ratio, steps, limit=limit)
    last = log.steps[-1]["change"]
    log.converged = bool(ratio < 1)
    if log.converged:
        log.needed = 1 if ratio == 0 else max(1, int(np.ceil(np.log(tolerance) / np.log(ratio))))
    log.truncated = log.converged and not (last is not None and last < tolerance)
    return log
