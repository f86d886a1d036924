"""Request and response models of the JSON API: declared once, they are the OpenAPI documentation."""
from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from ..core.kinematics import MAX_POINTS

MAX_ANGLE = 1000.0
MAX_PARAMS = 16                  # a mechanism has at most 6 parameters; unknown names are refused
Language = Literal["ru", "uk", "en"]
MechanismName = Literal["sine", "slider_crank", "slotted_link", "four_bar"]
KinematicsMechanism = Literal["sine", "slider_crank", "slotted_link", "four_bar", "general"]


class ParamInfo(BaseModel):
    name: str = Field(description="parameter name as used in `params`")
    unit: str = Field(description="SI unit ('m' for lengths, '1' for ratios and switches)")
    description: str
    default: float
    minimum: float = Field(description="smallest value the scene offers")
    maximum: float = Field(description="largest value the scene offers")
    integer: bool = Field(description="true for switches such as the assembly mode")


class OutputInfo(BaseModel):
    name: str
    unit: str
    description: str


class MechanismInfo(BaseModel):
    name: MechanismName
    title: str
    conventions: str = Field(description="frame, angle origin, sense of rotation and λ definitions, in words")
    params: list[ParamInfo]
    outputs: list[OutputInfo]


class AttachmentModel(BaseModel):
    """A point (centre of mass, tool point, joint for a later group) or a guide fixed on one of the element's
    links, in that link's frame: from its origin joint along its angle (see GET /api/v1/mechanisms/general)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    link: int | None = Field(None, description="which of the element's links (default: its first)")
    along: float = Field(0.0, description="m, along the link's direction from its origin joint")
    across: float = Field(0.0, description="m, to the left of that direction")
    angle: float = Field(0.0, description="guides only: the guide's angle to the link's direction, rad")


class FrameGuideModel(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    through: tuple[float, float] | str = Field((0.0, 0.0), description="[x, y] in m, or a frame joint's name")
    angle: float = Field(0.0, description="direction, rad counter-clockwise from +x")


class FrameModel(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    joints: dict[str, tuple[float, float]] = Field(default_factory=dict, max_length=64,
                                                   description="fixed joints {name: [x, y]} in m")
    guides: dict[str, FrameGuideModel] = Field(default_factory=dict, max_length=64, description="fixed guides")


class CrankModel(BaseModel):
    """The input link: a crank turning about a frame joint; θ₁ = angle0 + sense·φ."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    kind: Literal["crank"] = "crank"
    link: int = Field(1, ge=1, le=99)
    pivot: str = Field(description="the frame joint it turns about")
    joint: str = Field(description="name of its pin")
    length: float = Field(gt=0, description="m")
    angle0: float = Field(0.0, description="crank angle at φ = 0, rad")
    sense: Literal[1, -1] = Field(1, description="+1 counter-clockwise, −1 clockwise")
    points: dict[str, AttachmentModel] = Field(default_factory=dict, max_length=64)
    new_guides: dict[str, AttachmentModel] = Field(default_factory=dict, max_length=64)


class SliderInputModel(BaseModel):
    """The input link: a slider on a frame guide, A = P + s·u; s (m) over ``travel`` is the generalised
    coordinate (the answer's `phi` holds s; analogs are with respect to s)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    kind: Literal["slider"]
    link: int = Field(1, ge=1, le=99)
    guide: str = Field(description="the frame guide it slides along")
    joint: str = Field(description="name of its joint A (at s = 0 on the guide's point)")
    travel: tuple[float, float] = Field(description="[s_min, s_max] in m, s measured from the guide's point")
    points: dict[str, AttachmentModel] = Field(default_factory=dict, max_length=64)
    new_guides: dict[str, AttachmentModel] = Field(default_factory=dict, max_length=64)


class GroupModel(BaseModel):
    """A class-II structural group (kinds 1–5: RRR, RRP, RPR, PRP, RPP) attached to elements placed before."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    kind: Literal["RRR", "RRP", "RPR", "PRP", "RPP"]
    links: tuple[int, int] = Field(description="its two links' numbers [i, j]")
    outer: list[str] = Field(default_factory=list, max_length=2, description=(
        "outer joints: RRR [B, D]; RRP [B]; RPR [B (block), D (lever pivot)]; RPP [B]; PRP none"))
    guide: str | None = Field(None, description="RRP, RPP: the guide slider j runs along")
    guides: list[str] | None = Field(None, max_length=2, description="PRP: the two guides [g₁, g₂]")
    inner: str | None = Field(None, description="name of the inner joint (RRR, RRP, PRP: C; RPP: R, link j's "
                                                "point on the guide; RPR: the slide's name)")
    lengths: tuple[float, float] | None = Field(None, description="RRR: [BC, DC] in m")
    length: float | None = Field(None, description="RRP: BC in m")
    offset: float | None = Field(None, description="RPR: the slot's offset e from the lever pivot, m")
    angle: float | None = Field(None, description="RPP: the slot's angle α to the guide, rad (default π/2)")
    branch: Literal[1, -1] = Field(1, description="assembly branch σ (RRR, RRP, RPR)")
    points: dict[str, AttachmentModel] = Field(default_factory=dict, max_length=64)
    new_guides: dict[str, AttachmentModel] = Field(default_factory=dict, max_length=64)


