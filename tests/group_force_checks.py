"""Independent checks of the kinetostatics by groups (tests/test_group_forces*.py).

``link_sums``: the free-body sums ΣF and ΣM_O of every moving link, assembled here load by load and pair by
pair from the answer (Newton's third law between the two links of a pair; friction on both sides), not from the
solver's matrices.  ``power_fd``: the reduced moment of all the loads by power equality, with the velocity of
every load's point and every link's rotation from five-point central differences of the exact positions (not
the analogs).  ``direct``: the nonlinear equilibrium of every link with friction (3.3) computed from the unknowns
themselves, solved by scipy.optimize.fsolve for all the reactions and the balancing moment at once.
"""
import numpy as np
from scipy.optimize import fsolve

from server.core.structure.compose import compose
from server.core.structure.presets import presets


def cross(a, b):
    return (np.conj(a) * b).imag


def pair_loads(pair, x):
    """(force, couple) on link b from the pair's two unknowns x (…, 2)."""
    if pair.kind == "R":
        return x[..., 0] + 1j * x[..., 1], 0.0 * x[..., 0]
    return x[..., 0] * 1j * pair.u, x[..., 1]


def link_sums(result, unknowns, R01, balancing_along, friction):
    """ΣF (complex) and ΣM about the origin of every moving link, and the scales of force and moment."""
    n = result.phi.size
    F = {k: np.zeros(n, complex) for k in result.comp.links}
    M = {k: np.zeros(n) for k in result.comp.links}
    biggest = [np.zeros(n)]

    def add(link, force, z, couple):
        if link == 0:
            return
        F[link] = F[link] + force
        M[link] = M[link] + cross(z, force) + couple
        biggest[0] = np.maximum(biggest[0], np.abs(force))

    for load in result.loads:
        if load.force is not None:
            add(load.link, load.force, load.z, 0.0)
        else:
            M[load.link] = M[load.link] + load.moment
    for group in result.groups:
        x = unknowns[group.index]
        for p, pair in enumerate(group.pairs):
            force, couple = pair_loads(pair, x[:, 2 * p:2 * p + 2])
            add(pair.b, force, pair.z, couple)
            add(pair.a, -force, pair.z, -couple)
    for p, pair in enumerate(result.pairs):
        if pair.kind == "R":
            add(pair.b, 0j * pair.z, pair.z, friction[p])
            add(pair.a, 0j * pair.z, pair.z, -friction[p])
        else:
            add(pair.b, friction[p] * pair.u, pair.z, 0.0)
            add(pair.a, -friction[p] * pair.u, pair.z, 0.0)
    crank = result.crank_link
    pivot = result.pairs[-1].z
    add(crank, R01, pivot, result.sense * balancing_along)
    size = max([np.abs(j.z).max() for j in result.comp.joints.values()]
               + [np.abs(load.z).max() for load in result.loads if load.z is not None])
    return F, M, biggest[0], size


def residual(result, row):
    """The largest |ΣF|/force scale and |ΣM|/(force scale · size) over links and the angles of a table row
    that have reactions (none where the mechanism locks: those must be exactly the locked angles)."""
    F, M, scale, size = link_sums(result, row.unknowns, row.R01, row.balancing, row.friction)
    known = np.isfinite(row.balancing)
    assert np.array_equal(~known, result.locked | result.influence.singular)
    scale = np.where(scale > 0, scale, 1.0)
    force = max(np.max(np.abs(v[known]) / scale[known], initial=0.0) for v in F.values())
    moment = max(np.max(np.abs(v[known]) / (scale[known] * size), initial=0.0) for v in M.values())
    return max(force, moment)


def material(comp, link, z):
    """The point of ``link`` at z (φ of comp) in the link's own frame."""
    origin, angle = comp.links[link]
    return (z - origin.z) * np.exp(-1j * angle.th)


def power_fd(mechanism, result, h=2.5e-4):
    """−Σ(F·v + Mθ′)/ω₁ with v, θ′ from five-point central differences of positions: truncation ~h⁴|z⁽⁵⁾|/30
    (≈ 1e-16 at h = 2.5e-4 for the analogs of order 1–100 the random mechanisms reach), round-off ~1e-16·|z|/h."""
    phi = result.phi
    shifted = {m: compose(mechanism.linkage, phi + m * h) for m in (-2, -1, 1, 2)}
    weights = {-2: 1 / 12, -1: -8 / 12, 1: 8 / 12, 2: -1 / 12}
    total = np.zeros(phi.size)
    for load in result.loads:
        if load.force is not None:
            w = material(result.comp, load.link, load.z)
            v = sum(c * (shifted[m].links[load.link][0].z + w * np.exp(1j * shifted[m].links[load.link][1].th))
                    for m, c in weights.items()) / h
            total += (np.conj(load.force) * v).real
        else:
            th0 = result.comp.links[load.link][1].th
            d = sum(c * np.angle(np.exp(1j * (shifted[m].links[load.link][1].th - th0))) for m, c in weights.items()) / h
            total += load.moment * d
    return -total


