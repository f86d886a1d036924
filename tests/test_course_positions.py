"""The course project's kinematics sheet (server/core/course_project/): positions, scales and plans, each against
something the code under test does not compute:

- the extreme positions against geometry: the shaping machine's slotted lever (and so its ram) is at an extreme
  where the crank is perpendicular to the lever, sin θ₁ = −r/OC (to 1e-12 rad); the six-bar's rocker where the
  crank and the coupler are in line, |B − O| = l₂ ± l₁ (to 1e-12 m); the output's first analog is zero there
  (1e-10 of its largest value) and its values there bound it over a 0.01° grid;
- the working stroke against the ram's own motion (its x from the drawn joints) and the work P·H of the load
  with H = 2·CD·r/OC of the lever's swing; the slower stroke against the crank angle π + 2 arcsin(r/OC);
- the scales against the standard values enumerated here;
- every plan vector, every point's velocity and acceleration and every link's ω, ε against central differences
  in time of the exact composed positions along φ(t) = φ_i + ω₁t + ε₁t²/2 with ε₁ ≠ 0 (steps of 2e-3 s and
  1e-3 s, Richardson-extrapolated: truncation O(h⁶); round-off ≈ 5ε|z|/(1e-3 s)² ≈ 1e-9 m/s² against plans of
  10…100 m/s²): to 1e-9 of the plan's largest vector (measured ≤ 7e-11; 1.5e-9 at steps four times smaller,
  where the round-off grows as 1/h²).  The plan's vectors are checked one by
  one: an absolute one from the point's path, a rotation from the material points of its link, a sliding one
  from the slider's path in the guide's own frame, with the Coriolis term 2ω_g × v_r from the guide's turning.
"""
from __future__ import annotations

import copy
import json
import math

import numpy as np
import pytest

from server.core.course_project.kinematic_sheet import finite, kinematic_sheet, plan_of_positions
from server.core.course_project.positions import POSITION_COUNTS, stroke_positions
from server.core.course_project.scales import (FORCE_PLAN_MM, PLAN_MM, POSITIONS_MM, STANDARD_MANTISSAS, extent,
                                               standard_scale)
from server.core.mechanisms.base import GeometryError
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure import masses
from server.core.structure.compose import compose
from server.core.structure.masses import LinkMass, LinkMoment, MassModel, SliderForce
from server.core.structure.presets import presets
from structure_checks import differences

SHAPING = presets()["shaping_machine"]
CRANK, PIVOT, LEVER = 0.1, 0.3, 0.55          # the shaping machine: OA, OC and CD
SIX = {"frame": {"joints": {"O": [0, 0], "D": [0.25, 0]}},
       "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.08, "angle0": 0.3, "sense": -1},
       "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "D"], "inner": "B", "lengths": [0.22, 0.18],
                   "branch": 1, "points": {"P": {"link": 2, "along": 0.11, "across": 0.06}},
                   "new_guides": {"g3": {"link": 3, "along": 0.0, "across": 0.0, "angle": 0.0}}},
                  {"kind": "RRP", "links": [4, 5], "outer": ["P"], "guide": "g3", "inner": "E", "length": 0.2,
                   "branch": 1}]}       # a six-bar: a crank-rocker, its coupler point P drives a slider on the rocker


def shaping() -> GeneralMechanism:
    return GeneralMechanism(SHAPING["linkage"])


def shaping_model(**force) -> MassModel:
    """The preset's masses and its cutting force on the ram (sense −1: the working stroke runs against the
    guide's +x), with ``force``'s fields changed."""
    masses = SHAPING["dynamics"]["masses"]
    links = tuple(LinkMass(m["link"], m["mass"], tuple(m.get("centre", (0, 0))), m.get("inertia", 0.0))
                  for m in masses["links"])
    return MassModel(links, masses["gravity"], (SliderForce(**(masses["forces"][0] | force)),))


