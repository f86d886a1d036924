/**
 * The course project's sheets: A1 landscape (841 × 594 mm) with the ESKD frame (a 20 mm binding margin on the
 * left, 5 mm elsewhere: GOST 2.104) and the title block in the bottom right corner (185 × 55 mm: the student,
 * the group, the variant, the sheet's name, its scale, the maker (the app), the date, the sheet's number and
 * count), the drawings of each sheet laid out in rows at their own size (drawing_layout.layOutSheet: a drawing
 * is never scaled, so that it stays to the scale written on it):
 *   1 kinematics     the plan of positions, the velocity and acceleration plans of the drawn positions, the
 *                    output's diagrams;
 *   2 kinetostatics  the groups with their forces, the force plans, Zhukovsky's lever;
 *   3 dynamics       J(φ), M_c(φ), the works, ω₁ and ε₁, the energy–mass diagram and the flywheel.
 * Drawings that do not fit a sheet go on to a continuation sheet of the same name. sheetFileText() gives a
 * sheet as the text of an SVG file.
 */
import { formatNumber, plainText, richText } from "../../../common/view/notation.js";
import { svgElement } from "../../../common/view/svg.js";
import { eskdScale, fittedText, layOutSheet, sheetFrame, titleBlockCells, A1, FONT } from "../../model/drawing_layout.js";
import { inertiaDiagram, momentsDiagram, outputDiagrams, speedDiagram, worksDiagram } from "./diagrams.js";
import { LINES, r } from "./figure.js";
import { forcePlans } from "./force_plans.js";
import { groupsWithForces } from "./groups.js";
import { planOfPositions } from "./plan_of_positions.js";
import { accelerationPlan, velocityPlan } from "./plans.js";
import { flywheelDrawing, wittenbauerDiagram } from "./wittenbauer.js";
import { zhukovskyLever } from "./zhukovsky.js";

const INK = "#000";
const FONT_FAMILY = "DejaVu Sans, Arial, Helvetica, sans-serif";
const FRAME_LINE = 0.7;        // mm: the frame and the title block's outline (a main line)
const CELL_PAD = 0.5;          // mm inside a title block cell
const SMALLEST = 1.8;          // mm: the smallest font of the title block (GOST 2.304)

/** The drawings of each sheet kind, built from the answer. */
const SHEETS = {
  kinematics: (answer, t, lang) => [planOfPositions(answer, t, lang),
    ...(answer.positions.drawn?.length ? answer.positions.drawn : [answer.positions.chosen ?? 1]).flatMap((number) => [
      velocityPlan(answer, t, lang, { number }), accelerationPlan(answer, t, lang, { number })]),
    outputDiagrams(answer, t, lang)],
  kinetostatics: (answer, t, lang) => [groupsWithForces(answer, t, lang), forcePlans(answer, t, lang),
    zhukovskyLever(answer, t, lang)],
  dynamics: (answer, t, lang) => [inertiaDiagram(answer, t, lang), momentsDiagram(answer, t, lang),
    worksDiagram(answer, t, lang), speedDiagram(answer, t, lang), wittenbauerDiagram(answer, t, lang),
    flywheelDrawing(answer, t, lang)],
};
export const SHEET_KINDS = Object.keys(SHEETS);

/**
 * All sheets of the project: [{kind, number, svg}], numbered 1, 2, … in the order kinematics, kinetostatics,
 * dynamics (continuation sheets where a kind's drawings need more than one); options.kinds: only these kinds
 * (still numbered among all), options.date: the title block's date (a Date; default today).
 */
export function projectSheets(answer, t, lang, options = {}) {
  const pages = SHEET_KINDS.flatMap((kind) => pagesOf(SHEETS[kind](answer, t, lang)).map((drawings, k) => ({ kind, drawings, k })));
  return pages.map((page, i) => ({ kind: page.kind, number: i + 1, page }))
    .filter(({ kind }) => !options.kinds || options.kinds.includes(kind))
    .map(({ kind, number, page }) => ({ kind, number, svg: sheetSvg(page.drawings, {
      kind, number, count: pages.length, continued: page.k > 0, date: options.date ?? new Date() }, answer, t, lang) }));
}

/** Drawings (SVG elements with data-width-mm, data-height-mm) split into sheets: [[{svg, x, y}]]. */
function pagesOf(drawings) {
  const pages = [];
  let rest = drawings;
  while (rest.length) {
    const { placed, overflow } = layOutSheet(rest.map(size));
    pages.push(rest.map((svg, i) => placed[i] && { svg, ...placed[i] }).filter(Boolean));
    rest = overflow.map((i) => rest[i]);
  }
  return pages;
}

