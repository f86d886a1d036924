/**
 * The structural groups and the crank of the force analysis, each drawn apart at μ_l in the position of the
 * analysis (Chaika–Vasylenko §3.4, step 17): its links, pairs and slider blocks (as on the plan of positions),
 * its centres of mass, and every load on it as its free body carries it (forces_friction/model/group_free_body.js:
 * weights G, inertia forces Φ at the points of their resultant, the useful load P, the outer reactions R, friction;
 * moments as arcs: the inertia couples M_Φ at their link's centre, the balancing moment on the crank), the forces
 * at one force scale μ_F of this drawing (the largest force ARROW mm long), both scales written on it; a force
 * shorter than SHORTEST mm at μ_F is drawn SHORTEST mm long and dashed, for its direction (the force plans give
 * every force to scale).
 */
import { bodyParts } from "../../../forces_friction/model/group_free_body.js";
import { standardScale, unionBox, FONT } from "../../model/drawing_layout.js";
import { heading, pointSymbol, scaleText } from "./captions.js";
import { Figure } from "./figure.js";
import { groupCaption } from "./force_plans.js";
import { drawLinks } from "./plan_of_positions.js";

const ARROW = 28;              // mm: the largest force's arrow at most
const MARGIN = 10;             // mm around a body's drawing
const GAP = 14;                // mm between two bodies
const HEAD = 18;               // mm of the heading
const CAPTION = 8;             // mm of a body's caption
const MOMENT_RADIUS = 4;       // mm
const SHORTEST = 4;            // mm: a force shorter at μ_F is drawn this long and dashed (its direction shown)

/** The groups and the crank with their forces, answer.kinetostatics at its position, as an SVG in mm. */
export function groupsWithForces(answer, t, lang, options = {}) {
  const figure = groupsWithForcesFigure(answer, t, lang);
  return options.figure ? figure : figure.toSvg(figure.title, "cp-groups");
}

export function groupsWithForcesFigure(answer, t, lang) {
  const { kinetostatics: kinetic, scales, plan_of_positions: plan } = answer;
  const i = kinetic.number - 1;
  const muL = scales.mu_l;
  const bodies = kinetic.groups.map((body) => ({ body, parts: bodyParts(body) }));
  const largest = Math.max(1e-9, ...bodies.flatMap(({ parts }) => parts.forces.map((f) => Math.hypot(...f.force))));
  const muF = standardScale(largest, ARROW);
  const figure = new Figure();
  figure.title = t.project_dwg_groups.replace("{n}", kinetic.number);
  heading(figure, [0, 0], figure.title, [scaleText("μ_l", muL, t.units_m, t, lang),
    scaleText("μ_F", muF, t.units_N, t, lang)]);
  let left = 0;
  for (const { body, parts } of bodies) {
    const joints = plan.links.filter((link) => body.links.includes(link.link)).flatMap((link) => link.joints)
      .filter((name) => plan.joints[name]).map((name) => plan.joints[name][i]);
    const local = ([x, y]) => [x / muL, -y / muL];                       // mm from the plane's origin
    const tips = parts.forces.flatMap((f) => {
      const p = local(f.at);
      const stretch = Math.max(1, SHORTEST / (Math.hypot(...f.force) / muF || SHORTEST));
      return [p, [p[0] + stretch * f.force[0] / muF, p[1] - stretch * f.force[1] / muF]];
    });
    const box = unionBox([...joints.map(local), ...tips], MARGIN);
    const at = (p) => {
      const [x, y] = local(p);
      return [left + x - box.x, HEAD + CAPTION + y - box.y];
    };
    figure.text(groupCaption(body, t), [left, HEAD + 4], { size: FONT.label, attrs: { class: "cp-caption" } });
    drawLinks(figure, answer, i, at, { only: body.links });
    centres(figure, answer, body, i, at);
    for (const force of parts.forces) {
      const size = Math.hypot(...force.force) / muF;
      if (!(size > 0)) continue;
      const tail = at(force.at);
      const length = Math.max(size, SHORTEST);
      const tip = [tail[0] + force.force[0] / muF * length / size, tail[1] - force.force[1] / muF * length / size];
      figure.arrow(tail, tip, size < SHORTEST ? "dashed" : force.kind === "reaction" ? "main" : "thin",
        { "data-force": force.name ?? force.symbol, ...(size < SHORTEST ? { "data-to-scale": "false" } : {}) });
      figure.label(force.symbol, [tip[0] + 2.5 * (tip[0] - tail[0]) / length, tip[1] + 2.5 * (tip[1] - tail[1]) / length + 1.2],
        { target: tip, attrs: { "data-role": "force-name" } });
    }
    for (const moment of moments(body, parts, answer, i)) {
      const centre = at(moment.at);
      figure.momentArc(centre, MOMENT_RADIUS, moment.moment > 0, "thin", { "data-moment": moment.symbol });
      figure.label(moment.symbol === "balancing" ? t.symbol_balancing_moment : moment.symbol,
        [centre[0] - MOMENT_RADIUS - 1, centre[1] + MOMENT_RADIUS + 3], { target: centre, attrs: { "data-role": "moment-name" } });
    }
    left += Math.max(box.width, 45) + GAP;
  }
  return figure;
}

/** The centres of mass of the body's links: dots and their letters. */
function centres(figure, answer, body, i, at) {
  for (const link of body.links) {
    const path = answer.plan_of_positions.marked?.[`S${link}`];
    if (!path) continue;
    const p = at(path[i]);
    figure.dot(p, 0.6);
    figure.label(pointSymbol(`S${link}`), [p[0] + 2, p[1] + 4], { target: p, attrs: { "data-role": "letter" } });
  }
}

/**
 * The moments drawn on a body: the inertia couples at their link's centre of mass (a couple may be drawn
 * anywhere on its link), the others (friction in a pair, the balancing moment) where the free body puts them.
 */
function moments(body, parts, answer, i) {
  const inertia = body.loads.filter((load) => load.kind === "inertia" && Number.isFinite(load.moment) && load.moment !== 0)
    .map((load) => ({ symbol: `M_{Φ${load.link}}`, moment: load.moment,
      at: answer.plan_of_positions.marked?.[`S${load.link}`]?.[i] ?? Object.values(body.points)[0] }));
  return [...inertia, ...parts.moments.filter((m) => m.kind !== "inertia")];
}