SIX_MASSES = MassModel((LinkMass(2, 1.5, (0.11, 0.02), 0.01), LinkMass(3, 1.0, (0.09, 0.0), 0.005),
                        LinkMass(4, 1.0, (0.1, 0.0), 0.004), LinkMass(5, 2.0)))
STEP = 2e-3                                   # s: the stencil's wider step, φ moves ~0.02 rad
TIMES = np.arange(-4, 5) * STEP / 2


def ram_x(phi) -> np.ndarray:
    return compose(shaping().linkage, np.atleast_1d(np.asarray(phi, float))).joints["E"].z.real


# (b) the extreme positions and the working stroke

def test_shaping_extremes_are_where_the_crank_is_perpendicular_to_the_lever():
    sp = stroke_positions(shaping(), shaping_model(), 12)
    assert sp.output.name == "E/ram"
    crank_angles = sorted(sp.working_stroke)
    assert crank_angles == pytest.approx([math.pi + math.asin(CRANK / PIVOT), 2 * math.pi - math.asin(CRANK / PIVOT)],
                                         abs=1e-12)
    assert sp.stroke == pytest.approx(2 * LEVER * CRANK / PIVOT, rel=1e-12)


@pytest.mark.parametrize("mechanism, output", [(shaping, None), (lambda: GeneralMechanism(SIX), "link 3"),
                                               (lambda: GeneralMechanism(SIX), None)])
def test_the_output_analog_is_zero_at_the_extremes_and_they_bound_it(mechanism, output):
    mech = mechanism()
    sp = stroke_positions(mech, None, 8, output=output)
    fine = compose(mech.linkage, np.linspace(0, 2 * math.pi, 36001))
    q, q1, _ = sp.output.analogs(fine)
    at = sp.output.analogs(compose(mech.linkage, np.array(sp.working_stroke)))
    assert np.all(np.abs(at[1]) <= 1e-10 * np.abs(q1).max())
    low, high = sorted(at[0])
    assert low - 1e-15 <= q.min() and q.max() <= high + 1e-15
    assert q.min() - low < 1e-7 and high - q.max() < 1e-7      # the grid's (0.01°)²·|q″|/8 of the extreme


def test_six_bar_rocker_extremes_have_crank_and_coupler_in_line():
    mech = GeneralMechanism(SIX)
    sp = stroke_positions(mech, None, 12, output="link 3")
    b = compose(mech.linkage, np.array(sp.working_stroke)).joints["B"].z
    assert sorted(np.abs(b)) == pytest.approx([0.22 - 0.08, 0.22 + 0.08], abs=1e-12)


def test_the_load_resists_on_the_working_stroke_that_starts_at_position_one():
    sp = stroke_positions(shaping(), shaping_model(), 12)
    start, end = sp.working_stroke
    inside = start + np.linspace(0.01, 0.99, 50) * sp.spans[0]
    assert np.all(np.diff(ram_x(inside)) < 0)           # sense −1: the ram runs against +x, the load resists
    assert sp.phi0 == start and sp.phi[0] == start and sp.rule == "resisting_work"
    assert sp.works[0] == pytest.approx(3000 * 2 * LEVER * CRANK / PIVOT, rel=1e-9)      # P·H
    assert sp.works[1] == pytest.approx(0.05 * sp.works[0], rel=1e-9)                    # k·P·H


def test_the_other_sense_makes_the_quick_stroke_the_working_one():
    sp = stroke_positions(shaping(), shaping_model(sense=1), 12)
    assert sp.working_stroke[0] == pytest.approx(math.pi + math.asin(CRANK / PIVOT), abs=1e-12)
    assert sp.spans[0] < sp.spans[1] and sp.time_ratio > 1
    inside = sp.working_stroke[0] + np.linspace(0.01, 0.99, 50) * sp.spans[0]
    assert np.all(np.diff(ram_x(inside)) > 0)
    same = stroke_positions(shaping(), shaping_model(sense=1, k=1.0), 12)
    assert same.rule == "load_sense" and same.working_stroke == sp.working_stroke


