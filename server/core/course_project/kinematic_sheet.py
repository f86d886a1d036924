"""The kinematics sheet of the course project (Chaika–Vasylenko §3.4): the plan of positions, the velocity and
acceleration plans at every position, and the output's diagrams, as plain dicts for JSON.

At position i the crank turns at ω₁(φ_i) with ε₁(φ_i) (the real motion's values, or ω₁ₘ and 0).  Every
point's velocity and acceleration come from the closed-form analogs (Eremyants §2.1):

    v = z′ω₁,   a = z″ω₁² + z′ε₁,   a link's ω = θ′ω₁,  ε = θ″ω₁² + θ′ε₁

and every plan equation (structure/plans.py: v_C = v_B + v_CB, a_C = a_B + aⁿ_CB + aᵗ_CB, with a moving guide
a_B3 = a_B2 + aᵏ_B3B2 + aʳ_B3B2) gives its vectors and its residual against them.  A vector of magnitude V is drawn
V/μ mm long at the sheet's standard scale μ (scales.py), one μ_v and one μ_a for the plans of all positions.
"""
from __future__ import annotations

import math

import numpy as np

from ..mechanisms.general import GeneralMechanism
from ..structure.compose import Composition, compose
from ..structure.masses import MassModel, centre_points, pair_of, slider_link
from ..structure.plans import plans
from ..structure.state import Point, on_link
from .positions import StrokePositions, TWO_PI
from .scales import PLAN_MM, POSITIONS_MM, extent, plan_vertices, standard_scale

TRAJECTORY_POINTS = 361          # the turn at 1°


def link_joints(mechanism: GeneralMechanism) -> dict[int, list[str]]:
    """The joints that draw each moving link, in order along it (from the linkage's groups: the crank
    pivot → pin; RRR B → C, D → C; RRP rod B → C and the slider at C; RPR the block at B and the lever from D
    through B; PRP both blocks at C; RPP the block at B and the slotted link at R), then the points fixed on it."""
    linkage = mechanism.linkage
    crank = linkage.crank
    lines = {crank.link: [crank.pivot, crank.joint]}
    attached = list(crank.points)
    for group in linkage.groups:
        (i, j), outer, c = group.links, group.outer, group.inner
        if group.kind in ("RRR", "RRP"):
            lines |= {i: [outer[0], c], j: [outer[1], c] if group.kind == "RRR" else [c]}
        elif group.kind == "RPR":
            lines |= {i: [outer[0]], j: [outer[1], outer[0]]}
        else:
            lines |= {i: [outer[0] if outer else c], j: [c]}
        attached += group.points
    for point in attached:
        lines[point.link].append(point.name)
    return lines


def vector(z: complex, scale: float | None) -> dict:
    """A vector's x, y, magnitude and its length on the drawing, magnitude/μ mm (None without a scale)."""
    value = abs(z)
    return {"x": z.real, "y": z.imag, "value": value, "mm": None if scale is None else value / scale}


def marked_points(comp: Composition, model: MassModel | None) -> dict[str, Point]:
    """The centres of mass S_k of the model's links and the points of its loads that are no joint: a slider
    force acts at its slider's origin, a point force at its point (along, across) on its link, named by its name
    or F1, F2 … in order.  A centre keeps the name S_k unless a joint of that name stands elsewhere (then
    "S_k (centre)")."""
    if model is None:
        return {}
    marked = {}
    for item, (centre, _) in zip(model.links, centre_points(comp, model)):
        name = f"S{item.link}"
        if name in comp.joints and not np.allclose(comp.joints[name].z, centre.z, rtol=0, atol=1e-12):
            name = f"S{item.link} (centre)"
        marked[name] = centre
    for i, force in enumerate(model.forces):
        pair = pair_of(comp, force.joint, f"masses.forces.{i}.joint")
        origin = comp.links[slider_link(comp, pair)][0]
        if not any(origin is point for point in comp.joints.values()):
            marked[f"load {pair}"] = origin
    for force in model.point_forces:
        marked[force.label] = on_link(*comp.links[force.link], complex(*force.point))
    return marked


