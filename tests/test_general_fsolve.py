"""Joint positions of whole mechanisms against scipy.optimize.fsolve of all their loop-closure equations at once.

The unknowns are every group's two (RRR: θ_i, θ_j; RRP: θ_i, s; RPR: θ_j, s; PRP: s₁, s₂; RPP: s_j, s_i); the
equations every group's closure (RRR: B + l_BC e^{iθ_i} = D + l_DC e^{iθ_j}; RRP: B + l e^{iθ_i} = P + s u;
RPR: B = D + (s + ie) e^{iθ_j}; PRP: P₁ + s₁u₁ = P₂ + s₂u₂; RPP: B = P + s_j u + s_i e^{iα}u), with the
crank (or the input slider), the points and the guides placed from the unknowns here (written from the linkage's definition, not from
structure/), and solved together, from the code's answer perturbed by 1e-2 rad or m, to xtol 1e-14.  Every joint
agrees to 1e-10 m: fsolve's root is as exact as round-off (|F| ~ 1e-16) allows, amplified by the Jacobian's
inverse, at most 1/|det| = 5 per group here.
Every preset at 24 angles and ≥ 50 random mechanisms (the generator of test_structure_random).
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy.optimize import fsolve

from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.presets import presets
from server.core.structure.spec import KINDS, SliderInput

from test_structure_random import checked, linkages


def place(linkage, phi: float, x: np.ndarray):
    """Joints, guides and link frames of the whole linkage from the unknowns ``x``, and the closure residuals."""
    joints = {name: complex(*xy) for name, xy in linkage.joints.items()}
    guides = {name: (complex(*p), angle) for name, (p, angle) in linkage.guides.items()}
    frames, residual = {}, []

    def attach(element):
        for a in element.points:
            origin, angle = frames[a.link]
            joints[a.name] = origin + complex(a.along, a.across) * np.exp(1j * angle)
        for a in element.new_guides:
            origin, angle = frames[a.link]
            guides[a.name] = (origin + complex(a.along, a.across) * np.exp(1j * angle), angle + a.angle)

    crank = linkage.crank
    if isinstance(crank, SliderInput):           # the input slider: A = P + s u, its frame along the guide
        p, angle = guides[crank.guide]
        joints[crank.joint] = p + phi * np.exp(1j * angle)
        frames[crank.link] = (joints[crank.joint], angle)
    else:
        theta1 = crank.angle0 + crank.sense * phi
        frames[crank.link] = (joints[crank.pivot], theta1)
        joints[crank.joint] = joints[crank.pivot] + crank.length * np.exp(1j * theta1)
    attach(crank)
    for k, group in enumerate(linkage.groups):
        a, b = x[2 * k], x[2 * k + 1]
        i, j = group.links
        if group.kind == "RRR":
            pb, pd = joints[group.outer[0]], joints[group.outer[1]]
            c = pb + group.sizes[0] * np.exp(1j * a)
            gap = c - pd - group.sizes[1] * np.exp(1j * b)
            joints[group.inner] = c
            frames[i], frames[j] = (pb, a), (pd, b)
        elif group.kind == "RRP":
            pb, (p, g) = joints[group.outer[0]], guides[group.guides[0]]
            c = pb + group.sizes[0] * np.exp(1j * a)
            gap = c - p - b * np.exp(1j * g)
            joints[group.inner] = c
            frames[i], frames[j] = (pb, a), (c, g)
        elif group.kind == "RPR":
            pb, pd = joints[group.outer[0]], joints[group.outer[1]]
            gap = pd + (b + 1j * group.sizes[0]) * np.exp(1j * a) - pb
            frames[i], frames[j] = (pb, a), (pd, a)
        elif group.kind == "PRP":
            (p1, g1), (p2, g2) = guides[group.guides[0]], guides[group.guides[1]]
            c = p1 + a * np.exp(1j * g1)
            gap = c - p2 - b * np.exp(1j * g2)
            joints[group.inner] = c
            frames[i], frames[j] = (c, g1), (c, g2)
        else:
            pb, (p, g) = joints[group.outer[0]], guides[group.guides[0]]
            r = p + a * np.exp(1j * g)
            gap = r + b * np.exp(1j * (g + group.angle)) - pb
            joints[group.inner] = r
            frames[i], frames[j] = (pb, g + group.angle), (r, g)
        residual += [gap.real, gap.imag]
        attach(group)
    return joints, residual


def start(linkage, comp) -> np.ndarray:
    """The code's unknowns at the one angle of ``comp``: angles of the links, slides along the guides."""
    x = []
    for group in linkage.groups:
        i, j = group.links
        theta = lambda link: comp.links[link][1].th[0]
        if group.kind == "RRR":
            x += [theta(i), theta(j)]
        elif group.kind == "RRP":
            guide = comp.guides[group.guides[0]]
            c = comp.joints[group.inner].z[0]
            x += [theta(i), ((c - guide.point.z[0]) * np.exp(-1j * guide.angle.th[0])).real]
        elif group.kind == "RPR":
            b, d = comp.joints[group.outer[0]].z[0], comp.joints[group.outer[1]].z[0]
            x += [theta(j), ((b - d) * np.exp(-1j * theta(j))).real]
        elif group.kind == "PRP":
            c = comp.joints[group.inner].z[0]
            g1, g2 = comp.guides[group.guides[0]], comp.guides[group.guides[1]]
            x += [((c - g.point.z[0]) * np.exp(-1j * g.angle.th[0])).real for g in (g1, g2)]
        else:
            guide = comp.guides[group.guides[0]]
            r, b = comp.joints[group.inner].z[0], comp.joints[group.outer[0]].z[0]
            x += [((r - guide.point.z[0]) * np.exp(-1j * guide.angle.th[0])).real,
                  ((b - r) * np.exp(-1j * (guide.angle.th[0] + group.angle))).real]
    return np.array(x)


