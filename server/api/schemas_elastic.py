"""Request model of the elastic-machine API (/elastic): every input with its unit."""
from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from ..core.elastic.assemblies import OUTPUT as ASSEMBLIES
from .schemas import MAX_PARAMS, MechanismName
from .schemas_dynamics import InertiaInput, LoadInput, MotorInput


class CompliancesInput(BaseModel):
    """Compliances of the elastic linkage, Eremyants (1.24)–(1.25), (1.34); Drakunov–Tuleshova (2)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    e1: float = Field(0.0, ge=0, le=1, description="crank-shaft torsion e₁ = L₁/(G I_p1), rad/(N·m)")
    e2: float = Field(0.0, ge=0, le=1, description="rod/coupler tension–compression e₂ = l₂/(E F₂), m/N")
    e3: float = Field(0.0, ge=0, le=1, description="rocker-shaft torsion e₃ = L₃/(G I_p3), rad/(N·m) (four-bar)")


class DimensionsInput(BaseModel):
    """The elastic linkage's compliances from its parts, Eremyants (1.16), (1.24)–(1.25), (1.37): the crank
    shaft, the motor shaft behind the gear (inertias.gear_ratio = u) and the rod (its length is l₂)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    shaft_length: float = Field(0.3, gt=0, le=10, description="crank shaft's length L, m")
    shaft_diameter: float = Field(0.04, ge=1e-3, le=1, description="crank shaft's diameter d, m")
    rod_diameter: float = Field(0.02, ge=1e-3, le=1, description="rod's diameter d₂ (round section), m")
    motor_shaft_length: float = Field(0.2, ge=0, le=10, description="motor shaft's length L_D, m (0: none)")
    motor_shaft_diameter: float = Field(0.03, ge=1e-3, le=1, description="motor shaft's diameter d_D, m")
    shear_modulus: float = Field(8.0e10, ge=1e8, le=1e12, description="shear modulus G, Pa")
    young: float = Field(2.1e11, ge=1e8, le=1e12, description="Young's modulus E, Pa")