def test_without_loads_the_slower_stroke_is_the_working_one():
    sp = stroke_positions(shaping(), None, 12)
    slow = math.pi + 2 * math.asin(CRANK / PIVOT)
    assert sp.rule == "slower_stroke" and sp.works is None
    assert sp.spans == pytest.approx((slow, 2 * math.pi - slow), abs=1e-12)
    assert sp.time_ratio == pytest.approx(slow / (2 * math.pi - slow), rel=1e-12)


def test_a_moment_on_a_link_chooses_that_link_as_the_output():
    model = MassModel(moments=(LinkMoment(3, 50.0, 0.1, -1),))
    sp = stroke_positions(GeneralMechanism(SIX), model, 12)
    assert sp.output.name == "link 3" and sp.rule == "resisting_work"
    theta = compose(GeneralMechanism(SIX).linkage, sp.working_stroke[0] + np.linspace(0.01, 0.99, 50) * sp.spans[0])
    assert np.all(np.diff(np.unwrap(theta.links[3][1].th)) < 0)     # sense −1: clockwise on the working stroke


@pytest.mark.parametrize("angle", [0.0, math.pi])
def test_a_point_force_on_the_ram_takes_the_ram_and_the_stroke_it_resists(angle):
    """e = e^{iα} acts where its point moves against e: the ram's −x stroke for α = 0 (the slow one), +x for π."""
    model = MassModel(point_forces=(masses.PointForce(5, (0.1, -0.05), 2000.0, angle, name="K"),))
    sp = stroke_positions(shaping(), model, 12)
    assert sp.output.name == "E/ram" and sp.rule == "resisting_work" and sp.works[1] == pytest.approx(0, abs=1e-9)
    assert sp.works[0] == pytest.approx(2000 * 2 * LEVER * CRANK / PIVOT, rel=1e-9)
    inside = sp.working_stroke[0] + np.linspace(0.01, 0.99, 50) * sp.spans[0]
    assert np.all(np.diff(ram_x(inside)) * math.cos(angle) < 0)
    assert (sp.spans[0] > sp.spans[1]) == (angle == 0.0)
    sheet = kinematic_sheet(shaping(), sp, 10.0, 0.0, model)
    assert "K" in sheet["plan_of_positions"]["trajectories"]


# (c) the positions

@pytest.mark.parametrize("count", POSITION_COUNTS)
def test_positions_are_equally_spaced_from_the_working_stroke_start(count):
    sp = stroke_positions(shaping(), shaping_model(), count)
    steps = np.mod(np.diff(np.append(sp.phi, sp.phi[0])), 2 * math.pi)
    assert sp.count == count and np.allclose(steps, 2 * math.pi / count, rtol=0, atol=1e-12)
    assert np.all((sp.phi >= 0) & (sp.phi < 2 * math.pi))
    assert sp.phi[0] == sp.working_stroke[0] and np.count_nonzero(np.diff(sp.phi) < 0) == 1    # 340.5°, past 0
    velocity = compose(shaping().linkage, sp.phi).joints["E"].d1.real
    assert sp.working[0] and np.array_equal(sp.working[1:], velocity[1:] < 0)
    other = sp.other_extreme
    assert other["phi"] == sp.working_stroke[1] and other["after"] == int(sp.working.sum())
    assert other["label"] == f"{other['after']}′"


