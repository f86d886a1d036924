/**
 * The mechanism being edited, as the API's `linkage` JSON (GET /api/v1/mechanisms/general): the frame's
 * joints and guides, the input crank, class-II groups in the order they are attached. Lengths in metres,
 * angles in radians counter-clockwise from +x, y up. The model knows geometry and names, nothing of drawing.
 *
 * Each link has its own frame (spec.py): an origin joint and the link's angle θ; a point or guide on the link
 * is given there as along + i·across. Origins: crank → pivot; RRR i → B, j → D; RRP i → B, j → C; RPR i → B,
 * j → D; PRP i, j → C; RPP i → B, j → R.
 */

export const KINDS = ["RRR", "RRP", "RPR", "PRP", "RPP"];

/** What a group of each kind is attached to, in the order the student clicks them: joints and guides. */
export const PICKS = {
  RRR: ["joint", "joint", "place"], RRP: ["joint", "guide", "place"], RPR: ["joint", "joint"],
  PRP: ["guide", "guide"], RPP: ["joint", "guide"],
};

const MOVING = "ABCDEFGHKLMNPQRSTUVWXYZ";       // moving joints and points: A the crank's pin, then B, C … (no I, J, O)
const FRAME = "O";                               // frame joints: O, O₁, O₂ … as the textbook names the supports
const SUB = "₀₁₂₃₄₅₆₇₈₉";
const SNAP = 0.005;              // m: placed points snap to a 5 mm grid
const MILLIMETRE = 1e-3;

const snap = (value) => Math.round(value / SNAP) * SNAP;
const mm = (value) => Math.round(value / MILLIMETRE) * MILLIMETRE;
const round6 = (value) => Math.round(value * 1e6) / 1e6;
const subscript = (n) => String(n).replace(/\d/g, (d) => SUB[d]);

export function emptyLinkage() {
  return { frame: { joints: {}, guides: {} }, input: null, groups: [] };
}

/** Every joint and point name with the links it lies on (0: the frame), in order of placement. */
export function joints(linkage) {
  const out = new Map(Object.keys(linkage.frame.joints).map((name) => [name, [0]]));
  const crank = linkage.input;
  if (!crank) return out;
  out.set(crank.joint, [crank.link]);
  for (const [name, p] of Object.entries(crank.points ?? {})) out.set(name, [p.link ?? crank.link]);
  for (const group of linkage.groups) {
    const [i, j] = group.links;
    if (group.kind === "RPP") out.set(group.inner, [j]);
    else if (group.kind !== "RPR") out.set(group.inner, [i, j]);
    for (const [name, p] of Object.entries(group.points ?? {})) out.set(name, [p.link ?? i]);
  }
  return out;
}

/** Every guide name with the link that carries it (0: the frame). */
export function guides(linkage) {
  const out = new Map(Object.keys(linkage.frame.guides).map((name) => [name, 0]));
  for (const element of [linkage.input, ...linkage.groups].filter(Boolean)) {
    for (const [name, g] of Object.entries(element.new_guides ?? {})) out.set(name, g.link ?? element.links?.[0] ?? element.link);
  }
  return out;
}

/** The moving links: [number, what carries it ("crank" or the group's index)]. */
export function links(linkage) {
  if (!linkage.input) return [];
  return [[linkage.input.link, "crank"], ...linkage.groups.flatMap((g, k) => g.links.map((link) => [link, k]))];
}

/**
 * A group's name in the structural formula (server/core/structure/analysis.py, group_name): class II with
 * Artobolevsky's kind as the subscript and its links, "II₂(2,3)" for the RRP dyad of links 2 and 3
 * (Chaika–Vasylenko Fig. 3.3b). The one name of the group in the list, the drawings and the messages.
 */
export function groupName(group) {
  return `II${subscript(KINDS.indexOf(group.kind) + 1)}(${group.links.join(",")})`;
}

/** The names of all groups, in order of attachment (messages name a group by its index into it). */
export function groupNames(linkage) {
  return linkage.groups.map(groupName);
}

/**
 * A guide's label in the reader's language: the presets' guides by their textbook names (x–x for a slider's
 * line, x₁–x₁ and x₂–x₂ for two cylinders, the lever's slot), t.guide_label_<name>; the student's own by name.
 */
export function guideLabel(name, t) {
  return t[`guide_label_${name}`] ?? name;
}

