/** SVG elements for the linkage drawing, the metres → drawing-units mapping and the round lengths of scale bars. */
const SVG_NS = "http://www.w3.org/2000/svg";

export function setAttributes(node, attributes) {
  for (const [name, value] of Object.entries(attributes)) node.setAttribute(name, value);
}

export function svgElement(tag, attributes = {}, parent = null) {
  const node = document.createElementNS(SVG_NS, tag);
  setAttributes(node, attributes);
  parent?.append(node);
  return node;
}

/**
 * The uniform scale that fits points [x, y] (metres, y up) into width × height drawing units with a
 * margin pad, centred: k drawing units per metre, and point([x, y]) → [X, Y] with Y pointing down.
 */
export function fitScale(points, width, height, pad) {
  const xs = points.map((p) => p[0]).filter(Number.isFinite);
  const ys = points.map((p) => p[1]).filter(Number.isFinite);
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const k = Math.min((width - 2 * pad) / Math.max(x1 - x0, 1e-9), (height - 2 * pad) / Math.max(y1 - y0, 1e-9));
  const ox = (width - (x1 - x0) * k) / 2 - x0 * k;
  const oy = (height + (y1 - y0) * k) / 2 + y0 * k;
  return { k, point: ([x, y]) => [ox + x * k, oy - y * k] };
}

/** The largest of 1, 2, 5 × 10ᵏ not above value (> 0): the length of a scale bar. */
export function roundDown(value) {
  const power = 10 ** Math.floor(Math.log10(value));
  return [5, 2, 1].map((m) => m * power).find((candidate) => candidate <= value);
}
