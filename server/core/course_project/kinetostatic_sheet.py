"""The kinetostatics sheet at one position (Chaika–Vasylenko §3.1, the course project's step 17): the inertia loads
of every link, the reactions group by group, each group's force plan.

Inertia loads (3.1): F_in = −m a_S at S and M_in = −J_S ε; together they are the one force F_in acting along a
line at the distance h = |M_in|/|F_in| from S, on the side where F_in's moment about S is M_in: through the point
K = S + d with d = −M_in·iF_in/|F_in|² (d ⊥ F_in, d × F_in = M_in).

Force plan of a group: every force on the group's links from outside it (weights, inertia forces, useful loads,
the reactions of the pairs that join it to the rest, friction forces of prismatic pairs) laid tail to head at the
scale μ_F (N per mm) in the order known loads, then reactions: the group is in equilibrium, so the polygon
closes; its ``closure`` is |ΣF| relative to the largest force (round-off).  Couples (M_in, friction moments, a
prismatic pair's couple of its normal pressure) do not enter a force plan.  The crank's plan closes with the
frame's reaction R₀₁; the balancing moment is a couple.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..kinetostatics.groups.analysis import Approximation, GroupForces
from ..kinetostatics.groups.report import free_body, label, reaction_of


def xy(z) -> list[float]:
    return [float(np.real(z)), float(np.imag(z))]


def inertia_loads(result: GroupForces, k: int) -> list[dict]:
    """Each massive link's F_in (N, at S), M_in (N·m, counter-clockwise positive), the offset h (m) and the point
    K of their resultant (None where F_in vanishes: then the inertia load is the couple alone), at angle index k."""
    forces = {l.link: l for l in result.loads if l.kind == "inertia" and l.force is not None}
    couples = {l.link: l for l in result.loads if l.kind == "inertia" and l.force is None}
    out = []
    for link, load in forces.items():
        force, centre = complex(load.force[k]), complex(load.z[k])
        couple = float(couples[link].moment[k]) if link in couples else 0.0
        size = abs(force)
        shift = -couple * 1j * force / size**2 if size > 0 else None
        out.append({"link": link, "centre": xy(centre), "force": xy(force), "magnitude": size, "moment": couple,
                    "offset": abs(couple) / size if size > 0 else None,
                    "point": None if shift is None else xy(centre + shift)})
    return out


def outside_forces(result: GroupForces, row: Approximation, links: tuple[int, ...], k: int) -> list[dict]:
    """The forces on ``links`` from outside them at angle index k: the loads' forces, then the friction forces of
    the prismatic pairs joining them to the rest, then those pairs' reactions; each with its name and point."""
    inside = set(links)
    loads = [{"name": l.name, "kind": l.kind, "link": l.link, "at": xy(l.z[k]), "force": complex(l.force[k])}
             for l in result.loads if l.link in inside and l.force is not None]
    friction, reactions = [], []
    for index, pair in enumerate(result.pairs):
        if (pair.a in inside) == (pair.b in inside):
            continue                                      # internal to the group, or not touching it
        on, sign = (pair.b, 1.0) if pair.b in inside else (pair.a, -1.0)
        name = label(pair.a, pair.b) if sign > 0 else label(pair.b, pair.a)
        force, _ = reaction_of(result, row, index, pair, k)
        reactions.append({"name": f"R{name}", "kind": "reaction", "link": on, "at": xy(pair.z[k]),
                          "force": sign * force})
        z = float(row.friction[index, k])
        if pair.kind == "P" and z:
            friction.append({"name": f"F_f{name}", "kind": "friction", "link": on, "at": xy(pair.z[k]),
                             "force": complex(sign * z * pair.u[k])})
    return loads + friction + reactions


def force_plan(forces: list[dict], mu_f: float) -> dict:
    """The forces tail to head from the pole at μ_F (mm), and the polygon's closure |ΣF|/max|F|."""
    tip, vectors = 0j, []
    for item in forces:
        step = item["force"] / mu_f
        vectors.append({"name": item["name"], "kind": item["kind"], "force": xy(item["force"]),
                        "magnitude": abs(item["force"]), "mm": abs(step), "from": xy(tip), "to": xy(tip + step)})
        tip += step
    largest = max((abs(item["force"]) for item in forces), default=0.0)
    return {"vectors": vectors, "closure": abs(tip) * mu_f / largest if largest > 0 else 0.0}


def group_sheets(result: GroupForces, row: Approximation, k: int, mu_f: float) -> tuple[list[dict], list[dict]]:
    """At angle index k with the reactions and friction of ``row``: the free bodies group by group in the order
    solved (the last group first, the crank last: kinetostatics/groups/report.free_body), and each one's force
    plan at μ_F."""
    view = replace(result, solution=row)
    bodies = free_body(view, k)
    for body in bodies:
        for reaction in body["reactions"]:
            reaction["magnitude"] = float(np.hypot(*reaction["force"]))
    plans = []
    for body in bodies:
        forces = outside_forces(result, row, tuple(body["links"]), k)
        plans.append({"group": body["group"], "kind": body["kind"], "links": body["links"],
                      **force_plan(forces, mu_f)})
    return bodies, plans


def largest_force(result: GroupForces, row: Approximation, k: int) -> float:
    """The largest force of every group's plan at angle index k, N (what μ_F must fit)."""
    links = [g.links for g in result.groups] + [(result.crank_link,)]
    return max((abs(item["force"]) for group in links for item in outside_forces(result, row, group, k)),
               default=0.0)