def test_a_typed_start_wraps_and_keeps_the_strokes():
    extreme = stroke_positions(shaping(), shaping_model(), 12)
    for typed, wrapped in ((7.0, 7.0 - 2 * math.pi), (-1.0, 2 * math.pi - 1.0), (0.5, 0.5)):
        sp = stroke_positions(shaping(), shaping_model(), 12, start=typed)
        assert sp.typed and sp.phi0 == pytest.approx(wrapped, abs=1e-15) and sp.phi[0] == sp.phi0
        assert sp.working_stroke == extreme.working_stroke
        velocity = compose(shaping().linkage, sp.phi).joints["E"].d1.real
        assert np.array_equal(sp.working, velocity < 0)
    answer = json.loads(json.dumps(sp.as_dict(), allow_nan=False))
    assert answer["start"] == "typed" and answer["strokes"]["working"] == list(extreme.working_stroke)


# (d) the scales

def standard_values() -> np.ndarray:
    return np.array(sorted(float(f"{m:g}e{k}") for k in range(-12, 12) for m in STANDARD_MANTISSAS))


@pytest.mark.parametrize("length", [POSITIONS_MM, PLAN_MM, FORCE_PLAN_MM])
def test_scales_are_the_smallest_standard_values_that_fit(length):
    values = standard_values()
    for size in np.geomspace(1e-6, 1e5, 397).tolist() + [0.25, 0.5, 1.2, 3000.0]:
        mu = standard_scale(size, length)
        assert mu in values and size / mu <= length * (1 + 1e-12)
        smaller = values[values < mu][-1]
        assert size / smaller > length
    assert standard_scale(0.0, length) is None and standard_scale(math.nan, length) is None


def test_the_sheet_scales_fit_the_drawings():
    sheet = kinematic_sheet(shaping(), stroke_positions(shaping(), shaping_model(), 12), 10.0, 25.0,
                            shaping_model())
    mu = sheet["scales"]
    drawing = sheet["plan_of_positions"]
    xy = [p for table in ("joints", "marked", "trajectories") for path in drawing[table].values() for p in path]
    assert extent(np.array(xy)) / mu["mu_l"] <= POSITIONS_MM
    for row in sheet["kinematics"]:
        for plan, scale in (("velocity", mu["mu_v"]), ("acceleration", mu["mu_a"])):
            tips = [0j]
            for equation in row[plan]:
                tips += list(np.cumsum([complex(v["x"], v["y"]) for v in equation["vectors"]]))
                assert all(v["mm"] == pytest.approx(v["value"] / scale, rel=1e-15) for v in equation["vectors"])
            assert extent(np.array(tips)) / scale <= PLAN_MM


# (e) bad input

def test_bad_positions_count_names_the_field():
    for count in (0, 6, 10, 13, 36, True):
        with pytest.raises(GeometryError) as error:
            stroke_positions(shaping(), None, count)
        assert error.value.field == "positions"


@pytest.mark.parametrize("output", ["Z/ram", "link 9", "ram", "link"])
def test_an_output_the_linkage_does_not_have_names_the_field(output):
    with pytest.raises(GeometryError) as error:
        stroke_positions(shaping(), None, 12, output=output)
    assert error.value.field == "output" and output in error.value.reason


def test_an_output_that_does_not_reverse_or_reverses_twice_per_turn():
    with pytest.raises(GeometryError) as error:
        stroke_positions(shaping(), None, 12, output="link 1")
    assert error.value.field == "output" and "does not reverse" in error.value.reason
    six = copy.deepcopy(SIX)
    six["groups"][0]["points"]["P"] = {"link": 2, "along": 0.2, "across": 0.06}
    mech = GeneralMechanism(six)
    fine = compose(mech.linkage, np.linspace(0, 2 * math.pi, 36001))
    slide = ((fine.joints["E"].z - fine.joints["D"].z) * np.exp(-1j * fine.links[3][1].th)).real
    assert np.count_nonzero(np.diff(np.sign(np.diff(slide)))) == 4     # four extremes over the turn
    with pytest.raises(GeometryError) as error:
        stroke_positions(mech, None, 12, output="E/g3")
    assert error.value.field == "output" and "4 times per turn" in error.value.reason


