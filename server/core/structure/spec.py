"""A mechanism as data: the frame, the input crank and class-II groups in the order they are attached.

Parsed from a plain dict (the JSON of the API and of ``content/mechanisms/*.json``); every refusal is a
GeometryError naming the field (``linkage.groups.1.outer.0``) and the reason in words.  Lengths in metres,
angles in radians (counter-clockwise from +x).

    {"frame": {"joints": {"O": [0, 0]}, "guides": {"g0": {"through": [0, 0], "angle": 0}}},
     "input": {"kind": "crank", "link": 1, "pivot": "O", "joint": "A", "length": 0.1,
               "angle0": 0, "sense": 1, "points": {...}, "new_guides": {...}},
     (or a slider: {"kind": "slider", "link": 1, "guide": "g0", "joint": "A", "travel": [0, 0.2], ...}:
      A = P + s u along the frame guide g0, the generalised coordinate s over its travel instead of φ over a turn)
     "groups": [{"kind": "RRP", "links": [2, 3], "outer": ["A"], "guide": "g0", "inner": "B",
                 "length": 0.3, "branch": 1, "points": {...}, "new_guides": {...}}, ...]}

Kinds and their fields (outer elements must exist already: frame, input or an earlier group):
RRR outer [B, D], inner C, lengths [BC, DC], branch;  RRP outer [B], guide, inner C, length BC, branch;
RPR outer [B, D] (block at B, lever pivot D), offset e of the slot from D, branch;
PRP guides [g₁, g₂], inner C;  RPP outer [B], guide, inner R (the slotted link's point on the guide),
angle α of the slot to the guide.
``points`` {name: {"link": k, "along": x, "across": y}} and ``new_guides`` {name: {"link": k, "along": x,
"across": y, "angle": α}} are fixed on one of the element's links, in that link's frame: from its origin
joint along its angle (crank: pivot → pin; RRR: B → C and D → C; RRP: B → C and the slider at C along the
guide; RPR: block at B and lever from D, both along the slot; PRP: C along each guide; RPP: block at B along
the slot, link j from R along the guide).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..mechanisms.base import GeometryError

KINDS = ("RRR", "RRP", "RPR", "PRP", "RPP")
KIND_NUMBER = {kind: k + 1 for k, kind in enumerate(KINDS)}      # Artobolevsky's kinds 1…5
MAX_LINKS = 20
MAX_NUMBER = 1000.0              # |length|, |coordinate| ≤ 1000 m, |angle| ≤ 1000 rad: squares stay finite


@dataclass(frozen=True)
class Attachment:
    """A point or a guide fixed on a link, in the link's frame."""

    name: str
    link: int
    along: float
    across: float
    angle: float = 0.0


@dataclass(frozen=True)
class Crank:
    link: int
    pivot: str
    joint: str
    length: float
    angle0: float
    sense: int
    points: tuple[Attachment, ...] = ()
    new_guides: tuple[Attachment, ...] = ()


@dataclass(frozen=True)
class SliderInput:
    """The input link as a slider on a frame guide: its joint A = P + s u, s the generalised coordinate over
    ``travel`` (s_min, s_max); every analog is then with respect to s (A′ = u, A″ = 0; the slider does not
    turn: its frame is A along the guide)."""

    link: int
    guide: str
    joint: str
    travel: tuple[float, float]
    points: tuple[Attachment, ...] = ()
    new_guides: tuple[Attachment, ...] = ()


@dataclass(frozen=True)
class Group:
    kind: str
    links: tuple[int, int]
    outer: tuple[str, ...]
    guides: tuple[str, ...]
    inner: str
    sizes: tuple[float, ...]          # RRR (BC, DC); RRP (BC,); RPR (the slot's offset e,); PRP, RPP ()
    branch: int
    angle: float
    points: tuple[Attachment, ...] = ()
    new_guides: tuple[Attachment, ...] = ()


@dataclass(frozen=True)
class Linkage:
    joints: dict[str, tuple[float, float]]
    guides: dict[str, tuple[tuple[float, float], float]]
    crank: Crank | SliderInput         # the input link
    groups: tuple[Group, ...] = field(default_factory=tuple)

    @property
    def coordinate_range(self) -> tuple[float, float]:
        """The generalised coordinate's cycle: the crank's turn 0…2π, or the input slider's travel (m)."""
        return self.crank.travel if isinstance(self.crank, SliderInput) else (0.0, 2 * math.pi)


