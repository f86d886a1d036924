/**
 * The force plans of the position of the force analysis (Chaika–Vasylenko §3.4, step 17): each structural
 * group's closed force polygon and the crank's, at the sheet's μ_F, the forces head to tail in the order the
 * answer lays them (its `from` and `to`, mm, y up), each labelled as the group's free body names it (R₁₂, G₂,
 * Φ₂, P …: forces_friction/model/group_free_body.js), the polygon's start marked; under each polygon its
 * forces' lengths on paper and values. A force of F N is F/μ_F mm long.
 */
import { formatNumber, formatQuantity } from "../../../common/view/notation.js";
import { symbolOf } from "../../../forces_friction/model/group_free_body.js";
import { paperPlacement, textBox, FONT } from "../../model/drawing_layout.js";
import { heading, scaleText, textLines } from "./captions.js";
import { Figure } from "./figure.js";

const MARGIN = 8;              // mm around a polygon
const GAP = 12;                // mm between two polygons
const HEAD = 18;               // mm of the heading
const CAPTION = 7;             // mm of a polygon's caption above it

/** The force plans of answer.kinetostatics (fields: number, force_plans; scales.mu_F), side by side, as an SVG. */
export function forcePlans(answer, t, lang, options = {}) {
  const figure = forcePlansFigure(answer, t, lang);
  return options.figure ? figure : figure.toSvg(figure.title, "cp-force-plans");
}

/** A group's name as its free body is named: "Группа RRP: звенья 4, 5", "Кривошип 1". */
export function groupCaption(group, t) {
  return group.group === "crank" ? t.fb_group_crank
    : t.fb_group_named.replace("{kind}", group.kind).replace("{links}", group.links.join(", "));
}

/** A force's symbol in the textbook's notation, from the answer's name and kind. */
function forceSymbol(name, kind) {
  return symbolOf(name, kind === "reaction" ? "" : kind);
}

export function forcePlansFigure(answer, t, lang) {
  const { kinetostatics: kinetic, scales } = answer;
  const mu = scales.mu_F;
  const figure = new Figure();
  figure.title = t.project_dwg_force_plans.replace("{n}", kinetic.number);
  heading(figure, [0, 0], figure.title, [scaleText("μ_F", mu, t.units_N, t, lang)]);
  let left = 0;
  for (const plan of kinetic.force_plans) {
    const ends = plan.vectors.flatMap((v) => [v.from, v.to]).map(([x, y]) => [x * mu, y * mu]);   // back to N
    const place = paperPlacement([[0, 0], ...ends], mu, MARGIN);
    const caption = groupCaption(plan, t);
    const list = plan.vectors.map((v) => `${forceSymbol(v.name, v.kind)} = ${formatNumber(v.mm, lang, 1)} ${t.editor_mm}; `
      + `${formatQuantity(v.magnitude, lang, 4)} ${t.units_N}`);
    const width = Math.max(place.width, widest([caption], FONT.label), widest(list, FONT.small));
    const at = ([x, y]) => {
      const [px, py] = place.at([x * mu, y * mu]);
      return [left + px + (width - place.width) / 2, py + HEAD + CAPTION];
    };
    figure.text(caption, [left, HEAD + 3], { size: FONT.label, attrs: { class: "cp-caption" } });
    const start = plan.vectors.length ? at(plan.vectors[0].from) : at([0, 0]);
    figure.dot(start, 0.6, { "data-role": "polygon-start" });
    for (const v of plan.vectors) {
      const [a, b] = [at(v.from), at(v.to)];
      figure.arrow(a, b, v.kind === "reaction" ? "main" : "thin", { "data-force": v.name, "data-group": plan.group });
      const middle = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
      const length = Math.hypot(b[0] - a[0], b[1] - a[1]) || 1;
      const normal = [(b[1] - a[1]) / length, -(b[0] - a[0]) / length];
      figure.label(forceSymbol(v.name, v.kind), [middle[0] + normal[0] * 2.5, middle[1] + normal[1] * 2.5 + 1.2],
        { target: middle, attrs: { "data-role": "force-name" } });
    }
    const bottom = HEAD + CAPTION + place.height;
    textLines(figure, [left, bottom], list, FONT.small);
    left += width + GAP;
  }
  return figure;
}

/** The width (mm) of the widest of lines at font size. */
function widest(lines, size) {
  return Math.max(0, ...lines.map((line) => textBox(line, [0, 0], size, "start").width));
}
