/**
 * The parts of a force diagram, in drawing units (y down): force arrows with their symbols, moment arcs,
 * and the round numbers scale bars are drawn for. Each part returns an update for animation frames.
 */
import { setRichText } from "../../common/view/notation.js";
import { setAttributes, svgElement } from "../../common/view/svg.js";

const HEAD = [10, 4];          // arrowhead length and half-width
const LABEL_GAP = 10;          // from the arrow's tip to its symbol
const SHORTEST_LABELLED = 12;  // a shorter arrow is drawn without its symbol (the readings give its value)
const ARC_SPAN = 1.5 * Math.PI;

/** Path of a filled arrowhead with its tip at tip, pointing along the unit vector u. */
function headPath([x, y], [ux, uy], length) {
  const half = HEAD[1] * length / HEAD[0];
  const [bx, by] = [x - ux * length, y - uy * length];
  return `M${x} ${y} L${bx - uy * half} ${by + ux * half} L${bx + uy * half} ${by - ux * half} Z`;
}

/** A force arrow of the given class, labelled symbol at its free end. */
export function forceArrow(layer, className, symbol) {
  const group = svgElement("g", { class: `force ${className}` }, layer);
  const shaft = svgElement("line", { class: "force-shaft" }, group);
  const head = svgElement("path", { class: "force-head" }, group);
  const text = setRichText(svgElement("text", { class: "force-label" }, group), symbol);
  return {
    /**
     * The force vector [dx, dy] (drawing units) applied at point [X, Y]: the arrow starts there (it pulls),
     * or ends there if pushes; null or a vanishing vector hides it. beyondScale: the arrow is shorter than
     * the force scale says (drawn dashed).
     */
    update(point, vector, { pushes = false, beyondScale = false } = {}) {
      const length = vector ? Math.hypot(vector[0], vector[1]) : 0;
      group.style.display = length > 0.5 ? "" : "none";
      if (!(length > 0.5)) return;
      group.classList.toggle("beyond-scale", beyondScale);
      const u = [vector[0] / length, vector[1] / length];
      const tail = pushes ? [point[0] - vector[0], point[1] - vector[1]] : point;
      const tip = [tail[0] + vector[0], tail[1] + vector[1]];
      const headLength = Math.min(HEAD[0], 0.6 * length);
      setAttributes(shaft, { x1: tail[0], y1: tail[1], x2: tip[0] - u[0] * headLength, y2: tip[1] - u[1] * headLength });
      head.setAttribute("d", headPath(tip, u, headLength));
      text.style.display = length < SHORTEST_LABELLED ? "none" : "";
      const [end, away] = pushes ? [tail, -1] : [tip, 1];
      setAttributes(text, { x: end[0] + away * u[0] * LABEL_GAP, y: end[1] + away * u[1] * LABEL_GAP });
    },
  };
}

/** A moment drawn as a three-quarter arc of radius (drawing units) about a point, labelled symbol. */
export function momentArc(layer, className, symbol, radius) {
  const group = svgElement("g", { class: `force moment ${className}` }, layer);
  const arc = svgElement("path", { class: "force-shaft" }, group);
  const head = svgElement("path", { class: "force-head" }, group);
  const text = setRichText(svgElement("text", { class: "force-label" }, group), symbol);
  return {
    /** About centre [X, Y], counter-clockwise on the screen if moment > 0; null or 0 hides it. */
    update(centre, moment) {
      group.style.display = moment ? "" : "none";
      if (!moment) return;
      const sweep = moment > 0 ? -ARC_SPAN : ARC_SPAN;        // y points down: a negative angle turns anticlockwise
      const start = 0.75 * Math.PI;
      const end = start + sweep;
      const at = (angle, r = radius) => [centre[0] + r * Math.cos(angle), centre[1] + r * Math.sin(angle)];
      const [[x0, y0], [x1, y1]] = [at(start), at(end)];
      arc.setAttribute("d", `M${x0} ${y0} A${radius} ${radius} 0 1 ${sweep > 0 ? 1 : 0} ${x1} ${y1}`);
      const turn = Math.sign(sweep);
      head.setAttribute("d", headPath([x1, y1], [-Math.sin(end) * turn, Math.cos(end) * turn], HEAD[0]));
      const [lx, ly] = at(start, radius + 1.6 * LABEL_GAP);
      setAttributes(text, { x: lx, y: ly });
    },
  };
}

/** The round lengths of scale bars (common to every drawing). */
export { roundDown } from "../../common/view/svg.js";
