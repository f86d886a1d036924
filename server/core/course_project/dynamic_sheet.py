"""The dynamics sheet of the course project (Chaika–Vasylenko §3.4, the steady regime's steps 8–16): the reduced
moment of inertia and its parts, the reduced resisting moment and its parts, the works, the flywheel for [δ] by
four methods with its disk, the real motion ω₁(φ), ε₁(φ) with the flywheel, δ achieved and the efficiency.

    J(φ) = J₁ + J_rotor i² + Σ_k [m_k |z′_Sk|² + J_Sk θ′_k²]          Eremyants (1.3) (structure/reduction.py)
    M_c(φ) = M_useful + M_T,  M_useful = −Σ (F·z′ + M θ′) of the loads and weights   Eremyants (1.5)
    η = A_useful/A_д = ∫ M_useful dφ / ∫ M_c dφ over the turn        Chaika–Vasylenko (3.38)

The works, ΔT_I and the energy–mass diagram are the flywheel study's (dynamics/report.flywheel, on its Simpson
grid, the constant driving moment balancing the cycle); ω₁, ε₁ are the real motion's at the sheet's angles
(real_motion.py).
"""
from __future__ import annotations

import numpy as np

from ..dynamics.general_machine import GeneralMachine
from ..structure.compose import compose
from ..structure.reduction import reduced_inertia, reduced_loads
from .real_motion import RealMotion


def dynamic_sheet(machine: GeneralMachine, flywheel: dict, motion: RealMotion) -> dict:
    """The sheet on the flywheel study's angles (``flywheel``: report.flywheel's answer for ``machine``)."""
    phi = np.asarray(flywheel["phi"], float)
    comp = compose(machine.linkage.linkage, phi)
    inertia = reduced_inertia(machine.linkage, comp, machine.masses, machine.constant_inertia)
    loads = reduced_loads(machine.linkage, comp, machine.masses)
    parts = dict(loads.parts)
    if machine.rough:
        parts["friction"] = machine.dry(comp)[0]
    state = motion.state(phi)
    curves = flywheel["curves"]
    resisting = motion.resistance
    driving = resisting.useful_work + resisting.friction_work
    phi_max, w_max, phi_min, w_min = motion.extremes
    return {
        "phi": phi, "J": inertia.J, "dJ": inertia.dJ, "J_parts": inertia.parts,
        "M_c": sum(parts.values(), np.zeros(phi.shape)), "M_c_parts": parts,
        "works": {"driving": curves["work_driving"], "resisting": curves["work_resisting"],
                  "total": curves["work_total"]},
        "delta_T": curves["delta_t_i"],
        "wittenbauer": {**flywheel["wittenbauer"], "inertia_ii": curves["inertia_ii"], "work": curves["work_total"]},
        "flywheel": {key: flywheel[key] for key in ("methods", "group_i_existing", "flywheel_inertia", "disk",
                                                    "disk_as_printed", "rim", "numerics") if key in flywheel},
        "omega": state["omega"], "epsilon": state["epsilon"],
        "omega_max": {"phi": phi_max, "omega": w_max}, "omega_min": {"phi": phi_min, "omega": w_min},
        "omega_mean": motion.omega_mean, "delta_achieved": motion.delta,
        "kinetic_energy_start": motion.level,
        "driving_moment": motion.driving_moment,
        "efficiency": resisting.useful_work / driving if driving > 0 else None,
        "numerics": motion.numerics.as_dict(),
    }
