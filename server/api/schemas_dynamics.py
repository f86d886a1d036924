"""Request and response models of the dynamics API (/reduction, /motion, /flywheel): every input with its unit,
every answer's numerics in the one declared form (NumericsModel)."""
from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator
from pydantic_core import InitErrorDetails, PydanticCustomError

from ..core.dynamics.motors import INDICATOR_POINTS, TABLE_POINTS, polytropic_diagram
from ..core.structure.masses import (DIAGRAM_POINTS, FARTHEST, LinkMass, LinkMoment, LoadDiagram, MassModel,
                                     PointForce, SliderForce, diagram_problem)
from .schemas import MAX_PARAMS, LinkageModel, NumericsModel
from .schemas_cycle import CycleInput

Positive = Field(ge=0.0, le=1e6)
DynamicsMechanism = Literal["sine", "slider_crank", "slotted_link", "four_bar", "general"]
LinkNumber = Field(ge=1, le=99, description="the link's number in the linkage (1 = the input crank)")
TABLE_MOMENT = 1e7              # a free law's moments lie within ±TABLE_MOMENT, N·m
TABLE_GAP = 1e-6                # a free law's angles increase by at least this, rad
BOUNDS = {"greater_than_equal", "less_than", "less_than_equal"}


def _table_refusal(error: dict, code: str, degrees: bool) -> InitErrorDetails:
    """A refusal of a free law's table (pydantic's error, its type, field path and words kept) with what the page
    needs to say it in the reader's language (content/i18n err_<code>): ctx.code; a point's bound refused: point
    (its row, from 1), min and max (degrees for an angle, N·m for a moment); a length refused: min and max points."""
    ctx = dict(error.get("ctx") or {})
    loc = error["loc"]
    if error["type"] in BOUNDS and len(loc) == 1 and isinstance(loc[0], int):
        low, high = (0.0, 2 * math.pi) if degrees else (-TABLE_MOMENT, TABLE_MOMENT)
        scale = 180 / math.pi if degrees else 1.0
        ctx |= {"code": code, "point": loc[0] + 1, "min": low * scale, "max": high * scale}
    elif error["type"] in {"too_short", "too_long"}:
        ctx |= {"code": "free_law_points", "min": TABLE_POINTS[0], "max": TABLE_POINTS[1]}
    return InitErrorDetails(type=PydanticCustomError(error["type"], error["msg"], ctx or None), loc=loc,
                            input=error["input"])


def coded_table(value, handler, code: str, degrees: bool):
    """Validate a free law's list (handler: pydantic's own checks), its refusals coded for translation."""
    try:
        return handler(value)
    except ValidationError as refused:
        raise ValidationError.from_exception_data(
            refused.title, [_table_refusal(error, code, degrees) for error in refused.errors()]) from None


class InertiaInput(BaseModel):
    """Masses and moments of inertia of the links; defaults are zero (massless link)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    J1: float = Field(0.0, ge=0, le=1e4, description="crank with shaft and gears about the crank axis, kg·m²")
    m2: float = Field(0.0, ge=0, le=1e5, description="link 2 (rod, coupler or block) mass, kg")
    J_S2: float = Field(0.0, ge=0, le=1e4, description="link 2 moment of inertia about its centre of mass S2, kg·m²")
    m3: float = Field(0.0, ge=0, le=1e5, description="slider or yoke mass (sine, crank-slider), kg")
    J3: float = Field(0.0, ge=0, le=1e4, description="lever or rocker inertia about its pivot (slotted link, four-bar), kg·m²")
    J_rotor: float = Field(0.0, ge=0, le=1e4, description="motor rotor inertia, kg·m²")
    gear_ratio: float = Field(1.0, gt=0, le=1000, description="transmission ratio i = ω_motor/ω_crank")


class LoadInput(BaseModel):
    """Useful load and friction (Eremyants, chapter 3)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    force: float = Field(0.0, ge=0, le=1e7, description="P_c on the slider/yoke in N, or M₃ on the lever/rocker in N·m")
    return_factor: float = Field(1.0, ge=0, le=1, description="k_p (k_M): return-stroke load / working-stroke load")
    f: float = Field(0.0, ge=0, le=2, description="dry sliding-friction coefficient in the prismatic pairs")
    beta: float = Field(0.0, ge=0, le=1e6, description="viscous friction coefficient β, N·s/m")
    convention: Literal["consistent", "textbook"] = Field(
        "consistent", description="'textbook': the formulas as printed (3.6–3.9, 3.29–3.30, 3.44–3.49); "
                                  "'consistent': friction always resists, series summed exactly")
    crank_moment: float = Field(0.0, ge=0, le=1e7, description="constant resisting moment on the crank shaft, N·m")


