/**
 * The report's drawings and sheets, placed from the drawing functions of view/drawings/ (each takes (answer,
 * texts, lang, options) and returns an SVG element in millimetres): a figure with its caption, at its own scale
 * where it fits the page's width, shrunk to it where not (printed: to A4 between its margins); the A1 sheets of
 * each kind (kinematics, kinetostatics, dynamics, with their continuation sheets) offered as SVG files. A drawing
 * the answer cannot give (a function that throws) leaves its caption and the reason, never a blank page.
 */
import { element } from "../../common/view/dom.js";
import { inertiaDiagram, momentsDiagram, outputDiagrams, speedDiagram, worksDiagram } from "./drawings/diagrams.js";
import { forcePlans } from "./drawings/force_plans.js";
import { groupsWithForces } from "./drawings/groups.js";
import { planOfPositions } from "./drawings/plan_of_positions.js";
import { accelerationPlan, velocityPlan } from "./drawings/plans.js";
import { SHEET_KINDS, projectSheets, sheetFileText } from "./drawings/sheet.js";
import { flywheelDrawing, wittenbauerDiagram } from "./drawings/wittenbauer.js";
import { zhukovskyLever } from "./drawings/zhukovsky.js";
import { download } from "./report_table.js";

/** The drawing functions by figure name; options.position: the position of a plan. */
const DRAWINGS = {
  plan_of_positions: planOfPositions,
  output_diagrams: outputDiagrams,
  velocity_plan: (answer, t, lang, options) => velocityPlan(answer, t, lang, { number: options.position }),
  acceleration_plan: (answer, t, lang, options) => accelerationPlan(answer, t, lang, { number: options.position }),
  inertia_diagram: inertiaDiagram,
  moment_diagram: momentsDiagram,
  work_diagrams: worksDiagram,
  wittenbauer: wittenbauerDiagram,
  flywheel: flywheelDrawing,
  speed_diagrams: speedDiagram,
  groups_with_forces: groupsWithForces,
  force_plans: forcePlans,
  zhukovsky: zhukovskyLever,
};

/**
 * A figure: the drawing `name` for the answer (options.position: a position's plans), which carries its own
 * title and scales; where it cannot be drawn, its caption and the reason.
 */
export function figure(name, answer, options) {
  const { t, lang } = options;
  try {
    return element("figure", { className: "report-figure", "data-figure": name }, DRAWINGS[name](answer, t, lang, options));
  } catch (error) {
    const caption = t[`project_figure_${name}`].replace("{k}", String(options.position ?? ""));
    return element("figure", { className: "report-figure", "data-figure": name },
      element("p", { className: "figure-pending", textContent: `${t.project_figure_failed}: ${error.message}` }),
      element("figcaption", { rich: caption }));
  }
}

/** The sheets' downloads: one button per kind of A1 sheet, each of its sheets as an SVG file. */
export function sheetTools(answer, options) {
  const { t, lang } = options;
  return element("div", { className: "sheet-tools report-tools" }, ...SHEET_KINDS.map((kind) => {
    const button = element("button", { type: "button", className: "sheet-download", "data-sheet": kind,
      rich: `${t[`project_dwg_sheet_${kind}`]} (A1, SVG)` });
    button.addEventListener("click", () => {
      for (const sheet of projectSheets(answer, t, lang, { kinds: [kind] })) {
        download(`sheet-${sheet.number}-${kind}.svg`, sheetFileText(sheet.svg), "image/svg+xml");
      }
    });
    return button;
  }));
}
