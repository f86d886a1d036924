/**
 * A drawing of the course project as a list of parts on paper (millimetres, y down), then as an SVG whose user
 * unit is the millimetre: viewBox and width/height in mm, so that the drawing prints to scale. The parts are
 * what GOST 2.303 and 2.770 draw: main and thin lines, dashed and dash-dotted ones, vectors with a filled
 * head, revolute pairs, frame supports and guides hatched at 45°, slider blocks, texts; the labels are set
 * after all lines, each where it covers no other label nor mark and the fewest lines (drawing_layout.js).
 * Building a figure needs no DOM (Node runs it in the tests); only toSvg() makes elements.
 */
import { placeLabels, textBox, unionBox, FONT } from "../../model/drawing_layout.js";
import { plainText, richText } from "../../../common/view/notation.js";
import { svgElement } from "../../../common/view/svg.js";

/** Line types (GOST 2.303): widths and dashes in mm; ink black, so that a print is as on screen. */
export const LINES = {
  main: { "stroke-width": 0.5 },
  thin: { "stroke-width": 0.25 },
  dashed: { "stroke-width": 0.25, "stroke-dasharray": "3 1.5" },
  dashdot: { "stroke-width": 0.25, "stroke-dasharray": "8 1.5 1 1.5" },
  bold: { "stroke-width": 0.7 },
};
const INK = "#000";
const FONT_FAMILY = "DejaVu Sans, Arial, Helvetica, sans-serif";
const HEAD = { length: 3, half: 0.7 };       // a vector's arrowhead, mm
const PIN = 1.1;                              // a revolute pair's circle, mm
const HATCH = { step: 1.3, depth: 1.6 };      // hatching of the frame, mm
const SUPPORT = { height: 4, half: 2.5, ground: 4.5 };
const BLOCK = [7, 4.5];                       // a slider block, mm
const PAD = 4;                                // mm around everything drawn
const LEADER = 4;                             // mm: a label moved farther than this from its proposal gets a leader

export class Figure {
  constructor() {
    this.parts = [];
    this.labels = [];
    this.marks = [];                  // boxes no label may cover: pins, arrowheads, fixed texts
    this.segments = [];               // lines a label should not sit on
  }

