"""Request models of /motor-characteristic (the induction motor's static characteristic, the stability of the
operating point and the successive approximations of Lecture 10 §10.9–§10.10) and /flywheel-analysis (the
analysis problem of Merzalov's method: the flywheel's I given, δ found, Lecture 10 §10.4)."""
from __future__ import annotations

from typing import Literal

from pydantic import ConfigDict, Field, field_validator, model_validator

from .schemas_dynamics import FlywheelRequest, InertiaInput, LoadInput, MechanismChoice, MotorInput

CHARACTERISTIC_OUTPUTS = ("characteristic", "operating_point", "approximations", "joint")
ANALYSIS_OUTPUTS = ("analysis", "synthesis", "driving_moment", "transfer_functions")


class MotorCharacteristicRequest(MechanismChoice):
    """The machine of /motion driven by an induction motor ('kloss': the whole curve; 'induction': the
    linearised stable branch, Lecture 10 (L30))."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    inertias: InertiaInput = Field(default_factory=InertiaInput)
    load: LoadInput = Field(default_factory=LoadInput)
    motor: MotorInput
    tol: float = Field(1e-8, ge=1e-11, le=1e-2, description="successive approximations stop when two laws of "
                                                             "motion differ by less than tol (relative)")
    outputs: list[Literal[CHARACTERISTIC_OUTPUTS]] = Field(min_length=1, max_length=4)

    @field_validator("motor")
    @classmethod
    def induction_motor(cls, motor: MotorInput) -> MotorInput:
        if motor.kind not in ("kloss", "induction"):
            raise ValueError("the static characteristic is the induction motor's: kind 'kloss' or 'induction'")
        return motor


class FlywheelAnalysisRequest(FlywheelRequest):
    """The flywheel study's machine with the group-I inertia given: the δ it gives, beside the inertia [δ] needs."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    inertia: float = Field(ge=1e-6, le=1e6, description="the flywheel's moment of inertia I_м, kg·m² (added to "
                                                        "the crank's and rotor's I₁₀)")
    outputs: list[Literal[ANALYSIS_OUTPUTS]] = Field(min_length=1, max_length=4)

    @model_validator(mode="after")
    def crank_slider_figures(self):
        if "transfer_functions" in self.outputs and self.mechanism != "slider_crank":
            raise ValueError("outputs: the transfer functions u₂₁, V_qC, V_qS2 of Fig. 10.5 are the crank-slider's")
        return self