class LinkageModel(BaseModel):
    """A planar mechanism as data: frame, input link (a crank or a slider), class-II groups in the order they
    are attached."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    frame: FrameModel
    input: CrankModel | SliderInputModel
    groups: list[GroupModel] = Field(default_factory=list, max_length=20)


class PlanRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    phi: float = Field(ge=-MAX_ANGLE, le=MAX_ANGLE, description="crank angle of the plans, rad")
    omega1: float = Field(1.0, ge=-1e4, le=1e4, description="crank angular velocity ω₁, rad/s")
    epsilon1: float = Field(0.0, ge=-1e6, le=1e6, description="crank angular acceleration ε₁, rad/s²")


class KinematicsRequest(BaseModel):
    """Kinematics of one mechanism over a set of crank angles."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, json_schema_extra={"examples": [
        {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3, "e": 0.0}, "n": 361,
         "outputs": ["s", "u31", "du31", "u21", "du21", "joints"]}]})

    mechanism: KinematicsMechanism = Field(description=(
        "which mechanism; 'general': the one given in `linkage`"))
    linkage: LinkageModel | None = Field(None, description=(
        "with mechanism 'general': the mechanism as data (GET /api/v1/mechanisms/general)"))
    plan: PlanRequest | None = Field(None, description="with the output 'plan': the angle, ω₁ and ε₁ of the plans")
    params: dict[str, float] = Field(default_factory=dict, max_length=MAX_PARAMS, description=(
        "lengths in metres and switches; missing ones take the defaults of GET /api/v1/mechanisms"))
    phi: list[float] | None = Field(default=None, max_length=MAX_POINTS,
                                    description="crank angles in radians (give this or `n`)")
    n: int | None = Field(default=None, ge=2, le=MAX_POINTS,
                          description="number of equally spaced angles over one closed cycle, 0…cycle")
    outputs: list[str] = Field(min_length=1, max_length=40, description=(
        "names of the outputs wanted, e.g. s, u31, du31, s2, u21, du21, chi21, v_s2, a_s2, joints, special, "
        "harmonics (of u31), harmonics_du31, info; each mechanism lists its own"))

    @field_validator("phi")
    @classmethod
    def finite_angles(cls, phi):
        """Reported at loc ["body", "phi"]: NaN, ±Infinity and absurdly large angles."""
        if phi is not None and not all(math.isfinite(x) and abs(x) <= MAX_ANGLE for x in phi):
            raise ValueError(f"every angle in `phi` must be a finite number of radians, |φ| ≤ {MAX_ANGLE:g}")
        return phi

    @model_validator(mode="after")
    def one_grid(self):
        if (self.phi is None) == (self.n is None):
            raise ValueError("give exactly one of `phi` (angles in radians) or `n` (number of points)")
        if (self.mechanism == "general") != (self.linkage is not None):
            raise ValueError("`linkage` goes with mechanism 'general', and only with it")
        if self.mechanism == "general" and self.params:
            raise ValueError("a general mechanism takes its lengths in `linkage`, not in `params`")
        if "plan" in self.outputs and self.plan is None:
            raise ValueError("the output 'plan' needs the field `plan` (its angle phi, omega1, epsilon1)")
        return self


class KinematicsResponse(BaseModel):
    mechanism: KinematicsMechanism
    params: dict[str, float] = Field(description="the complete parameter set used (defaults filled in)")
    cycle: float = Field(description="length of one kinematic cycle in φ, rad (2π, or 4π for a change-point "
                                     "four-bar without stroke limiter)")
    phi: list[float] = Field(description="crank angles, rad")
    outputs: dict[str, Any] = Field(description=(
        "exactly the requested outputs: arrays over phi (null where undefined), joints as "
        "{name: [[x, y], …]}, special positions as a list"))
    units: dict[str, str] = Field(description="unit of each returned output")
    warnings: list[str] = Field(description="sentences about singular or near-singular positions")


class NumericsModel(BaseModel):
    """How a result was computed (server/core/numerics.py, ``Numerics``): declared once for every answer.
    A field the method has no use for is null."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    method: str = Field(description="what was computed and how, in the reader's language")
    code: str = Field("", description="names the method for the interface's translations")
    why: str | None = Field(None, description="why this method was chosen (stiffness, smoothness)")
    rtol: float | None = Field(None, gt=0, description="relative tolerance asked")
    steps: int | None = Field(None, ge=0, description="accepted steps or grid intervals")
    rejected: int | None = Field(None, ge=0, description="rejected steps")
    nfev: int | None = Field(None, ge=0, description="evaluations of the right-hand side")
    njev: int | None = Field(None, ge=0, description="evaluations of the Jacobian")
    nlu: int | None = Field(None, ge=0, description="LU decompositions")
    iterations: int | None = Field(None, ge=0, description="iterations of the outer loop (shooting, root finding, "
                                                           "successive approximations)")
    cycles: int | None = Field(None, ge=0, description="cycles integrated")
    stiffness_ratio: float | None = Field(None, ge=0, description="largest ratio of the eigenvalues' magnitudes")
    converged: bool | None = Field(None, description="whether the iteration met its tolerance (null: nothing iterates)")
    runtime_ms: float | None = Field(None, ge=0, description="wall-clock time, ms")
    error_estimate: float | None = Field(None, ge=0, description="estimated relative error of the result (null: "
                                                                 "nothing to compare with)")
    energy_residual: float | None = Field(None, ge=0, description="|net work| / driving work over the run")
    message: str = Field("", description="how it ended, in words")
    message_code: str = Field("", description="names a routine message for the interface's translations")
    message_context: dict[str, Any] = Field(default_factory=dict, description="the numbers of that message")
    why_context: dict[str, Any] = Field(default_factory=dict, description="the numbers of the `why` text")