  #add(part) {
    this.parts.push(part);
    return part;
  }

  /** A straight line of type kind (LINES) from a to b; attrs go onto the element (data-role …). */
  line(a, b, kind = "thin", attrs = {}) {
    this.segments.push([a, b]);
    return this.#add({ type: "line", points: [a, b], kind, attrs });
  }

  /** An open polyline (a trajectory, a curve); points with a null or non-finite coordinate break it. */
  polyline(points, kind = "thin", attrs = {}) {
    const runs = [[]];
    for (const p of points) {
      if (p && Number.isFinite(p[0]) && Number.isFinite(p[1])) runs.at(-1).push(p);
      else if (runs.at(-1).length) runs.push([]);
    }
    for (const run of runs) run.slice(1).forEach((p, i) => this.segments.push([run[i], p]));
    return this.#add({ type: "path", runs: runs.filter((r) => r.length > 1), kind, attrs });
  }

  /** A closed polygon, not filled. */
  polygon(points, kind = "thin", attrs = {}) {
    points.forEach((p, i) => this.segments.push([p, points[(i + 1) % points.length]]));
    return this.#add({ type: "path", runs: [points], closed: true, kind, attrs });
  }

  circle(centre, radius, kind = "thin", attrs = {}) {
    return this.#add({ type: "circle", centre, radius, kind, attrs });
  }

  /** A small filled dot (a point of a plan, a marked position). */
  dot(centre, radius = 0.5, attrs = {}) {
    this.marks.push(unionBox([centre], radius));
    return this.#add({ type: "circle", centre, radius, kind: "thin", filled: true, attrs });
  }

  /** A revolute pair: a circle of PIN mm, white inside. */
  pin(centre, attrs = {}) {
    this.marks.push(unionBox([centre], PIN));
    return this.#add({ type: "circle", centre, radius: PIN, kind: "thin", white: true, attrs });
  }

  /**
   * A vector from a to b (mm): a line of type kind with a filled head at b; a vector shorter than the head
   * gets a head of half its length; one shorter than 0.05 mm is not drawn (returns null).
   */
  arrow(a, b, kind = "main", attrs = {}) {
    const length = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (length < 0.05) return null;
    const u = [(b[0] - a[0]) / length, (b[1] - a[1]) / length];
    const head = Math.min(HEAD.length, 0.5 * length);
    const half = HEAD.half * head / HEAD.length;
    const base = [b[0] - u[0] * head, b[1] - u[1] * head];
    const tip = [base[0] - u[1] * half, base[1] + u[0] * half];
    const other = [base[0] + u[1] * half, base[1] - u[0] * half];
    this.segments.push([a, base]);
    this.marks.push(unionBox([b, tip, other]));
    return this.#add({ type: "arrow", points: [a, base], head: [b, tip, other], kind, attrs });
  }

  /**
   * A frame support under a revolute pair at centre (GOST 2.770): a triangle down to a ground line hatched
   * below it; angle (rad, screen, 0 = down) turns it away from the links.
   */
  support(centre, angle = 0, attrs = {}) {
    const turn = ([x, y]) => [centre[0] + x * Math.cos(angle) - y * Math.sin(angle),
      centre[1] + x * Math.sin(angle) + y * Math.cos(angle)];
    const { height, half, ground } = SUPPORT;
    const lines = [[[0, 0], [-half, height]], [[0, 0], [half, height]], [[-ground, height], [ground, height]]];
    for (let x = -ground; x < ground - 1e-9; x += HATCH.step) {
      lines.push([[x + HATCH.depth, height], [x, height + HATCH.depth]]);
    }
    const turned = lines.map(([p, q]) => [turn(p), turn(q)]);
    this.marks.push(unionBox(turned.flat()));
    return this.#add({ type: "lines", lines: turned, kind: "thin", attrs: { "data-role": "support", ...attrs } });
  }

  /**
   * A moment as a three-quarter arc of radius (mm) about centre with an arrowhead at its end: counter-clockwise
   * as seen on paper for a positive moment (the quantity's plane has y up).
   */
  momentArc(centre, radius, positive, kind = "thin", attrs = {}) {
    const sense = positive ? -1 : 1;                   // y down: a decreasing screen angle turns counter-clockwise
    const start = 0.75 * Math.PI;
    const points = [];
    for (let k = 0; k <= 24; k += 1) {
      const angle = start + sense * 1.5 * Math.PI * k / 24;
      points.push([centre[0] + radius * Math.cos(angle), centre[1] + radius * Math.sin(angle)]);
    }
    this.polyline(points.slice(0, -2), kind, attrs);
    return this.arrow(points.at(-3), points.at(-1), kind, attrs);
  }

  /** A fixed guide from a to b (mm): a main line hatched on the side side (+1: left of a → b, −1: right). */
  guide(a, b, side = 1, attrs = {}) {
    const length = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (!(length > 0)) return null;
    const u = [(b[0] - a[0]) / length, (b[1] - a[1]) / length];
    const n = [u[1] * side, -u[0] * side];
    const lines = [[a, b]];
    for (let s = 0; s + HATCH.depth <= length + 1e-9; s += HATCH.step) {
      const p = [a[0] + u[0] * (s + HATCH.depth), a[1] + u[1] * (s + HATCH.depth)];
      lines.push([p, [a[0] + u[0] * s + n[0] * HATCH.depth, a[1] + u[1] * s + n[1] * HATCH.depth]]);
    }
    this.segments.push([a, b]);
    return this.#add({ type: "lines", lines, kind: "thin", attrs: { "data-role": "guide", ...attrs } });
  }

  /** A slider block centred at centre, its long side along the direction (rad, screen). */
  block(centre, direction, kind = "main", attrs = {}) {
    const [w, h] = BLOCK;
    const corners = [[-w / 2, -h / 2], [w / 2, -h / 2], [w / 2, h / 2], [-w / 2, h / 2]].map(([x, y]) =>
      [centre[0] + x * Math.cos(direction) - y * Math.sin(direction), centre[1] + x * Math.sin(direction) + y * Math.cos(direction)]);
    corners.forEach((p, i) => this.segments.push([p, corners[(i + 1) % 4]]));
    return this.#add({ type: "path", runs: [corners], closed: true, kind, white: true, attrs: { "data-role": "block", ...attrs } });
  }

  /**
   * A label (notation markup) that the placement may move: proposed at `at` (its anchor on the base line);
   * the earlier a label is given, the nearer it stays to where it was proposed. target: the point it names;
   * a label moved far from it gets a thin leader line to it.
   */
  label(text, at, { size = FONT.label, anchor = "middle", target = null, attrs = {} } = {}) {
    const label = { text, at, fontSize: size, anchor, target, attrs };
    this.labels.push(label);
    return label;
  }

  /** A text that stays where it is put (a caption, a scale); labels keep off it. */
  text(text, at, { size = FONT.label, anchor = "start", attrs = {} } = {}) {
    const box = textBox(text, at, size, anchor);
    this.marks.push(box);
    return this.#add({ type: "text", text, at, size, anchor, box, attrs });
  }

  /** Places the labels (drawing_layout.placeLabels) within bounds, if given; returns the placed labels. */
  placeLabels(bounds = null) {
    this.placed = placeLabels(this.labels, { marks: this.marks, segments: this.segments, bounds });
    return this.placed;
  }

  /** The box of everything drawn and written, mm, PAD around it. */
  extent(pad = PAD) {
    const items = [];
    for (const part of this.parts) {
      if (part.type === "line" || part.type === "arrow") items.push(...part.points, ...(part.head ?? []));
      else if (part.type === "path") items.push(...part.runs.flat());
      else if (part.type === "lines") items.push(...part.lines.flat());
      else if (part.type === "circle") items.push(unionBox([part.centre], part.radius));
      else if (part.type === "text") items.push(part.box);
    }
    items.push(...(this.placed ?? []).map((label) => label.box));
    return unionBox(items, pad);
  }

  /**
   * The figure as an SVG element: user units mm, viewBox the extent, width and height in mm (so that it prints
   * at its size), the labels placed first if they are not yet; title: its accessible name (notation markup).
   */
  toSvg(title, className = "") {
    if (!this.placed) this.placeLabels();
    const box = this.extent();
    const svg = svgElement("svg", {
      viewBox: `${r(box.x)} ${r(box.y)} ${r(box.width)} ${r(box.height)}`,
      width: `${r(box.width)}mm`, height: `${r(box.height)}mm`, class: `cp-drawing ${className}`.trim(),
      role: "img", "aria-label": plainText(title), "font-family": FONT_FAMILY, "data-width-mm": r(box.width),
      "data-height-mm": r(box.height) });
    svgElement("title", {}, svg).textContent = plainText(title);
    const lines = svgElement("g", { stroke: INK, fill: "none", "stroke-linecap": "round" }, svg);
    for (const part of this.parts) drawPart(svg, lines, part);
    const labels = svgElement("g", { class: "cp-labels", fill: INK }, svg);
    for (const label of this.placed) {
      const leader = leaderLine(label);
      if (leader) {
        svgElement("line", { x1: r(leader[0][0]), y1: r(leader[0][1]), x2: r(leader[1][0]), y2: r(leader[1][1]),
          stroke: INK, ...LINES.thin, class: "cp-leader" }, lines);
      }
      const node = svgElement("text", { class: "cp-label", x: r(label.x), y: r(label.y), "font-size": label.fontSize,
        "text-anchor": label.anchor, ...label.attrs }, labels);
      node.append(richText(label.text, { svg: true }));
    }
    return svg;
  }
}