class MotorInput(BaseModel):
    """Motor characteristic at the motor shaft (torque N·m, speed rad/s)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    kind: Literal["constant", "linear", "induction", "kloss", "indicator", "table"] = Field(
        description="constant M₀; linear M₀ − bω; induction: linearised stable branch (Lecture 10 (L30)); "
                    "kloss: Kloss curve (standard addition, not in the lecture); indicator: piston engine; "
                    "table: a free law M_P(φ₁) at the crank (Chaika–Vasylenko §3.4, step 9), table_phi and "
                    "table_moment, linear between the points and periodic over a turn")
    M0: float = Field(0.0, ge=0, le=1e7, description="constant, linear: torque at standstill, N·m")
    b: float = Field(0.0, ge=0, le=1e6, description="linear: slope of the characteristic, N·m·s/rad")
    M_nominal: float = Field(0.0, ge=0, le=1e7, description="induction: nominal torque M_н, N·m")
    omega_nominal: float = Field(0.0, ge=0, le=1e4, description="induction: nominal speed ω_н, rad/s")
    omega_sync: float = Field(0.0, ge=0, le=1e4, description="induction, kloss: synchronous (no-load) speed ω_с, rad/s")
    M_max: float = Field(0.0, ge=0, le=1e7, description="kloss: breakdown torque M_к, N·m")
    s_critical: float = Field(0.1, gt=0, lt=1, description="kloss: critical slip s_к")
    p_max: float = Field(0.0, ge=0, le=1e9, description="indicator: maximum cylinder pressure, Pa")
    piston_diameter: float = Field(0.0, ge=0, le=5, description="indicator: piston diameter, m")
    expansion: list[float] = Field(default_factory=lambda: polytropic_diagram()[0], min_length=INDICATOR_POINTS,
                                   max_length=INDICATOR_POINTS, description="indicator: p/p_max on expansion at x/H = 0, 0.1, …, 1 (assumed polytropic by default)")
    compression: list[float] = Field(default_factory=lambda: polytropic_diagram()[1], min_length=INDICATOR_POINTS,
                                     max_length=INDICATOR_POINTS, description="indicator: p/p_max on compression at x/H = 0, 0.1, …, 1")
    strokes: Literal[2, 4] = Field(2, description="indicator: two-stroke (cycle 2π) or four-stroke (cycle 4π)")
    table_phi: list[Annotated[float, Field(ge=0, lt=2 * math.pi)]] | None = Field(
        None, min_length=TABLE_POINTS[0], max_length=TABLE_POINTS[1],
        description="table: crank angles φ_j of the free law, rad, increasing within one turn [0, 2π)")
    table_moment: list[Annotated[float, Field(ge=-TABLE_MOMENT, le=TABLE_MOMENT)]] | None = Field(
        None, min_length=TABLE_POINTS[0], max_length=TABLE_POINTS[1],
        description="table: the driving moment M_P(φ_j) at the crank shaft, N·m, one per angle")

    @field_validator("table_phi", mode="wrap")
    @classmethod
    def increasing(cls, value, handler):
        """Angles within the turn and increasing; a refusal names the point (err_free_law_angle, _increasing)."""
        phi = coded_table(value, handler, "free_law_angle", degrees=True)
        for k in range(1, len(phi or ())):
            if phi[k] - phi[k - 1] < TABLE_GAP:
                raise PydanticCustomError(
                    "value_error", "Value error, the angles of a free law must increase, at least 1e-6 rad apart",
                    {"code": "free_law_increasing", "point": k + 1, "previous": k, "bound": math.degrees(phi[k - 1])})
        return phi

    @field_validator("table_moment", mode="wrap")
    @classmethod
    def bounded(cls, value, handler):
        """Moments within ±TABLE_MOMENT; a refusal names the point (err_free_law_moment)."""
        return coded_table(value, handler, "free_law_moment", degrees=False)

    @model_validator(mode="after")
    def consistent(self):
        if self.kind == "induction" and not 0 < self.omega_nominal < self.omega_sync:
            raise ValueError("induction motor: need 0 < omega_nominal < omega_sync")
        if self.kind == "kloss" and not (self.omega_sync > 0 and self.M_max > 0):
            raise ValueError("Kloss curve: need omega_sync > 0 and M_max > 0")
        if self.kind == "linear" and self.b == 0:
            raise ValueError("linear motor: the slope b must be positive (b = 0 is the constant-torque motor)")
        if self.kind == "indicator" and not (self.p_max > 0 and self.piston_diameter > 0):
            raise ValueError("piston engine: need p_max > 0 and piston_diameter > 0")
        if self.kind == "table" and (self.table_phi is None or self.table_moment is None
                                     or len(self.table_phi) != len(self.table_moment)):
            raise ValueError("a free law M_P(φ₁): need table_phi and table_moment, one moment per angle")
        if self.kind != "table" and (self.table_phi is not None or self.table_moment is not None):
            raise ValueError("table_phi and table_moment belong to the free law (kind 'table') only")
        if not all(0 <= x <= 1 for x in self.expansion + self.compression):
            raise ValueError("indicator diagram ordinates are p/p_max, between 0 and 1")
        return self


class LinkMassInput(BaseModel):
    """One moving link of a general mechanism: mass, centre of mass on the link, moment of inertia about it."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    link: int = LinkNumber
    mass: float = Field(ge=0, le=1e5, description="m, kg")
    centre: tuple[float, float] = Field((0.0, 0.0), description=(
        "centre of mass S in the link's own frame [along, across], m: from the link's origin joint along its "
        "direction, and to the left of it (as the linkage's points)"))
    inertia: float = Field(0.0, ge=0, le=1e4, description="J_S about the centre of mass, kg·m²")

    @field_validator("centre")
    @classmethod
    def finite_centre(cls, centre):
        if not all(math.isfinite(x) and abs(x) <= 1000 for x in centre):
            raise ValueError("the centre's coordinates must be finite numbers of metres, at most 1000 m")
        return centre


