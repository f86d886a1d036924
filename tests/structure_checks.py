"""Independent checks of a composed linkage, shared by tests/test_structure*.py and tests/test_general*.py.

- analogs against five-point central differences of the exact positions at steps h = 1e-3 and h/2 rad,
  Richardson-extrapolated (16D(h/2) − D(h))/15: truncation O(h⁶f⁽⁷⁾, h⁶f⁽⁸⁾), which stays below rel 1e-6 even
  where a short link makes the high derivatives large (f⁽ⁿ⁾ ~ n!/δⁿ near a dead position δ away); round-off
  ≈ 10ε|z|/(h/2)² ≈ 1e-8·|z|;
- each group's defining constraints (lengths, points on guides) evaluated from the positions;
- each group's loop closure solved again by scipy.optimize.fsolve from a perturbed start (xtol 1e-14).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import fsolve

from server.core.structure.compose import compose

H = 1e-3
STENCIL = np.arange(-4, 5) * H / 2


def differences(f: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivative at the middle of five samples spaced h (fourth-order central formulas)."""
    d1 = (-f[4] + 8 * f[3] - 8 * f[1] + f[0]) / (12 * h)
    d2 = (-f[4] + 16 * f[3] - 30 * f[2] + 16 * f[1] - f[0]) / (12 * h**2)
    return d1, d2


