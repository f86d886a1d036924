"""Request model of /friction-influence: the crank-slider machine of /forces with one f in every pair, swept
(Chaika–Vasylenko §3.4, steps 18–19, and §4)."""
from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from .schemas import MAX_PARAMS
from .schemas_forces import ForceLoadsInput, WearPartsInput

OUTPUTS = ("sweep", "cycle")


class RadiiInput(BaseModel):
    """The journal radii of the revolute pairs (the friction circles are ρ = f·r)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    r14: float = Field(0.02, gt=0, le=1, description="journal radius at O (main bearing), m")
    r12: float = Field(0.015, gt=0, le=1, description="journal radius at A (crank pin), m")
    r23: float = Field(0.01, gt=0, le=1, description="journal radius at B (piston pin), m")


class FrictionInfluenceRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    mechanism: Literal["slider_crank"] = Field("slider_crank", description="the crank-slider of /forces")
    outputs: list[Literal[OUTPUTS]] = Field(list(OUTPUTS), min_length=1, max_length=2, description=(
        "sweep: each figure over f = 0 … f_max; cycle: the curves at f = 0 and at f overlaid, and the comparison"))
    params: dict[str, float] = Field(default_factory=dict, max_length=MAX_PARAMS,
                                     description="crank-slider lengths l1, l2, e (m) and a2")
    loads: ForceLoadsInput = Field(default_factory=ForceLoadsInput, description=(
        "masses, J1 (the crank's own inertia, group I), the mean speed omega and the slider's load; a working "
        "machine in steady motion: no gas force, epsilon 0"))
    pairs: RadiiInput = Field(default_factory=RadiiInput)
    f: float = Field(0.1, ge=0, le=2, description="the friction coefficient shown against f = 0, in every pair")
    f_max: float = Field(0.3, gt=0, le=2, description="the sweep's largest f")
    count: int = Field(13, ge=3, le=41, description="the sweep's number of f values, 0 … f_max")
    delta: float = Field(0.0125, ge=1e-3, le=0.5, description="[δ]: the coefficient of speed fluctuation allowed")
    flywheel: float = Field(0.0, ge=0, le=1e4,
                            description="a flywheel already on the crank, kg·m² (0: the machine as it is)")
    wear: WearPartsInput | None = Field(default_factory=WearPartsInput, description="the wear's parts; null: no wear")
    n: int = Field(181, ge=13, le=1441,
                   description="points over one closed cycle, an odd number (the error estimate halves the grid)")
    tolerance: float = Field(1e-9, ge=1e-14, le=1e-2, description="ε_R of the friction equilibrium (as /forces)")

    @field_validator("n")
    @classmethod
    def odd(cls, value: int) -> int:
        if value % 2 == 0:
            raise ValueError("an odd number of points: the error estimate takes every other one")
        return value

    @field_validator("loads")
    @classmethod
    def steady_working_machine(cls, loads: ForceLoadsInput) -> ForceLoadsInput:
        if loads.gas is not None:
            raise ValueError("gas: the explorer takes a working machine (the load on the slider), not an engine")
        if loads.epsilon != 0:
            raise ValueError("epsilon: the machine runs steadily about its mean speed (epsilon 0)")
        return loads

    @model_validator(mode="after")
    def inertia(self):
        if self.loads.J1 <= 0 and self.flywheel <= 0:
            raise ValueError("loads.J1: the crank needs some inertia for the equation of motion (or give a flywheel)")
        return self