class LoadDiagramInput(BaseModel):
    """A useful-load diagram over the slider's stroke, as the indicator diagram: P/P_max at equally spaced
    positions x/H = 0…1 from the start of the working stroke, for the working and the return stroke."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    working_stroke: list[float] = Field(min_length=2, max_length=41, description="P/P_max on the working stroke")
    return_stroke: list[float] = Field(min_length=2, max_length=41, description="P/P_max on the return stroke")

    @field_validator("working_stroke", "return_stroke")
    @classmethod
    def ratios(cls, points):
        if not all(math.isfinite(p) and 0 <= p <= 1 for p in points):
            raise ValueError("each point is P/P_max, a number from 0 to 1")
        return points


class SliderForceInput(BaseModel):
    """A useful load on a slider along its guide, against the motion: P on the working stroke, k·P on the return."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    joint: str = Field(min_length=1, max_length=40, description=(
        "the sliding pair as named in the kinematics' `slides` (\"E/ram\"), or the slider's joint (\"E\")"))
    working: float = Field(ge=0, le=1e7, description="P on the working stroke, N")
    k: float = Field(1.0, ge=0, le=1, description="k: return-stroke load / working-stroke load")
    sense: Literal[1, -1] = Field(1, description="+1: the working stroke moves along the guide's direction")
    diagram: LoadDiagramInput | None = Field(None, description=(
        "a useful-load diagram instead of the constant P: then `working` is P_max and `k` is not used"))

    @model_validator(mode="after")
    def diagram_or_k(self):
        if self.diagram is not None and self.k != 1.0:
            raise ValueError("with a load diagram the return stroke's load is its own row, not k·P")
        return self

    def force(self, factor: float = 1.0) -> SliderForce:
        """The core's force, its P (or P_max) times ``factor``."""
        diagram = None if self.diagram is None else (tuple(self.diagram.working_stroke),
                                                     tuple(self.diagram.return_stroke))
        return SliderForce(self.joint, self.working * factor, self.k, self.sense, diagram)


