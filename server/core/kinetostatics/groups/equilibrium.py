"""The equilibrium of each structural group and of the crank, linear in the reactions (Chaika–Vasylenko §3.1).

A class-II group has two links and three pairs; each pair's reaction has two unknowns (R: R_x, R_y at the
joint; P: the normal force N ⊥ the line and the couple M of the normal pressure), so six unknowns against the
six equations of the two links: ΣF_x = ΣF_y = ΣM_O = 0 for each (moments about the origin of the frame).
The 6 × 6 system is solved at every angle by one LU for all its right-hand sides (influence.influence_pass); its
determinant vanishes only at the group's dead positions (its links or guides in line), where the reactions are
NaN, said in words by the caller.

The groups are taken in reverse order of attachment: a later group's reactions on earlier links are loads
(−R, Newton's third law) when the earlier group is solved; then the crank: R₀₁ = −ΣF, and the balancing
moment from ΣM = 0 about the origin.

Friction enters as known loads (3.3): a moment on each side of a revolute pair, a force along the line of a
prismatic pair.  Everything is linear, so the reactions are affine in the friction loads z:
R(z) = R⁽⁰⁾ + Σ_p z_p R⁽ᵖ⁾, computed once per angle for the loads (column 0) and for a unit friction load in
each pair (columns 1…K): every approximation, and Newton's method on the friction equilibrium, then costs
only these sums.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...structure.state import cross
from .influence import influence_pass
from .pairs import GroupPairs, KinematicPair

DEAD_POSITION = 1e-12     # |det| of a group's 6 × 6 system below this share of Hadamard's bound: a dead position


@dataclass
class Influence:
    """Reactions as affine functions of the friction loads, columns c = 0 (loads) and 1…K (unit friction).

    group_unknowns[g]: (C, N, 6) per group in order of attachment (pair p: unknowns 2p, 2p + 1);
    crank: (C, N) complex R₀₁; balancing: (C, N) counter-clockwise balancing moment on the crank."""

    group_unknowns: list[np.ndarray]
    crank: np.ndarray
    balancing: np.ndarray
    singular: np.ndarray              # (N,) a group at a dead position

    def at(self, z: np.ndarray) -> tuple[list[np.ndarray], np.ndarray, np.ndarray]:
        """The reactions for friction loads z (K, N) of the pairs the influence was computed for."""
        weights = np.concatenate([np.ones((1, z.shape[1])), z])
        combine = lambda x: np.einsum("cn...,cn->n...", x, weights)
        return [combine(x) for x in self.group_unknowns], combine(self.crank), combine(self.balancing)


def columns(pair: KinematicPair) -> np.ndarray:
    """(N, 3, 2): what the pair's two unknowns put into (F_x, F_y, M_O) of link b (link a gets the negative)."""
    z = pair.z
    n = z.size
    out = np.zeros((n, 3, 2))
    if pair.kind == "R":
        out[:, 0, 0], out[:, 1, 1] = 1.0, 1.0
        out[:, 2, 0], out[:, 2, 1] = -z.imag, z.real          # z × (1, 0), z × (0, 1)
    else:
        normal = 1j * pair.u
        out[:, 0, 0], out[:, 1, 0], out[:, 2, 0] = normal.real, normal.imag, cross(z, normal)
        out[:, 2, 1] = 1.0
    return out


def friction_unit(pair: KinematicPair) -> tuple[np.ndarray, np.ndarray]:
    """A unit friction load on link b of the pair: (force, moment about O): a unit moment (R), a unit force
    along the line at z (P)."""
    if pair.kind == "R":
        return np.zeros(pair.z.size, complex), np.ones(pair.z.size)
    return pair.u, cross(pair.z, pair.u)


def group_matrix(group: GroupPairs) -> np.ndarray:
    """(N, 6, 6): rows (F_x, F_y, M_O) of link i then link j; columns the pairs' unknowns."""
    n = group.pairs[0].z.size
    A = np.zeros((n, 6, 6))
    rows = {group.links[0]: 0, group.links[1]: 3}
    for p, pair in enumerate(group.pairs):
        block = columns(pair)
        A[:, rows[pair.b]:rows[pair.b] + 3, 2 * p:2 * p + 2] += block
        if pair.a in rows:
            A[:, rows[pair.a]:rows[pair.a] + 3, 2 * p:2 * p + 2] -= block
    return A


def solve_all(groups: list[GroupPairs], crank_link: int, pivot: KinematicPair, force: dict, moment: dict,
              friction_pairs: list[KinematicPair]) -> Influence:
    """Reverse order of attachment, then the crank, for the loads and each unit friction load at once.

    force, moment: the loads' resultants per link (N,) (complex force, moment about O);
    friction_pairs: the K pairs whose friction is a load (the crank's pivot among them)."""
    n = pivot.z.size
    C = len(friction_pairs) + 1
    row = {link: r for r, link in enumerate(sorted(set(force) | {0}))}
    Fx, Fy, Mo = (np.zeros((len(row), n, C)) for _ in range(3))    # each link's loads, angle first, C columns
    for k in force:
        Fx[row[k], :, 0] += force[k].real
        Fy[row[k], :, 0] += force[k].imag
        Mo[row[k], :, 0] += moment[k]
    for c, pair in enumerate(friction_pairs, start=1):
        f, m = friction_unit(pair)
        for link, sign in ((pair.b, 1.0), (pair.a, -1.0)):
            if link in row:
                Fx[row[link], :, c] += sign * f.real
                Fy[row[link], :, c] += sign * f.imag
                Mo[row[link], :, c] += sign * m
    order = list(reversed(groups))
    A = np.stack([group_matrix(group) for group in order])
    blocks = np.stack([np.stack([columns(pair) for pair in group.pairs]) for group in order])
    links = np.array([[row[link] for link in group.links] for group in order])
    outer = np.array([[-1 if pair.a in group.links else row[pair.a] for pair in group.pairs] for group in order])
    x, singular = influence_pass(A, blocks, links, outer, Fx, Fy, Mo, DEAD_POSITION)
    unknowns: list[np.ndarray] = [None] * len(groups)
    for g, group in enumerate(order):
        unknowns[group.index] = x[g].transpose(2, 0, 1)                 # (C, N, 6)
    R01 = np.empty((C, n), complex)
    R01.real, R01.imag = -Fx[row[crank_link]].T, -Fy[row[crank_link]].T
    balancing = -(Mo[row[crank_link]].T + cross(pivot.z[None], R01))
    return Influence(unknowns, R01, balancing, singular)
