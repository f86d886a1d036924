/**
 * The parts of a kinematic diagram, in drawing units: the drawing itself (with the frame's hatching and
 * an arrowhead), fixed pivots with a hatched base, guides, bars (links), pins, slider blocks and joint
 * labels. Moving parts return an `update` for animation frames.
 */
import { plainText, setRichText } from "./notation.js";
import { setAttributes, svgElement } from "./svg.js";

const PIN_RADIUS = 4.5;
const HATCH_DEPTH = 7;

/** An empty drawing of width × height drawing units, described by label, with the defs the parts use. */
export function drawing(width, height, label) {
  const svg = svgElement("svg", {
    viewBox: `0 0 ${width} ${height}`, class: "linkage-drawing", role: "img", "aria-label": plainText(label) });
  const defs = svgElement("defs", {}, svg);
  const hatch = svgElement("pattern", {
    id: "hatch", width: 6, height: 6, patternUnits: "userSpaceOnUse", patternTransform: "rotate(45)" }, defs);
  svgElement("line", { x1: 0, y1: 0, x2: 0, y2: 6, class: "hatch-line" }, hatch);
  const arrow = svgElement("marker", {
    id: "arrow", viewBox: "0 0 10 10", refX: 8, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" }, defs);
  svgElement("path", { d: "M0 0 L10 5 L0 10 Z", class: "arrow-head" }, arrow);
  return svg;
}

/** A frame pivot at [x, y]: a triangular support standing on a hatched base. */
export function framePivot(layer, [x, y]) {
  const pivot = svgElement("g", { class: "frame-pivot", transform: `translate(${x} ${y})` }, layer);
  svgElement("path", { class: "support", d: "M0 0 L-9 16 L9 16 Z" }, pivot);
  svgElement("rect", { class: "hatch", x: -15, y: 16, width: 30, height: HATCH_DEPTH }, pivot);
  svgElement("line", { class: "ground", x1: -15, y1: 16, x2: 15, y2: 16 }, pivot);
}

/** A straight frame guide from x0 to x1 at height y, hatched on the side given by side = +1 (below) or −1. */
export function guide(layer, x0, x1, y, side = 1) {
  svgElement("rect", {
    class: "hatch", x: x0, y: side > 0 ? y : y - HATCH_DEPTH, width: x1 - x0, height: HATCH_DEPTH }, layer);
  svgElement("line", { class: "ground", x1: x0, y1: y, x2: x1, y2: y }, layer);
}

/** A link drawn as a bar between two points. */
export function bar(layer, className = "bar") {
  const line = svgElement("line", { class: className }, layer);
  return { update: ([x1, y1], [x2, y2]) => setAttributes(line, { x1, y1, x2, y2 }) };
}

/** A revolute joint. */
export function pin(layer) {
  const circle = svgElement("circle", { class: "pin", r: PIN_RADIUS }, layer);
  return { update: ([cx, cy]) => setAttributes(circle, { cx, cy }) };
}

/** A block (slider, slot block) of width × height centred at a point, turned by angle degrees. */
export function block(layer, width, height, className = "block") {
  const rect = svgElement("rect", { class: className, x: -width / 2, y: -height / 2, width, height }, layer);
  return { update: ([x, y], angle = 0) => rect.setAttribute("transform", `translate(${x} ${y}) rotate(${angle})`) };
}

/** A joint's letter, placed at an offset [dx, dy] from the joint. */
export function label(layer, text, [dx, dy]) {
  const node = setRichText(svgElement("text", { class: "joint-label" }, layer), text);
  return { update: ([x, y]) => setAttributes(node, { x: x + dx, y: y + dy }) };
}

/** Angle in degrees of the screen direction from a to b. */
export function screenAngle([ax, ay], [bx, by]) {
  return Math.atan2(by - ay, bx - ax) * 180 / Math.PI;
}
