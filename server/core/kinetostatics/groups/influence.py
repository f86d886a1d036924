"""The groups' equilibrium pass of equilibrium.solve_all compiled (numba): angle by angle, each group's 6 × 6 system
solved by one LU for the loads and every unit friction load at once, its outer pairs' reactions taken off the
earlier links' loads (Newton's third law), as the numpy pass did (its answers bitwise).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .dense import lu


@njit(cache=True)
def _group_angle(A, B, relative, M, piv):
    """B ← A⁻¹B (6 × C) by one LU of A (partial pivoting), all columns at once; False where A is at a dead
    position, |det A| ≤ ``relative`` · Π_j ‖A e_j‖ (Hadamard's bound on |det A|): B is NaN there."""
    m, C = B.shape
    hadamard = 1.0
    for j in range(m):
        s = 0.0
        for i in range(m):
            s += A[i, j] * A[i, j]
        hadamard *= np.sqrt(s)
    M[:, :] = A
    det = lu(M, piv)
    if not abs(det) > relative * hadamard:
        B[:, :] = np.nan
        return False
    for c in range(m):                                  # P B, then L⁻¹, then U⁻¹ on all columns at once
        p = piv[c]
        if p != c:
            for j in range(C):
                B[c, j], B[p, j] = B[p, j], B[c, j]
    for i in range(m):
        for l in range(i):
            f = M[i, l]
            for j in range(C):
                B[i, j] -= f * B[l, j]
    for i in range(m - 1, -1, -1):
        for l in range(i + 1, m):
            f = M[i, l]
            for j in range(C):
                B[i, j] -= f * B[l, j]
        d = M[i, i]
        for j in range(C):
            B[i, j] /= d
    return True


@njit(cache=True)
def influence_pass(A, blocks, links, outer, Fx, Fy, Mo, relative):
    """The groups in the order given (reverse order of attachment), angle by angle, for C load columns at once
    (equilibrium.solve_all): group g's six unknowns x from A[g] x = −(F_i, M_i, F_j, M_j), then each of its outer
    pairs' reactions on the earlier link a taken off a's loads, −(∂F, ∂M)/∂x · x (Newton's third law).

    A (G, N, 6, 6); blocks (G, 3, N, 3, 2) of equilibrium.columns; links (G, 2) and outer (G, 3) rows of the
    load arrays (−1: a pair inside the group); Fx, Fy, Mo (L, N, C) the links' loads, changed in place.
    Returns x (G, N, 6, C) and the dead positions (N,)."""
    G, n = A.shape[0], A.shape[1]
    C = Fx.shape[2]
    x = np.empty((G, n, 6, C))
    singular = np.zeros(n, np.bool_)
    M, piv = np.empty((6, 6)), np.empty(6, np.int64)
    for k in range(n):
        for g in range(G):
            B = x[g, k]
            for side in range(2):
                row = links[g, side]
                for c in range(C):
                    B[3 * side, c] = -Fx[row, k, c]
                    B[3 * side + 1, c] = -Fy[row, k, c]
                    B[3 * side + 2, c] = -Mo[row, k, c]
            if not _group_angle(A[g, k], B, relative, M, piv):
                singular[k] = True
            for p in range(3):
                a = outer[g, p]
                if a < 0:
                    continue
                block = blocks[g, p, k]
                for c in range(C):
                    Fx[a, k, c] -= block[0, 0] * B[2 * p, c] + block[0, 1] * B[2 * p + 1, c]
                    Fy[a, k, c] -= block[1, 0] * B[2 * p, c] + block[1, 1] * B[2 * p + 1, c]
                    Mo[a, k, c] -= block[2, 0] * B[2 * p, c] + block[2, 1] * B[2 * p + 1, c]
    return x, singular


def warm_up() -> None:
    """Compile (or load from the disk cache) the pass."""
    influence_pass(np.tile(np.eye(6), (1, 2, 1, 1)), np.zeros((1, 3, 2, 3, 2)), np.array([[0, 1]]),
                   np.array([[2, -1, -1]]), np.ones((3, 2, 2)), np.ones((3, 2, 2)), np.ones((3, 2, 2)), 1e-12)
