/**
 * Where everything is at one frame of the table: joints, guides (fixed ones and those carried by moving
 * links), and each link as the lines and slider blocks that show it. Plain numbers, no drawing.
 * A point on a link: z = z_O + (along + i·across)e^{iθ} (spec.py, state.on_link); a guide on a link runs at
 * θ + α through such a point.
 */
import { carrier, linkOrigin, links } from "./linkage.js";
import { anglesAt, positionsAt } from "./table.js";

const add = (a, b) => [a[0] + b[0], a[1] + b[1]];
const polar = (r, angle) => [r * Math.cos(angle), r * Math.sin(angle)];

/** A point given in a link's frame {origin, angle} (metres). */
function onLink(frame, along, across) {
  const [c, s] = [Math.cos(frame.angle), Math.sin(frame.angle)];
  return [frame.origin[0] + along * c - across * s, frame.origin[1] + along * s + across * c];
}

/** Positions and angles at frame k: {joints, angles, frameOf(link), guideAt(name)}. */
export function stateAt(linkage, table, k) {
  const joints = { ...Object.fromEntries(Object.entries(linkage.frame.joints)), ...(table ? positionsAt(table, k) : {}) };
  const angles = table ? anglesAt(table, k) : {};
  const frameOf = (link) => {
    const origin = joints[linkOrigin(linkage, link)];
    const angle = angles[String(link)];
    return origin && Number.isFinite(angle) ? { origin, angle } : null;
  };
  const guideAt = (name) => {
    const fixed = linkage.frame.guides[name];
    if (fixed) {
      const through = typeof fixed.through === "string" ? linkage.frame.joints[fixed.through] : fixed.through;
      return { point: through ?? [0, 0], angle: fixed.angle ?? 0, moving: false };
    }
    for (const element of [linkage.input, ...linkage.groups].filter(Boolean)) {
      const g = element.new_guides?.[name];
      if (!g) continue;
      const frame = frameOf(g.link ?? element.links?.[0] ?? element.link);
      if (!frame) return null;
      return { point: onLink(frame, g.along ?? 0, g.across ?? 0), angle: frame.angle + (g.angle ?? 0), moving: true };
    }
    return null;
  };
  return { joints, angles, frameOf, guideAt };
}

/** The furthest a slider gets from the lever's pivot over the turn (to draw the lever long enough). */
function reach(table, from, to) {
  if (!table) return 0.1;
  const a = table.outputs.joints[from];
  const b = table.outputs.joints[to];
  if (!a || !b) return 0.1;
  return Math.max(0.05, ...a.map((p, k) => (p[0] === null || b[k][0] === null ? 0 : Math.hypot(b[k][0] - p[0], b[k][1] - p[1]))));
}

/** The lines and blocks that show each moving link at state s. */
export function linkShapes(linkage, table, s) {
  const shapes = [];
  const pointsOf = (element, link) => Object.entries(element.points ?? {})
    .filter(([, p]) => (p.link ?? element.links?.[0] ?? element.link) === link).map(([name]) => s.joints[name]);
  for (const [link] of links(linkage)) {
    const element = carrier(linkage, link);
    const origin = s.joints[linkOrigin(linkage, link)];
    const lines = [];
    const blocks = [];
    const extras = pointsOf(element, link);
    const kind = element === linkage.input ? (element.kind === "slider" ? "slider" : "crank") : element.kind;
    const isI = element.links?.[0] === link;
    const angle = s.angles[String(link)];
    if (kind === "crank") lines.push([origin, s.joints[element.joint]]);
    else if (kind === "slider") blocks.push({ at: origin, angle });
    else if (kind === "RRR") lines.push([origin, s.joints[element.inner]]);
    else if (kind === "RRP") {
      if (isI) lines.push([origin, s.joints[element.inner]]);
      else blocks.push({ at: s.joints[element.inner], angle: s.guideAt(element.guide)?.angle ?? 0 });
    } else if (kind === "RPR") {
      if (isI) blocks.push({ at: s.joints[element.outer[0]], angle });
      else if (origin && Number.isFinite(angle)) {
        const long = reach(table, element.outer[1], element.outer[0]) * 1.1;
        const along = Object.values(element.points ?? {}).filter((p) => p.link === link).map((p) => p.along ?? 0);
        lines.push([origin, add(origin, polar(Math.max(long, ...along), angle))]);
      }
    } else if (kind === "PRP") {
      blocks.push({ at: s.joints[element.inner], angle: s.guideAt(element.guides[isI ? 0 : 1])?.angle ?? 0 });
    } else if (kind === "RPP") {
      if (isI) blocks.push({ at: s.joints[element.outer[0]], angle: angle + (element.angle ?? Math.PI / 2) });
      else if (origin && Number.isFinite(angle)) {
        blocks.push({ at: origin, angle });
        const slot = angle + (element.angle ?? Math.PI / 2);
        const b = s.joints[element.outer[0]];
        const to = b ? ((b[0] - origin[0]) * Math.cos(slot) + (b[1] - origin[1]) * Math.sin(slot)) : 0.1;
        lines.push([add(origin, polar(Math.min(0, to) - 0.05, slot)), add(origin, polar(Math.max(0, to) + 0.05, slot))]);
      }
    }
    for (const p of extras) lines.push([origin, p]);
    shapes.push({ link, lines, blocks });
  }
  return shapes;
}

/** Every guide with where it is at state s. */
export function guideShapes(s, guideNames) {
  return guideNames.map((name) => ({ name, ...(s.guideAt(name) ?? {}) })).filter((g) => g.point);
}