def trajectories(mechanism: GeneralMechanism, model: MassModel | None) -> dict[str, list]:
    """The centres' and the load points' paths over the turn at 1° ([[x, y], …], the loads at joints too)."""
    comp = compose(mechanism.linkage, np.linspace(0.0, TWO_PI, TRAJECTORY_POINTS))
    paths = {name: p.z for name, p in marked_points(comp, model).items()}
    for i, force in enumerate(model.forces if model is not None else ()):
        joint = pair_of(comp, force.joint, f"masses.forces.{i}.joint").split("/")[0]
        if joint in comp.joints:
            paths[joint] = comp.joints[joint].z
    return {name: xy_list(z) for name, z in paths.items()}


def xy_list(z: np.ndarray) -> list[list[float]]:
    return np.stack([z.real, z.imag], axis=-1).tolist()


def plan_of_positions(mechanism: GeneralMechanism, comp: Composition, marked: dict[str, Point],
                      model: MassModel | None) -> dict:
    """The joints and the ``marked`` points (centres, loads) at every position, the links' lines (joint names),
    every guide (its point and angle at every position, the link that carries it), the trajectories over the
    turn."""
    slides = {}
    for pair in comp.slides:
        slides.setdefault(slider_link(comp, pair), []).append(pair)
    guides = {name: {"link": g.link, "point": xy_list(g.point.z), "angle": g.angle.th.tolist()}
              for name, g in comp.guides.items()}
    for group in comp.groups:          # an RPP's slot: on the slotted link through R, along the block's frame
        if group.kind == "RPP":
            block, slotted = group.links
            slot = list(group.slides)[1].split("/")[1]
            guides[slot] = {"link": slotted, "point": xy_list(comp.links[slotted][0].z),
                            "angle": comp.links[block][1].th.tolist()}
    return {"joints": {name: xy_list(p.z) for name, p in comp.joints.items()},
            "marked": {name: xy_list(p.z) for name, p in marked.items()},
            "links": [{"link": k, "joints": names, "slides": slides.get(k, [])}
                      for k, names in sorted(link_joints(mechanism).items())],
            "guides": guides, "trajectories": trajectories(mechanism, model)}


def position_rows(comp: Composition, marked: dict[str, Point], positions: StrokePositions, omega1: np.ndarray,
                  epsilon1: np.ndarray) -> tuple[list[dict], float | None, float | None]:
    """One row per position (module docstring) and the scales μ_v, μ_a: the smallest standard values at which
    every plan and every point's vector fits PLAN_MM."""
    points = comp.joints | marked
    rows, v_ends, a_ends = [], [], []
    for k in range(positions.count):
        plan = plans(comp, float(omega1[k]), float(epsilon1[k]), k)
        v = {name: p.d1[k] * omega1[k] for name, p in points.items()}
        a = {name: p.d2[k] * omega1[k] ** 2 + p.d1[k] * epsilon1[k] for name, p in points.items()}
        v_ends += plan_vertices(plan["velocity"]) + list(v.values())
        a_ends += plan_vertices(plan["acceleration"]) + list(a.values())
        rows.append((plan, v, a))
    mu_v, mu_a = standard_scale(extent(np.array(v_ends)), PLAN_MM), standard_scale(extent(np.array(a_ends)), PLAN_MM)
    table = []
    for k, (plan, v, a) in enumerate(rows):
        table.append({"number": k + 1, "phi": float(positions.phi[k]), "working": bool(positions.working[k]),
                      "omega1": float(omega1[k]), "epsilon1": float(epsilon1[k]),
                      "points": {name: {"v": vector(v[name], mu_v), "a": vector(a[name], mu_a)} for name in v},
                      "links": plan["links"],
                      "velocity": drawn(plan["velocity"], mu_v), "acceleration": drawn(plan["acceleration"], mu_a)})
    return table, mu_v, mu_a


def drawn(equations: list[dict], scale: float | None) -> list[dict]:
    """The plan's equations with every vector's (and the analytic value's) length in mm at ``scale``."""
    mm = (lambda value: None) if scale is None else (lambda value: value / scale)
    return [equation | {"vectors": [v | {"mm": mm(v["value"])} for v in equation["vectors"]],
                        "analytic": equation["analytic"] | {"mm": mm(equation["analytic"]["value"])}}
            for equation in equations]