def check(linkage, phi: float) -> None:
    comp = compose(linkage, np.array([phi]))
    guess = start(linkage, comp)
    shifted = guess + 1e-2 * np.where(np.arange(guess.size) % 2, 1.0, -1.0)
    root, info, flag, message = fsolve(lambda x: place(linkage, phi, x)[1], shifted, xtol=1e-14, full_output=True)
    # MINPACK's flags 3 and 5 ("xtol too small", "not making good progress") also end at round-off, the
    # residual (~1e-17 m) says whether the root was reached
    assert max(abs(np.array(info["fvec"]))) <= 1e-13, (flag, message)
    joints, _ = place(linkage, phi, root)
    for name, z in joints.items():
        assert abs(z - comp.joints[name].z[0]) <= 1e-10, (name, z, comp.joints[name].z[0])


@pytest.mark.parametrize("name", sorted(presets()))
def test_preset_positions(name):
    """24 crank angles over the turn, or 24 positions over an input slider's travel."""
    mech = GeneralMechanism(presets()[name]["linkage"])
    start, end = mech.linkage.coordinate_range
    for phi in np.linspace(start, end, 24, endpoint=False) + 0.011 * (end - start) / (2 * np.pi):
        check(mech.linkage, phi)


@pytest.mark.parametrize("kind", KINDS)
@settings(max_examples=12, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])     # no dependence on the machine's speed
@given(data=st.data())
def test_random_positions(kind, data):
    """12 draws per first-group kind: 60 mechanisms, each with a second group of a random kind."""
    raw, phi0 = data.draw(linkages(kind, data.draw(st.sampled_from([1, -1]))))
    linkage = checked(raw)
    assume(linkage is not None)
    comp = compose(linkage, np.array([phi0]))
    assume(all(g.closes[0] and abs(g.determinant[0]) >= 0.2 for g in comp.groups))
    assume(all(abs(comp.joints[g.outer[0]].z[0] - comp.joints[g.outer[1]].z[0]) >= 0.02
               for g in linkage.groups if len(g.outer) == 2))
    check(linkage, phi0)
