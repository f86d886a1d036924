"""Scenes (lessons) and interface texts, read from content/ as data: no Python per lesson."""
from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from .expression import parse
from ..paths import CONTENT
from .scene_files import ContentError, resolved_scene

CONTENT_DIR = CONTENT
LANGUAGES = ("ru", "uk", "en")
DEFAULT_LANGUAGE = "ru"

Text = dict[str, str]


class Slider(BaseModel):
    """A slider sets params[param] = value × params[scale] (or value itself when scale is empty).

    In dynamics scenes ``param`` and ``scale`` are dotted paths into the request body
    ("load.f", "params.l2", "inertias.m3"), and ``to_si`` converts the shown value to SI
    (π/180 for a slider in degrees).
    """

    id: str
    param: str
    also: list[str] = Field(default_factory=list, description="more paths set to the same value (one f for all pairs)")
    scale: str = ""
    to_si: float = 1.0
    min: float
    max: float
    step: float
    default: float
    label: Text
    english: Text | None = Field(default=None, description="the other convention shown beside the slider")
    log: bool = False
    locked: bool = Field(False, description="an assignment fixed this value: the student cannot move it")
    relative: dict[str, float] | None = Field(None, description="min, max, step, default as multiples of the "
                                                                "request's value at param (a mechanism from the address)")


class Toggle(BaseModel):
    id: str
    param: str
    options: list[float | str]
    default: float | str
    label: Text
    option_labels: list[Text]
    display: Literal["radio", "select"] = Field("radio", description="radio buttons, or a drop-down list "
                                                                      "(a table's rows)")


class Variant(BaseModel):
    """One mechanism set-up offered in a scene."""

    id: str
    mechanism: str
    label: Text
    text: Text
    fixed: dict[str, float] = {}
    sliders: list[Slider] = []
    toggles: list[Toggle] = []
    overlay: Slider | None = None
    overlay_values: list[float] = []
    panels: list[str]
    request: dict = Field(default_factory=dict, description="dynamics scenes: the request body before the sliders")
    address: dict | None = Field(None, description="the mechanism comes from the page address: request keys → "
                                                   "dotted paths in its documents m, d (scene_files.py)")


class AngleGrid(BaseModel):
    """The crank angles a student may choose, in degrees: min, min + step, …, max."""

    model_config = ConfigDict(extra="forbid")
    min: float = Field(ge=0, le=360, allow_inf_nan=False)
    max: float = Field(ge=0, le=360, allow_inf_nan=False)
    step: float = Field(ge=0.1, le=180, allow_inf_nan=False)

    @model_validator(mode="after")
    def on_grid(self):
        if self.min >= self.max:
            raise ValueError("min must be below max")
        if abs((self.max - self.min) / self.step - round((self.max - self.min) / self.step)) > 1e-9:
            raise ValueError("max − min must be a whole number of steps")
        return self

    def holds(self, angle: float) -> bool:
        k = (angle - self.min) / self.step
        return self.min - 1e-9 <= angle <= self.max + 1e-9 and abs(k - round(k)) <= 1e-9


class Readout(BaseModel):
    """One number read from an endpoint's answer: ``path`` in it, reduced over φ by ``reduce``."""

    model_config = ConfigDict(frozen=True)
    outputs: tuple[str, ...]
    path: str
    reduce: Literal["value", "max", "min"] = "value"


class Question(BaseModel):
    """A question an assignment can ask about a scene: a number the server computes from the student's
    variant. ``path`` names it in the endpoint's answer ("flywheel_inertia", "outputs.u31"), ``reduce``
    turns an array over φ into one number; ``hides`` are the outputs the student's page must not ask for
    (they would show the answer), and with them every panel that shows one.

    Kinds: ``readout`` (that number); ``at_angle`` (the array at a crank angle the student chooses on the
    ``angle`` grid and states with the answer; kinematics scenes); ``combination`` (``expression`` over the
    named ``readouts``, server/lessons/expression.py); ``prediction`` (the readout, predicted before the
    panels showing its ``hides`` open on the student's page: they open once the question is closed)."""

    id: str
    label: Text
    kind: Literal["readout", "at_angle", "combination", "prediction"] = "readout"
    unit: str = Field("", description="key of the unit in content/i18n (units_<unit>): m, kg_m2, N_m, rad_s")
    outputs: list[str] = Field(default_factory=list, description="outputs to request when computing the answer")
    path: str = ""
    reduce: Literal["value", "max", "min"] = "value"
    angle: AngleGrid | None = Field(None, description="at_angle: the angles the student may choose, degrees")
    readouts: dict[str, Readout] = Field(default_factory=dict, description="combination: the named readouts")
    expression: str = Field("", description="combination: e.g. du_max / du_min")
    tolerance: float = Field(0.02, gt=0, lt=1, description="relative, by default")
    variants: list[str] = Field(default_factory=list, description="the variants it applies to (empty: all)")
    hides: list[str]

    @model_validator(mode="after")
    def complete(self):
        if self.kind == "combination":
            if not self.readouts:
                raise ValueError(f"question {self.id}: a combination needs readouts")
            parse(self.expression, set(self.readouts))
        elif not (self.outputs and self.path):
            raise ValueError(f"question {self.id}: outputs and path are needed")
        if (self.kind == "at_angle") != (self.angle is not None):
            raise ValueError(f"question {self.id}: an angle grid goes with kind at_angle, and only with it")
        return self

    def readout_list(self) -> list[Readout]:
        """Every readout the answer is computed from."""
        if self.kind == "combination":
            return list(self.readouts.values())
        return [Readout(outputs=self.outputs, path=self.path, reduce=self.reduce)]


