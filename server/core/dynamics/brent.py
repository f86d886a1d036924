"""Brent's method compiled with numba: scipy's brentq (scipy/optimize/Zeros/brentq.c) ported line for line, so
that on the same function the root is the very double scipy finds. The compiled loops of the dynamics call it
with a compiled function of their own: the flywheel's level T₀ (compiled.periodic_level) and the two roots of
each successive approximation of Lecture 10 §10.10 (approximations_compiled.py).

numba inlines it into its caller (``inline="always"``, in numba's IR): it runs under the caller's error model,
and the caller stays cacheable on disk (a compiled function passed on as a value would be a dynamic global).
"""
from __future__ import annotations

import math

from numba import njit

CONVERGED, NO_CONVERGENCE, NAN_VALUE, NO_SIGN_CHANGE = 0, 1, 2, 3     # the status brentq returns


@njit(cache=True, error_model="numpy", inline="always")
def brentq(f, args, xa, xb, xtol, rtol, iterations):
    """The x in [xa, xb] where f(x, *args) = 0 (f a compiled function, args a tuple), to xtol + rtol·|x|.
    Returns (root, status): CONVERGED; NO_CONVERGENCE within ``iterations`` (scipy's RuntimeError); NAN_VALUE, f
    gave a NaN (scipy's ValueError); NO_SIGN_CHANGE on the bracket (scipy's ValueError)."""
    xpre, xcur = xa, xb
    xblk, fblk, spre, scur = 0.0, 0.0, 0.0, 0.0
    fpre = f(xpre, *args)
    if math.isnan(fpre):
        return xpre, NAN_VALUE
    fcur = f(xcur, *args)
    if math.isnan(fcur):
        return xcur, NAN_VALUE
    if fpre == 0:
        return xpre, CONVERGED
    if fcur == 0:
        return xcur, CONVERGED
    if (fpre < 0) == (fcur < 0):
        return xcur, NO_SIGN_CHANGE
    for _ in range(iterations):
        if fpre != 0 and fcur != 0 and (fpre < 0) != (fcur < 0):
            xblk = xpre
            fblk = fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre = xcur
            xcur = xblk
            xblk = xpre
            fpre = fcur
            fcur = fblk
            fblk = fpre
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur, CONVERGED
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:            # interpolate
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                       # extrapolate
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre = scur             # good short step
                scur = stry
            else:
                spre = sbis             # bisect
                scur = sbis
        else:
            spre = sbis                 # bisect
            scur = sbis
        xpre = xcur
        fpre = fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = f(xcur, *args)
        if math.isnan(fcur):
            return xcur, NAN_VALUE
    return xcur, NO_CONVERGENCE
