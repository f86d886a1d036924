/**
 * The report's drawings and sheets, placed from the drawing functions of view/drawings/ (each takes (answer,
 * texts, lang, options) and returns an SVG element): a figure with its caption, as wide as the page (printed:
 * as wide as A4 between its margins); the A1 sheets offered as SVG files. A drawing the answer cannot give
 * (a function that throws) leaves its caption and the reason, never a blank page.
 */
import { element } from "../../common/view/dom.js";
import { download } from "./report_table.js";

/** The drawing functions by figure name, and the sheets by name ({name: function}). */
const DRAWINGS = {};
const SHEETS = {};

/** A figure: the drawing `name` for the answer (options.position: a position's plans) under its caption. */
export function figure(name, answer, options) {
  const { t, lang } = options;
  const caption = options.position ? t[`project_figure_${name}`].replace("{k}", String(options.position))
    : t[`project_figure_${name}`];
  const draw = DRAWINGS[name];
  let body;
  try {
    body = draw ? draw(answer, t, lang, options) : null;
  } catch (error) {
    body = element("p", { className: "figure-pending", textContent: `${t.project_figure_failed}: ${error.message}` });
  }
  return element("figure", { className: "report-figure", "data-figure": name },
    body ?? element("p", { className: "figure-pending", textContent: t.project_figure_pending }),
    element("figcaption", { rich: caption }));
}

/** The sheets' downloads: one button per A1 sheet, its SVG as a file. */
export function sheetTools(answer, options) {
  const { t, lang } = options;
  const names = Object.keys(SHEETS);
  if (!names.length) return element("p", { className: "hint", textContent: t.project_figure_pending });
  return element("div", { className: "sheet-tools" }, ...names.map((name) => {
    const button = element("button", { type: "button", className: "sheet-download", "data-sheet": name,
      textContent: `${t[`project_sheet_${name}`]} (SVG)` });
    button.addEventListener("click", () => {
      const svg = SHEETS[name](answer, t, lang, options);
      download(`${name}.svg`, `<?xml version="1.0" encoding="UTF-8"?>\n${new XMLSerializer().serializeToString(svg)}`,
        "image/svg+xml");
    });
    return button;
  }));
}