class Scene(BaseModel):
    id: str = Field(pattern=r"^[a-z0-9]+(-[a-z0-9]+)*$", description="lowercase words joined by hyphens: its URL")
    former_ids: list[str] = Field(default_factory=list, description=(
        "ids it had before: their URLs redirect here, and assignments made with them still find it"))
    order: int
    kind: Literal["kinematics", "dynamics", "project"] = Field("kinematics", description=(
        "project: the course project of a linkage (endpoint course-project), computed on /project; the scene "
        "lists its design data and opens them there and in the editor"))
    endpoint: Literal["kinematics", "reduction", "motion", "flywheel", "elastic", "forces", "wear",
                      "angular-acceleration", "bearings", "motor-characteristic",
                      "flywheel-analysis", "friction-influence", "course-project"] = "kinematics"
    source: Text
    title: Text
    summary: Text
    text: Text
    details: Text | None = Field(None, description=(
        "the sources' details (equations, misprints, conventions), folded below the short task-oriented text"))
    outputs: list[str]
    panels: dict[str, dict]
    variants: list[Variant]
    presets: list[dict] = Field(default_factory=list, description="named ranges of a slider, e.g. [δ] by machine type")
    questions: list[Question] = Field(default_factory=list, description="what an assignment can ask")

    @model_validator(mode="after")
    def answerable(self):
        """A question at a chosen angle needs the kinematics endpoint, which takes the angles themselves."""
        for q in self.questions:
            if q.kind == "at_angle" and self.kind != "kinematics":
                raise ValueError(f"question {q.id}: kind at_angle needs a kinematics scene")
        return self


def _check_languages(texts: dict, where: str) -> None:
    missing = [lang for lang in LANGUAGES if not texts.get(lang)]
    if missing:
        raise ValueError(f"{where}: missing translation {missing}")


@lru_cache(maxsize=1)
def scene_documents() -> dict[str, dict]:
    """Every scene file of content/scenes (by file stem) as the app reads it."""
    return read_scene_documents(CONTENT_DIR)


def read_scene_documents(content: Path) -> dict[str, dict]:
    """The scene files of content/scenes with shared sliders (content/sliders.json), inheriting variants and
    mechanism presets (content/mechanisms) and the pickers of content/tables resolved (scene_files.py), each slider
    checked with the file, the variant and the slider named."""
    shared = json.loads((content / "sliders.json").read_text(encoding="utf-8"))
    presets = {path.stem: json.loads(path.read_text(encoding="utf-8"))
               for path in sorted((content / "mechanisms").glob("*.json"))}
    tables = {path.stem: json.loads(path.read_text(encoding="utf-8"))
              for path in sorted((content / "tables").glob("*.json"))}
    documents = {}
    for path in sorted((content / "scenes").glob("*.json")):
        document = resolved_scene(json.loads(path.read_text(encoding="utf-8")), path.name, shared, presets, tables)
        for variant in document["variants"]:
            for index, slider in enumerate([*variant.get("sliders", []), variant.get("overlay") or {}]):
                if isinstance(slider, dict) and slider:
                    _check_slider(slider, f"{path.name}: variant {variant['id']}, slider {slider.get('id', index)}")
        documents[path.stem] = document
    return documents


def _check_slider(slider: dict, where: str) -> None:
    try:
        Slider.model_validate(slider)
    except ValidationError as error:
        reasons = "; ".join(f"{'.'.join(map(str, e['loc'])) or 'slider'}: {e['msg']}" for e in error.errors())
        raise ContentError(f"{where}: {reasons}") from None


class Catalogue(dict):
    """The scenes by id, in order; a former id (``Scene.former_ids``) finds its scene too, though it is not listed:
    ``catalogue.get("flywheel_analysis")`` is the scene now called "flywheel-analysis"."""

    def __init__(self, ordered: list[Scene]):
        super().__init__((s.id, s) for s in ordered)
        self.former = {old: s for s in ordered for old in s.former_ids}

    def __missing__(self, scene_id: str) -> Scene:
        if scene_id in self.former:
            return self.former[scene_id]
        raise KeyError(scene_id)

    def get(self, scene_id, default=None):
        return super().get(scene_id) or self.former.get(scene_id, default)

    def __contains__(self, scene_id) -> bool:
        return super().__contains__(scene_id) or scene_id in self.former


@lru_cache(maxsize=1)
def scenes() -> Catalogue:
    """All scenes in content/scenes, ordered, each checked to carry all three languages; former ids find theirs."""
    loaded = []
    for name, document in scene_documents().items():
        where = f"{name}.json"
        scene = Scene.model_validate(document)
        for key in ("title", "summary", "text", "source") + ("details",) * (scene.details is not None):
            _check_languages(getattr(scene, key), f"{where}: {key}")
        for variant in scene.variants:
            _check_languages(variant.label, f"{where}: {variant.id}.label")
        for question in scene.questions:
            _check_languages(question.label, f"{where}: question {question.id}")
        loaded.append(scene)
    taken = [i for s in loaded for i in (s.id, *s.former_ids)]
    if len(taken) != len(set(taken)):
        raise ContentError(f"scene ids or former ids used twice: {sorted({i for i in taken if taken.count(i) > 1})}")
    return Catalogue(sorted(loaded, key=lambda s: s.order))


@lru_cache(maxsize=len(LANGUAGES))
def interface_texts(lang: str) -> dict[str, str]:
    """Interface strings of one language (content/i18n/<lang>.json)."""
    return json.loads((CONTENT_DIR / "i18n" / f"{lang}.json").read_text(encoding="utf-8"))


def language(requested: str | None) -> str:
    return requested if requested in LANGUAGES else DEFAULT_LANGUAGE
