"""What the force scene shows of a general mechanism: reactions by pair, friction, the table of approximations,
the crank check (3.2), the efficiency over the cycle (3.38) and the free-body data of every group at one angle.

Names: a reaction R_ab is the force link a exerts on link b (0 the frame), as the crank-slider's R₁₂, R₂₃; a
prismatic pair's normal force N_ab and the lever l = M/N of its normal pressure from the pair's point along
the line (3.20).
"""
from __future__ import annotations

import numpy as np

from .analysis import GroupForces
from .pairs import KinematicPair


def label(a: int, b: int) -> str:
    return f"{a}{b}" if a < 10 and b < 10 else f"{a},{b}"


def pair_table(result: GroupForces) -> list[dict]:
    return [{"name": p.name, "kind": p.kind, "links": [p.a, p.b], "label": label(p.a, p.b),
             "group": k // 3 if k < 3 * len(result.groups) else None} for k, p in enumerate(result.pairs)]


def pair_forces(result: GroupForces, row) -> tuple[dict, dict, dict]:
    """Reactions (N, 2) by R_ab, normal forces and their levers by N_ab (prismatic pairs)."""
    reactions, normals, levers = {}, {}, {}
    for group in result.groups:
        x = row.unknowns[group.index]
        for p, pair in enumerate(group.pairs):
            name = label(pair.a, pair.b)
            if pair.kind == "R":
                reactions[f"R{name}"] = x[:, 2 * p:2 * p + 2]
            else:
                force = x[:, 2 * p] * 1j * pair.u
                reactions[f"R{name}"] = np.stack([force.real, force.imag], 1)
                normals[f"N{name}"] = x[:, 2 * p]
                with np.errstate(divide="ignore", invalid="ignore"):
                    levers[f"l{name}"] = x[:, 2 * p + 1] / x[:, 2 * p]
    reactions[f"R{label(0, result.crank_link)}"] = np.stack([row.R01.real, row.R01.imag], 1)
    return reactions, normals, levers


def friction_loads(result: GroupForces, row) -> dict:
    """Each pair's friction load on link b: a moment (R, N·m) or a force along the line (P, N)."""
    return {f"{'M' if p.kind == 'R' else 'F'}{label(p.a, p.b)}": row.friction[k] for k, p in enumerate(result.pairs)}


def efficiency(result: GroupForces) -> dict:
    """η = |A_useful|/(|A_useful| + A_friction) over the cycle (Chaika–Vasylenko (3.38), second form).

    A_useful: the work against the useful loads, −∫Σ(F·z′ + Mθ′)dφ over the slider forces and load moments;
    A_friction: what the pairs dissipate, ∫Σ|z_p||relative_p|dφ (a friction moment times the relative
    rotation, a friction force times the sliding, per unit crank angle).  η = 1 exactly without friction."""
    phi = result.phi
    useful = -sum(((np.conj(l.force) * l.rate).real if l.force is not None else l.moment * l.rate)
                  for l in result.loads if l.kind == "useful") if any(l.kind == "useful" for l in result.loads) \
        else np.zeros(phi.size)
    lost = sum(np.abs(result.solution.friction[k] * p.relative) for k, p in enumerate(result.pairs))
    driving = result.solution.balancing
    if not (np.isfinite(driving).all() and np.isfinite(lost).all()):
        return {"efficiency": None, "work_useful": None, "work_driving": None, "work_friction": None}
    a_useful, a_lost = abs(float(np.trapezoid(useful, phi))), float(np.trapezoid(lost, phi))
    return {"efficiency": 1.0 if a_lost == 0 else a_useful / (a_useful + a_lost), "work_useful": a_useful,
            "work_driving": float(np.trapezoid(driving, phi)), "work_friction": a_lost}


def crank_check(result: GroupForces) -> dict:
    """(3.2): the balancing moment against the moment known from the dynamics, the reduced moment of all the
    loads by power equality; without friction the difference is the arithmetic's, with friction friction's share
    (relative to the largest reduced moment).  The frictionless balancing moment is the first approximation."""
    reduced = result.reduced_moment
    scale = max(float(np.nanmax(np.abs(reduced))), 1e-300)
    first = result.approximations[0].balancing
    return {"frictionless": float(np.nanmax(np.abs(first - reduced))) / scale,
            "with_friction": float(np.nanmax(np.abs(result.solution.balancing - reduced))) / scale}


def xy(z) -> list[float]:
    return [float(np.real(z)), float(np.imag(z))]


def free_body(result: GroupForces, k: int) -> list[dict]:
    """At angle index k: per group (reverse order of attachment, as solved) and then the crank, the loads on
    each link: points, applied loads, the reactions of every pair on it (its own pairs' and, by the third law,
    those of the later groups attached to it), the friction and the friction circles ρ = f·r — each force with
    its point, each couple with its value."""
    row = result.solution
    links_of = {g.index: g.links for g in result.groups}
    bodies = []

    def body(title, kind, links, pairs):
        entry = {"group": title, "kind": kind, "links": list(links), "points": {}, "loads": [], "reactions": [],
                 "friction": [], "friction_circles": {}}
        for load in result.loads:
            if load.link in links:
                item = {"name": load.name, "link": load.link, "kind": load.kind}
                if load.force is not None:
                    item |= {"at": xy(load.z[k]), "force": xy(load.force[k])}
                else:
                    item["moment"] = float(load.moment[k])
                entry["loads"].append(item)
        for index, pair in pairs:
            reaction, couple = reaction_of(result, row, index, pair, k)
            entry["points"][pair.joint] = xy(pair.z[k])
            c = result.coefficients[index]
            if pair.kind == "R":
                entry["friction_circles"][pair.joint] = c.f * c.r
            for link, sign in ((pair.b, 1.0), (pair.a, -1.0)):
                if link not in links:
                    continue
                name = label(pair.a, pair.b) if sign > 0 else label(pair.b, pair.a)
                entry["reactions"].append({"name": f"R{name}", "pair": pair.name, "kind": pair.kind, "link": link,
                                           "at": xy(pair.z[k]), "force": xy(sign * reaction),
                                           "moment": float(sign * couple)})
                z = float(row.friction[index, k])
                entry["friction"].append({"name": f"{'M' if pair.kind == 'R' else 'F'}{name}", "pair": pair.name,
                                          "link": link, "at": xy(pair.z[k]),
                                          **({"moment": sign * z} if pair.kind == "R" else
                                             {"force": xy(sign * z * pair.u[k])})})
        return entry

    indexed = list(enumerate(result.pairs))
    touching = lambda links: [(i, p) for i, p in indexed if p.a in links or p.b in links]
    for group in reversed(result.groups):
        bodies.append(body(group.index, group.kind, links_of[group.index], touching(links_of[group.index])))
    crank = result.crank_link
    entry = body("crank", "crank", (crank,), touching((crank,)))
    entry["balancing_moment"] = float(result.sense * row.balancing[k])      # counter-clockwise, N·m
    bodies.append(entry)
    return bodies


def reaction_of(result: GroupForces, row, index: int, pair: KinematicPair, k: int) -> tuple[complex, float]:
    """The force (and a prismatic pair's couple) link a exerts on link b at angle index k."""
    if index >= 3 * len(result.groups):
        return complex(row.R01[k]), 0.0
    x = row.unknowns[index // 3][k, 2 * (index % 3):2 * (index % 3) + 2]
    if pair.kind == "R":
        return complex(x[0], x[1]), 0.0
    return complex(x[0] * 1j * pair.u[k]), float(x[1])


def group_forces_report(result: GroupForces, at: float) -> dict:
    """Everything the force scene draws for a general mechanism; the free bodies at the grid angle nearest ``at``
    (rad)."""
    row = result.solution
    reactions, normals, levers = pair_forces(result, row)
    k = int(np.argmin(np.abs(np.angle(np.exp(1j * (result.phi - at))))))
    table = [{"change": a.change, "balancing_moment": float(a.balancing[k]),
              "reactions": {name: float(np.hypot(*v[k])) for name, v in pair_forces(result, a)[0].items()}}
             for a in result.approximations]
    return {
        "phi": result.phi,
        "points": {name: np.stack([p.z.real, p.z.imag], 1) for name, p in result.comp.joints.items()},
        "pairs": pair_table(result),
        "reactions": reactions,
        "magnitudes": {name: np.hypot(v[:, 0], v[:, 1]) for name, v in reactions.items()},
        "normals": normals,
        "levers": levers,
        "balancing_moment": row.balancing,
        "reduced_moment": result.reduced_moment,
        "friction": friction_loads(result, row),
        "friction_circles": {label(p.a, p.b): c.f * c.r for p, c in zip(result.pairs, result.coefficients)
                             if p.kind == "R"},
        "iteration": {"changes": [a.change for a in result.approximations], "ratio": result.ratio,
                      "approximations": len(result.approximations), "ratios": result.ratios, "table": table,
                      "at": float(result.phi[k])},
        "converged": result.converged,
        "locked": result.locked,
        "free_body": {"phi": float(result.phi[k]), "bodies": free_body(result, k)},
        "crank_check": crank_check(result),
        "numerics": result.numerics,
        **efficiency(result),
    }
