"""A general mechanism: the input crank and class-II groups composed in order (server/core/structure/),
behind the one ``Mechanism`` interface.

Outputs (by name; nothing unrequested is computed): joint positions and their first and second analogs
(x′, y′, x″, y″), link angles θ with θ′, θ″, slides along guides and slots with s′, s″, the structural analysis,
special positions (each group's limits of assembly, found exactly by bisection; dead positions, output
reversals), and the velocity and acceleration plans at one angle.  Where a group cannot be assembled the values are
NaN (null in the answer) with a sentence naming the group and the angles; where it closes nowhere the mechanism is
refused.  A group is named as the structural formula names it ("II₂(2,3)", analysis.group_name).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..structure import change_points
from ..structure.analysis import analyse, group_name
from ..structure.compose import Composition, compose
from ..structure.plans import plans
from ..structure.spec import Linkage, SliderInput, parse
from .base import (Evaluation, GeometryError, Notice, OutputSpec, SpecialPosition, angle_ranges, ranges_text,
                   wrap_angle)
from .mechanism import Mechanism

CHECK_POINTS = 721               # the full turn checked for assembly at 0.5°
LIMIT_STEPS = 46                 # a grid step halved 46 times: 0.5° → 1.2e-16 rad, below round-off
SMALL_TRANSMISSION = np.sin(np.radians(10))    # as the four-bar's warning (FourBar.proximity_warnings)

GENERAL_OUTPUTS = (
    OutputSpec("joints", "m", "joint and point coordinates (x, y) over φ"),
    OutputSpec("joints_d1", "m", "first analogs (x′, y′) = dr/dφ of every joint: velocity v = r′ω₁"),
    OutputSpec("joints_d2", "m", "second analogs (x″, y″) = d²r/dφ²: acceleration a = r″ω₁² + r′ε₁"),
    OutputSpec("angles", "rad", "angle θ of every moving link, counter-clockwise from +x"),
    OutputSpec("angles_d1", "1", "θ′ = dθ/dφ of every link (ω = θ′ω₁)"),
    OutputSpec("angles_d2", "1", "θ″ = d²θ/dφ² of every link"),
    OutputSpec("slides", "m", "slider travel s along its guide or slot, by pair (joint/guide)"),
    OutputSpec("slides_d1", "m", "s′ = ds/dφ (sliding velocity analog)"),
    OutputSpec("slides_d2", "m", "s″ = d²s/dφ²"),
    OutputSpec("structure", "1", "structural analysis: n, p₅, p₄, W, the structural formula, the class"),
    OutputSpec("special", "rad", "per group: limits of assembly, dead positions, the smallest |sin| of its "
               "transmission angle, output reversals (extreme positions of its links and slides); each with kind, "
               "phi, group, group_kind, link or slide, value and text (in the request's language)"),
    OutputSpec("plan", "m/s, m/s²", "velocity and acceleration plans at one angle (request field `plan`)"),
)


@dataclass(frozen=True)
class GroupSpecial(SpecialPosition):
    """A special position of one group as data: the group's number (as in linkage.groups), its kind and name
    ("II₂(2,3)"), the link or slide it concerns (output reversals), and at a limit of assembly whether the group
    assembles just after it (at larger φ); the English ``description`` is for scripts, the pages say it from
    these fields (server/api/messages.py: special_text)."""

    group: int = 0
    group_kind: str = ""
    link: int | None = None
    slide: str | None = None
    name: str = ""
    assembles_after: bool | None = None

    def as_dict(self) -> dict:
        return super().as_dict() | {"group": self.group, "group_kind": self.group_kind, "link": self.link,
                                    "slide": self.slide, "name": self.name, "assembles_after": self.assembles_after}


class GeneralMechanism(Mechanism):
    """A linkage given as data (structure/spec.py); ``params`` are unused (the lengths are in the data)."""

    name = "general"
    title = "Mechanism composed of class-II structural groups"
    conventions = ("Frame x to the right, y up; angles counter-clockwise from +x; the crank angle θ₁ = θ₀ + σφ, or "
                   "an input slider's displacement s along its frame guide (then `phi` holds s in m over its travel, "
                   "and every analog is with respect to s: θ′ in 1/m, x′ dimensionless). Groups attach in order to "
                   "joints and guides that exist already.")
    params = ()

    def __init__(self, linkage: dict | Linkage):
        self.linkage = linkage if isinstance(linkage, Linkage) else parse(linkage)
        self.structure = analyse(self.linkage)

    @property
    def outputs(self):
        return GENERAL_OUTPUTS

    @property
    def sliding_pairs(self):
        return tuple(compose(self.linkage, np.zeros(1)).slides)

    def require_crank(self, what: str) -> None:
        """Refuse a slider-driven linkage where ``what`` (the dynamics, the kinetostatics) needs the crank's
        full turn as the machine's cycle."""
        if isinstance(self.linkage.crank, SliderInput):
            raise GeometryError("linkage.input.kind", f"{what} of a general mechanism takes a crank as the input "
                                "link (its cycle is the crank's turn); a slider input is for the kinematics",
                                "slider_input_kinematics_only", what=what)

    def require_full_turn(self) -> Composition:
        """Refuse a linkage one of whose groups cannot be assembled somewhere on the crank's turn (checked at
        0.5°): a machine needs the whole turn (every dynamics endpoint and the dynamics estimate answer alike).
        The composition over the turn is handed back."""
        turn = compose(self.linkage, self.turn())
        for k, group in enumerate(turn.groups):
            if not group.closes.all():
                ranges = ranges_text(angle_ranges(turn.phi, ~group.closes))
                raise GeometryError(f"linkage.groups.{k}", f"the {group.kind} group cannot be assembled at "
                                    f"φ = {ranges}: the crank cannot turn fully, a machine needs the whole turn",
                                    "no_full_turn", group=k)
        return turn

    def require_even_change_points(self) -> None:
        """Refuse a machine one of whose groups passes an odd number of change points a turn: continued through
        them it comes back to its start only after two turns, and a machine's cycle is one turn."""
        points = change_points.find(self.linkage)
        for k, group in enumerate(self.linkage.groups):
            if change_points.per_turn(points, k) % 2:
                name = group_name(group.kind, list(group.links))
                raise GeometryError(f"linkage.groups.{k}", f"group {name} passes an odd number of change points a "
                                    "turn: continued through them the linkage comes back to its start only after "
                                    "two turns, and a machine's cycle is one turn", "change_point_odd", group=name)

    def turn(self, points: int = CHECK_POINTS) -> np.ndarray:
        """The generalised coordinate over its cycle: the crank's turn, or the input slider's travel (m)."""
        return np.linspace(*self.linkage.coordinate_range, points)

    def check_geometry(self, p) -> None:
        """Refuse a linkage one of whose groups closes at no crank angle of the turn (checked at 0.5°)."""
        self.check_closure(compose(self.linkage, self.turn()))

    def check_closure(self, comp: Composition) -> None:
        """Where a group closes nowhere on ``comp``'s angles, look again over the whole turn at 0.5°; refuse
        the linkage if it closes nowhere there either."""
        for k, group in enumerate(comp.groups):
            if group.undetermined is not None and comp.phi.size > 1 and group.undetermined.all():
                raise GeometryError(f"linkage.groups.{k}", f"the RPR group's block joint {self.linkage.groups[k].outer[0]} "
                                    f"lies on the lever's pivot {self.linkage.groups[k].outer[1]} at every crank angle: "
                                    "the slot through the pivot may point any way, the lever's angle is not "
                                    "determined (the lever is free)", "rpr_block_on_pivot", group=k,
                                    block=self.linkage.groups[k].outer[0], pivot=self.linkage.groups[k].outer[1])
        if all(group.closes.any() for group in comp.groups):
            return
        turn = compose(self.linkage, self.turn())
        for k, group in enumerate(turn.groups):
            if not group.closes.any():
                raise GeometryError(f"linkage.groups.{k}", f"the {group.kind} group cannot be assembled at any "
                                    "crank angle: its lengths cannot close the loop", "never_closes", group=k)

    def evaluate(self, p, phi, wanted) -> Evaluation:
        """The outputs at φ from the groups composed in order of attachment (Chaika–Vasylenko §3.1), the
        analogs z′, z″ as in Eremyants §2.1; undefined (NaN) near a change point."""
        return self.outputs_of(compose(self.linkage, phi, "null"), wanted)

    def outputs_of(self, comp: Composition, wanted) -> Evaluation:
        """The wanted array outputs of a composed linkage."""
        phi = comp.phi
        ev = Evaluation(phi)
        ev.warnings = assembly_notices(comp, self.linkage)
        ordered = phi.size > 1 and bool(np.all(np.diff(phi) > 0))
        for name in wanted:
            if name.startswith("joints"):
                part = {"joints": "z", "joints_d1": "d1", "joints_d2": "d2"}[name]
                table = {j: xy_pairs(getattr(pt, part)) for j, pt in comp.joints.items()}
                if name == "joints":
                    ev.joints = table
                ev.values[name] = table
            elif name.startswith("angles"):
                part = {"angles": "th", "angles_d1": "d1", "angles_d2": "d2"}[name]
                ev.values[name] = {str(k): unwrapped(getattr(a, part), part == "th" and ordered)
                                   for k, (_, a) in sorted(comp.links.items())}
            elif name.startswith("slides"):
                part = {"slides": "s", "slides_d1": "d1", "slides_d2": "d2"}[name]
                ev.values[name] = {k: getattr(s, part) for k, s in comp.slides.items()}
        return ev

    def sliding_squares(self, p, ev):
        """S(φ) = Σ s′² over the prismatic pairs (Eremyants (3.15)–(3.17)), from the composed slides."""
        comp = compose(self.linkage, ev.phi)
        return sum((s.d1**2 for s in comp.slides.values()), np.zeros_like(ev.phi, dtype=float))

    def special_positions(self, p) -> list[SpecialPosition]:
        turn = compose(self.linkage, self.turn())
        return sorted(special_positions(turn, self.linkage) + reversals(self.linkage, turn), key=lambda sp: sp.phi)

    def plan(self, phi: float, omega1: float, epsilon1: float) -> dict:
        return plans(compose(self.linkage, np.array([float(phi)]), "null"), omega1, epsilon1)

    def describe(self, p):
        return self.structure


