"""The general mechanism's reduction checked against what it is not computed from.

J(φ): twice the kinetic energy of all links at unit crank speed, Σ m|dz_S/dφ|² + J_S(dθ/dφ)², with dz_S/dφ and
dθ/dφ from central differences of the exact positions (S placed on its link from the link's origin joint and
angle; no analog of the code under test), rel 1e-7: fourth-order differences at h = 1e-3 and h/2 extrapolated
by Richardson (structure_checks.richardson), truncation O(h⁶f⁽⁷⁾) — the plain h = 1e-3 difference left 3.5e-6 on
θ′ ≈ 14 of a short link in a drawn PRP + RRR case, the extrapolated one ~1e-11 — and round-off ≈ 1e-16|z|/(h/2)
≈ 1e-13.
dJ/dφ: the same difference of J itself (rel 1e-7).
M_c: virtual work of every load (−F·δz − M δθ, gravity m g δy_S) with δ from differences of the positions,
the stroke factor from the sign of that difference (rel 1e-7 of the largest part, |w| ≥ 1e-3 m so the sign is
certain).
Every preset and random mechanisms of all five kinds (the generator of test_structure_random).
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.masses import LinkMass, LinkMoment, MassModel, SliderForce, centre_kinematics
from server.core.structure.presets import presets
from server.core.structure.reduction import reduced_inertia, reduced_loads
from server.core.structure.spec import KINDS

from structure_checks import STENCIL, richardson
from test_structure_random import checked, linkages



def derivative(values: np.ndarray) -> np.ndarray:
    """d/dφ at φ₀ from the nine samples at φ₀ + STENCIL (last axis), Richardson-extrapolated differences."""
    return richardson(np.moveaxis(values, -1, 0))[0]


def positions(linkage, model: MassModel, phi0: float):
    """At φ₀ + STENCIL: each mass's centre z_S and link angle θ (unwrapped), the joints, the guides' angles."""
    comp = compose(linkage, phi0 + STENCIL)
    centres = np.array([comp.links[m.link][0].z + complex(*m.centre) * np.exp(1j * comp.links[m.link][1].th)
                        for m in model.links]).reshape(len(model.links), STENCIL.size)
    angles = {k: np.unwrap(a.th) for k, (_, a) in comp.links.items()}
    return comp, centres, angles


def kinetic_inertia(linkage, model: MassModel, phi0: float, constant: float) -> float:
    """2T/ω₁² from differences of the positions."""
    _, centres, angles = positions(linkage, model, phi0)
    v = derivative(centres)
    return constant + sum(m.mass * abs(v[i]) ** 2 + m.inertia * derivative(angles[m.link]) ** 2
                          for i, m in enumerate(model.links))


def virtual_work_moment(linkage, model: MassModel, phi0: float) -> float:
    """M_c = −(δA of the loads)/δφ, every displacement from differences of the positions."""
    comp, centres, angles = positions(linkage, model, phi0)
    total = model.gravity * sum(m.mass * derivative(centres[i]).imag for i, m in enumerate(model.links))
    for force in model.forces:
        joint, guide = force.joint.split("/")
        # the displacement along the guide (every loaded slider below runs on a fixed guide)
        w = (derivative(comp.joints[joint].z) * np.exp(-1j * comp.guides[guide].angle.th[0])).real
        k = 1.0 if force.sense * w >= 0 else force.k
        total += k * force.working * abs(w)
    for moment in model.moments:
        d1 = derivative(angles[moment.link])
        k = 1.0 if moment.sense * d1 >= 0 else moment.k
        total += k * moment.working * abs(d1)
    return total


def analytic(linkage, model, phi0, constant):
    comp = compose(linkage, phi0 + STENCIL)
    inertia = reduced_inertia(None, comp, model, constant)     # the composition given: no mechanism needed
    loads = reduced_loads(None, comp, model)
    middle = STENCIL.size // 2
    return (inertia.J[middle], inertia.dJ[middle], derivative(inertia.J), loads.total[middle],
            max([abs(p[middle]) for p in loads.parts.values()] + [1.0]))


def check(linkage, model, phi0, constant=0.3):
    J, dJ, slope, moment, scale = analytic(linkage, model, phi0, constant)
    expected = kinetic_inertia(linkage, model, phi0, constant)
    assert abs(J - expected) <= 1e-7 * expected, (J, expected)
    assert abs(dJ - slope) <= 1e-7 * (abs(slope) + J), (dJ, slope)
    work = virtual_work_moment(linkage, model, phi0)
    assert abs(moment - work) <= 1e-7 * scale, (moment, work)


def preset_model(name: str) -> MassModel:
    masses = presets()[name].get("dynamics", {}).get("masses")
    if masses is None:
        return MassModel()
    return MassModel(tuple(LinkMass(m["link"], m["mass"], tuple(m.get("centre", (0, 0))), m.get("inertia", 0.0))
                           for m in masses["links"]), masses.get("gravity", 9.81),
                     tuple(SliderForce(**f) for f in masses.get("forces", [])),
                     tuple(LinkMoment(**m) for m in masses.get("moments", [])))


def pair_names(model, comp):
    """Forces named by their full pair (joint/guide), as the check above reads them."""
    names = []
    for f in model.forces:
        found = f.joint if "/" in f.joint else [p for p in comp.slides if p.split("/")[0] == f.joint][0]
        names.append(SliderForce(found, f.working, f.k, f.sense))
    return MassModel(model.links, model.gravity, tuple(names), model.moments)


@pytest.mark.parametrize("name", sorted(name for name, preset in presets().items()        # crank-driven: the
                                         if preset["linkage"]["input"].get("kind", "crank") == "crank"))  # machine's cycle
def test_preset_reduction(name):
    linkage = GeneralMechanism(presets()[name]["linkage"]).linkage
    model = preset_model(name)
    if not model.links:      # the four fixed mechanisms' presets: a mass model of every link, both loads
        comp = compose(linkage, np.array([0.0]))
        model = MassModel(tuple(LinkMass(k, 1.0 + k, (0.03 * k, -0.01), 0.01 * k) for k in sorted(comp.links)),
                          moments=(LinkMoment(max(comp.links), 50.0, 0.3),))
    model = pair_names(model, compose(linkage, np.array([0.0])))
    for phi0 in np.linspace(0, 2 * np.pi, 13)[:-1] + 0.017:
        check(linkage, model, phi0)


@pytest.mark.parametrize("kind", KINDS)
@settings(max_examples=12, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])     # no dependence on the machine's speed
@given(data=st.data())
def test_random_reduction(kind, data):
    raw, phi0 = data.draw(linkages(kind, data.draw(st.sampled_from([1, -1]))))
    linkage = checked(raw)
    assume(linkage is not None)
    comp = compose(linkage, phi0 + STENCIL)
    assume(all(g.closes.all() and np.abs(g.determinant).min() >= 0.2 for g in comp.groups))
    # a group on two coincident outer joints (a draw can put a point on the crank's pivot) has no defined angle
    assume(all(np.abs(comp.joints[g.outer[0]].z - comp.joints[g.outer[1]].z).min() >= 0.02
               for g in linkage.groups if len(g.outer) == 2))
    links = sorted(comp.links)
    masses = tuple(LinkMass(k, data.draw(st.floats(0.1, 20)), (data.draw(st.floats(-0.3, 0.3)),
                                                                data.draw(st.floats(-0.3, 0.3))),
                            data.draw(st.floats(0, 2))) for k in links)
    on_fixed = [p for p in comp.slides if "/" in p and p.split("/")[1] in comp.guides
                and comp.guides[p.split("/")[1]].link == 0 and abs(comp.slides[p].d1[4]) >= 1e-3]
    forces = tuple(SliderForce(p, data.draw(st.floats(10, 5000)), data.draw(st.floats(0, 1)),
                               data.draw(st.sampled_from([1, -1]))) for p in on_fixed)
    turning = [k for k in links if abs(comp.links[k][1].d1[4]) >= 1e-3]
    moments = tuple(LinkMoment(k, data.draw(st.floats(1, 500)), data.draw(st.floats(0, 1)),
                               data.draw(st.sampled_from([1, -1]))) for k in turning[:2])
    check(linkage, MassModel(masses, 9.81, forces, moments), phi0)


def test_centre_kinematics_against_differences():
    """The kinetostatics' view of the centres (real (L, 2, N) arrays, θ, θ′, θ″): first and second analogs
    against Richardson differences of the positions, rel 1e-6 (the second difference's round-off, ≈ 1e-8|z|,
    sets the bound), at 12 angles of the shaping machine with its preset masses."""
    mech = GeneralMechanism(presets()["shaping_machine"]["linkage"])
    model = preset_model("shaping_machine")
    for phi0 in np.linspace(0, 2 * np.pi, 12, endpoint=False) + 0.02:
        fine = centre_kinematics(mech, model, phi0 + STENCIL)
        here = centre_kinematics(mech, model, np.array([phi0]))
        for row in range(len(model.links)):
            for axis in range(2):
                d1, d2 = richardson(fine.positions[row, axis])
                assert abs(d1 - here.first[row, axis, 0]) <= 1e-6 * (abs(d1) + 1e-3)
                assert abs(d2 - here.second[row, axis, 0]) <= 1e-6 * (abs(d2) + 1e-2)
            d1, d2 = richardson(np.unwrap(fine.theta[row]))
            assert abs(d1 - here.theta_d1[row, 0]) <= 1e-6 * (abs(d1) + 1e-3)
            assert abs(d2 - here.theta_d2[row, 0]) <= 1e-6 * (abs(d2) + 1e-2)