class DiagramInput(BaseModel):
    """A load diagram p(x) = P/P_max through points [x, p], monotone cubic (PCHIP) between them, zero outside
    [x_first, x_last]."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    over: Literal["stroke", "phi"] = Field(description=(
        "'stroke': x is the travel as a fraction 0…1 of the whole travel from the extreme where the working "
        "stroke starts (a point along its fixed force line, a link's angle between its extreme angles); 'phi': x "
        "is the crank angle φ, rad, 0…2π"))
    points: list[tuple[float, float]] = Field(min_length=2, max_length=DIAGRAM_POINTS, description=(
        "[x, P/P_max] pairs, x strictly increasing, P/P_max from 0 to 1"))

    @field_validator("points")
    @classmethod
    def diagram_points(cls, points, info):
        over = info.data.get("over")
        problem = diagram_problem(over, points) if over else None
        if problem:
            raise ValueError(problem[1])
        return points

    def diagram(self) -> LoadDiagram:
        """The core's diagram."""
        return LoadDiagram(self.over, tuple((float(x), float(p)) for x, p in self.points))


class LinkMomentInput(BaseModel):
    """A useful load moment on a link, against its rotation: M₀ on the working stroke, k·M₀ on the return, times
    p(x) of a diagram where one is given."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    link: int = LinkNumber
    working: float = Field(ge=0, le=1e7, description="M₀ on the working stroke (its peak with a diagram), N·m")
    k: float = Field(1.0, ge=0, le=1, description="k: return-stroke moment / working-stroke moment")
    sense: Literal[1, -1] = Field(1, description="+1: the working stroke turns the link counter-clockwise")
    diagram: DiagramInput | None = Field(None, description=(
        "M = k M₀ p(x) against the rotation: over 'phi' the crank angle, over 'stroke' the link's angle between "
        "its extreme angles from the working stroke's start (a rocking link only)"))

    def moment(self, factor: float = 1.0) -> LinkMoment:
        """The core's moment, its M₀ times ``factor``."""
        return LinkMoment(self.link, self.working * factor, self.k, self.sense,
                          None if self.diagram is None else self.diagram.diagram())


class DirectionInput(BaseModel):
    """The direction of a point force: fixed in the frame, or turning with its link."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    kind: Literal["fixed", "link"] = Field(description=(
        "'fixed': α from +x, counter-clockwise; 'link': α from the link's direction (its origin joint along its "
        "angle), turning with it"))
    angle: float = Field(0.0, ge=-1000, le=1000, description="α, rad, counter-clockwise")


class PointForceInput(BaseModel):
    """A force at a point of a moving link (a tool point, a press's slide, a crusher's jaw): F = P p(x) e."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    link: int = LinkNumber
    point: tuple[float, float] = Field(description=(
        "the point [along, across] in the link's own frame, m: from the link's origin joint along its direction, "
        "and to the left of it (as the centres of mass)"))
    name: str | None = Field(None, min_length=1, max_length=8, description="a label for drawings, e.g. \"K\"")
    magnitude: float = Field(ge=0, le=1e7, description="P, N (P_max with a diagram)")
    direction: DirectionInput = Field(default_factory=lambda: DirectionInput(kind="fixed"), description=(
        "e, the force's unit vector: {kind: 'fixed' | 'link', angle: α in rad}"))
    acts: Literal["working", "always"] = Field("working", description=(
        "'working': only where the point moves against e (the force does negative work: the working stroke), "
        "zero where it moves along e; 'always': at every angle"))
    diagram: DiagramInput | None = Field(None, description=(
        "P·p(x) instead of the constant P; over 'stroke' only with a fixed direction"))

    @field_validator("point")
    @classmethod
    def near_point(cls, point):
        if not (all(math.isfinite(x) for x in point) and math.hypot(*point) <= FARTHEST):
            raise ValueError(f"the point's coordinates must be finite numbers of metres, at most {FARTHEST:g} m "
                             "from the link's origin")
        return point

    def force(self, factor: float = 1.0) -> PointForce:
        """The core's point force, its P (or P_max) times ``factor``."""
        return PointForce(self.link, tuple(self.point), self.magnitude * factor, self.direction.angle,
                          self.direction.kind, self.acts, None if self.diagram is None else self.diagram.diagram(),
                          self.name)


