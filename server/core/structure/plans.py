"""Velocity and acceleration plans (планы скоростей и ускорений) at one crank angle, group by group.

Each group's vector equations (group.py) are evaluated with ω₁, ε₁: a velocity term is V ω₁, an acceleration
term A ω₁² + V ε₁ (Eremyants §2.1: v = z′ω₁, a = z″ω₁² + z′ε₁).  Every equation's sum is compared with the
target point's analytic velocity and acceleration from the closed-form analogs (``residual``, m/s and m/s²),
which the textbook's graphical construction only approximates; the plan is drawn from the pole p (π).
"""
from __future__ import annotations

from .compose import Composition


def vector(value: complex) -> dict:
    """A plan's vector: its x, y and magnitude |z|."""
    return {"x": float(value.real), "y": float(value.imag), "value": float(abs(value))}


def plans(comp: Composition, omega1: float, epsilon1: float, k: int = 0) -> dict:
    """The plans at the k-th angle of ``comp``: every vector (x, y, magnitude) with its label and kind."""
    velocity, acceleration = [], []
    for number, group in enumerate(comp.groups):
        plan = group.plan()
        targets = comp.joints | plan.coincident
        for (target, terms), (_, acc_terms) in zip(plan.velocity, plan.acceleration):
            point = targets[target]
            vectors = [{"name": t.name, "kind": t.kind, **vector(t.v[k] * omega1)} for t in terms]
            total = sum(t.v[k] * omega1 for t in terms)
            analytic = point.d1[k] * omega1
            velocity.append({"group": number, "kind": group.kind, "target": target, "vectors": vectors,
                             "equation": f"p{target.lower()} = " + " + ".join(t.name for t in terms),
                             "analytic": vector(analytic), "residual": float(abs(total - analytic))})
            vectors = [{"name": t.name, "kind": t.kind, **vector(t.a[k] * omega1**2 + t.v[k] * epsilon1)}
                       for t in acc_terms]
            total = sum(t.a[k] * omega1**2 + t.v[k] * epsilon1 for t in acc_terms)
            analytic = point.d2[k] * omega1**2 + point.d1[k] * epsilon1
            acceleration.append({"group": number, "kind": group.kind, "target": target, "vectors": vectors,
                                 "equation": f"π{target.lower()} = " + " + ".join(t.name for t in acc_terms),
                                 "analytic": vector(analytic), "residual": float(abs(total - analytic))})
    links = {str(link): {"omega": float(angle.d1[k] * omega1),
                         "epsilon": float(angle.d2[k] * omega1**2 + angle.d1[k] * epsilon1)}
             for link, (_, angle) in comp.links.items()}
    points = {name: {"v": vector(p.d1[k] * omega1), "a": vector(p.d2[k] * omega1**2 + p.d1[k] * epsilon1)}
              for name, p in comp.joints.items()}
    return {"phi": float(comp.phi[k]), "omega1": omega1, "epsilon1": epsilon1, "velocity": velocity,
            "acceleration": acceleration, "links": links, "points": points}
