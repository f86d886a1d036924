"""Request model of /bearings: the plain-bearing designer (Chaika–Vasylenko §2) on a pair of the crank-slider
whose kinetostatics (the /forces request's params, loads and pairs) gives the bearing's load."""
from __future__ import annotations

import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationInfo, field_validator

from ..core.bearings.report import OUTPUTS
from ..core.bearings.tables import TABLES
from ..core.bearings.dry import KCAL_PER_HOUR
from .schemas import MAX_PARAMS
from .schemas_forces import ForceLoadsInput, PairsInput


class BearingInput(BaseModel):
    """The bearing of one pair: its kind, material, geometry, lubricant and heat removal."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    pair: Literal["O", "A", "B"] = Field("O", description="main bearing O (R₄₁), crank pin A (R₁₂), piston pin B (R₂₃)")
    kind: Literal["dry", "semi_fluid", "fluid"] = Field("dry", description="dry (Table 2.1), semi-fluid or fluid (Table 2.2)")
    material: str = Field("bronze_brof", max_length=40, description="a row of Table 2.1 (dry) or 2.2 (semi-fluid, fluid)")
    diameter: float = Field(0.04, ge=1e-3, le=1.0, description="journal diameter d, m")
    length_ratio: float = Field(1.0, ge=0.2, le=4.0, description="relative length l̄_z = l_z/d")
    clearance_ratio: float = Field(0.001, ge=1e-5, le=0.01, description="radial clearance h₀/d")
    friction: float | None = Field(None, ge=0.0, le=1.0, description="dry: f instead of Table 2.1's (the high end)")
    viscosity: float = Field(0.02, ge=1e-4, le=10.0, description="lubricant's dynamic viscosity μ, Pa·s")
    density: float = Field(880.0, ge=100.0, le=3000.0, description="lubricant's density, kg/m³ (ν = μ/ρ)")
    wrap: float = Field(2 * math.pi, gt=0.0, le=2 * math.pi + 1e-9, description="wrap angle α of the film, rad")
    ambient: float = Field(20.0, ge=-60.0, le=200.0, description="ambient temperature T_B, °C")
    transfer: float = Field(11 * KCAL_PER_HOUR, ge=1.0, le=1000.0, description="heat-transfer coefficient k′, W/(m²·K) (the book's 8…14 kcal/(m²·h·°C) = 9.3…16.3)")
    heat_path: Literal["bushing", "shaft"] = Field("bushing", description="heat removed through the bushing (2.12) or the shaft (2.13)")
    housing_area: float = Field(20.0, ge=1.0, le=500.0, description="(2.12): A_k over the bearing's own surface π·d·l_z")
    shaft_length: float = Field(3.5, ge=3.0, le=4.0, description="(2.13): shaft length on each side, in d")
    hours: float = Field(8.0, gt=0.0, le=24.0, description="(2.13): working time in a shift t_z, h")

    @field_validator("material")
    @classmethod
    def in_table(cls, value: str, info: ValidationInfo) -> str:
        kind = info.data.get("kind", "dry")
        if value not in TABLES[kind]:
            table = "2.1" if kind == "dry" else "2.2"
            raise ValueError(f"not a material of Table {table} for a {kind} bearing: one of {', '.join(TABLES[kind])}")
        return value


class BearingsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    mechanism: Literal["slider_crank"] = Field("slider_crank", description="the crank-slider whose reactions load the bearing")
    outputs: list[Literal[OUTPUTS]] = Field(["checks"], min_length=1, max_length=len(OUTPUTS), description="what the scene shows")
    params: dict[str, float] = Field(default_factory=dict, max_length=MAX_PARAMS, description="crank-slider lengths l1, l2, e (m) and a2")
    loads: ForceLoadsInput = Field(default_factory=ForceLoadsInput)
    pairs: PairsInput = Field(default_factory=PairsInput)
    n: int = Field(181, ge=13, le=1441, description="points over one closed cycle")
    tolerance: float = Field(1e-9, ge=1e-14, le=1e-2, description="ε_R of the friction equilibrium (as /forces)")
    bearing: BearingInput = Field(default_factory=BearingInput)