def test_a_crank_that_cannot_turn_fully_names_its_group():
    four_bar = copy.deepcopy(presets()["four_bar"]["linkage"])
    four_bar["input"]["length"] = 0.3                  # 0.3 + 0.4 > 0.35 + 0.3: not a crank (Grashof)
    with pytest.raises(GeometryError) as error:
        stroke_positions(GeneralMechanism(four_bar), None, 12)
    assert error.value.field == "linkage.groups.0" and "cannot turn fully" in error.value.reason
    with pytest.raises(GeometryError) as error:
        stroke_positions(GeneralMechanism(presets()["slider_driven_crank"]["linkage"]), None, 12)
    assert error.value.field == "linkage.input.kind"
    with pytest.raises(GeometryError) as error:
        stroke_positions(shaping(), None, 12, start=math.inf)
    assert error.value.field == "start"


# (a) the plans against central differences of the exact positions

def time_derivatives(samples: np.ndarray) -> tuple[complex, complex]:
    """d/dt and d²/dt² at t = 0 from samples at TIMES: the fourth-order central formulas at STEP/2 and STEP,
    Richardson-extrapolated, (16D(h/2) − D(h))/15."""
    fine, coarse = differences(samples[2:7], STEP / 2), differences(samples[::2], STEP)
    return tuple((16 * f - c) / 15 for f, c in zip(fine, coarse))


class Paths:
    """The exact composed positions along φ(t) = φ_i + ω₁t + ε₁t²/2 at TIMES, and the independent velocities
    and accelerations of the plans' vectors from them."""

    def __init__(self, linkage, phi: float, omega: float, epsilon: float):
        self.comp = compose(linkage, phi + omega * TIMES + epsilon * TIMES**2 / 2)

    def frame(self, link: int) -> tuple[np.ndarray, np.ndarray]:
        """A link's origin and (unwrapped) angle over the stencil; the frame's are 0."""
        if link == 0:
            return np.zeros(TIMES.shape, complex), np.zeros(TIMES.shape)
        origin, angle = self.comp.links[link]
        return origin.z, np.unwrap(angle.th)

    def material(self, link: int, z0: complex) -> np.ndarray:
        """The path of the link's material point that is at z0 at t = 0."""
        origin, theta = self.frame(link)
        return origin + (z0 - origin[4]) * np.exp(1j * (theta - theta[4]))

    def at(self, joint: str) -> complex:
        return self.comp.joints[joint].z[4]

    def absolute(self, path: np.ndarray) -> tuple[list, list]:
        v, a = time_derivatives(path)
        return [v], [a]

    def rotation(self, link: int, start: complex, end: complex) -> tuple[list, list]:
        """v_BA and aⁿ_BA, aᵗ_BA of two material points of one link: r = B − A differentiated, aⁿ its part
        along r."""
        r = self.material(link, end) - self.material(link, start)
        v, a = time_derivatives(r)
        radial = r[4] / abs(r[4])
        normal = (a * radial.conjugate()).real * radial
        return [v], [normal, a - normal]

    def sliding(self, moving: int, guide: int, z0: complex) -> tuple[list, list]:
        """The relative velocity and aᵏ, aʳ of the moving link's point at z0 in the guide link's own frame:
        ρ = (X − O_g)e^{−iθ_g}, v_r = ρ̇e^{iθ_g}, aʳ = ρ̈e^{iθ_g}, aᵏ = 2iθ̇_g v_r."""
        origin, theta = self.frame(guide)
        v, a = time_derivatives((self.material(moving, z0) - origin) * np.exp(-1j * theta))
        turn, spin = np.exp(1j * theta[4]), time_derivatives(theta)[0].real
        return [v * turn], [2j * spin * v * turn, a * turn]

    def equations(self, linkage) -> list[tuple[str, list, list]]:
        """Each plan equation's target and expected vectors, group by group in the order of plans.py."""
        out = []
        for group in linkage.groups:
            (i, j), outer, c = group.links, group.outer, group.inner
            host = [self.comp.guides[g].link for g in group.guides]
            if group.kind == "RRR":
                eqs = [(c, self.absolute(self.comp.joints[p].z), self.rotation(link, self.at(p), self.at(c)))
                       for p, link in zip(outer, (i, j))]
            elif group.kind == "RRP":
                b = outer[0]
                eqs = [(c, self.absolute(self.comp.joints[b].z), self.rotation(i, self.at(b), self.at(c))),
                       (c, self.absolute(self.material(host[0], self.at(c))), self.sliding(j, host[0], self.at(c)))]
            elif group.kind == "RPR":
                b, d = outer
                eqs = [(f"{b}{j}", self.absolute(self.comp.joints[b].z), self.sliding(j, i, self.at(b))),
                       (f"{b}{j}", self.absolute(self.comp.joints[d].z), self.rotation(j, self.at(d), self.at(b)))]
            elif group.kind == "PRP":
                eqs = [(c, self.absolute(self.material(g, self.at(c))), self.sliding(link, g, self.at(c)))
                       for g, link in zip(host, (i, j))]
            else:
                b = outer[0]
                eqs = [(f"{b}{j}", self.absolute(self.comp.joints[b].z), self.sliding(j, i, self.at(b))),
                       (f"{b}{j}", self.absolute(self.material(host[0], self.at(b))),
                        self.sliding(j, host[0], self.at(b)))]
            out += [(target, av + rv, aa + ra) for target, (av, aa), (rv, ra) in eqs]
        return out


