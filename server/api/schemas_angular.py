"""Request and response models of /angular-acceleration: the coupler's angular acceleration (Kuleshova–Tokhtar (1)–(4)), every input
with its unit; signs in the one convention of server/core/angular_acceleration.py."""
from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, model_validator

from .schemas import NumericsModel

# The slowest crank allowed (ω₀ = 10⁻³ rad/s) turns once in 6283 s; within ±10⁴ s the fastest law allowed
# (ω₀ = 10³ rad/s, ε₀ = 10³ rad/s²) reaches φ = 5·10¹⁰ rad, where float64 still resolves 10⁻⁵ rad, so sin φ
# keeps its digits. Beyond, φ loses them, and the accelerating law's t² overflows to inf (null answers).
T_MAX_S = 1e4


class AngularRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    outputs: list[Literal["angular"]] = Field(["angular"], max_length=1, description="the components and the points")
    mechanism: Literal["crank_slider", "trammel"] = Field("crank_slider", description="central crank-slider or "
                                                                                       "elliptic trammel")
    lam: float = Field(0.5, ge=0.01, lt=1, description="λ = OA/AB (the paper's; the textbook's l₂/l₁ is 1/λ); "
                                                    "from 0.01: a rod 100 cranks long is a straight-line guide")
    length: float = Field(1.0, ge=1e-3, le=10, description="crank OA, m (from 1 mm: a subnormal length "
                                                           "overflowed 1/AP)")
    law: Literal["constant", "accelerating", "harmonic"] = Field("constant", description="crank law")
    omega0: float = Field(np.pi / 6, ge=1e-3, le=1e3, description="crank speed ω₀ at t = 0, rad/s")
    epsilon0: float = Field(0.0, ge=-1e3, le=1e3, description="accelerating law: ε₀, rad/s²")
    amplitude: float = Field(0.0, ge=0, lt=1, description="harmonic law: ω = ω₀(1 + a sin νt), a")
    frequency: float = Field(1.0, gt=0, le=1e3, description="harmonic law: ν, rad/s")
    t: list[Annotated[float, Field(ge=-T_MAX_S, le=T_MAX_S)]] | None = Field(
        None, max_length=10001, description=f"times, s, within ±{T_MAX_S:g} s (default: one crank turn)")
    n: int = Field(361, ge=3, le=10001, description="samples over one turn when t is not given")

    @model_validator(mode="after")
    def forward(self):
        if self.law == "accelerating" and self.epsilon0 < 0:
            raise ValueError("a decelerating crank stops before a full turn: give ε₀ ≥ 0")
        return self


class AngularResponse(BaseModel):
    t: list[float] = Field(description="times, s")
    phi: list[float] = Field(description="crank angle from the slider's line, φ = 0 with the crank pointing away "
                                         "from the slider, in the sense the crank turns, rad")
    omega: list[float] = Field(description="crank speed ω, rad/s")
    epsilon_crank: list[float] = Field(description="crank acceleration ε_OA, rad/s²")
    psi: list[float] | None = Field(None, description="crank-slider: rod angle ψ, in the crank's sense, rad")
    omega_coupler: list[float] = Field(description="coupler speed ω_AB (ω_BD), positive in the crank's sense, rad/s")
    inv_AP: list[float] = Field(description="1/AP, AP signed from A towards O, m⁻¹ (0 where P is at infinity)")
    epsilon_star: list[float] = Field(description="ε* = a_A^τ/AP, rad/s²")
    epsilon_star2: list[float] = Field(description="ε** = V_A·d(1/AP)/dt, rad/s²")
    epsilon: list[float] = Field(description="ε_AB = ε* + ε**, rad/s²")
    psi_dd: list[float] = Field(description="the coupler's angular acceleration by the independent route, rad/s²")
    points: dict[str, list[list[float | None]]] = Field(description="O, A, B (and D), P, m; P null at infinity")
    numerics: NumericsModel
    warnings: list[str]
