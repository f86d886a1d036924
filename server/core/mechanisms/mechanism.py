"""Abstract mechanism: the shared part of the interface and output selection."""
from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np

from .base import (COMMON_OUTPUTS, TWO_PI, Evaluation, GeometryError, OutputSpec, ParamSpec,
                   SpecialPosition)


class Mechanism(ABC):
    """A planar linkage driven by crank 1 through the generalised coordinate φ (rad).

    Subclasses give ``name``, ``title``, ``params``, ``conventions`` and implement
    :meth:`check`, :meth:`positions` and :meth:`special_positions`.
    """

    name: str
    title: str
    conventions: str
    params: tuple[ParamSpec, ...]
    extra_outputs: tuple[OutputSpec, ...] = ()
    sliding_pairs: tuple[str, ...] = ()     # transfer functions of the prismatic pairs' sliding speeds
    link2_rotation: str | None = "u21"      # the transfer function link 2 turns with (None: it translates)
    link3_translates: bool = False          # link 3 slides (mass m₃) rather than turns (J₃)
    piston: bool = False                    # a piston on link 3: an indicator diagram can drive it

    @property
    def outputs(self) -> tuple[OutputSpec, ...]:
        return COMMON_OUTPUTS + self.extra_outputs

    def defaults(self) -> dict[str, float]:
        return {p.name: p.default for p in self.params}

    def check(self, params: dict[str, float]) -> dict[str, float]:
        """Fill defaults, check ranges; return the complete parameter set or raise GeometryError."""
        full = self.defaults() | {k: float(v) for k, v in params.items()}
        for spec in self.params:
            value = full[spec.name]
            if not np.isfinite(value):
                raise GeometryError(spec.name, "must be a finite number", "not_finite")
            if spec.integer and value != round(value):
                raise GeometryError(spec.name, "must be a whole number", "not_integer")
            if spec.unit == "m" and value < 0 and spec.minimum >= 0:
                raise GeometryError(spec.name, "a length cannot be negative", "negative_length")
            if not spec.minimum <= value <= spec.maximum:
                raise GeometryError(spec.name, f"must lie between {spec.minimum:g} and {spec.maximum:g} {spec.unit}",
                                    "out_of_range", minimum=spec.minimum, maximum=spec.maximum)
        unknown = set(full) - {p.name for p in self.params}
        if unknown:
            raise GeometryError(sorted(unknown)[0], f"not a parameter of the {self.name} mechanism",
                                "unknown_param")
        self.check_geometry(full)
        return full

    @abstractmethod
    def check_geometry(self, p: dict[str, float]) -> None:
        """Raise GeometryError when the linkage cannot be assembled or the crank cannot turn fully."""

    def cycle(self, p: dict[str, float]) -> float:
        """Length of one kinematic cycle in φ (rad): 2π unless the mechanism says otherwise."""
        return TWO_PI

    def jumps(self, p: dict[str, float]) -> list[float]:
        """Crank angles (rad) where the transfer functions jump (a stroke limiter); none by default."""
        return []

    @abstractmethod
    def evaluate(self, p: dict[str, float], phi: np.ndarray, wanted: set[str]) -> Evaluation:
        """Compute the wanted outputs at crank angles ``phi`` (rad). The parameters may also be arrays of
        shape (M, 1): M linkages of one ``branch`` at once, every output that depends on them then of shape
        (M, N) (points (M, N, 2)); what is not elementwise over φ (reductions, warnings) is left to
        ``per_linkage``."""

    def branch(self, p: dict) -> tuple:
        """What selects evaluate's formulas by a scalar test of the parameters; linkages evaluated at once
        share it (None in a place: they do not). None by default: the formulas are the same for all."""
        return ()

    def per_linkage(self, p: dict[str, float], ev: Evaluation, wanted: set[str]) -> None:
        """Add to ``ev`` (one linkage's evaluation) what is not elementwise over φ; nothing by default.
        evaluate calls it for a single linkage; a caller that evaluated several at once calls it for each."""

    def sliding_squares(self, p: dict[str, float], ev: Evaluation) -> np.ndarray:
        """S(φ) = Σ u² over the prismatic pairs, so that viscous friction gives M_T = β ω S(φ)
        (Eremyants (3.15)–(3.17), (3.33), (3.50*)); ``ev``: the mechanism evaluated at ev.phi."""
        return sum((ev.values[name] ** 2 for name in self.sliding_pairs), np.zeros_like(ev.phi, dtype=float))

    def textbook_inertia(self, p: dict[str, float], constant: float, inertias, phi: np.ndarray) -> np.ndarray | None:
        """The textbook's closed form of J(φ) where it gives one (``constant`` = J₁ + J_rotor i²); None here."""
        return None

    def friction_steps(self, p: dict[str, float], phi: float, force: float, f: float, tolerance: float,
                       max_steps: int) -> tuple[float, list[dict], dict]:
        """The textbook's successive approximations of the friction forces at φ: the series' ratio, the rows,
        the limit in closed form (dynamics/friction_iteration.py); only where the textbook iterates."""
        raise ValueError(f"the textbook iterates friction forces only for the sine mechanism and the "
                         f"crank-slider, not for {self.name}")

    def elastic_angles(self, values: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """θ₁₂ = crank − rod angle and θ₂₃ = rod − rocker angle (CCW) with their derivatives in φ, for the
        elastic linkage (elastic/stiffness.py); ``values``: the evaluation with "phi"."""
        raise ValueError(f"no elastic linkage model for {self.name}")

    def reduction_errata(self, p: dict[str, float], m3: float, omega: float) -> list[dict]:
        """The misprints of the textbook's reduction formulas for this mechanism (errata.py); none here."""
        return []

    def proximity_warnings(self, p: dict[str, float]) -> list:
        """Sentences for configurations close to a singular one (large but finite transfer functions)."""
        return []

    def piston_travel(self, p: dict[str, float], phi: np.ndarray, ev: Evaluation | None = None) -> np.ndarray:
        """x/H: a piston's travel from top dead centre over its stroke (``piston`` mechanisms only; ``ev``: the
        mechanism already evaluated at phi)."""
        raise ValueError(f"the {self.name} mechanism has no piston")

    def resisting(self, p: dict[str, float], load, phi: np.ndarray, values: dict, k: np.ndarray):
        """M_c of the useful load and dry friction of this mechanism (dynamics/resistance.py builds it:
        Eremyants ch. 3 for each mechanism); ``values`` its evaluation at phi, k the stroke factor."""
        raise ValueError(f"no resisting-moment model for the {self.name} mechanism")

    def harmonic_claim(self, p: dict[str, float], spectrum: dict) -> dict | None:
        """The book's claim about the spectrum of u′₃₁, where it makes one (kinematics.py); none here."""
        return None

    @abstractmethod
    def special_positions(self, p: dict[str, float]) -> list[SpecialPosition]:
        """Dead centres, rocker extremes and similar positions within one cycle."""

    def special_positions_many(self, linkages: list[dict]) -> list[list[SpecialPosition]]:
        """special_positions of several linkages of one ``branch``; one by one unless a mechanism does better."""
        return [self.special_positions(p) for p in linkages]

    def describe(self, p: dict[str, float]) -> dict:
        """Words about the configuration (class, type of motion) for the scene header."""
        return {}