def close(vectors: list[dict], expected: list[complex], scale: float) -> bool:
    return len(vectors) == len(expected) and all(
        abs(complex(v["x"], v["y"]) - z) <= 1e-9 * scale for v, z in zip(vectors, expected))


@pytest.mark.parametrize("mechanism, model", [
    (shaping, shaping_model()), (lambda: GeneralMechanism(SIX), SIX_MASSES),
    (lambda: GeneralMechanism(presets()["lever_ram"]["linkage"]), None),
    (lambda: GeneralMechanism(presets()["sine"]["linkage"]), None)], ids=["shaping", "six_bar", "lever_ram", "sine"])
def test_plans_points_and_links_match_differences_of_the_exact_positions(mechanism, model):
    mech = mechanism()
    sp = stroke_positions(mech, model, 12)
    omega, epsilon = 10 + 2 * np.sin(sp.phi), 30 * np.cos(sp.phi) - 12
    sheet = kinematic_sheet(mech, sp, omega, epsilon, model)
    coriolis = 0.0
    for k, row in enumerate(sheet["kinematics"]):
        paths = Paths(mech.linkage, sp.phi[k], omega[k], epsilon[k])
        assert row["phi"] == sp.phi[k] and row["omega1"] == omega[k] and row["epsilon1"] == epsilon[k]
        v_scale = max(v["value"] for eq in row["velocity"] for v in eq["vectors"])
        a_scale = max(v["value"] for eq in row["acceleration"] for v in eq["vectors"])
        expected = paths.equations(mech.linkage)
        assert len(expected) == len(row["velocity"]) == len(row["acceleration"])
        for (target, velocity, acceleration), v_eq, a_eq in zip(expected, row["velocity"], row["acceleration"]):
            assert v_eq["target"] == a_eq["target"] == target
            assert close(v_eq["vectors"], velocity, v_scale), (target, v_eq, velocity)
            assert close(a_eq["vectors"], acceleration, a_scale), (target, a_eq, acceleration)
            assert v_eq["residual"] <= 1e-12 * v_scale and a_eq["residual"] <= 1e-12 * a_scale
            coriolis = max([coriolis] + [v["value"] for v in a_eq["vectors"] if v["kind"] == "coriolis"])
        for name, point in row["points"].items():
            if name.startswith("S") and name[1:].isdigit() and model is not None:
                link = int(name[1:])
                item = next(m for m in model.links if m.link == link)
                origin, theta = paths.frame(link)
                path = origin + complex(*item.centre) * np.exp(1j * theta)
            else:
                path = paths.comp.joints[name].z
            v, a = time_derivatives(path)
            assert abs(complex(point["v"]["x"], point["v"]["y"]) - v) <= 1e-9 * v_scale, name
            assert abs(complex(point["a"]["x"], point["a"]["y"]) - a) <= 1e-9 * a_scale, name
        w_scale = max(abs(values["omega"]) for values in row["links"].values())
        e_scale = max(abs(values["epsilon"]) for values in row["links"].values())
        for link, values in row["links"].items():
            w, e = time_derivatives(paths.frame(int(link))[1])
            assert values["omega"] == pytest.approx(w.real, abs=1e-9 * w_scale)
            assert values["epsilon"] == pytest.approx(e.real, abs=1e-9 * e_scale)
    if mechanism is shaping:
        assert coriolis > 1.0            # the slotted lever's Coriolis term is there, and checked


