"""250 random mechanisms (hypothesis): crank + a first group of each kind on each branch + a second random group,
every group on a guide or joint of the frame, the crank or the first group (moving guides included, so the
Coriolis terms are not zero).  Each mechanism is built to close at φ₀ and kept only where every group is away
from its limit of assembly and dead positions: |det| ≥ 0.2 (the sine of the angle between the group's links or
guides), so the analogs are at most ~1/0.2² times the crank's and the differences stay accurate.

Checked at φ₀: analogs against five-point central differences of the exact positions (rel 1e-6, with an
absolute floor for analogs near zero, 1e-7 for first and 1e-6 for second analogs: see ``floor``);
lengths and guide constraints to 1e-12 m; positions against fsolve of each group's loop closure to 1e-10; the
plans' vector equations against the analytic velocities and accelerations to 1e-12 (relative to the largest
vector, ω₁²l₁ at least), and every Coriolis vector against 2ω × v_r computed here from the link angles and slides.
"""
import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from server.core.mechanisms.base import GeometryError
from server.core.structure.analysis import analyse
from server.core.structure.compose import compose
from server.core.structure.plans import plans
from server.core.structure.spec import KINDS, parse

from structure_checks import analog_errors, constraint_residuals, fsolve_errors

coordinate = st.floats(-0.4, 0.4)
angle = st.floats(-np.pi, np.pi)


@st.composite
def linkages(draw, first_kind: str, first_branch: int):
    """A crank and two groups, as the JSON the API takes, and the angle φ₀ it is built to close at."""
    raw = {"frame": {"joints": {"O": [0.0, 0.0], "F": [draw(coordinate), draw(coordinate)]},
                     "guides": {"g0": {"through": [draw(coordinate), draw(coordinate)], "angle": draw(angle)},
                                "g1": {"through": [draw(coordinate), draw(coordinate)], "angle": draw(angle)}}},
           "input": {"link": 1, "pivot": "O", "joint": "A", "length": draw(st.floats(0.05, 0.2)),
                     "angle0": draw(angle), "sense": draw(st.sampled_from([1, -1])),
                     "new_guides": {"c1": {"along": draw(coordinate), "across": draw(coordinate),
                                           "angle": draw(angle)}}},
           "groups": []}
    phi0 = draw(st.floats(0, 2 * np.pi))
    for k, kind in enumerate((first_kind, draw(st.sampled_from(KINDS)))):
        comp = compose(parse(raw), np.array([phi0]))
        # the first group placed within reach (nearly parallel guides of a PRP put its joint far away)
        assume(all(np.isfinite(p.z[0]) and abs(p.z[0]) < 10 for p in comp.joints.values()))
        moving = [n for n in comp.joints if n not in raw["frame"]["joints"]]
        guides = list(comp.guides)
        links = [2 + 2 * k, 3 + 2 * k]
        group = {"kind": kind, "links": links,
                 "branch": first_branch if k == 0 else draw(st.sampled_from([1, -1])),
                 "points": {f"P{k}": {"link": draw(st.sampled_from(links)), "along": draw(coordinate),
                                      "across": draw(coordinate)}},
                 "new_guides": {f"h{k}": {"link": draw(st.sampled_from(links)), "along": draw(coordinate),
                                          "across": draw(coordinate), "angle": draw(angle)}}}
        b = draw(st.sampled_from(moving))
        zb = comp.joints[b].z[0]
        if kind in ("RRR", "RPR"):
            d = draw(st.sampled_from(["O", "F"] + [n for n in moving if n != b]))
            zd = comp.joints[d].z[0]
            group["outer"] = [b, d]
            if kind == "RRR":
                zc = complex(draw(coordinate), draw(coordinate))
                group["inner"] = f"C{k}"
                group["lengths"] = [abs(zc - zb), abs(zc - zd)]
                assume(min(group["lengths"]) > 0.02)
            else:
                group["offset"] = draw(st.floats(-0.4, 0.4)) * abs(zb - zd)
        elif kind == "PRP":
            group["guides"] = draw(st.lists(st.sampled_from(guides), min_size=2, max_size=2, unique=True))
            group["inner"] = f"C{k}"
        else:
            g = comp.guides[draw(st.sampled_from(guides))]
            group["outer"] = [b]
            group["guide"] = [n for n in guides if comp.guides[n] is g][0]
            group["inner"] = f"C{k}"
            if kind == "RRP":
                h = abs(((zb - g.point.z[0]) * np.exp(-1j * g.angle.th[0])).imag)
                group["length"] = h + draw(st.floats(0.02, 0.3))
            else:
                group["angle"] = draw(st.floats(0.4, np.pi - 0.4))
        raw["groups"].append(group)
    return raw, phi0