/** A sliding pair as the API names it ("E/ram": the slider E on the guide ram) with its guide's label: "E/x–x". */
export function slideLabel(pair, t) {
  const [joint, guide] = pair.split("/");
  return guide === undefined ? pair : `${joint}/${guideLabel(guide, t)}`;
}

function usedNames(linkage) {
  const names = new Set([...joints(linkage).keys(), ...guides(linkage).keys()]);
  for (const group of linkage.groups) names.add(group.inner);
  return names;
}

/** The first moving joint's letter (then letter + subscript) that names nothing yet: A, B, C … in order. */
export function freeName(linkage) {
  const used = usedNames(linkage);
  for (let round = 0; ; round += 1) {
    for (const letter of MOVING) {
      const name = round ? `${letter}${subscript(round)}` : letter;
      if (!used.has(name)) return name;
    }
  }
}

/** The next frame joint's name: O, then O₁, O₂ … */
export function freeFrameName(linkage) {
  const used = usedNames(linkage);
  for (let k = 0; ; k += 1) {
    const name = k ? `${FRAME}${subscript(k)}` : FRAME;
    if (!used.has(name)) return name;
  }
}

function freeGuideName(linkage) {
  const used = usedNames(linkage);
  for (let k = 1; ; k += 1) if (!used.has(`g${k}`)) return `g${k}`;
}

const nextLink = (linkage) => Math.max(0, ...links(linkage).map(([link]) => link)) + 1;

export function addFrameJoint(linkage, [x, y]) {
  const name = freeFrameName(linkage);
  linkage.frame.joints[name] = [snap(x), snap(y)];
  return name;
}

export function addFrameGuide(linkage, [x, y], angle = 0) {
  const name = freeGuideName(linkage);
  linkage.frame.guides[name] = { through: [snap(x), snap(y)], angle };
  return name;
}

/** The crank about the frame joint `pivot`, its pin where the student clicked (length and θ₀ from it). */
export function setCrank(linkage, pivot, pin) {
  const [x0, y0] = linkage.frame.joints[pivot];
  const [dx, dy] = [snap(pin[0]) - x0, snap(pin[1]) - y0];
  const length = mm(Math.hypot(dx, dy)) || 0.1;
  linkage.input = { kind: "crank", link: 1, pivot, joint: freeName(linkage), length,
    angle0: round6(Math.atan2(dy, dx)), sense: 1 };
}

/**
 * The input slider on the frame guide `guide` {point, angle}, its joint where the student clicked (projected
 * on the guide): s measured from the guide's point, the travel 100 mm on from the click (edited in the list).
 */
export function setSlider(linkage, guide, at, line) {
  const s = mm((snap(at[0]) - line.point[0]) * Math.cos(line.angle) + (snap(at[1]) - line.point[1]) * Math.sin(line.angle));
  linkage.input = { kind: "slider", link: 1, guide, joint: freeName(linkage), travel: [s, mm(s + 0.1)] };
}

const cross = (a, b) => a[0] * b[1] - a[1] * b[0];
const minus = (a, b) => [a[0] - b[0], a[1] - b[1]];

/**
 * A new group of `kind` on the picked elements (joint and guide names in PICKS order); `place` is where the
 * student clicked the inner joint (RRR, RRP): the lengths and the assembly branch are read from it.
 * at(name) gives a joint's position now, guideAt(name) a guide's {point, angle} now.
 */
export function addGroup(linkage, kind, picked, place, at, guideAt) {
  const link = nextLink(linkage);
  const group = { kind, links: [link, link + 1] };
  const inner = freeName(linkage);
  if (kind === "RRR") {
    const [b, d] = picked.map(at);
    const c = [snap(place[0]), snap(place[1])];
    Object.assign(group, { outer: picked.slice(0, 2), inner, lengths: [mm(Math.hypot(...minus(c, b))),
      mm(Math.hypot(...minus(c, d)))], branch: cross(minus(d, b), minus(c, b)) >= 0 ? 1 : -1 });
  } else if (kind === "RRP") {
    const b = at(picked[0]);
    const { point, angle } = guideAt(picked[1]);
    const u = [Math.cos(angle), Math.sin(angle)];
    const c = [snap(place[0]), snap(place[1])];
    const along = (p) => (p[0] - point[0]) * u[0] + (p[1] - point[1]) * u[1];
    const onGuide = [point[0] + along(c) * u[0], point[1] + along(c) * u[1]];     // C lies on the guide
    Object.assign(group, { outer: [picked[0]], guide: picked[1], inner,
      length: mm(Math.hypot(...minus(onGuide, b))), branch: along(c) >= along(b) ? 1 : -1 });
  } else if (kind === "RPR") {
    Object.assign(group, { outer: picked.slice(0, 2), offset: 0, branch: 1, inner: `s${link}${link + 1}` });
  } else if (kind === "PRP") {
    Object.assign(group, { guides: picked.slice(0, 2), inner });
  } else {
    Object.assign(group, { outer: [picked[0]], guide: picked[1], inner, angle: round6(Math.PI / 2) });
  }
  linkage.groups.push(group);
  return group;
}