def reduction_moment(mechanism, model, result, omega, epsilon):
    """The balancing moment the dynamics' reduction implies (structure/reduction.py: kinetic-energy equality
    for J(φ), power equality for the loads): M = J(φ)ε₁ + ½ J′(φ)ω₁² + M_c(φ), since the inertia loads'
    reduced moment is −Σ(F_in·z′ + M_in θ′) = J ε₁ + ½ J′ ω₁²."""
    from server.core.structure.reduction import reduced_inertia, reduced_loads
    inertia = reduced_inertia(mechanism, result.comp, model, 0.0)
    return inertia.J * epsilon + 0.5 * inertia.dJ * omega**2 + reduced_loads(mechanism, result.comp, model).total


def direct(result, k, start):
    """fsolve of the full friction equilibrium at angle index k: unknowns every group's six, R₀₁ and the
    balancing moment; the friction of each pair from its own reaction, −sgn(relative)·f·ρ·|R| (3.3)."""
    groups = result.groups
    g = len(groups)

    def unpack(v):
        unknowns = [v[6 * i:6 * i + 6][None] for i in range(g)]
        R01 = np.array([v[6 * g] + 1j * v[6 * g + 1]])
        return unknowns, R01, np.array([v[6 * g + 2]])

    def friction_of(unknowns, R01):
        out = []
        for p, pair in enumerate(result.pairs):
            c = result.coefficients[p]
            if p < 3 * g:
                x = unknowns[p // 3][0, 2 * (p % 3):2 * (p % 3) + 2]
                size = abs(complex(*x)) * c.r if pair.kind == "R" else abs(x[0])
            else:
                size = abs(R01[0]) * c.r
            out.append([-np.sign(pair.relative[k]) * c.f * size])
        return np.array(out)

    sub = Slice(result, k)

    def equations(v):
        unknowns, R01, balancing = unpack(v)
        F, M, _, _ = link_sums(sub, unknowns, R01, balancing, friction_of(unknowns, R01))
        return np.concatenate([[F[link][0].real, F[link][0].imag, M[link][0]] for link in sorted(F)])

    solution, info, _, _ = fsolve(equations, start, full_output=True, xtol=1e-14)
    return unpack(solution), np.max(np.abs(info["fvec"]))


class Slice:
    """The answer restricted to one angle (what link_sums reads)."""

    def __init__(self, result, k):
        from dataclasses import replace
        self.phi = result.phi[k:k + 1]
        self.comp = CompSlice(result.comp, k)
        self.loads = [replace(l, z=None if l.z is None else l.z[k:k + 1],
                              force=None if l.force is None else l.force[k:k + 1],
                              moment=None if l.moment is None else np.atleast_1d(l.moment[k:k + 1]),
                              rate=l.rate[k:k + 1]) for l in result.loads]
        self.groups = [replace(gr, pairs=tuple(cut(p, k) for p in gr.pairs)) for gr in result.groups]
        self.pairs = [cut(p, k) for p in result.pairs]
        self.crank_link, self.sense = result.crank_link, result.sense


class CompSlice:
    def __init__(self, comp, k):
        from server.core.structure.state import Angle, Point
        self.links = {n: (Point(o.z[k:k + 1], o.d1[k:k + 1], o.d2[k:k + 1]), Angle(a.th[k:k + 1], a.d1[k:k + 1], a.d2[k:k + 1]))
                      for n, (o, a) in comp.links.items()}
        self.joints = {n: Point(p.z[k:k + 1], p.d1[k:k + 1], p.d2[k:k + 1]) for n, p in comp.joints.items()}


def cut(pair, k):
    from dataclasses import replace
    return replace(pair, z=pair.z[k:k + 1], u=None if pair.u is None else pair.u[k:k + 1],
                   relative=pair.relative[k:k + 1])


def crank_driven() -> list[str]:
    """The presets whose input link is a crank: the kinetostatics' cycle is the crank's turn (a slider-driven
    preset is for the kinematics, and /forces refuses it: tests/test_general_slider_input.py)."""
    return sorted(name for name, preset in presets().items() if preset["linkage"]["input"].get("kind", "crank") == "crank")