class MassInput(BaseModel):
    """Mass model and loads of a general mechanism (links not listed are massless)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    links: list[LinkMassInput] = Field(default_factory=list, max_length=40)
    gravity: float = Field(9.81, ge=0, le=100, description="g along −y, m/s² (0: the mechanism lies horizontally)")
    forces: list[SliderForceInput] = Field(default_factory=list, max_length=20)
    moments: list[LinkMomentInput] = Field(default_factory=list, max_length=40)
    point_forces: list[PointForceInput] = Field(default_factory=list, max_length=20, description=(
        "forces at points of moving links (docs/loads.md)"))
    friction: float = Field(0.0, ge=0, le=2, description="f in the pairs (kinetostatics by groups)")
    pair_radius: float = Field(0.0, ge=0, le=1, description="radius r of the revolute pairs' journals, m")
    load_factor: float = Field(1.0, ge=0, le=10, description=(
        "every useful load (each force's P or P_max, each point force's P, each moment's M₀) times this: the "
        "scenes' slider on the student's own mechanism scales the loads of its table"))

    def model(self) -> MassModel:
        """The core's mass model, each useful load's working value times ``load_factor``."""
        factor = self.load_factor
        return MassModel(tuple(LinkMass(m.link, m.mass, tuple(m.centre), m.inertia) for m in self.links),
                         self.gravity, tuple(f.force(factor) for f in self.forces),
                         tuple(m.moment(factor) for m in self.moments), self.friction, self.pair_radius,
                         tuple(p.force(factor) for p in self.point_forces))


class PairFrictionInput(BaseModel):
    """f and the journal radius r of one pair of a general mechanism (Chaika–Vasylenko (3.3))."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    f: float = Field(0.0, ge=0, le=2, description="friction coefficient")
    r: float = Field(0.0, ge=0, le=1, description="journal radius of a revolute pair, m (unused for a prismatic one)")
    beta: float = Field(0.0, ge=0, le=1e6, description=(
        "viscous friction β of the pair in the equation of motion: N·m·s (revolute), N·s/m (prismatic)"))

PairFrictionMap = dict[Annotated[str, Field(min_length=1, max_length=40)], PairFrictionInput]
PairFrictionField = Field(default_factory=dict, max_length=64, description=(
    "with mechanism 'general': f and r of single pairs by name (a joint, a guide, an RPR's slide, 'B/slot'), "
    "instead of masses.friction and masses.pair_radius"))


class MechanismChoice(BaseModel):
    """Which mechanism: one of the four with `params`, or 'general' with `linkage` and `masses`."""

    mechanism: DynamicsMechanism = Field(description="which mechanism; 'general': the one given in `linkage`")
    linkage: LinkageModel | None = Field(None, description=(
        "with mechanism 'general': the mechanism as data (GET /api/v1/mechanisms/general)"))
    masses: MassInput | None = Field(None, description=(
        "with mechanism 'general': each link's mass, centre of mass and J_S, the loads on sliders and links, g, "
        "and f, r of every pair"))
    pair_friction: PairFrictionMap = PairFrictionField
    params: dict[str, float] = Field(default_factory=dict, max_length=MAX_PARAMS, description="lengths in metres, as for /kinematics")

    @model_validator(mode="after")
    def general_fields(self):
        general = self.mechanism == "general"
        if general != (self.linkage is not None):
            raise ValueError("`linkage` goes with mechanism 'general', and only with it")
        if not general and (self.masses is not None or self.pair_friction):
            raise ValueError("`masses` and `pair_friction` go with mechanism 'general' (the four mechanisms take "
                             "`inertias`, `load`)")
        if general and self.params:
            raise ValueError("a general mechanism takes its lengths in `linkage`, not in `params`")
        return self