def xy_pairs(z: np.ndarray) -> np.ndarray:
    """(N, 2) array of (x, y) from complex z: the same memory read as float pairs."""
    return np.ascontiguousarray(z, dtype=complex).view(np.float64).reshape(-1, 2)


def unwrapped(values: np.ndarray, unwrap: bool) -> np.ndarray:
    """A link's angle continuous along an ordered grid (no 2π jumps), NaN where the group does not close."""
    if not unwrap or not np.isfinite(values).all():
        return values
    return np.unwrap(values)


def assembly_limits(linkage: Linkage, comp: Composition, steps: int = LIMIT_STEPS) -> dict[tuple[int, int], float]:
    """Every group's limits of assembly, exact: {(group k, grid step e): φ} for each step [φ_e, φ_e+1] of
    ``comp`` over which the group's loop stops or starts closing (RRR: the triangle BCD flattens, |BD| = BC + CD
    or |BC − CD|; RRP: the rod perpendicular to the guide; RPR: |BD| = e).  The step is bisected ``steps`` times
    on whether the group closes at its middle (one composition of the linkage per halving for all steps of all
    groups at once): a 0.5° step ends within 0.5°·2⁻⁴⁶ ≈ 1.2·10⁻¹⁶ rad of the limit, the round-off of the
    closure's own test."""
    brackets = [(k, int(e)) for k, group in enumerate(comp.groups)
                for e in np.flatnonzero(group.closes[:-1] != group.closes[1:])]
    if not brackets:
        return {}
    edges = np.array([e for _, e in brackets])
    low, high = comp.phi[edges].astype(float), comp.phi[edges + 1].astype(float)
    closed_low = np.array([comp.groups[k].closes[e] for k, e in brackets])
    for _ in range(steps):
        middle = 0.5 * (low + high)
        with np.errstate(invalid="ignore", divide="ignore"):       # at a limit itself the analogs are unbounded
            fine = compose(linkage, middle)
        closes = np.array([fine.groups[k].closes[i] for i, (k, _) in enumerate(brackets)])
        low, high = np.where(closes == closed_low, middle, low), np.where(closes == closed_low, high, middle)
    return {bracket: float(0.5 * (a + b)) for bracket, a, b in zip(brackets, low, high)}