def checked(raw):
    """The parsed linkage, or None where the draw made an invalid mechanism (a rigid group: both outer pairs
    on one link) — those are refused by the analysis, tested in tests/test_general_api.py."""
    linkage = parse(raw)
    try:
        analyse(linkage)
    except GeometryError as error:
        assert error.code == "rigid_group"
        return None
    return linkage


def floor(name: str) -> float:
    """The absolute floor of an analog's check (for analogs near zero, where a relative bound means nothing):
    the positions carry the round-off of the composition, |δz| ≲ 1e-14 (a chain of square roots and arctangents,
    each amplified by up to 1/|det| = 5); the Richardson second difference multiplies it by
    (64/12)·(16/15)/(h/2)² ≈ 2.3e7, i.e. ≈ 2e-7, and the first difference by ≈ 2e3: floors 1e-6 and 1e-7."""
    return 1e-6 if "″" in name else 1e-7


@pytest.mark.parametrize("branch", [1, -1])
@pytest.mark.parametrize("kind", KINDS)
@settings(max_examples=25, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])     # no dependence on the machine's speed
@given(data=st.data())
def test_random_mechanism(kind, branch, data):
    raw, phi0 = data.draw(linkages(kind, branch))
    linkage = checked(raw)
    assume(linkage is not None)
    comp = compose(linkage, np.array([phi0]))
    assume(all(g.closes[0] and abs(g.determinant[0]) >= 0.2 for g in comp.groups))

    for name, error, size in analog_errors(linkage, phi0):
        assert error <= 1e-6 * size + floor(name), name
    assert max(constraint_residuals(linkage, comp)) <= 1e-12
    assert max(fsolve_errors(linkage, comp)) <= 1e-10

    omega1, epsilon1 = 7.0, -3.0
    plan = plans(comp, omega1, epsilon1)
    for equation in plan["velocity"] + plan["acceleration"]:
        # relative to the largest vector, with the crank pin's ω₁²l₁ as the floor where all vanish (dead centre)
        scale = max(v["value"] for v in equation["vectors"]) + omega1**2 * linkage.crank.length
        assert equation["residual"] <= 1e-12 * scale, equation["equation"]
    expected_coriolis(linkage, comp, plan, omega1)


def expected_coriolis(linkage, comp, plan, omega1):
    """a^k = 2ω_g × v_r of every slide on a guide, from the guide's link angle and the slide's s′ (here)."""
    for number, group in enumerate(linkage.groups):
        terms = {v["name"]: complex(v["x"], v["y"]) for eq in plan["acceleration"] if eq["group"] == number
                 for v in eq["vectors"] if v["kind"] == "coriolis"}
        if group.kind in ("RRP", "PRP"):
            for name in group.guides:
                guide = comp.guides[name]
                slide = comp.slides[f"{group.inner}/{name}"]
                expected = 2j * guide.angle.d1[0] * omega1 * slide.d1[0] * omega1 * np.exp(1j * guide.angle.th[0])
                first = group.kind == "PRP" and name == group.guides[0]
                link = group.links[0] if first else group.links[1]      # the slider on this guide
                got = terms[f"k_{group.inner}{link}{group.inner}{guide.link}"]
                assert abs(got - expected) <= 1e-12 * (abs(expected) + omega1**2 * 0.1)
        elif group.kind == "RPR":
            lever = comp.links[group.links[1]][1]
            slide = comp.slides[group.inner]
            expected = -2j * lever.d1[0] * omega1 * slide.d1[0] * omega1 * np.exp(1j * lever.th[0])
            b = group.outer[0]
            got = terms[f"k_{b}{group.links[1]}{b}{group.links[0]}"]
            assert abs(got - expected) <= 1e-12 * (abs(expected) + omega1**2 * 0.1)