class BearingInput(BaseModel):
    """Ball bearings in the rod's joints B and C, Eremyants (1.43)–(1.44)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    balls: int = Field(9, ge=3, le=60, description="number of balls z")
    r_inner: float = Field(0.01, gt=0, le=1, description="radius r₁ of the inner race where the balls touch, m")
    r_outer: float = Field(0.011, gt=0, le=1, description="radius r₂ of the outer race, m")
    young: float = Field(2.1e11, gt=0, le=1e12, description="Young's modulus E, Pa")
    poisson: float = Field(0.3, ge=0, lt=0.5, description="Poisson's ratio μ")


COMMON_FIELDS = {"model", "mechanism", "params", "inertias", "load", "t_end", "n", "rtol", "method", "outputs"}
MODEL_FIELDS = {        # the fields each model reads besides the common ones (bearing: with the "bearings" output)
    "two_mass": {"motor", "J_motor", "c", "b", "omega0", "twist0"},
    "kinematic_drive": {"c", "b", "speed", "omega0", "twist0"},
    "three_mass": {"motor", "J_motor", "J_middle", "c", "compliances", "b", "b1", "omega0", "twist0"},
    "elastic_linkage": {"motor", "J_motor", "compliances", "dimensions", "b", "omega0", "twist0"},
    "elastic_four_bar": {"motor", "J_motor", "compliances", "b", "omega0", "twist0"},
}


class ElasticRequest(BaseModel):
    """An elastic machine, its time span and the outputs wanted."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    model: Literal["two_mass", "kinematic_drive", "three_mass", "elastic_linkage", "elastic_four_bar"] = Field(
        description="two_mass: belt drive (1.20)–(1.21); kinematic_drive: powerful motor φ₁ = ωt (1.22)–(1.23); "
                    "three_mass: (1.40)–(1.42); elastic_linkage: c(φ) of the linkage (1.29)/(1.34), (1.31)–(1.32); "
                    "elastic_four_bar: Drakunov–Tuleshova's two-mass model with c_n(φ₁) and damping b_n")
    mechanism: MechanismName
    params: dict[str, float] = Field(default_factory=dict, max_length=MAX_PARAMS, description="lengths in metres, as for /kinematics")
    inertias: InertiaInput = Field(default_factory=InertiaInput, description="the mechanism side; J1 is the crank")
    load: LoadInput = Field(default_factory=LoadInput)
    motor: MotorInput = Field(default_factory=lambda: MotorInput(kind="constant"))
    J_motor: float = Field(0.0, ge=0, le=1e4, description="motor side of the first spring, kg·m²")
    J_middle: float = Field(0.0, ge=0, le=1e4, description="three-mass: the middle mass, kg·m²")
    c: float = Field(0.0, ge=0, le=1e12, description="constant stiffness (belt, or the first spring), N·m/rad")
    compliances: CompliancesInput = Field(default_factory=CompliancesInput)
    dimensions: DimensionsInput | None = Field(None, description=(
        "elastic_linkage: e₁ and e₂ from the parts instead of `compliances` (Eremyants (1.16), (1.24)–(1.25))"))
    b: float = Field(0.0, ge=0, le=1e9, description="damping across the spring next to the mechanism, N·m·s/rad")
    b1: float = Field(0.0, ge=0, le=1e9, description="three-mass: damping across the first spring, N·m·s/rad")
    speed: float = Field(0.0, ge=0, le=1e4, description="kinematic drive: the motor side's constant speed, rad/s")
    omega0: float = Field(0.0, ge=0, le=1e4, description="initial speed of every mass, rad/s")
    twist0: float = Field(0.0, ge=-1, le=1, description="initial twist of the spring next to the mechanism, rad")
    t_end: float = Field(1.0, ge=1e-3, le=20, description="time span, s")
    n: int = Field(801, ge=11, le=4001, description="samples of the time histories")
    rtol: float = Field(1e-6, ge=1e-10, le=1e-2, description="relative tolerance")
    method: Literal["auto", "DOP853", "RK45", "Radau", "BDF", "LSODA"] = Field(
        "auto", description="auto: chosen by the stiffness the server measures")
    bearing: BearingInput = Field(default_factory=lambda: BearingInput(), description="ball bearings in B and C")
    outputs: list[Literal["histories", "modal", "rigid", "bearings", "compliance", ASSEMBLIES]] = Field(
        min_length=1, max_length=6, description=(
        "histories: time histories with numerics; modal: c(φ), e(φ), natural frequency and damping ratio over a "
        "turn (closed forms); rigid: the rigid machine's start-up on the same times; bearings: the successive "
        "approximations of the ball-bearing stiffness (1.44) over the largest rod force (elastic crank-slider); "
        "compliance: e₁, e₂ from `dimensions` with the erratum of (1.16)/(1.37), printed beside corrected; "
        f"{ASSEMBLIES}: I_n, I_n′, c_n, c_n′ over a turn for both assemblies of the elastic four-bar "
        "(Drakunov–Tuleshova (2), (9), (10))"))

    @model_validator(mode="after")
    def only_used_fields(self):
        """A field the model does not use is refused by name (it would be ignored silently otherwise)."""
        used = COMMON_FIELDS | MODEL_FIELDS[self.model] | ({"bearing"} if "bearings" in self.outputs else set())
        for name in sorted(self.model_fields_set - used):
            raise ValueError(f"{name}: the {self.model} model does not use it")
        if "J_rotor" in self.inertias.model_fields_set:
            raise ValueError("inertias.J_rotor: the elastic models take the motor side's inertia as J_motor, reduced "
                             "to the crank (the rotor sits on the other side of the spring)")
        if self.model == "kinematic_drive" and "gear_ratio" in self.inertias.model_fields_set:
            raise ValueError("inertias.gear_ratio: the kinematic_drive model prescribes the crank-side speed; no "
                             "motor characteristic is reduced through a gear")
        return self

    @model_validator(mode="after")
    def complete(self):
        needs_linkage = self.model in ("three_mass", "elastic_linkage", "elastic_four_bar")
        if self.dimensions is not None and "compliances" in self.model_fields_set:
            raise ValueError("dimensions: give the compliances or the dimensions, not both")
        if "compliance" in self.outputs and self.dimensions is None:
            raise ValueError("compliance: give the dimensions the compliances are computed from")
        if needs_linkage and self.dimensions is None and not (
                self.compliances.e1 or self.compliances.e2 or self.compliances.e3):
            raise ValueError(f"{self.model}: give the linkage's compliances e1, e2 (e3)")
        if self.model in ("two_mass", "kinematic_drive", "three_mass") and self.c <= 0:
            raise ValueError(f"{self.model}: give the stiffness c > 0")
        if self.model == "elastic_four_bar" and self.mechanism != "four_bar":
            raise ValueError("elastic_four_bar: the mechanism is the four_bar")
        if self.model in ("elastic_linkage", "three_mass") and self.mechanism not in ("slider_crank", "four_bar"):
            raise ValueError("an elastic linkage is a slider_crank or a four_bar")
        if ASSEMBLIES in self.outputs and not (needs_linkage and self.mechanism == "four_bar"):
            raise ValueError(f"{ASSEMBLIES}: the two assemblies are those of a four_bar with elastic links "
                             "(models three_mass, elastic_linkage, elastic_four_bar)")
        if "bearings" in self.outputs and not (self.model == "elastic_linkage" and self.mechanism == "slider_crank"):
            raise ValueError("bearings: the iteration of Eremyants §1.4 is for the elastic crank-slider linkage")
        if self.model == "kinematic_drive" and self.speed <= 0:
            raise ValueError("kinematic_drive: give the motor side's speed > 0")
        if self.model != "kinematic_drive" and self.J_motor <= 0:
            raise ValueError(f"{self.model}: give the motor side's inertia J_motor > 0")
        if self.model == "three_mass" and self.J_middle <= 0:
            raise ValueError("three_mass: give the middle mass J_middle > 0")
        return self
