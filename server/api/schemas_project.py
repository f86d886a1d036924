"""Request model of POST /api/v1/course-project: the whole course project of a linkage in steady motion
(docs/course_project.md)."""
from __future__ import annotations

import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationInfo, field_validator

from .schemas import LinkageModel
from .schemas_dynamics import MassInput, PairFrictionField, PairFrictionMap


class GroupOneInput(BaseModel):
    """Group I on the crank's shaft (its inertia is constant): the crank with its shaft and gears, the motor's rotor
    through the transmission; the flywheel is added to it."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    J1: float = Field(0.0, ge=0, le=1e4, description="the crank with its shaft and gears about the crank's axis, kg·m²")
    J_rotor: float = Field(0.0, ge=0, le=1e4, description="the motor's rotor about its axis, kg·m²")
    gear_ratio: float = Field(1.0, gt=0, le=1000, description="transmission ratio i = ω_motor/ω₁")


class TitleInput(BaseModel):
    """The report's title block, free text."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    student: str = Field("", max_length=80, description="the student's name")
    group: str = Field("", max_length=80, description="the student's group")
    variant: str = Field("", max_length=80, description="the variant of the assignment")


class CourseProjectRequest(BaseModel):
    """The course project of a crank-driven linkage (Chaika–Vasylenko §3.4): kinematics at N positions, the
    dynamics with the flywheel for [δ], the kinetostatics at the real motion with Zhukovsky's lever."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    linkage: LinkageModel = Field(description="the mechanism as data (GET /api/v1/mechanisms/general), a crank as "
                                              "its input")
    masses: MassInput = Field(description="the links' masses, centres of mass and J_S; the useful loads; g; f and r "
                                          "of every pair")
    pair_friction: PairFrictionMap = PairFrictionField
    inertias: GroupOneInput = Field(default_factory=GroupOneInput, description=(
        "group I: J1, J_rotor and the gear ratio i (the flywheel is fitted on the crank's shaft)"))
    omega_mean: float = Field(ge=1e-3, le=1e4, description="the crank's mean angular velocity ω₁ₘ = (ω_max + "
                                                           "ω_min)/2, rad/s (n₁ = 30ω₁ₘ/π rpm)")
    delta: float = Field(ge=1e-4, le=0.5, description="the permissible coefficient of speed fluctuation [δ]")
    positions: Literal[8, 12, 24] = Field(12, description="the number of positions N of the crank: 8, 12 or 24")
    start: float | None = Field(None, ge=-100, le=100, description=(
        "φ₀ of position 1, rad; null: the extreme position that starts the working stroke"))
    output: str | None = Field(None, min_length=1, max_length=40, description=(
        "the output that defines the strokes: a sliding pair (\"E/ram\") or a link (\"link 3\"); null: found "
        "(the loaded slide, else the last group's slide or link)"))
    chosen: int | None = Field(None, ge=1, le=24, description=(
        "the position of the force analysis, 1…N; null: the one with the largest useful load"))
    drawn: list[int] = Field(default_factory=list, max_length=24, description=(
        "positions whose plans are drawn to scale, each 1…N; empty: the chosen one"))
    title: TitleInput = Field(default_factory=TitleInput, description="the title block of the report")

    @field_validator("chosen")
    @classmethod
    def chosen_position(cls, chosen: int | None, info: ValidationInfo) -> int | None:
        count = info.data.get("positions", 24)
        if chosen is not None and not 1 <= chosen <= count:
            raise ValueError(f"position {chosen} is not among the positions 1…{count}")
        return chosen

    @field_validator("drawn")
    @classmethod
    def drawn_positions(cls, drawn: list[int], info: ValidationInfo) -> list[int]:
        count = info.data.get("positions", 24)
        if not all(1 <= k <= count for k in drawn):
            raise ValueError(f"each drawn position is one of the positions 1…{count}")
        return drawn

    @field_validator("start")
    @classmethod
    def finite_start(cls, start: float | None) -> float | None:
        if start is not None and not math.isfinite(start):
            raise ValueError("φ₀ is a finite angle in rad")
        return start
