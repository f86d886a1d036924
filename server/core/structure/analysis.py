"""Structural analysis (Chaika–Vasylenko §3.1, Fig. 3.3, (3.4)): the order of attachment checked,
Chebyshev's formula W = 3n − 2p₅ − p₄, the structural formula I(0,1) → II₂(2,3) → …, the class.

A group may attach only to elements that exist already (frame, input, earlier groups): otherwise it would
close a loop through a later group, and the composition in order could not place it.  Both outer pairs of a
group on one and the same link would make a rigid triangle with it, not a structural group (W = 0 alone).
"""
from __future__ import annotations

from dataclasses import dataclass

from ..mechanisms.base import GeometryError
from .spec import KIND_NUMBER, MAX_LINKS, Linkage, SliderInput

SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def group_name(kind: str, links) -> str:
    """A group as the structural formula names it: class II, Artobolevsky's kind as the subscript, its links
    ("II₂(2,3)": the RRP dyad of links 2 and 3, Chaika–Vasylenko Fig. 3.3b); the one name of the group on every
    page (list, drawings, special positions, warnings)."""
    return f"II{str(KIND_NUMBER[kind]).translate(SUBSCRIPT)}({links[0]},{links[1]})"


@dataclass(frozen=True)
class Pair:
    """A lower kinematic pair: R (revolute, at a joint) or P (prismatic, along a guide or a slot)."""

    name: str
    kind: str
    links: tuple[int, int]


def outer_elements(group) -> list[tuple[str, str]]:
    """(element, 'joint' | 'guide') the group attaches to."""
    return [(o, "joint") for o in group.outer] + [(g, "guide") for g in group.guides]


def group_pairs(group, home: dict[str, int], host: dict[str, int]) -> list[Pair]:
    """The group's three pairs: two outer (to earlier links) and one inner (between its links i, j)."""
    i, j = group.links
    kind = group.kind
    if kind == "RRR":
        b, d = group.outer
        return [Pair(b, "R", (home[b], i)), Pair(group.inner, "R", (i, j)), Pair(d, "R", (home[d], j))]
    if kind == "RRP":
        return [Pair(group.outer[0], "R", (home[group.outer[0]], i)), Pair(group.inner, "R", (i, j)),
                Pair(group.guides[0], "P", (host[group.guides[0]], j))]
    if kind == "RPR":
        b, d = group.outer
        return [Pair(b, "R", (home[b], i)), Pair(group.inner, "P", (i, j)), Pair(d, "R", (home[d], j))]
    if kind == "PRP":
        g1, g2 = group.guides
        return [Pair(g1, "P", (host[g1], i)), Pair(group.inner, "R", (i, j)), Pair(g2, "P", (host[g2], j))]
    b, g = group.outer[0], group.guides[0]
    return [Pair(b, "R", (home[b], i)), Pair(f"{b}/slot", "P", (i, j)), Pair(g, "P", (host[g], j))]


def new_joints(group) -> dict[str, set[int]]:
    """Joints the group places, with the links they belong to (RPR places none: its block is at B)."""
    i, j = group.links
    if group.kind == "RPR":
        return {}
    if group.kind == "RPP":
        return {group.inner: {j}}
    return {group.inner: {i, j}}