def unassembled_ranges(phi: np.ndarray, closes: np.ndarray, limits: dict[int, float]) -> list[list[float]]:
    """The stretches (degrees, [from, to]) where a group does not close: each run of grid points without a
    closure, its ends moved out to the exact limits ``limits`` {grid step: φ} (the grid's own ends where the
    run reaches them)."""
    ranges = []
    for start, end in runs(~closes):
        a = limits.get(start - 1, phi[start]) if start > 0 else phi[0]
        b = limits.get(end, phi[end]) if end < phi.size - 1 else phi[-1]
        ranges.append([float(np.degrees(a)), float(np.degrees(b))])
    return ranges


def solved_name(group) -> str:
    """A solved group's name in the structural formula, from its kind and its two links (in order)."""
    return group_name(group.kind, list(group.links))


def runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) index of every run of True in ``mask``."""
    edges = np.flatnonzero(np.diff(np.concatenate(([0], mask.astype(np.int8), [0]))))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2])]


def change_point_runs(comp: Composition, k: int, points: tuple) -> np.ndarray:
    """Grid points of group k that belong to a change point: the run of |sin| < SMALL_TRANSMISSION around each
    of its change points (periodic over the turn).  The links come in line there because of the change
    point, where the continuing motion's analogs stay bounded: no dead position."""
    phi, det = comp.phi, np.abs(comp.groups[k].determinant)
    mask = np.zeros(phi.size, bool)
    small = ~(det >= SMALL_TRANSMISSION)
    periodic = phi.size > 2 and abs(phi[-1] - phi[0] - change_points.TURN) < 1e-9
    for cp in points:
        if cp.group != k:
            continue
        distance = np.abs(change_points.offset(phi, cp.phi))
        start = int(np.argmin(distance))
        if distance[start] > 2 * (phi[1] - phi[0] if phi.size > 1 else 0.0) + cp.half_width:
            continue
        for step in (1, -1):
            i = start
            for _ in range(phi.size):
                if not small[i] and i != start:
                    break
                mask[i] = True
                i += step
                if not 0 <= i < phi.size:
                    if not periodic:
                        break
                    i = 1 if step == 1 else phi.size - 2
                    mask[0 if step == -1 else -1] = True
    if periodic:
        mask[0] = mask[-1] = mask[0] | mask[-1]
    return mask