def number(value, where: str, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise GeometryError(where, "must be a finite number", "not_finite")
    if abs(value) > MAX_NUMBER:
        raise GeometryError(where, f"must lie between −{MAX_NUMBER:g} and {MAX_NUMBER:g} (m or rad)", "out_of_range",
                            minimum=-MAX_NUMBER, maximum=MAX_NUMBER)
    if positive and value <= 0:
        raise GeometryError(where, "must be a positive length (m)", "negative_length")
    return float(value)


def name_of(value, where: str) -> str:
    if not isinstance(value, str) or not 1 <= len(value) <= 16 or "/" in value:
        raise GeometryError(where, "must be a name of 1 to 16 characters without '/'", "linkage_shape")
    return value


def mapping(value, where: str) -> dict:
    if value is None:
        return {}
    if not isinstance(value, dict) or len(value) > 64:
        raise GeometryError(where, "must be an object of at most 64 entries", "linkage_shape")
    return value


def xy(value, where: str) -> tuple[float, float]:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise GeometryError(where, "must be [x, y] in metres", "linkage_shape")
    return number(value[0], f"{where}.0"), number(value[1], f"{where}.1")


def branch_of(value, where: str) -> int:
    if value not in (1, -1) or isinstance(value, bool):
        raise GeometryError(where, "the assembly branch must be +1 or −1", "assembly_sign")
    return int(value)


def attachments(raw, where: str, links: tuple[int, ...], with_angle: bool) -> tuple[Attachment, ...]:
    out = []
    for name, item in mapping(raw, where).items():
        at = f"{where}.{name}"
        item = mapping(item, at)
        link = item.get("link", links[0])
        if link not in links:
            raise GeometryError(f"{at}.link", f"must be one of this element's links {list(links)}", "linkage_shape")
        out.append(Attachment(name_of(name, at), link, number(item.get("along", 0.0), f"{at}.along"),
                              number(item.get("across", 0.0), f"{at}.across"),
                              number(item.get("angle", 0.0), f"{at}.angle") if with_angle else 0.0))
    return tuple(out)


def parse_slider(raw: dict, where: str) -> SliderInput:
    """The input slider: a frame guide (checked in analysis.py), its joint and its travel s_min < s_max."""
    link = link_number(raw.get("link", 1), f"{where}.link")
    travel = raw.get("travel")
    if not isinstance(travel, (list, tuple)) or len(travel) != 2:
        raise GeometryError(f"{where}.travel", "the input slider's travel is [s_min, s_max] in metres",
                            "linkage_shape")
    travel = (number(travel[0], f"{where}.travel.0"), number(travel[1], f"{where}.travel.1"))
    if not travel[0] < travel[1]:
        raise GeometryError(f"{where}.travel", "s_min must be smaller than s_max", "slider_travel")
    return SliderInput(link, name_of(raw.get("guide"), f"{where}.guide"), name_of(raw.get("joint"), f"{where}.joint"),
                       travel, attachments(raw.get("points"), f"{where}.points", (link,), False),
                       attachments(raw.get("new_guides"), f"{where}.new_guides", (link,), True))


def parse_crank(raw, where: str) -> Crank | SliderInput:
    raw = mapping(raw, where)
    if raw.get("kind", "crank") == "slider":
        return parse_slider(raw, where)
    if raw.get("kind", "crank") != "crank":
        raise GeometryError(f"{where}.kind", "the input link is a crank ('crank') or a slider ('slider')",
                            "linkage_shape")
    link = link_number(raw.get("link", 1), f"{where}.link")
    sense = raw.get("sense", 1)
    if sense not in (1, -1) or isinstance(sense, bool):
        raise GeometryError(f"{where}.sense", "must be +1 (counter-clockwise) or −1 (clockwise)", "linkage_shape")
    return Crank(link, name_of(raw.get("pivot"), f"{where}.pivot"), name_of(raw.get("joint"), f"{where}.joint"),
                 number(raw.get("length"), f"{where}.length", positive=True),
                 number(raw.get("angle0", 0.0), f"{where}.angle0"), int(sense),
                 attachments(raw.get("points"), f"{where}.points", (link,), False),
                 attachments(raw.get("new_guides"), f"{where}.new_guides", (link,), True))


def link_number(value, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 99:
        raise GeometryError(where, "a moving link is numbered by a whole number 1…99 (0 is the frame)", "linkage_shape")
    return value


def parse_group(raw, where: str) -> Group:
    raw = mapping(raw, where)
    kind = raw.get("kind")
    if kind not in KINDS:
        raise GeometryError(f"{where}.kind", f"must be one of {', '.join(KINDS)} (class II groups)", "linkage_shape")
    links = raw.get("links")
    if not isinstance(links, (list, tuple)) or len(links) != 2:
        raise GeometryError(f"{where}.links", "a class II group has two links: [i, j]", "linkage_shape")
    links = (link_number(links[0], f"{where}.links.0"), link_number(links[1], f"{where}.links.1"))
    if links[0] == links[1]:
        raise GeometryError(f"{where}.links", "the group's two links must differ", "linkage_shape")
    n_outer, n_guides = {"RRR": (2, 0), "RRP": (1, 1), "RPR": (2, 0), "PRP": (0, 2), "RPP": (1, 1)}[kind]
    outer = tuple(raw.get("outer") or ())
    if len(outer) != n_outer:
        raise GeometryError(f"{where}.outer", f"{kind} takes {n_outer} outer joint(s)", "linkage_shape")
    outer = tuple(name_of(o, f"{where}.outer.{k}") for k, o in enumerate(outer))
    guides = tuple(raw.get("guides") or ()) if kind == "PRP" else (raw.get("guide"),) * n_guides
    if len(guides) != n_guides:
        raise GeometryError(f"{where}.guides", f"{kind} slides along {n_guides} guides [g₁, g₂]", "linkage_shape")
    guides = tuple(name_of(g, f"{where}.guide" if kind != "PRP" else f"{where}.guides.{k}")
                   for k, g in enumerate(guides))
    lengths: tuple[float, ...] = ()
    if kind == "RRR":
        raw_l = raw.get("lengths")
        if not isinstance(raw_l, (list, tuple)) or len(raw_l) != 2:
            raise GeometryError(f"{where}.lengths", "RRR takes two lengths [BC, DC] in metres", "linkage_shape")
        lengths = tuple(number(v, f"{where}.lengths.{k}", positive=True) for k, v in enumerate(raw_l))
    elif kind == "RRP":
        lengths = (number(raw.get("length"), f"{where}.length", positive=True),)
    elif kind == "RPR":
        lengths = (number(raw.get("offset", 0.0), f"{where}.offset"),)
    inner = name_of(raw.get("inner"), f"{where}.inner") if kind != "RPR" else name_of(
        raw.get("inner", f"s{links[0]}{links[1]}"), f"{where}.inner")
    angle = number(raw.get("angle", math.pi / 2), f"{where}.angle") if kind == "RPP" else 0.0
    if kind == "RPP" and abs(math.sin(angle)) < 1e-6:
        raise GeometryError(f"{where}.angle", "the slot must cross the guide (α ≠ 0, π): parallel, the group "
                                              "cannot be assembled", "rpp_parallel")
    branch = branch_of(raw.get("branch", 1), f"{where}.branch") if kind in ("RRR", "RRP", "RPR") else 1
    return Group(kind, links, outer, guides, inner, lengths, branch, angle,
                 attachments(raw.get("points"), f"{where}.points", links, False),
                 attachments(raw.get("new_guides"), f"{where}.new_guides", links, True))


def parse(raw) -> Linkage:
    """The linkage from its JSON; names and numbers checked here, the order of attachment in analysis.py."""
    raw = mapping(raw, "linkage")
    frame = mapping(raw.get("frame"), "linkage.frame")
    joints = {name_of(k, f"linkage.frame.joints.{k}"): xy(v, f"linkage.frame.joints.{k}")
              for k, v in mapping(frame.get("joints"), "linkage.frame.joints").items()}
    guides = {}
    for k, v in mapping(frame.get("guides"), "linkage.frame.guides").items():
        at = f"linkage.frame.guides.{k}"
        v = mapping(v, at)
        through = v.get("through", [0.0, 0.0])
        point = joints.get(through) if isinstance(through, str) else xy(through, f"{at}.through")
        if point is None:
            raise GeometryError(f"{at}.through", f"no frame joint '{through}'", "unknown_element", element=through)
        guides[name_of(k, at)] = (point, number(v.get("angle", 0.0), f"{at}.angle"))
    groups = raw.get("groups") or []
    if not isinstance(groups, list):
        raise GeometryError("linkage.groups", "must be a list of groups", "linkage_shape")
    if len(groups) > MAX_LINKS:
        raise GeometryError("linkage.groups", f"at most {MAX_LINKS} links: {len(groups)} groups are too many",
                            "too_many_links")
    return Linkage(joints, guides, parse_crank(raw.get("input"), "linkage.input"),
                   tuple(parse_group(g, f"linkage.groups.{k}") for k, g in enumerate(groups)))