/**
 * The leader of a label moved more than LEADER mm from where it was proposed: from its target to the nearest
 * point of its box (null if it stays near or names no point).
 */
function leaderLine(label) {
  if (!label.target || label.moved <= LEADER) return null;
  const { box } = label;
  const [tx, ty] = label.target;
  const near = [Math.min(Math.max(tx, box.x), box.x + box.width), Math.min(Math.max(ty, box.y), box.y + box.height)];
  return Math.hypot(near[0] - tx, near[1] - ty) > 1 ? [label.target, near] : null;
}

/** A coordinate written to 0.001 mm. */
export function r(value) {
  return Math.round(value * 1000) / 1000;
}

const pathData = (runs, closed) => runs.map((run) => `M${run.map(([x, y]) => `${r(x)} ${r(y)}`).join(" L")}${closed ? " Z" : ""}`).join(" ");

function drawPart(svg, lines, part) {
  const style = LINES[part.kind] ?? LINES.thin;
  const fill = part.white ? { fill: "#fff" } : part.filled ? { fill: INK } : {};
  if (part.type === "line") {
    const [[x1, y1], [x2, y2]] = part.points;
    svgElement("line", { x1: r(x1), y1: r(y1), x2: r(x2), y2: r(y2), ...style, ...part.attrs }, lines);
  } else if (part.type === "path") {
    svgElement("path", { d: pathData(part.runs, part.closed), ...style, ...fill, ...part.attrs }, lines);
  } else if (part.type === "lines") {
    svgElement("path", { d: part.lines.map(([[x1, y1], [x2, y2]]) => `M${r(x1)} ${r(y1)} L${r(x2)} ${r(y2)}`).join(" "),
      ...style, ...part.attrs }, lines);
  } else if (part.type === "circle") {
    svgElement("circle", { cx: r(part.centre[0]), cy: r(part.centre[1]), r: r(part.radius), ...style, ...fill,
      ...part.attrs }, lines);
  } else if (part.type === "arrow") {
    const group = svgElement("g", { class: "cp-vector", ...part.attrs }, lines);
    const [[x1, y1], [x2, y2]] = part.points;
    svgElement("line", { x1: r(x1), y1: r(y1), x2: r(x2), y2: r(y2), ...style }, group);
    svgElement("path", { d: pathData([part.head], true), fill: INK, stroke: "none" }, group);
  } else if (part.type === "text") {
    const node = svgElement("text", { x: r(part.at[0]), y: r(part.at[1]), "font-size": part.size,
      "text-anchor": part.anchor, fill: INK, stroke: "none", class: "cp-text", ...part.attrs }, svg);
    node.append(richText(part.text, { svg: true }));
  }
}
