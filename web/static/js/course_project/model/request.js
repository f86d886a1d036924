/**
 * The body of POST /api/v1/course-project for a project: the linkage, the masses and loads, the group-I
 * inertias, ω₁ₘ and [δ] from the design data (its flywheel part), and the settings (positions, start, output,
 * chosen, drawn, title). No DOM.
 */
const MASS_KEYS = ["links", "gravity", "forces", "moments", "point_forces", "friction", "pair_radius"];

/** The request of the project {linkage, dynamics (completed), settings}. */
export function projectRequest({ linkage, dynamics, settings }) {
  const masses = Object.fromEntries(MASS_KEYS.filter((key) => dynamics.masses[key] !== undefined)
    .filter((key) => key !== "point_forces" || dynamics.masses.point_forces.length)      // none: the field left out
    .map((key) => [key, dynamics.masses[key]]));
  const { J1, J_rotor, gear_ratio } = dynamics.inertias;
  return {
    linkage, masses, inertias: { J1, J_rotor, gear_ratio },
    omega_mean: dynamics.flywheel.omega_mean, delta: dynamics.flywheel.delta,
    positions: settings.positions, start: settings.start, output: settings.output, chosen: settings.chosen,
    drawn: settings.drawn ?? [], title: settings.title,
  };
}