class ReductionRequest(MechanismChoice):
    """Reduced moment of inertia and of the resisting forces over one cycle; no equation of motion."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    inertias: InertiaInput = Field(default_factory=InertiaInput)
    load: LoadInput = Field(default_factory=LoadInput)
    n: int = Field(361, ge=3, le=10001, description="points over one closed cycle")
    omega: float = Field(1.0, ge=0, le=1e4, description="crank speed ω₁, rad/s: of the viscous moment β ω Σu² "
                                                        "and of cycle_moments' powers")
    iteration_phi: float = Field(math.pi / 2, ge=-100, le=100, description="crank angle of the friction iteration, rad")
    cycle: CycleInput | None = Field(None, description="cycle_moments: the crank-slider's cylinder, gravity, "
                                                       "efficiency and drawing (Chaika–Vasylenko §3.4)")
    outputs: list[Literal["inertia", "resisting", "friction_iteration", "errata", "cycle_moments"]] = Field(
        min_length=1, max_length=5, description="errata: the source's misprints of the formulas used (Eremyants "
                                                "(3.38)/(3.39) crank-slider, (3.50)/(3.53) slotted link), printed "
                                                "beside corrected with the value each gives; cycle_moments: the "
                                                "reduced moments and works over the cycle (Chaika–Vasylenko steps "
                                                "8–10, Fig. 3.7)")


class MotionRequest(MechanismChoice):
    """The machine's equation of motion: steady cycle and/or start-up."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    inertias: InertiaInput = Field(default_factory=InertiaInput)
    load: LoadInput = Field(default_factory=LoadInput)
    motor: MotorInput
    outputs: list[Literal["steady", "startup"]] = Field(min_length=1, max_length=2)
    omega0: float = Field(0.0, ge=0, le=1e4, description="crank speed at φ = 0 for the start-up, rad/s")
    omega_mean: float | None = Field(None, ge=1e-3, le=1e4, description=(
        "mean crank speed (ω_max + ω_min)/2, rad/s: needed when the moments depend on φ alone"))
    balance: bool = Field(False, description="add the constant crank moment that balances the cycle work (engine)")
    rtol: float = Field(1e-8, ge=1e-11, le=1e-2, description="relative tolerance of the steady cycle")
    max_cycles: int = Field(60, ge=1, le=200, description="cycles of the start-up at most")


class Erratum(BaseModel):
    key: str = Field(description="which misprint (a key of the translations)")
    source: str = Field(description="the book")
    equation: str = Field(description="the equation's number in the book")
    printed_value: float | None = Field(description="the value the formula as printed gives")
    printed_unit: str = Field(description="the unit of printed_value (a key of the translations)")
    corrected_value: float | None = Field(description="the value the corrected formula gives")
    unit: str = Field(description="the unit of corrected_value (a key of the translations)")


class ReductionResponse(BaseModel):
    phi: list[float] | None = Field(None, description="crank angles over one closed cycle, rad (absent when only "
                                                      "errata are asked: they are values of the cycle, not of φ)")
    errata: list[Erratum] | None = Field(None, description="the source's misprints of the formulas used, beside "
                                                          "the corrected ones, with the value each gives")
    inertia: dict | None = Field(None, description="J, dJ (kg·m², kg·m²/rad), mean J̄, variable part J̃, the parts "
                                                   "of each link, and the textbook approximation where one exists")
    resisting: dict | None = Field(None, description="M_c total and its parts (useful, dry, viscous), N·m; its "
                                                     "mean M_c0 in both conventions; friction angle θ = arctan f, rad; "
                                                     "the angles of self-locking, if any")
    friction_iteration: dict | None = Field(None, description="the successive approximations at iteration_phi: "
                                                              "forces of each step (N), ratio of the series, converged")
    numerics: NumericsModel | None = Field(None, description="how M_c and its mean M_c0 were computed")
    cycle_moments: dict | None = Field(None, description="M_P, M_kO, M_G, M_O, M_Σ (N·m) and their works (J) over "
                                                         "the cycle, the balancing moment, the powers (W), the "
                                                         "graphical integration with its scales, and its numerics")
    warnings: list[str]


class StartupOutput(BaseModel):
    phi: list[float] | None = Field(None, description="crank angle of the run, rad (at most ~4000 points)")
    omega: list[float] | None = Field(None, description="ω(φ) from the start, rad/s")
    t: list[float] | None = Field(None, description="t(φ) from the start, s")
    numerics: NumericsModel = Field(description="how the start-up was computed")


class MotionResponse(BaseModel):
    phi: list[float] | None = Field(None, description="crank angles over the steady cycle, rad")
    omega: list[float] | None = Field(None, description="ω(φ) on the steady cycle, rad/s (the phase portrait)")
    t: list[float] | None = Field(None, description="t(φ) from the start of the cycle, s")
    epsilon: list[float] | None = Field(None, description="ε(φ), rad/s²")
    omega_mean: float | None = Field(None, description="(ω_max + ω_min)/2, rad/s")
    omega_time_mean: float | None = Field(None, description="cycle angle / cycle time, rad/s")
    delta: float | None = Field(None, description="coefficient of speed fluctuation (ω_max − ω_min)/ω_mean")
    efficiency: float | None = Field(None, description="η = A_useful/A_driving over the steady cycle, A_driving = "
                                                       "A_useful + A_friction: 1 without friction, in [0, 1]; null "
                                                       "(with a warning) where the friction work is negative")
    works: dict | None = Field(None, description="works over the cycle, J: driving, useful, dry and viscous friction, net")
    numerics: NumericsModel | None = Field(None, description="how the steady cycle was computed")
    startup: StartupOutput | None = Field(None, description="start-up transient with its own numerics")
    warnings: list[str]