def richardson(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivative from nine samples spaced H/2: D(H/2) and D(H) extrapolated (error O(H⁶))."""
    fine = differences(values[2:7], H / 2)
    coarse = differences(values[::2], H)
    return tuple((16 * f - c) / 15 for f, c in zip(fine, coarse))


def analog_errors(linkage, phi0: float) -> list[tuple[str, float, float]]:
    """(name, |analog − difference|, scale) for every joint's z′, z″, link's θ′, θ″ and slide's s′, s″ at φ₀."""
    exact = compose(linkage, phi0 + STENCIL)
    here = compose(linkage, np.array([phi0]))
    rows = []
    for name, p in exact.joints.items():
        d1, d2 = richardson(p.z)
        rows += [(f"{name}′", abs(d1 - here.joints[name].d1[0]), abs(d1)),
                 (f"{name}″", abs(d2 - here.joints[name].d2[0]), abs(d2))]
    for link, (_, a) in exact.links.items():
        d1, d2 = richardson(np.unwrap(a.th))
        rows += [(f"θ{link}′", abs(d1 - here.links[link][1].d1[0]), abs(d1)),
                 (f"θ{link}″", abs(d2 - here.links[link][1].d2[0]), abs(d2))]
    for name, s in exact.slides.items():
        d1, d2 = richardson(s.s)
        rows += [(f"{name}′", abs(d1 - here.slides[name].d1[0]), abs(d1)),
                 (f"{name}″", abs(d2 - here.slides[name].d2[0]), abs(d2))]
    return rows


def line_distance(z, p, theta):
    """Signed distance of z from the line through p at angle θ."""
    return ((z - p) * np.exp(-1j * theta)).imag


def constraint_residuals(linkage, comp) -> list[float]:
    """Every group's constraints from the composed positions (m): zero up to round-off."""
    out = []
    j, g = comp.joints, comp.guides
    for group in linkage.groups:
        j_link = group.links[1]
        if group.kind == "RRR":
            b, d, c = j[group.outer[0]].z, j[group.outer[1]].z, j[group.inner].z
            out += [np.abs(c - b) - group.sizes[0], np.abs(c - d) - group.sizes[1]]
        elif group.kind == "RRP":
            b, c, guide = j[group.outer[0]].z, j[group.inner].z, g[group.guides[0]]
            out += [np.abs(c - b) - group.sizes[0], line_distance(c, guide.point.z, guide.angle.th)]
        elif group.kind == "RPR":
            b, d = j[group.outer[0]].z, j[group.outer[1]].z
            lever = comp.links[j_link][1].th
            out.append(line_distance(b, d, lever) - group.sizes[0])
        elif group.kind == "PRP":
            c = j[group.inner].z
            for name in group.guides:
                out.append(line_distance(c, g[name].point.z, g[name].angle.th))
        else:
            b, r, guide = j[group.outer[0]].z, j[group.inner].z, g[group.guides[0]]
            out += [line_distance(r, guide.point.z, guide.angle.th),
                    line_distance(b, r, guide.angle.th + group.angle)]
    return [float(np.max(np.abs(x))) for x in out]


def fsolve_errors(linkage, comp, k: int = 0) -> list[float]:
    """Each group's unknowns solved again by fsolve from the code's answer perturbed by 2 %, with the outer
    elements from the composition: the distance of fsolve's root from the code's position (m or rad)."""
    errors = []
    j, g = comp.joints, comp.guides
    rng = np.random.default_rng(7)
    for group in linkage.groups:
        if group.kind == "RRR":
            b, d, c = (j[n].z[k] for n in (*group.outer, group.inner))
            a_len, b_len = group.sizes

            def eqs(x, b=b, d=d, a_len=a_len, b_len=b_len):
                z = complex(*x)
                return [abs(z - b) ** 2 - a_len**2, abs(z - d) ** 2 - b_len**2]
            start = np.array([c.real, c.imag]) * (1 + 0.02 * rng.standard_normal(2))
            root = fsolve(eqs, start, xtol=1e-14)
            errors.append(abs(complex(*root) - c))
        elif group.kind == "RRP":
            b, c, guide = j[group.outer[0]].z[k], j[group.inner].z[k], g[group.guides[0]]
            p, u = guide.point.z[k], np.exp(1j * guide.angle.th[k])
            s0 = ((c - p) * np.conj(u)).real
            root = fsolve(lambda x: [abs(p + x[0] * u - b) ** 2 - group.sizes[0] ** 2],
                          [s0 * (1 + 0.02) + 0.001], xtol=1e-14)
            errors.append(abs(p + root[0] * u - c))
        elif group.kind == "RPR":
            b, d = j[group.outer[0]].z[k], j[group.outer[1]].z[k]
            theta = comp.links[group.links[1]][1].th[k]
            s0 = ((b - d) * np.exp(-1j * theta)).real
            e = group.sizes[0]

            def eqs(x, b=b, d=d, e=e):
                z = d + (x[0] + 1j * e) * np.exp(1j * x[1]) - b
                return [z.real, z.imag]
            root = fsolve(eqs, [s0 * 1.02, theta + 0.02], xtol=1e-14)
            errors.append(abs(np.angle(np.exp(1j * (root[1] - theta)))))
        else:
            first = g[group.guides[0]]
            if group.kind == "PRP":
                second = g[group.guides[1]]
                u1, u2 = np.exp(1j * first.angle.th[k]), np.exp(1j * second.angle.th[k])
                p1, p2, target = first.point.z[k], second.point.z[k], j[group.inner].z[k]

                def eqs(x, p1=p1, p2=p2, u1=u1, u2=u2):
                    z = p1 + x[0] * u1 - p2 - x[1] * u2
                    return [z.real, z.imag]
                root = fsolve(eqs, [0.1, -0.1], xtol=1e-14)
                errors.append(abs(p1 + root[0] * u1 - target))
            else:
                b, r = j[group.outer[0]].z[k], j[group.inner].z[k]
                u = np.exp(1j * first.angle.th[k])
                v = u * np.exp(1j * group.angle)
                p = first.point.z[k]

                def eqs(x, p=p, u=u, v=v, b=b):
                    z = p + x[0] * u + x[1] * v - b
                    return [z.real, z.imag]
                root = fsolve(eqs, [0.1, -0.1], xtol=1e-14)
                errors.append(abs(p + root[0] * u - r))
    return errors
