"""Small dense linear algebra for the compiled kernels of the group kinetostatics (compiled.py, influence.py):
one matrix at a time, K ≲ 10, without LAPACK's call overhead.

LU with partial pivoting (Golub & Van Loan, Matrix Computations, Alg. 3.4.1), the column below the pivot scaled
by the pivot's reciprocal as LAPACK's dgetf2 does; its determinant the product of the pivots with the
permutation's sign (NaN for a matrix with a non-finite entry, as numpy's).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def norm(x, y):
    """|(x, y)| = √(x² + y²) (a reaction's magnitude: far from overflow, and twice as fast as hypot)."""
    return math.sqrt(x * x + y * y)


@njit(cache=True)
def lu(A, piv):
    """A = PLU in place (partial pivoting); det(A), NaN if A has a non-finite entry."""
    K = A.shape[0]
    for i in range(K):
        for j in range(K):
            if not np.isfinite(A[i, j]):
                return np.nan
    det = 1.0
    for c in range(K):
        p, big = c, abs(A[c, c])
        for i in range(c + 1, K):
            if abs(A[i, c]) > big:
                p, big = i, abs(A[i, c])
        piv[c] = p
        if p != c:
            det = -det
            for j in range(K):
                A[c, j], A[p, j] = A[p, j], A[c, j]
        d = A[c, c]
        det *= d
        if d != 0.0:
            inverse = 1.0 / d                            # LAPACK's dgetf2 scales by the reciprocal too
            for i in range(c + 1, K):
                A[i, c] *= inverse
                f = A[i, c]
                for j in range(c + 1, K):
                    A[i, j] -= f * A[c, j]
    return det


@njit(cache=True)
def lu_solve(A, piv, b):
    """x with (PLU) x = b, in place of b."""
    K = b.size
    for c in range(K):
        p = piv[c]
        if p != c:
            b[c], b[p] = b[p], b[c]
    for i in range(K):
        for j in range(i):
            b[i] -= A[i, j] * b[j]
    for i in range(K - 1, -1, -1):
        for j in range(i + 1, K):
            b[i] -= A[i, j] * b[j]
        b[i] /= A[i, i]


@njit(cache=True)
def i_minus(J, A):
    """A = I − J."""
    K = J.shape[0]
    for i in range(K):
        for j in range(K):
            A[i, j] = (1.0 if i == j else 0.0) - J[i, j]


@njit(cache=True)
def spectral_radius(J):
    """max |λ| of J, its non-finite entries taken as 0 (friction.spectral_radius)."""
    K = J.shape[0]
    if K == 0:
        return 0.0
    M = np.empty((K, K), np.complex128)
    for i in range(K):
        for j in range(K):
            M[i, j] = J[i, j] if np.isfinite(J[i, j]) else 0.0
    return np.abs(np.linalg.eigvals(M)).max()