class FlywheelRequest(MechanismChoice):
    """Flywheel for a permissible δ: Merzalov, Gutyar, Wittenbauer and the exact periodic solution."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    inertias: InertiaInput = Field(default_factory=InertiaInput, description="J1 + J_rotor·i² is the group I "
                                                                            "the machine already has (I₁₀)")
    load: LoadInput = Field(default_factory=LoadInput)
    motor: MotorInput
    omega_mean: float = Field(ge=1e-3, le=1e4, description="mean crank speed (ω_max + ω_min)/2, rad/s")
    delta: float = Field(ge=1e-4, le=0.5, description="permissible coefficient of speed fluctuation [δ]")
    balance: bool = Field(True, description="constant crank moment M_c = A_д/Φ balancing the cycle work")
    width_ratio: float = Field(0.2, ge=0.02, le=2, description="disk width over diameter ψ_b = b/D")
    density: float = Field(7800.0, ge=500, le=25000, description="flywheel material density, kg/m³")
    outputs: list[Literal["flywheel"]] = Field(["flywheel"], max_length=1, description="the whole flywheel study")


class FlywheelResponse(BaseModel):
    phi: list[float] | None = Field(None, description="crank angles over one cycle, rad")
    methods: list[dict] | None = Field(None, description="for merzalov, gutyar, wittenbauer, exact: I_I (kg·m²), "
                                                         "additional I_доп = I_I − I₁₀, energy swing (J), δ achieved")
    flywheel_inertia: float | None = Field(None, description="flywheel inertia to fit (exact method), kg·m²")
    curves: dict | None = Field(None, description="A_д, A_с, A_Σ, T_II, ΔT_I (J), I_II (kg·m²), Δω, ω before and "
                                                  "after the flywheel (rad/s), ε (rad/s²)")
    wittenbauer: dict | None = Field(None, description="energy–mass diagram: tangent intercepts, slopes, contact "
                                                       "angles and the intersection (origin of the true axes)")
    disk: dict | None = Field(None, description="solid disk: diameter, width (m), mass (kg)")
    numerics: NumericsModel | None = Field(None, description="how the flywheel was computed")
    warnings: list[str]


class EstimateRequest(BaseModel):
    """A general mechanism (crank-driven) whose masses, loads and motor are to be estimated."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    linkage: LinkageModel


class FlywheelEstimate(BaseModel):
    """The flywheel request's part of the estimate: a constant motor moment, the mean speed and [δ]."""

    motor: MotorInput
    omega_mean: float = Field(description="mean crank speed ω_ср the flywheel is sized at, rad/s")
    delta: float = Field(description="permissible coefficient of speed fluctuation [δ]")
    balance: bool = Field(description="the motor moment balances the work per cycle")


class LoadPlaces(BaseModel):
    """Where a useful load may stand on the mechanism, each place with a first load on its slow stroke."""

    forces: list[SliderForceInput] = Field(description=(
        "one per sliding pair, named as in the kinematics' `slides` (masses.forces.joint): P = 1000 N, k = 0.1"))
    moments: list[LinkMomentInput] = Field(description=(
        "one per moving link, the crank included: M = P·l/2 with P = 1000 N and l the link's length, k = 0.1"))


class EstimateResponse(BaseModel):
    """A first estimate for a student's own mechanism (server/core/structure/estimate.py: uniform bars of 10 kg/m,
    J_S = ml²/12, a 1000 N load on the last frame slider's slow stroke with k = 0.1, a linear motor through a gear
    i = 10 that carries the load from rest); the same keys as a preset's "dynamics"."""

    masses: MassInput
    inertias: InertiaInput
    motor: MotorInput
    flywheel: FlywheelEstimate
    load_places: LoadPlaces
