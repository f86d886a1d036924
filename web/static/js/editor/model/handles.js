/**
 * What the student may drag in the drawing, and what dragging it changes in the mechanism's data, at the input
 * position shown (the crank angle φ, or the input slider's s). A handle is put where the pointer is, and the
 * data are read back from there, the rest of the mechanism standing as it stands at that position:
 * - a frame joint, or a frame guide's point: its coordinates;
 * - the crank's pin A: the crank's length |OA| and its angle at φ = 0, θ₀ = atan2(A − O) − sense·φ
 *   (the crank's angle is θ₀ + sense·φ: server/core/structure/compose.py);
 * - the input slider's joint: its travel moved along the guide so that the shown s is the pointer's projection;
 * - an RRR group's inner joint C: both lengths |BC|, |DC| and the branch (the side of BD that C is on);
 * - an RRP group's inner joint C: C projected on the guide, the length |BC| and the branch (C ahead of B's
 *   projection along the guide, or behind it);
 * - a point or a guide on a moving link: along, across in the link's frame (z = z_O + (along + i·across)e^{iθ});
 * - a guide's angle (a second handle at a distance from its point): the guide's angle (to the link's, on a link).
 * The joints of the other groups (RPR, PRP, RPP) are where their guides and links put them: nothing to drag.
 * Lengths and coordinates in metres (written to 0.1 mm), angles in radians counter-clockwise from +x. No DOM.
 */
const WRITTEN = 1e-4;                    // m: lengths and coordinates written to 0.1 mm
const ANGLE_WRITTEN = 1e-6;              // rad

const written = (value) => Number((Math.round(value / WRITTEN) * WRITTEN).toFixed(4)) || 0;
const writtenAngle = (value) => Number((Math.round(value / ANGLE_WRITTEN) * ANGLE_WRITTEN).toFixed(6)) || 0;
const minus = (a, b) => [a[0] - b[0], a[1] - b[1]];
const cross = (a, b) => a[0] * b[1] - a[1] * b[0];
const wrap = (angle) => Math.atan2(Math.sin(angle), Math.cos(angle));

/** [along, across] of the world point p in a link's frame {origin, angle}. */
function inFrame(frame, p) {
  const [dx, dy] = minus(p, frame.origin);
  const [c, s] = [Math.cos(frame.angle), Math.sin(frame.angle)];
  return [dx * c + dy * s, -dx * s + dy * c];
}

/** The link a point or guide of an element lies on (its own `link`, else the element's first link). */
const linkOf = (element, item) => item.link ?? element.links?.[0] ?? element.link;

/** The elements (the input, then the groups) with their points and guides on links. */
function attachments(linkage) {
  return [linkage.input, ...linkage.groups].filter(Boolean);
}

/**
 * Every handle at state s (geometry.js stateAt: joints, guideAt, frameOf): [{id, kind, name, at}], at in metres;
 * a guide's angle handle `reach` metres from its point `from`. Handles whose place is unknown (a group that does not
 * close there) are left out.
 */
export function handles(linkage, s, reach) {
  const out = [];
  const add = (kind, name, at, extra = {}) => {
    if (at && Number.isFinite(at[0]) && Number.isFinite(at[1])) out.push({ id: `${kind}:${name}`, kind, name, at, ...extra });
  };
  const addAngle = (name, line) => add("guide_angle", name,
    [line.point[0] + reach * Math.cos(line.angle), line.point[1] + reach * Math.sin(line.angle)], { from: line.point });
  for (const [name, p] of Object.entries(linkage.frame.joints)) add("frame", name, p);
  const input = linkage.input;
  if (input) add(input.kind === "slider" ? "input_slider" : "crank", input.joint, s.joints[input.joint]);
  linkage.groups.forEach((group, k) => {
    if (group.kind === "RRR" || group.kind === "RRP") add(group.kind, group.inner, s.joints[group.inner], { group: k });
  });
  for (const element of attachments(linkage)) {
    for (const name of Object.keys(element.points ?? {})) add("point", name, s.joints[name]);
  }
  for (const [name, g] of Object.entries(linkage.frame.guides)) {
    const line = s.guideAt(name);
    if (!line) continue;
    if (Array.isArray(g.through)) add("guide", name, line.point);
    addAngle(name, line);
  }
  for (const element of attachments(linkage)) {
    for (const name of Object.keys(element.new_guides ?? {})) {
      const line = s.guideAt(name);
      if (!line) continue;
      add("guide", name, line.point);
      addAngle(name, line);
    }
  }
  return out;
}

