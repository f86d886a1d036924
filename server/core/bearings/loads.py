"""The load of a bearing over the cycle, from the kinetostatics of the same crank-slider.

A pair's bearing carries the pair's reaction (Chaika–Vasylenko §3.1): the main bearing O the reaction R₄₁
of the frame on the crank, the crank pin A the reaction R₁₂, the piston pin B the reaction R₂₃.  The journal
turns in its bush at the pairs' relative angular velocity: |ω₁| at O, |ω₂ − ω₁| at A, |ω₂| at B (ω₂ the rod's).
Chaika–Vasylenko's F_e of (2.1)–(2.5) is one load; for a load that varies over the cycle the strength
criterion (2.3) takes its peak, the heat criteria (2.9), (2.12), (2.13) the mean over the cycle of the heat,
p(φ)·V(φ) (the cycle runs at constant ω₁, so the mean over φ is the mean over time).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinetostatics.crank_slider import ForceAnalysis


@dataclass(frozen=True)
class PairLoad:
    """|R|(φ) in N and the relative angular speed ω_rel(φ) in rad/s over the cycle φ (rad)."""

    pair: str
    phi: np.ndarray
    force: np.ndarray
    omega: np.ndarray

    @property
    def peak(self) -> float:
        """The largest |R| over the cycle, N."""
        return float(self.force.max())

    @property
    def mean(self) -> float:
        """The mean of |R| over the cycle (trapezoidal rule on the closed cycle)."""
        return float(np.trapezoid(self.force, self.phi) / (self.phi[-1] - self.phi[0]))

    def cycle_mean(self, values: np.ndarray) -> float:
        """(1/Φ)∫ values dφ over the analysed cycle (trapezoidal rule)."""
        return float(np.trapezoid(values, self.phi) / (self.phi[-1] - self.phi[0]))


def pair_load(analysis: ForceAnalysis, pair: str, omega1: float) -> PairLoad:
    """The reaction magnitude and the relative angular speed of pair O, A or B over the analysed cycle; ω₁ is
    the crank speed the analysis ran at (it turns clockwise: the rod's counter-clockwise ω₂ = −u₂₁ω₁)."""
    omega2 = analysis.applied["omega2"]
    reaction = {"O": analysis.R41, "A": analysis.final.R12, "B": analysis.final.R23}[pair]
    relative = {"O": np.full_like(omega2, abs(omega1)), "A": np.abs(omega2 + omega1), "B": np.abs(omega2)}[pair]
    return PairLoad(pair, analysis.phi, np.linalg.norm(reaction, axis=1), relative)
