/**
 * What a preview draws: the dotted paths of the answer's leaves that a variant's panels draw while a slider
 * is dragged (plots, polar plots, drawings and their cursors), sent as the family request's "fields". The
 * server prunes every member of the family to them (server/families/family.py): nothing else is rounded, checked
 * or sent, and numbers in tables and readouts keep coming from the exact answer. No DOM: bench/ and tests/
 * run this module in Node to send what the page sends.
 *
 * Each panel kind says what it draws from its spec in the scene (content/scenes): a plot its x and its
 * series (and the path whose nulls cut a series); a polar plot its curves' θ and r; a kinematics plot its
 * outputs on the crank-angle grid with the special positions it marks; a drawing the leaves its view reads
 * at a crank angle (FIELDS_OF below, one entry per view module: keep it beside any change of what that view
 * reads in a preview). Panels a preview leaves as they are (figures, tables, numerics, calculators, studies)
 * draw nothing. A path may name a whole object ("points"); one the answer does not hold is harmless.
 */

/** The crank-angle grid and what a kinematics figure is laid out by. */
const KINEMATICS_FRAME = ["mechanism", "params", "cycle", "phi", "outputs.special"];

const FIELDS_OF = {
  // kinematics_scene.js: LinkageView (joints at φ, ghosts at the special positions) and PlotsView (figures.js)
  linkage: () => [...KINEMATICS_FRAME, "outputs.joints"],
  plot: (spec) => (spec.outputs ? [...KINEMATICS_FRAME, ...spec.outputs.map((name) => `outputs.${name}`)]
    : [spec.x, ...spec.series.flatMap((series) => [series.y, ...(series.gaps ? [series.gaps] : [])]),
      ...(spec.series_each ? [spec.series_each.path] : [])]),
  polar: (spec) => spec.series.flatMap((series) => [series.theta, series.r]),
  // dynamics panel views with a preview (dynamics_view.js PANEL_VIEWS with drawAt)
  free_body: () => ["phi", "points", "reactions", "applied", "friction", "friction_circles", "balancing_moment"],
  group_free_body: () => ["free_body"],
  gear_train: () => ["phi", "points", "inv_AP", "omega_coupler", "epsilon_star", "epsilon_star2", "epsilon"],
  wittenbauer: (spec) => ["phi", spec.x, spec.y, spec.diagram],
  flywheel_drawing: (spec) => [spec.disk],
};

/** The fields of the variant's panels (scene: content/scenes/<id>.json as the page has it), sorted, once each. */
export function previewFields(scene, variant) {
  const paths = new Set();
  for (const id of variant.panels) {
    const spec = scene.panels[id];
    const fields = spec && Object.hasOwn(FIELDS_OF, spec.kind) ? FIELDS_OF[spec.kind](spec) : [];
    for (const path of fields) if (typeof path === "string" && path) paths.add(path);
  }
  return [...paths].sort();
}
