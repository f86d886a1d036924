/**
 * The equations the project uses, each named by its source and number (the interface texts project_eq_<id>:
 * the formula in the notation markup, _source: "Chaika–Vasylenko (3.24)", and where the source prints an error
 * the app corrects, _printed: the printed form and what the app computes instead). The list follows the
 * report's sections; the friction items only when the project has friction.
 */
import { element } from "../../common/view/dom.js";

export const EQUATIONS = ["mobility", "positions", "analogs", "reduced_inertia", "reduced_moment", "driving", "delta",
  "motion", "merzalov", "gutyar", "wittenbauer", "flywheel_part", "disk", "inertia_loads", "groups", "lever",
  "reduced_balance", "friction_moment", "efficiency"];
const WITH_FRICTION = new Set(["friction_moment"]);

/** The list as an ordered list: the source in bold, the formula, the printed form where there is one. */
export function equationsList(answer, { t }) {
  const friction = Boolean(answer.kinetostatics?.friction);
  return element("ol", { className: "report-equations", id: "project-equations" },
    ...EQUATIONS.filter((id) => friction || !WITH_FRICTION.has(id)).map((id) => element("li", { "data-equation": id },
      element("strong", { textContent: t[`project_eq_${id}_source`] }), " — ", element("span", { rich: t[`project_eq_${id}`] }),
      ...(t[`project_eq_${id}_printed`] ? [element("br"), element("span", { className: "printed", rich: t[`project_eq_${id}_printed`] })] : []))));
}