def analyse(linkage: Linkage) -> dict:
    """Check the order of attachment and count; raise GeometryError (field, reason) or return the analysis."""
    owners: dict[str, set[int]] = {name: {0} for name in linkage.joints}
    host: dict[str, int] = {name: 0 for name in linkage.guides}
    later = {}
    for k, group in enumerate(linkage.groups):
        for name in list(new_joints(group)) + [a.name for a in group.points + group.new_guides]:
            later.setdefault(name, k)
    crank = linkage.crank
    slider = isinstance(crank, SliderInput)
    if slider and crank.guide not in linkage.guides:
        raise GeometryError("linkage.input.guide", f"the input slider runs along a frame guide; '{crank.guide}' is "
                                                   "not one of linkage.frame.guides", "unknown_element",
                            element=crank.guide)
    if not slider and crank.pivot not in linkage.joints:
        raise GeometryError("linkage.input.pivot", f"the crank turns about a frame joint; '{crank.pivot}' is not "
                                                   "one of linkage.frame.joints", "unknown_element",
                            element=crank.pivot)
    declared: dict[int, str] = {crank.link: "the input slider" if slider else "the input crank"}
    duplicate: list[str] = []

    def place(name: str, links: set[int], where: str) -> None:
        if name in owners or name in host:
            raise GeometryError(where, f"the name '{name}' is used already", "duplicate_name")
        owners[name] = links

    def place_guides(guides, where: str) -> None:
        """Each new guide on its link, under a name not used yet."""
        for a in guides:
            if a.name in owners or a.name in host:
                raise GeometryError(f"{where}.new_guides.{a.name}", f"the name '{a.name}' is used already",
                                    "duplicate_name")
            host[a.name] = a.link

    place(crank.joint, {crank.link}, "linkage.input.joint")
    for a in crank.points:
        place(a.name, {a.link}, f"linkage.input.points.{a.name}")
    place_guides(crank.new_guides, "linkage.input")
    formula = [f"I(0,{crank.link})"]
    groups, pairs = [], [Pair(crank.guide, "P", (0, crank.link)) if slider else Pair(crank.pivot, "R", (0, crank.link))]
    for k, group in enumerate(linkage.groups):
        where = f"linkage.groups.{k}"
        attached: set[int] = set()
        for m, (name, what) in enumerate(outer_elements(group)):
            field = f"{where}.outer.{m}" if what == "joint" else (
                f"{where}.guides.{m - len(group.outer)}" if group.kind == "PRP" else f"{where}.guide")
            known = owners if what == "joint" else host
            if name not in known:
                if later.get(name) == k:
                    reason = f"a loop: the group attaches to its own {what} '{name}'"
                elif name in later:
                    reason = (f"a loop: the {what} '{name}' is placed only by the later group {later[name]}; "
                              "groups are attached in order, each to elements that exist already")
                else:
                    reason = f"the {what} '{name}' does not exist (yet): no frame element, crank or earlier group has it"
                raise GeometryError(field, reason, "unknown_element", element=name)
            attached |= known[name] if what == "joint" else {known[name]}
        if len(attached) == 1:
            link = attached.pop()
            raise GeometryError(f"{where}.outer" if group.outer else f"{where}.guides",
                                f"both outer pairs are on link {link}: the group would form a rigid triangle "
                                "with it, not a structural group", "rigid_group", link=link)
        for link in group.links:
            if link in declared:
                duplicate.append(f"link {link} is declared by {declared[link]} and by group {k}")
            declared.setdefault(link, f"group {k}")
        home = {n: min(o) for n, o in owners.items()}
        pairs.extend(group_pairs(group, home, host))
        for name, links in new_joints(group).items():
            place(name, links, f"{where}.inner")
        for a in group.points:
            place(a.name, {a.link}, f"{where}.points.{a.name}")
        place_guides(group.new_guides, where)
        number = KIND_NUMBER[group.kind]
        formula.append(group_name(group.kind, group.links))
        groups.append({"name": group_name(group.kind, group.links), "kind": group.kind, "class": 2, "order": 2,
                       "kind_number": number,
                       "links": list(group.links), "attached_to": sorted(attached)})
    n = len(declared)
    if n > MAX_LINKS:
        raise GeometryError("linkage.groups", f"{n} moving links: at most {MAX_LINKS}", "too_many_links")
    p5, p4 = len(pairs), 0
    mobility = 3 * n - 2 * p5 - p4
    if mobility != 1:
        raise GeometryError("linkage.groups", f"W = 3n − 2p₅ − p₄ = 3·{n} − 2·{p5} − {p4} = {mobility} ≠ 1: "
                            + "; ".join(duplicate), "mobility", mobility=mobility)
    return {"n": n, "p5": p5, "p4": p4, "W": mobility, "input": "slider" if slider else "crank",
            "formula": " → ".join(formula), "class": 2 if linkage.groups else 1,
            "groups": groups,
            "pairs": [{"name": p.name, "kind": p.kind, "links": list(p.links)} for p in pairs]}
