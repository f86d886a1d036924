/**
 * The linkage drawn to scale from the joints table of the current answer (DRAWINGS says how for each
 * mechanism): frame pivots and guides, links as bars, blocks, joint letters; the crank circle with the
 * special positions marked on it and the linkage shown faintly in each of them; an arc giving the
 * sense in which φ grows; below, a scale bar of a round length. Animation frames move the parts to positions
 * interpolated in the table; the letters then move off each other, the parts and the edges (label_placement.js).
 */
import { DRAWN_PARTS, placeLabels } from "./label_placement.js";
import { bar, drawing, framePivot, label, pin } from "./linkage_parts.js";
import { DRAWINGS } from "./linkage_drawings.js";
import { geometryMessage } from "./messages.js";
import { degrees, formatNumber, unitText } from "./notation.js";
import { jointsAt, specialPositions } from "../model/positions_table.js";
import { fitScale, roundDown, svgElement } from "./svg.js";

const WIDTH = 560;
const HEIGHT = 340;
const LEGEND = 24;                 // drawing units at the bottom for the scale bar
const PAD = 40;
const SENSE_ARC = Math.PI / 3;     // rad of crank angle spanned by the arc that shows the sense of φ

export class LinkageView {
  constructor(container, { t, lang }) {
    this.container = container;
    this.t = t;
    this.lang = lang;
    this.svg = drawing(WIDTH, HEIGHT, t.drawing);
    this.picture = svgElement("g", {}, this.svg);
    this.update = null;
    this.crankPlace = null;
    container.append(this.svg);
  }

  /** Where the crank turns, for turning it by hand (crank_drag.js): {centre, start, sense}, or null. */
  crank() {
    return this.update ? this.crankPlace : null;
  }

  /**
   * Draw the answer at crank angle phi (rad), or say why the mechanism cannot be assembled; drawing
   * (linkage_drawings.js) is the mechanism's own unless given (the crank-slider with a flywheel).
   */
  show(answer, phi, drawing = DRAWINGS[answer.data?.mechanism]) {
    this.container.querySelector(".geometry-error")?.remove();
    this.svg.style.display = answer.ok ? "" : "none";
    if (!answer.ok) {
      this.update = null;
      this.container.append(geometryMessage(answer.error, this.t));
      return;
    }
    this.table = answer.data;
    this.#build(drawing, this.table);
    this.drawAt(phi);
  }

  drawAt(phi) {
    if (this.update) this.update(jointsAt(this.table, phi));
  }

  #build(drawing, table) {
    const joints = table.outputs.joints;
    const params = table.params;
    const scale = fitScale([...Object.values(joints).flat(), ...drawing.extent(params, table)], WIDTH, HEIGHT - LEGEND, PAD);
    const frame = svgElement("g", { class: "frame" });
    const ghosts = svgElement("g", { class: "ghosts" });
    const marks = svgElement("g", { class: "special-marks" });
    const moving = svgElement("g", { class: "moving" });
    const legend = svgElement("g", { class: "scale-legend", transform: `translate(12 ${HEIGHT - LEGEND / 2})` });
    this.picture.replaceChildren(frame, ghosts, marks, moving, legend);
    this.#scaleBar(legend, scale.k);

    drawing.frame?.(frame, scale, params, table);
    for (const name of drawing.pivots) framePivot(frame, scale.point(joints[name][0]));
    this.#crankCircle(marks, drawing, scale, table);
    for (const sp of specialPositions(table)) {
      const ghost = this.#movingParts(svgElement("g", { class: "ghost" }, ghosts), drawing, scale, params, false);
      ghost(jointsAt(table, sp.phi));
    }
    this.update = this.#movingParts(moving, drawing, scale, params, true);
  }

  /** Bars, blocks, pins and (if labelled) letters; returns update(joints in metres). */
  #movingParts(layer, drawing, scale, params, labelled) {
    const parts = drawing.parts?.(layer, scale, params);
    const bars = drawing.links.map(() => bar(layer));
    const pinned = [...new Set([...drawing.pivots, ...drawing.links.flat()])];
    const pins = pinned.map(() => pin(layer));
    const letters = labelled ? Object.entries(drawing.labels).map(([name, offset]) => [name, label(layer, name, offset)]) : [];
    return (joints) => {
      const points = Object.fromEntries(Object.entries(joints).map(([name, p]) => [name, scale.point(p)]));
      parts?.(points);
      drawing.links.forEach(([a, b], i) => bars[i].update(points[a], points[b]));
      pinned.forEach((name, i) => pins[i].update(points[name]));
      for (const [name, letter] of letters) letter.update(points[name]);
      if (labelled) {
        placeLabels(this.svg, [...this.svg.querySelectorAll(".moving .joint-label, .sense-label")],
          [...this.svg.querySelectorAll(`.moving :is(${DRAWN_PARTS}), .frame :is(${DRAWN_PARTS}), .sense-arc, .scale-legend`)]);
      }
    };
  }

  /** A bar of a round length about a quarter of the drawing's width, and that length in metres. */
  #scaleBar(layer, k) {
    const length = roundDown(0.25 * (WIDTH - 2 * PAD) / k);
    const units = length * k;
    svgElement("path", { class: "scale-bar", d: `M0 -4 V4 M0 0 H${units} M${units} -4 V4` }, layer);
    svgElement("text", { class: "scale-label", x: units + 8, y: 0 }, layer).textContent =
      `${formatNumber(length, this.lang)} ${unitText("m", this.t)}`;
  }

  /** Circle of the crank pin, a mark at each special position, and an arc showing the sense of φ. */
  #crankCircle(layer, drawing, scale, table) {
    const [pivotName, pinName] = drawing.crank;
    const at = (phi) => jointsAt(table, phi);
    const [pivot, crankPin] = [at(0)[pivotName], at(0)[pinName]];
    const centre = scale.point(pivot);
    const radius = Math.hypot(crankPin[0] - pivot[0], crankPin[1] - pivot[1]) * scale.k;
    svgElement("circle", { class: "crank-circle", cx: centre[0], cy: centre[1], r: radius }, layer);
    for (const sp of specialPositions(table)) {
      const [cx, cy] = scale.point(at(sp.phi)[pinName]);
      const mark = svgElement("circle", { class: `special-mark ${sp.kind}`, cx, cy, r: 4 }, layer);
      svgElement("title", {}, mark).textContent =
        `${this.t[sp.kind]}: φ = ${formatNumber(degrees(sp.phi), this.lang, 1)}°`;
    }
    const arcRadius = radius * 0.45;
    const direction = (phi) => {
      const [x, y] = scale.point(at(phi)[pinName]);
      return Math.atan2(y - centre[1], x - centre[0]);
    };
    const start = direction(0);
    const turn = Math.atan2(Math.sin(direction(SENSE_ARC) - start), Math.cos(direction(SENSE_ARC) - start));
    const end = start + turn;
    this.crankPlace = { centre, start, sense: Math.sign(turn) };
    const point = (angle) => [centre[0] + arcRadius * Math.cos(angle), centre[1] + arcRadius * Math.sin(angle)];
    const [[x0, y0], [x1, y1]] = [point(start), point(end)];
    svgElement("path", {
      class: "sense-arc", "marker-end": "url(#arrow)",
      d: `M${x0} ${y0} A${arcRadius} ${arcRadius} 0 0 ${turn > 0 ? 1 : 0} ${x1} ${y1}` }, layer);
    const [lx, ly] = point(start + turn / 2).map((v, i) => v + (v - centre[i]) * 0.45);
    svgElement("text", { class: "sense-label", x: lx, y: ly }, layer).textContent = "φ";
  }
}
