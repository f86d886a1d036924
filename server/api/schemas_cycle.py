"""The input of the reduced moments over the cycle of a single-cylinder crank-slider machine (/reduction, output
"cycle_moments"): the engine (two- or four-stroke) or the compressor, the links' gravity, the efficiency and the
drawing of the graphical integration (Chaika–Vasylenko §3.2, §3.4 steps 8–10, Fig. 3.7). The field names and
the defaults are the core's (server/core/dynamics/cycle_moments.py)."""
from __future__ import annotations

import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from ..core.dynamics.cycle_moments import MODES, Cylinder, Drawing, Masses
from ..core.dynamics.motors import INDICATOR_POINTS

DRAWING, CYLINDER, MASSES = Drawing(), Cylinder(), Masses()


class DrawingInput(BaseModel):
    """The drawing of Fig. 3.7 (the chord method of graphical integration)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    per_turn: Literal[12, 24] = Field(DRAWING.per_turn, description="intervals per turn (12: 30° positions)")
    pole: float = Field(DRAWING.pole, ge=10, le=200, description="pole distance K, mm (the book: 30 … 60)")
    width: float = Field(DRAWING.width, ge=60, le=600, description="length of the φ axis per turn, mm")
    height: float = Field(DRAWING.height, ge=10, le=300, description="largest ordinate of the moment diagram, mm")
    reading: float = Field(DRAWING.reading, ge=0, le=2, description="precision an ordinate is read to, mm (0: exact)")

    def core(self) -> Drawing:
        return Drawing(**self.model_dump())


class CycleInput(BaseModel):
    """The cylinder's gas, the links' gravity and the efficiency; masses m₂, m₃ are the request's inertias."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    mode: Literal[MODES] = Field(CYLINDER.mode, description=(
        "two_stroke, four_stroke: an engine (M_P from the gas, M_kO constant over the cycle 2π or 4π); "
        "compressor: M_kO from the gas, the motor's M_P constant over 2π"))
    p_max: float = Field(ge=1e3, le=5e7, description="largest gas pressure over the crankcase's, Pa (engine: the "
                                                   "indicator diagram's peak; compressor: discharge over suction)")
    bore: float = Field(ge=1e-3, le=2, description="cylinder bore D, m")
    expansion: list[float] | None = Field(None, min_length=INDICATOR_POINTS, max_length=INDICATOR_POINTS,
                                          description="engine: p/p_max on expansion at x/H = 0, 0.1, …, 1 from "
                                                      "top dead centre (none: the assumed polytrope)")
    compression: list[float] | None = Field(None, min_length=INDICATOR_POINTS, max_length=INDICATOR_POINTS,
                                            description="engine: p/p_max on compression at x/H = 0, 0.1, …, 1")
    suction: float = Field(CYLINDER.suction, gt=0, le=1e7, description="compressor: suction pressure, absolute, Pa")
    clearance: float = Field(CYLINDER.clearance, gt=0, le=1, description="compressor: clearance volume / swept volume")
    exponent: float = Field(CYLINDER.exponent, ge=1, le=1.8, description="compressor: polytropic exponent n")
    m1: float = Field(MASSES.m1, ge=0, le=1e5, description="crank mass, kg")
    crank_centre: float = Field(MASSES.crank_centre, ge=-2, le=2, description="ρ₁ = l_OS₁/l₁ (0: balanced crank)")
    g: float = Field(MASSES.g, ge=0, le=100, description="gravity, m/s²")
    guide_angle: float = Field(MASSES.guide_angle, ge=-math.pi, le=math.pi, description=(
        "inclination α of the guide, rad: g⃗ = g(−sin α, −cos α) with x along the guide away from the crank"))
    efficiency: float = Field(gt=0, le=1, description="engine: mechanical η_m (N_e = η_m N_i); compressor: η_Σ "
                                                      "of the drive from the motor to the crank (N_motor = N_e/η_Σ)")
    drawing: DrawingInput = Field(default_factory=DrawingInput)

    @model_validator(mode="after")
    def diagram(self):
        if not all(0 <= x <= 1 for x in (self.expansion or []) + (self.compression or [])):
            raise ValueError("indicator diagram ordinates are p/p_max, between 0 and 1")
        if self.mode == "compressor" and (self.expansion or self.compression):
            raise ValueError("a compressor's diagram follows from p_max, suction, clearance and exponent")
        return self

    def cylinder(self) -> Cylinder:
        return Cylinder(self.mode, self.p_max, self.bore, tuple(self.expansion) if self.expansion else None,
                        tuple(self.compression) if self.compression else None, self.suction, self.clearance,
                        self.exponent)

    def masses(self, m2: float, m3: float) -> Masses:
        return Masses(self.m1, self.crank_centre, m2, m3, self.g, self.guide_angle)