def test_the_sheet_is_plain_json_with_the_output_diagrams():
    model = shaping_model()
    sp = stroke_positions(shaping(), model, 12)
    sheet = kinematic_sheet(shaping(), sp, 10.0, 0.0, model)
    assert json.loads(json.dumps(sheet, allow_nan=False)) == sheet and sheet["notices"] == []
    diagram = sheet["output_diagrams"]
    assert diagram["quantity"] == "s" and diagram["unit"] == "m" and len(diagram["phi"]) == 361
    ram = ram_x(np.array(diagram["phi"]))
    assert np.allclose(diagram["s"], ram - ram[0], rtol=0, atol=1e-14)      # the ram's x from the working start
    assert min(diagram["s"]) == pytest.approx(-2 * LEVER * CRANK / PIVOT, abs=1e-6)
    assert [m["label"] for m in diagram["marks"]] == [str(i) for i in range(1, 13)] + ["8′"]
    drawing = sheet["plan_of_positions"]
    assert all(len(path) == 12 for path in drawing["joints"].values())
    assert set(drawing["trajectories"]) == {"S2", "S3", "S4", "S5", "E"}
    lines = {line["link"]: line for line in drawing["links"]}
    assert lines[1]["joints"] == ["O", "A"] and lines[5]["slides"] == ["E/ram"]
    assert drawing["guides"]["ram"]["angle"] == [0.0] * 12


def test_undefined_values_become_null_with_their_places_listed():
    missing = []
    tree = finite({"a": [1.0, math.nan], "b": {"c": np.float64(math.inf), "d": "text", "e": None}}, "", missing)
    assert tree == {"a": [1.0, None], "b": {"c": None, "d": "text", "e": None}}
    assert missing == [".a.1", ".b.c"]


@pytest.mark.parametrize("name", ["sine", "shaping_machine", "lever_ram", "v_engine"])
def test_every_sliding_pair_has_its_guide_drawn_where_its_block_is(name):
    """The plan of positions carries the guide of every sliding pair named "joint/guide" (an RPP's slot included),
    and the block's joint lies on it: joint − point is along the guide's angle (cross product zero to 1e-12 m)."""
    preset = presets()[name]
    mechanism = GeneralMechanism(preset["linkage"])
    phi = np.linspace(0.0, 2 * np.pi, 7)
    comp = compose(mechanism.linkage, phi)
    plan = plan_of_positions(mechanism, comp, {}, None)
    for pair in comp.slides:
        if "/" not in pair:
            continue
        joint, guide = pair.split("/")
        drawn = plan["guides"][guide]
        for k in range(phi.size):
            offset = complex(*plan["joints"][joint][k]) - complex(*drawn["point"][k])
            along = complex(math.cos(drawn["angle"][k]), math.sin(drawn["angle"][k]))
            assert abs((offset * along.conjugate()).imag) < 1e-12, (pair, k)