def change_point_mask(linkage: Linkage, phi: np.ndarray) -> np.ndarray:
    """Where any group is within a change point's neighbourhood (its analogs undefined)."""
    points = change_points.find(linkage)
    masks = [m for k in range(len(linkage.groups)) if (m := change_points.near(points, k, phi)) is not None]
    return np.any(masks, axis=0) if masks else np.zeros(np.shape(phi), bool)


def undefined_at(value, mask: np.ndarray):
    """Every array over the angles in ``value`` (nested in dicts) NaN where ``mask`` holds: the values at points
    near a change point, sent as null."""
    if not mask.any():
        return value
    if isinstance(value, dict):
        return {key: undefined_at(v, mask) for key, v in value.items()}
    if isinstance(value, np.ndarray) and value.shape[-1:] == mask.shape:
        return np.where(mask, np.nan, value)
    return value


def change_point_notices(linkage: Linkage, integrated: bool = False) -> list[Notice]:
    """A sentence per change point (which group, at which angle, its neighbourhood, the branch kept), one per
    group that passes an odd number a turn, and (``integrated``: an answer with means over the cycle or the
    motion) one saying that those integrate the continuing motion's limit there."""
    notes = []
    points = change_points.find(linkage)
    for cp in points:
        group = linkage.groups[cp.group]
        name = group_name(group.kind, list(group.links))
        after = "+1" if group.branch * change_points.signs(points, cp.group, np.array([cp.phi + cp.half_width]))[0] > 0 \
            else "−1"
        notes.append(Notice("group_change_point",
                            f"Group {name} {group.kind} passes a change point at φ = {np.degrees(cp.phi):.1f}°: its "
                            "loop lies flat (its links in line), two assemblies meet there and the crank's motion "
                            "does not determine the velocities; the analogs within "
                            f"±{np.degrees(cp.half_width):.3f}° of it are undefined (null). The linkage is kept "
                            "moving as it was drawn: past the change point its assembly is σ = "
                            f"{after} (angles continuous, velocities bounded; a parallelogram stays a "
                            "parallelogram).",
                            {"group": name, "index": cp.group, "kind": group.kind,
                             "phi": float(np.degrees(cp.phi)), "width": float(np.degrees(cp.half_width)),
                             "sigma": after}))
    for k, group in enumerate(linkage.groups):
        if change_points.per_turn(points, k) % 2:
            name = group_name(group.kind, list(group.links))
            notes.append(Notice("group_change_point_odd",
                                f"Group {name} {group.kind} passes an odd number of change points a turn: kept on "
                                "its continuing motion it comes back to its start after two turns only (the second "
                                "on the other assembly); the values shown are the first turn's.",
                                {"group": name, "index": k, "kind": group.kind}))
    if integrated and points:
        notes.append(Notice("change_point_limit", "At the change points the values at single angles are not sent "
                            "(null); the means over the cycle, the motion and the flywheel integrate the continuing "
                            "motion's limit there (the change point itself is a single angle)."))
    return notes