/** The element (crank or group) that carries `link`. */
export function carrier(linkage, link) {
  if (linkage.input?.link === link) return linkage.input;
  return linkage.groups.find((g) => g.links.includes(link));
}

/** The joint names of a link's origin (see the module's comment). */
export function linkOrigin(linkage, link) {
  const element = carrier(linkage, link);
  if (element === linkage.input) return element.kind === "slider" ? element.joint : element.pivot;
  const [i] = element.links;
  if (element.kind === "PRP") return element.inner;
  if (link === i) return element.outer[0];
  return { RRR: element.outer?.[1], RRP: element.inner, RPR: element.outer?.[1], RPP: element.inner }[element.kind];
}

/** A point of interest fixed on `link` where the student clicked; frame = {origin: [x, y], angle}. */
export function addPoint(linkage, link, place, frame) {
  const element = carrier(linkage, link);
  const [dx, dy] = minus([snap(place[0]), snap(place[1])], frame.origin);
  const [c, s] = [Math.cos(frame.angle), Math.sin(frame.angle)];
  const name = freeName(linkage);
  element.points = { ...(element.points ?? {}), [name]: { link, along: mm(dx * c + dy * s), across: mm(-dx * s + dy * c) } };
  return name;
}

/** A guide fixed on `link` through the point clicked, along the link (its angle α to the link set in the list). */
export function addLinkGuide(linkage, link, place, frame) {
  const element = carrier(linkage, link);
  const [dx, dy] = minus([snap(place[0]), snap(place[1])], frame.origin);
  const [c, s] = [Math.cos(frame.angle), Math.sin(frame.angle)];
  const name = freeGuideName(linkage);
  element.new_guides = { ...(element.new_guides ?? {}),
    [name]: { link, along: mm(dx * c + dy * s), across: mm(-dx * s + dy * c), angle: 0 } };
  return name;
}

/**
 * The joint `from` (a frame joint, the crank's pin, a group's inner joint or a point) named `to` wherever the
 * mechanism refers to it; false, and nothing changed, where `to` is empty, longer than 16 characters, holds "/"
 * or names another element already.
 */
export function renameJoint(linkage, from, to) {
  const name = to.trim();
  if (!name || name.length > 16 || name.includes("/") || (name !== from && usedNames(linkage).has(name))) return false;
  const swap = (old) => (old === from ? name : old);
  const rekeyed = (object) => Object.fromEntries(Object.entries(object).map(([key, value]) => [swap(key), value]));
  linkage.frame.joints = rekeyed(linkage.frame.joints);
  for (const element of [linkage.input, ...linkage.groups].filter(Boolean)) {
    for (const field of ["pivot", "joint", "inner"]) if (element[field] !== undefined) element[field] = swap(element[field]);
    if (element.outer) element.outer = element.outer.map(swap);
    if (element.points) element.points = rekeyed(element.points);
  }
  return true;
}

/** The mechanism as the API takes it, or null while it has no crank. */
export function requestLinkage(linkage) {
  return linkage.input ? linkage : null;
}

/** A linkage read from outside (a file, the address, a preset) with the parts the editor needs. */
export function normalised(raw) {
  if (!raw || typeof raw !== "object") throw new Error("not a mechanism");
  const frame = raw.frame ?? {};
  return { frame: { joints: { ...(frame.joints ?? {}) }, guides: { ...(frame.guides ?? {}) } },
    input: raw.input ? { kind: "crank", ...raw.input } : null,
    groups: Array.isArray(raw.groups) ? raw.groups.map((g) => structuredClone(g)) : [] };
}