def output_diagrams(mechanism: GeneralMechanism, positions: StrokePositions) -> dict:
    """The output over the turn at 1° from position 1: φ = φ₀ … φ₀ + 2π, its displacement from the working
    stroke's start (s − s_start in m, or θ − θ_start in rad, unwrapped), its first and second analogs (m, or
    1), and the positions marked at φ₀ + 2π(i − 1)/N (and k′, the working stroke's end)."""
    output, phi0, count = positions.output, positions.phi0, positions.count
    phi = phi0 + np.linspace(0.0, TWO_PI, TRAJECTORY_POINTS)
    q, q1, q2 = output.analogs(compose(mechanism.linkage, phi))
    start = positions.extremes[0]
    shift = q - start if output.kind == "slide" else np.unwrap(q) - (q[0] - math.remainder(q[0] - start, TWO_PI))
    other = positions.other_extreme
    marks = [{"label": str(i + 1), "number": i + 1, "phi": phi0 + TWO_PI * i / count,
              "working": bool(positions.working[i])} for i in range(count)]
    marks.append({"label": other["label"], "number": None,
                  "phi": phi0 + float(np.mod(other["phi"] - phi0, TWO_PI)), "working": False})
    return {"quantity": "s" if output.kind == "slide" else "theta", "unit": output.unit, "origin": start,
            "phi": phi.tolist(), "s": shift.tolist(), "s1": q1.tolist(), "s2": q2.tolist(), "marks": marks}


def finite(tree, path: str, missing: list[str]):
    """The answer with every NaN or ±inf replaced by None, their places listed in ``missing``."""
    if isinstance(tree, dict):
        return {key: finite(value, f"{path}.{key}", missing) for key, value in tree.items()}
    if isinstance(tree, list):
        return [finite(value, f"{path}.{i}", missing) for i, value in enumerate(tree)]
    if isinstance(tree, (float, np.floating)):
        if math.isfinite(tree):
            return float(tree)
        missing.append(path)
        return None
    return tree


def kinematic_sheet(mechanism: GeneralMechanism, positions: StrokePositions, omega1, epsilon1=0.0,
                    model: MassModel | None = None) -> dict:
    """The kinematics sheet at the N positions, ω₁ and ε₁ (rad/s, rad/s²; numbers or arrays of N, one per
    position): ``scales`` (μ_l, μ_v, μ_a), ``plan_of_positions``, ``kinematics`` (one row per position),
    ``output_diagrams`` and ``notices`` (the values a group could not give, None in the answer)."""
    omega1 = np.broadcast_to(np.asarray(omega1, float), positions.phi.shape)
    epsilon1 = np.broadcast_to(np.asarray(epsilon1, float), positions.phi.shape)
    comp = compose(mechanism.linkage, positions.phi)
    marked = marked_points(comp, model)
    drawing = plan_of_positions(mechanism, comp, marked, model)
    everything = [xy for table in ("joints", "marked", "trajectories") for path in drawing[table].values()
                  for xy in path]
    rows, mu_v, mu_a = position_rows(comp, marked, positions, omega1, epsilon1)
    sheet = {"scales": {"mu_l": standard_scale(extent(np.array(everything)), POSITIONS_MM), "mu_v": mu_v,
                        "mu_a": mu_a},
             "plan_of_positions": drawing, "kinematics": rows,
             "output_diagrams": output_diagrams(mechanism, positions)}
    missing: list[str] = []
    sheet = finite(sheet, "", missing)
    sheet["notices"] = [] if not missing else [
        {"code": "value_undefined", "text": f"{len(missing)} values are undefined (a group cannot give them at "
         f"that position: a dead position or a limit of assembly), null in the answer: "
         f"{', '.join(m.lstrip('.') for m in missing[:10])}{' …' if len(missing) > 10 else ''}",
         "context": {"places": [m.lstrip(".") for m in missing]}}]
    return sheet
