"""Request models of the force-analysis API (/forces, /wear, /efficiency-chain)."""
from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from .schemas import MAX_PARAMS, LinkageModel
from .schemas_dynamics import MassInput, MotorInput, PairFrictionField, PairFrictionMap
from .schemas_wear import TabulatedReactions


class PairsInput(BaseModel):
    """Friction coefficients and journal radii of the crank-slider's pairs (Chaika–Vasylenko (3.3))."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    f14: float = Field(0.0, ge=0, le=2, description="main bearing O (crank–frame), revolute")
    f12: float = Field(0.0, ge=0, le=2, description="crank pin A (crank–rod), revolute")
    f23: float = Field(0.0, ge=0, le=2, description="piston pin B (rod–slider), revolute")
    f34: float = Field(0.0, ge=0, le=2, description="slider in its guide, prismatic")
    r14: float = Field(0.02, gt=0, le=1, description="journal radius at O, m")
    r12: float = Field(0.015, gt=0, le=1, description="journal radius at A, m")
    r23: float = Field(0.01, gt=0, le=1, description="journal radius at B, m")


class ForceLoadsInput(BaseModel):
    """Masses, inertias, the crank's motion and the piston force."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    m2: float = Field(0.0, ge=0, le=1e5, description="rod mass, kg")
    J_S2: float = Field(0.0, ge=0, le=1e4, description="rod inertia about S2, kg·m²")
    m3: float = Field(0.0, ge=0, le=1e5, description="slider mass, kg")
    J1: float = Field(0.0, ge=0, le=1e4, description="reduced inertia of the parts geared to the crank, kg·m²")
    omega: float = Field(10.0, gt=0, le=1e4, description="crank speed along its rotation, rad/s")
    epsilon: float = Field(0.0, ge=-1e6, le=1e6, description="crank angular acceleration, rad/s²")
    force: float = Field(0.0, ge=0, le=1e7, description="working machine: the load P_c on the slider, N")
    return_factor: float = Field(1.0, ge=0, le=1, description="k_p on the return stroke")
    gravity: bool = True
    guide_angle: float = Field(0.0, ge=-3.2, le=3.2, description="inclination α of the guide, rad")
    gas: MotorInput | None = Field(None, description="a piston engine: the indicator diagram gives the piston force")

    @model_validator(mode="after")
    def engine(self):
        if self.gas is not None and self.gas.kind != "indicator":
            raise ValueError("gas: an indicator diagram (kind 'indicator')")
        return self


class ForcesRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    mechanism: Literal["slider_crank", "general"] = Field("slider_crank", description=(
        "the crank-slider (Chaika–Vasylenko §3.1), or 'general': the mechanism in `linkage`, by structural groups"))
    linkage: LinkageModel | None = Field(None, description=(
        "with mechanism 'general': the mechanism as data (GET /api/v1/mechanisms/general)"))
    masses: MassInput | None = Field(None, description=(
        "with mechanism 'general': masses, centres, J_S, the useful loads, g, and f, r of every pair"))
    pair_friction: PairFrictionMap = PairFrictionField
    free_body_phi: float = Field(0.0, ge=-100, le=100, description=(
        "with mechanism 'general': the crank angle of the free-body diagrams and of the table, rad"))
    outputs: list[Literal["forces", "wear"]] = Field(["forces"], max_length=2, description="what the scene shows")
    params: dict[str, float] = Field(default_factory=dict, max_length=MAX_PARAMS, description="crank-slider lengths l1, l2, e (m) and a2")
    loads: ForceLoadsInput = Field(default_factory=ForceLoadsInput)
    pairs: PairsInput = Field(default_factory=PairsInput)
    n: int = Field(361, ge=13, le=1441, description="points over one closed cycle")
    tolerance: float = Field(1e-9, ge=1e-14, le=1e-2, description="ε_R: relative error of the reactions the friction equilibrium is solved to (and the change that ends the textbook's table)")

    @model_validator(mode="after")
    def general_fields(self):
        general = self.mechanism == "general"
        if general != (self.linkage is not None):
            raise ValueError("`linkage` goes with mechanism 'general', and only with it")
        if not general and (self.masses is not None or self.pair_friction):
            raise ValueError("`masses` and `pair_friction` go with mechanism 'general' (the crank-slider takes "
                             "`loads` and `pairs`)")
        if general:
            if self.params:
                raise ValueError("a general mechanism takes its lengths in `linkage`, not in `params`")
            if "wear" in self.outputs and not isinstance(self, WearPartsInput):
                raise ValueError("outputs: wear is asked of /wear")
            kept = {"omega", "epsilon"}
            loads = self.loads.model_dump(exclude_defaults=True)
            if set(loads) - kept or self.pairs.model_dump(exclude_defaults=True):
                raise ValueError("a general mechanism takes its masses and loads in `masses` and its friction in "
                                 "`masses.friction`, `masses.pair_radius` and `pair_friction`; of `loads` only "
                                 "omega and epsilon")
        return self