/** The element (input or group) that has the point or guide `name` on one of its links. */
function owner(linkage, key, name) {
  return attachments(linkage).find((element) => element[key]?.[name]);
}

/**
 * The mechanism's data changed so that the handle is at p (m): linkage is changed in place; s is the state at
 * the shown input position before the drag, shown the input's value there (φ, rad, or the slider's s, m);
 * angleStep (rad, optional) rounds a dragged guide angle to its multiples. Gives where the handle's joint is
 * drawn now ([x, y]: p, or p projected on its guide), or null for a guide (drawn from the data).
 */
export function moveHandle(linkage, handle, p, s, shown, angleStep = 0) {
  const { kind, name } = handle;
  if (kind === "frame") {
    linkage.frame.joints[name] = [written(p[0]), written(p[1])];
    return linkage.frame.joints[name];
  }
  if (kind === "crank") {
    const crank = linkage.input;
    const arm = minus(p, linkage.frame.joints[crank.pivot]);
    const length = written(Math.hypot(...arm));
    if (!(length > 0)) return null;
    crank.length = length;
    crank.angle0 = writtenAngle(wrap(Math.atan2(arm[1], arm[0]) - (crank.sense ?? 1) * shown));
    return p;
  }
  if (kind === "input_slider") {
    const slider = linkage.input;
    const line = s.guideAt(slider.guide);
    const u = [Math.cos(line.angle), Math.sin(line.angle)];
    const along = (p[0] - line.point[0]) * u[0] + (p[1] - line.point[1]) * u[1];
    const shift = written(along - shown);
    slider.travel = slider.travel.map((end) => written(end + shift));
    const at = shown + shift;
    return [line.point[0] + at * u[0], line.point[1] + at * u[1]];
  }
  if (kind === "RRR") {
    const group = linkage.groups[handle.group];
    const [b, d] = group.outer.map((outer) => s.joints[outer]);
    group.lengths = [written(Math.hypot(...minus(p, b))), written(Math.hypot(...minus(p, d)))];
    group.branch = cross(minus(d, b), minus(p, b)) >= 0 ? 1 : -1;
    return p;
  }
  if (kind === "RRP") {
    const group = linkage.groups[handle.group];
    const b = s.joints[group.outer[0]];
    const line = s.guideAt(group.guide);
    const u = [Math.cos(line.angle), Math.sin(line.angle)];
    const along = (q) => (q[0] - line.point[0]) * u[0] + (q[1] - line.point[1]) * u[1];
    const c = [line.point[0] + along(p) * u[0], line.point[1] + along(p) * u[1]];     // C lies on the guide
    group.length = written(Math.hypot(...minus(c, b)));
    group.branch = along(c) >= along(b) ? 1 : -1;
    return c;
  }
  if (kind === "point") {
    const element = owner(linkage, "points", name);
    const point = element.points[name];
    const frame = s.frameOf(linkOf(element, point));
    if (!frame) return null;
    [point.along, point.across] = inFrame(frame, p).map(written);
    return p;
  }
  const frameGuide = linkage.frame.guides[name];
  if (kind === "guide") {
    if (frameGuide) frameGuide.through = [written(p[0]), written(p[1])];
    else {
      const element = owner(linkage, "new_guides", name);
      const guide = element.new_guides[name];
      const frame = s.frameOf(linkOf(element, guide));
      if (frame) [guide.along, guide.across] = inFrame(frame, p).map(written);
    }
    return null;
  }
  if (kind === "guide_angle") {
    const line = s.guideAt(name);
    const direction = minus(p, line.point);
    if (!(Math.hypot(...direction) > 0)) return null;
    let angle = Math.atan2(direction[1], direction[0]);
    if (angleStep > 0) angle = Math.round(angle / angleStep) * angleStep;
    if (frameGuide) frameGuide.angle = writtenAngle(angle);
    else {
      const element = owner(linkage, "new_guides", name);
      const guide = element.new_guides[name];
      const frame = s.frameOf(linkOf(element, guide));
      if (frame) guide.angle = writtenAngle(wrap(angle - frame.angle));
    }
    return null;
  }
  return null;
}

/** Whether every joint of the table is placed at row k: the mechanism assembles at the shown input position. */
export function assemblesAt(table, k) {
  return Object.values(table.outputs.joints).every((rows) => rows[k] && rows[k][0] !== null && rows[k][1] !== null);
}