def assembly_notices(comp: Composition, linkage: Linkage | None = None, integrated: bool = False) -> list[Notice]:
    """A sentence per group that cannot be assembled at some of the angles (which group, which angles: with the
    ``linkage`` given, between its exact limits of assembly, else between grid points), or that comes close to a
    dead position: |sin| of the angle between its links (the transmission angle μ for RRR) below sin 10°, the
    threshold the four-bar module warns at; the analogs grow as 1/sin μ there.  The group is named as in the
    structural formula ("II₁(2,3)": solved_name)."""
    notes = change_point_notices(linkage, integrated) if linkage is not None else []
    limits = assembly_limits(linkage, comp) if linkage is not None else {}
    points = change_points.find(linkage) if linkage is not None else ()
    for k, group in enumerate(comp.groups):
        name = solved_name(group)
        det = np.abs(np.where(group.closes & ~change_point_runs(comp, k, points), group.determinant, np.nan))
        if np.isfinite(det).any() and np.nanmin(det) < SMALL_TRANSMISSION:
            worst = int(np.nanargmin(det))
            mu, at = float(np.degrees(np.arcsin(min(det[worst], 1.0)))), float(np.degrees(comp.phi[worst]))
            notes.append(Notice("group_dead_position",
                                f"Group {name} {group.kind} comes close to a dead position: its links are {mu:.2f}° "
                                f"from a line at φ = {at:.1f}°, the velocity and acceleration analogs are large there.",
                                {"group": name, "index": k, "kind": group.kind, "mu": mu, "phi": at}))
        if not group.closes.all():
            ranges = unassembled_ranges(comp.phi, group.closes, {e: phi for (g, e), phi in limits.items() if g == k})
            notes.append(Notice("group_cannot_assemble",
                                f"Group {name} {group.kind} cannot be assembled at φ = {ranges_text(ranges)}: "
                                "its loop does not close there (limit of assembly), the values are undefined.",
                                {"group": name, "index": k, "kind": group.kind, "ranges": ranges}))
    return notes


def special_positions(comp: Composition, linkage: Linkage) -> list[GroupSpecial]:
    """Per group: where it stops or starts closing (limit of assembly, exact: assembly_limits) and where its
    determinant changes sign or is smallest (dead position: the group's links in line, the analogs unbounded)."""
    out = []
    phi = comp.phi
    points = change_points.find(linkage)
    for cp in points:
        group = linkage.groups[cp.group]
        out.append(GroupSpecial("change_point", cp.phi, f"group {cp.group} ({group.kind}): change point, its loop flat "
                                "while the crank passes; the assembly continued through it", None, cp.group, group.kind,
                                name=group_name(group.kind, list(group.links))))
    for (k, edge), at in sorted(assembly_limits(linkage, comp).items()):
        group = comp.groups[k]
        out.append(GroupSpecial("limit_of_assembly", at, f"group {k} ({group.kind}): limit of assembly", None, k,
                                group.kind, name=solved_name(group), assembles_after=not bool(group.closes[edge])))
    for k, group in enumerate(comp.groups):
        name = solved_name(group)
        closes = group.closes
        det = np.where(closes & ~change_point_runs(comp, k, points), group.determinant, np.nan)
        if np.isfinite(det).any():
            worst = int(np.nanargmin(np.abs(det)))
            out.append(GroupSpecial("smallest_determinant", float(phi[worst]),
                                    f"group {k} ({group.kind}): closest to a dead position (|sin| of the "
                                    "angle between its links or guides)", float(abs(det[worst])), k, group.kind,
                                    name=name))
            signs = np.sign(det)
            for edge in np.flatnonzero(signs[:-1] * signs[1:] < 0):
                out.append(GroupSpecial("dead_position", float(phi[edge]),
                                        f"group {k} ({group.kind}): dead position, its links in line", None, k,
                                        group.kind, name=name))
    return out