class WearPartsInput(BaseModel):
    """The pin and piston, the wear intensities I_s (Table 1.1) and the service life: by default the two-stroke
    engine of Chaika–Vasylenko §4.3."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    pin_diameter: float = Field(0.02, ge=1e-3, le=1, description="piston pin diameter d₂₃, m")
    pin_length: float = Field(0.025, ge=1e-3, le=1, description="pin bearing length l_z23, m")
    piston_diameter: float = Field(0.075, ge=1e-3, le=2, description="piston diameter D_p, m")
    piston_length: float = Field(0.076, ge=1e-3, le=2, description="piston length L_p, m")
    I_pin: float = Field(0.6e-10, gt=0, le=1e-3, description="wear intensity of the pin")
    I_bush: float = Field(1.0e-10, gt=0, le=1e-3, description="wear intensity of the bush")
    I_piston: float = Field(2e-12, gt=0, le=1e-3, description="wear intensity of the piston")
    I_cylinder: float = Field(3e-12, gt=0, le=1e-3, description="wear intensity of the cylinder liner")
    hours: float = Field(1000, gt=0, le=1e6, description="service life, h")


class WearRequest(ForcesRequest, WearPartsInput):
    """The wear of Chaika–Vasylenko §4 for a crank-slider (by default the two-stroke engine of §4.3)."""

    mechanism: Literal["slider_crank", "general"] = Field("slider_crank", description=(
        "the crank-slider (Chaika–Vasylenko §4), or 'general': every pair of the mechanism in `linkage`"))

    rpm: float = Field(2400, ge=1, le=1e5, description="crank speed, rev/min (one cycle per revolution)")
    reactions: Literal["kinetostatics", "table_4_3"] | TabulatedReactions = Field(
        "kinetostatics", description="the loads: the kinetostatics of params and loads, the reaction columns of "
        "Chaika–Vasylenko Table 4.3 (its engine at 2400 rpm) or a table of them; with a table no params, loads, "
        "pairs, n or tolerance")

    @model_validator(mode="after")
    def table_alone(self):
        fixed = {"rpm"} if self.reactions == "table_4_3" else set()       # Table 4.3 is at 2400 rpm
        given = sorted(self.model_fields_set & {"params", "loads", "pairs", "n", "tolerance", *fixed})
        if self.reactions != "kinetostatics" and given:
            raise ValueError(f"reactions from a table take no kinetostatics: leave out {', '.join(given)}")
        if self.mechanism == "general" and self.reactions != "kinetostatics":
            raise ValueError("a general mechanism's reactions come from its kinetostatics (reactions: "
                             "'kinetostatics')")
        return self


class ChainRequest(BaseModel):
    """Efficiency of mechanisms in series (3.39) or in parallel (3.40)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    efficiencies: list[float] = Field(min_length=1, max_length=50, description="η_k of each mechanism, 0…1")
    works: list[Annotated[float, Field(ge=0, le=1e12)]] | None = Field(
        None, max_length=50, description="parallel only: driving work A_P,k of each branch, J (0…10¹²)")

    @model_validator(mode="after")
    def sizes(self):
        if not all(0 <= e <= 1 for e in self.efficiencies):
            raise ValueError("each efficiency lies between 0 and 1")
        if self.works is not None and (len(self.works) != len(self.efficiencies) or min(self.works) < 0):
            raise ValueError("one non-negative work per branch")
        return self
