"""The kinematic pairs of a general mechanism as the kinetostatics sees them (Chaika–Vasylenko §3.1, Fig. 3.3).

Every pair joins link ``a`` (the earlier link, or the group's first link for the inner pair) to link ``b``;
its reaction is the force (and for a prismatic pair the couple) that ``a`` exerts on ``b``; ``b`` exerts the
opposite on ``a`` (Newton's third law).  A revolute pair R acts at its joint z; a prismatic pair P along its
line (a point z on the line, unit direction u): the normal force N·iu and the couple M of the normal pressure
about z, whose lever along the guide is l = M/N (the offset of the normal force, (3.20)).

The relative motion decides the sense of friction (3.3): for R the relative angular-velocity analog
θ′_b − θ′_a, for P the sliding-velocity analog of b's point at z relative to a's, along u:
Re(ū (v_b(z) − v_a(z))) with v_k(z) = z′_Ok + iθ′_k (z − z_Ok) (rigid-body kinematics).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...structure.compose import Composition
from ...structure.spec import Linkage


@dataclass(frozen=True)
class KinematicPair:
    name: str
    kind: str                      # "R" or "P"
    a: int                         # the link that acts (0: the frame)
    b: int                         # the link acted on
    z: np.ndarray                  # (N,) complex: the joint, or a point of the sliding line
    u: np.ndarray | None           # (N,) complex unit direction of the sliding line (P only)
    relative: np.ndarray           # (N,) θ′_b − θ′_a (R) or the sliding analog of b along u (P)
    joint: str = ""                # the joint at z (a slider's joint for P)


@dataclass(frozen=True)
class GroupPairs:
    """One structural group: its kind, its links (i, j), its three pairs (outer, inner, outer as listed)."""

    index: int
    kind: str
    links: tuple[int, int]
    pairs: tuple[KinematicPair, ...]


def link_velocity(comp: Composition, link: int, z: np.ndarray) -> np.ndarray:
    """Velocity analog of the point of ``link`` at z (the frame's is zero)."""
    if link == 0:
        return np.zeros_like(z)
    origin, angle = comp.links[link]
    return origin.d1 + 1j * angle.d1 * (z - origin.z)


def turning(comp: Composition, link: int) -> np.ndarray:
    """θ′ of a link (0 for the frame)."""
    return np.zeros(comp.phi.size) if link == 0 else comp.links[link][1].d1


def carriers(linkage: Linkage) -> tuple[dict[str, int], dict[str, int]]:
    """The link that carries each joint (the lowest-numbered of a joint shared by two links, as the structural
    analysis counts it) and each guide."""
    home = {name: 0 for name in linkage.joints}
    host = {name: 0 for name in linkage.guides}
    crank = linkage.crank
    home[crank.joint] = crank.link
    for element in (crank, *linkage.groups):
        if element is not crank:
            i, j = element.links
            if element.kind == "RPP":
                home[element.inner] = j
            elif element.kind != "RPR":
                home[element.inner] = min(i, j)
        for a in element.points:
            home[a.name] = a.link
        for a in element.new_guides:
            host[a.name] = a.link
    return home, host


def revolute(comp: Composition, name: str, a: int, b: int) -> KinematicPair:
    """Pair R at joint ``name``: relative turning θ′_b − θ′_a, the sense of its friction moment f·R·r
    (Chaika–Vasylenko (3.3))."""
    return KinematicPair(name, "R", a, b, comp.joints[name].z, None, turning(comp, b) - turning(comp, a), name)


def prismatic(comp: Composition, name: str, joint: str, u: np.ndarray, a: int, b: int) -> KinematicPair:
    """Pair P along u at ``joint``: sliding analog Re(ū(v_b − v_a)), the sense of its friction force f·N
    (Chaika–Vasylenko (3.3))."""
    z = comp.joints[joint].z
    slip = link_velocity(comp, b, z) - link_velocity(comp, a, z)
    return KinematicPair(name, "P", a, b, z, u, (np.conj(u) * slip).real, joint)


def group_pairs(linkage: Linkage, comp: Composition) -> list[GroupPairs]:
    """Each group's pairs with their points, lines and relative motion (order of attachment)."""
    home, host = carriers(linkage)
    out = []
    for k, group in enumerate(linkage.groups):
        i, j = group.links
        c = group.inner
        if group.kind == "RRR":
            b, d = group.outer
            pairs = (revolute(comp, b, home[b], i), revolute(comp, c, i, j), revolute(comp, d, home[d], j))
        elif group.kind == "RRP":
            b, g = group.outer[0], group.guides[0]
            pairs = (revolute(comp, b, home[b], i), revolute(comp, c, i, j),
                     prismatic(comp, g, c, comp.guides[g].angle.unit(), host[g], j))
        elif group.kind == "RPR":
            b, d = group.outer
            pairs = (revolute(comp, b, home[b], i), prismatic(comp, c, b, comp.links[j][1].unit(), i, j),
                     revolute(comp, d, home[d], j))
        elif group.kind == "PRP":
            g1, g2 = group.guides
            pairs = (prismatic(comp, g1, c, comp.guides[g1].angle.unit(), host[g1], i), revolute(comp, c, i, j),
                     prismatic(comp, g2, c, comp.guides[g2].angle.unit(), host[g2], j))
        else:                                                        # RPP: block i at B, slotted link j at R
            b, g = group.outer[0], group.guides[0]
            pairs = (revolute(comp, b, home[b], i), prismatic(comp, f"{b}/slot", b, comp.links[i][1].unit(), i, j),
                     prismatic(comp, g, c, comp.guides[g].angle.unit(), host[g], j))
        out.append(GroupPairs(k, group.kind, (i, j), pairs))
    return out


def crank_pair(linkage: Linkage, comp: Composition) -> KinematicPair:
    """The crank's pivot: the frame on the crank."""
    crank = linkage.crank
    return revolute(comp, crank.pivot, 0, crank.link)