def reversals(linkage: Linkage, turn: Composition, steps: int = 4) -> list[GroupSpecial]:
    """Output reversals (extreme positions: a slider's dead centre, a rocker's extreme): where a link's θ′ or
    a slide's s′ changes sign on the 0.5° grid, refined by Newton's method on the closed-form analogs,
    φ ← φ − q′/q″ (quadratic: four steps take the grid's 0.5° to round-off)."""
    found = []
    slider = isinstance(linkage.crank, SliderInput)
    size = max(float(np.max(np.abs(point.z))) for point in turn.joints.values())
    for k, group in enumerate(turn.groups):
        quantities = [(f"link {link}", "links", link) for link in group.links] + \
                     [(f"slide {name}", "slides", name) for name in group.slides]
        for label, table, key in quantities:
            scale = 1.0 if table == "links" else size         # θ′ against the crank's 1, s′ against the linkage
            found += [((k, group.kind), label, table, key, start)
                      for start in sign_changes(turn.phi, analogs(turn, table, key)[1], not slider, scale)]
    if not found:
        return []
    phi = np.array([f[4] for f in found])
    for _ in range(steps):
        fine = compose(linkage, phi)
        step = np.array([analogs(fine, t, key)[1][i] / analogs(fine, t, key)[2][i]
                         for i, (_, _, t, key, _) in enumerate(found)])
        phi = phi - step
    fine = compose(linkage, phi)
    return [GroupSpecial("output_reversal", float(phi[i]) if slider else wrap_angle(phi[i]),
                         f"group {k}: {label} reverses (its first analog is zero): an extreme position",
                         float(analogs(fine, table, key)[0][i]), k, kind,
                         key if table == "links" else None, key if table == "slides" else None,
                         solved_name(turn.groups[k]))
            for i, ((k, kind), label, table, key, _) in enumerate(found)]


def sign_changes(phi: np.ndarray, d1: np.ndarray, periodic: bool = True, scale: float = 0.0) -> list[float]:
    """Starting values where d1 changes sign over one turn (periodic: the grid's ends are the same angle) or
    over an input slider's travel (not periodic: its ends are the travel's ends): between two grid points by
    linear interpolation, or at a grid point where it is zero up to round-off (1e-12 of its largest value, and
    1e-9 of ``scale``: a coupler that only translates, θ′ = 0 up to round-off, never reverses)."""
    d, h = (d1[:-1] if periodic else d1), phi[1] - phi[0]
    tiny = max(1e-12 * np.nanmax(np.abs(d), initial=0.0), 1e-9 * scale)
    sign = np.where(np.abs(d) <= tiny, 0.0, np.sign(d))
    after, before = np.roll(sign, -1), np.roll(sign, 1)
    if not periodic:
        after[-1] = before[0] = 0.0
    between = np.flatnonzero(sign * after < 0)
    at = np.flatnonzero((sign == 0) & (before * after < 0))
    return [phi[k] - d[k] * h / (np.roll(d, -1)[k] - d[k]) for k in between] + [phi[k] for k in at]


def analogs(comp: Composition, table: str, key) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A link's (θ, θ′, θ″) or a slide's (s, s′, s″)."""
    if table == "links":
        angle = comp.links[key][1]
        return angle.th, angle.d1, angle.d2
    slide = comp.slides[key]
    return slide.s, slide.d1, slide.d2


def compute_general(linkage: dict, outputs: list[str], phi: np.ndarray | None = None, n: int | None = None,
                    plan: dict | None = None):
    """The kinematics endpoint's general path: the linkage checked (structure, assembly), ``outputs`` at
    ``phi`` (rad) or on ``n`` points over one turn, the plans at ``plan["phi"]``.  GeometryError names the
    field and the reason."""
    from ..kinematics import MAX_POINTS, KinematicsResult

    mech = GeneralMechanism(linkage)
    known = {o.name for o in GENERAL_OUTPUTS}
    for i, name in enumerate(outputs):
        if name not in known:
            raise GeometryError(f"outputs.{i}", f"'{name}' is not an output of a general mechanism; "
                                                f"available: {', '.join(sorted(known))}")
    if phi is None:
        if n is None or not 2 <= n <= MAX_POINTS:
            raise GeometryError("n", f"give between 2 and {MAX_POINTS} points")
        phi = mech.turn(n)
    comp = compose(mech.linkage, phi, "null")
    mech.check_closure(comp)
    start, end = mech.linkage.coordinate_range
    result = KinematicsResult("general", {}, end - start, phi)
    wanted = set(outputs)
    ev = mech.outputs_of(comp, wanted)
    result.warnings.extend(ev.warnings)
    for name in outputs:
        if name == "structure":
            result.outputs[name] = mech.structure
        elif name == "special":
            result.outputs[name] = [sp.as_dict() for sp in mech.special_positions({})]
        elif name == "plan":
            result.outputs[name] = mech.plan(plan["phi"], plan.get("omega1", 1.0), plan.get("epsilon1", 0.0))
        else:
            result.outputs[name] = ev.values[name]
    return result