const size = (svg) => ({ width: Number(svg.dataset.widthMm), height: Number(svg.dataset.heightMm) });

/** The sheet's name: its kind's, "(continued)" on a continuation sheet. */
function sheetName(kind, t, continued = false) {
  const name = t[`project_dwg_sheet_${kind}`];
  return continued ? t.project_dwg_continued.replace("{name}", name) : name;
}

function sheetSvg(drawings, info, answer, t, lang) {
  const sheet = sheetFrame(A1);
  const name = sheetName(info.kind, t, info.continued);
  const svg = svgElement("svg", { viewBox: `0 0 ${A1.width} ${A1.height}`, width: `${A1.width}mm`, height: `${A1.height}mm`,
    class: `cp-sheet cp-sheet-${info.kind}`, role: "img", "aria-label": plainText(name), "font-family": FONT_FAMILY,
    "data-sheet": info.number });
  svgElement("title", {}, svg).textContent = plainText(name);
  svgElement("rect", { x: 0, y: 0, width: A1.width, height: A1.height, fill: "#fff", stroke: INK, ...LINES.thin,
    class: "cp-sheet-edge" }, svg);
  const { frame } = sheet;
  svgElement("rect", { x: frame.x, y: frame.y, width: frame.width, height: frame.height, fill: "none", stroke: INK,
    "stroke-width": FRAME_LINE, class: "cp-frame" }, svg);
  for (const { svg: drawing, x, y } of drawings) {
    const { width, height } = size(drawing);
    drawing.setAttribute("x", r(x));
    drawing.setAttribute("y", r(y));
    drawing.setAttribute("width", r(width));
    drawing.setAttribute("height", r(height));
    svg.append(drawing);
  }
  titleBlock(svg, sheet.titleBlock, titleTexts(info, name, answer, t, lang), t);
  return svg;
}

/** What the title block's cells hold (cell name → text); captions are the texts of their keys. */
function titleTexts(info, name, answer, t, lang) {
  const title = answer.title ?? {};
  const scale = info.kind === "dynamics" ? "—" : eskdScale(answer.scales.mu_l, (x) => formatNumber(x, lang));
  const date = new Intl.DateTimeFormat(lang, { day: "2-digit", month: "2-digit", year: "2-digit" }).format(info.date);
  return {
    student: title.student ?? "", group: title.group ?? "", variant: title.variant ?? "", date,
    designation: `${t.project_dwg_designation} ${title.variant || "—"}.${String(info.number).padStart(2, "0")}`,
    sheet_name: name, scale, maker: t.app_title, work_kind: t.project_dwg_work_kind,
    sheet_number: t.project_dwg_tb_sheet_number.replace("{n}", info.number),
    sheet_count: t.project_dwg_tb_sheet_count.replace("{n}", info.count),
  };
}

/**
 * The title block: its cells' lines, the outline in a main line, each cell's value (texts) or printed caption
 * (the text of its key project_dwg_<cell>) fitted into it.
 */
function titleBlock(svg, block, texts, t) {
  const group = svgElement("g", { class: "cp-title-block", transform: `translate(${block.x} ${block.y})` }, svg);
  const sizes = { designation: FONT.title, sheet_name: FONT.caption };
  for (const cell of titleBlockCells()) {
    svgElement("rect", { x: cell.x, y: cell.y, width: cell.width, height: cell.height, fill: "none", stroke: INK,
      ...LINES.thin, "data-cell": cell.name }, group);
    const text = cell.caption ? t[`project_dwg_${cell.name}`] : texts[cell.name];
    if (!text) continue;
    const size = Math.min(sizes[cell.name] ?? FONT.label, cell.height - 1.2);
    const fitted = fittedText(text, cell.width - 2 * CELL_PAD, size, SMALLEST);
    const node = svgElement("text", { x: r(cell.x + cell.width / 2), y: r(cell.y + cell.height / 2 + 0.36 * fitted.size),
      "font-size": r(fitted.size), "text-anchor": "middle", fill: INK, "data-cell": cell.name }, group);
    node.append(richText(fitted.text, { svg: true }));
  }
  svgElement("rect", { x: 0, y: 0, width: block.width, height: block.height, fill: "none", stroke: INK,
    "stroke-width": FRAME_LINE }, group);
}

/** A sheet (or any drawing) as the text of an SVG file: the XML declaration, then the element with its xmlns. */
export function sheetFileText(svg) {
  return `<?xml version="1.0" encoding="UTF-8"?>\n${new XMLSerializer().serializeToString(svg)}\n`;
}
