/**
 * Free-body diagrams of a general mechanism's Assur groups and its crank (model: group_free_body.js), side by
 * side, each in its own cell at the cursor's crank angle: the group's joints and links, the loads on its links
 * (weights G, inertia forces Φ and moments M_Φ, the useful load P), the reactions of the neighbouring links and
 * the frame (R₃₄: link 3 on link 4), friction (moments M_f in revolute pairs, forces F_f in prismatic ones) and
 * the friction circles ρ = f·r (magnified); the crank with its balancing moment. Every body's forces share one
 * scale (the largest force of the picture is REFERENCE_ARROW long). Below, each body's outer reactions with
 * their values at that angle. On a narrow screen (a phone) the bodies are drawn one below the other.
 */
import { element } from "../../common/view/dom.js";
import { forceArrow, momentArc } from "./force_parts.js";
import { DRAWN_PARTS, placeLabels } from "../../common/view/label_placement.js";
import { drawing, label, pin } from "../../common/view/linkage_parts.js";
import { degrees, formatNumber, formatQuantity, setRichText } from "../../common/view/notation.js";
import { fitScale, setAttributes, svgElement } from "../../common/view/svg.js";
import { bodyParts, GroupFreeBody, symbolOf } from "../model/group_free_body.js";

const WIDTH = 960;
const HEIGHT = 360;
const PAD = 90;                 // drawing units around a body's joints: room for the arrows
const REFERENCE_ARROW = 100;     // drawing units of the largest force of the picture
const CIRCLE = 9;               // drawing units of the largest friction circle (magnified)
const MOMENT_RADIUS = 16;
const ARC_STEP = 9;             // drawing units between concentric moment arcs about one point
const CAPTION = 30;             // drawing units above a cell's picture for its caption
const SHORTEST = 0.4;           // the force scale is not cut below this share of the reference
const ROOM = 18;                // drawing units kept between an arrow's end and its cell's edge (its symbol)
const NARROW = 620;             // CSS px: a narrower panel draws the bodies one below the other
const STACKED = [480, 300];     // drawing units of one body's cell in that layout
const CLASS_OF = { useful: "load" };   // the crank-slider's diagram's colours (app.css): reaction, load, inertia, …
const classOf = (kind) => CLASS_OF[kind] ?? kind;

export class GroupFreeBodyView {
  constructor(body, spec, { t, lang }, model) {
    this.t = t;
    this.lang = lang;
    this.svg = drawing(WIDTH, HEIGHT, spec.title[lang]);
    this.svg.classList.add("group-free-body");
    this.angle = element("p", { className: "note group-free-body-angle" });
    this.list = element("dl", { className: "figures-list free-body-readings" });
    body.append(this.angle, this.svg, this.list);
    this.body = body;
    this.stacked = null;
    this.bodies = new GroupFreeBody(model, lang, (freeBody) => this.#draw(freeBody));
    new ResizeObserver(() => {            // a phone turned, a window narrowed: lay out again if it changes
      if (this.freeBody && this.#narrow() !== this.stacked) this.#draw(this.freeBody);
    }).observe(body);
  }

  #narrow() {
    return this.body.clientWidth > 0 && this.body.clientWidth < NARROW;
  }

  holds(data) {
    return Array.isArray(data.free_body?.bodies) && data.free_body.bodies.length > 0;
  }

  show(data) {
    this.bodies.take(data);
  }

  drawAt(phi) {
    this.bodies.at(phi);
  }

  #draw(freeBody) {
    const { t, lang } = this;
    this.svg.replaceChildren(this.svg.querySelector("defs"));
    this.freeBody = freeBody;
    this.stacked = this.#narrow();
    const bodies = freeBody.bodies;
    const [cell, height] = this.stacked ? STACKED : [WIDTH / bodies.length, HEIGHT];
    this.svg.setAttribute("viewBox", `0 0 ${this.stacked ? cell : WIDTH} ${this.stacked ? height * bodies.length : height}`);
    const parts = bodies.map(bodyParts);
    const largest = Math.max(1e-12, ...parts.flatMap((p) => p.forces.map((f) => Math.hypot(...f.force))));
    const largestCircle = Math.max(1e-12, ...parts.flatMap((p) => p.circles.map((c) => c.radius)));
    const cells = bodies.map((body) => {
      const scale = fitScale(Object.values(body.points), cell, height - CAPTION, Math.min(PAD, cell / 4));
      return (p) => { const [x, y] = scale.point(p); return [x, y + CAPTION]; };
    });
    // one force scale (drawing units per N) for every body, the largest force REFERENCE_ARROW long unless an
    // arrow would then leave its cell: then all are shortened alike (down to SHORTEST of it at most), so that
    // every arrow and its symbol stay in the drawing
    const arrowScale = Math.max(SHORTEST * REFERENCE_ARROW / largest, Math.min(REFERENCE_ARROW / largest,
      ...parts.flatMap((p, i) => p.forces.map((f) =>
        room(cells[i](f.at), [f.force[0], -f.force[1]], f.kind === "reaction", [cell, height])))));
    bodies.forEach((body, i) => {
      const layer = svgElement("g", { class: "free-body-cell", "data-group": String(body.group),
        transform: this.stacked ? `translate(0 ${i * height})` : `translate(${i * cell} 0)` }, this.svg);
      const caption = body.group === "crank" ? t.fb_group_crank
        : t.fb_group_named.replace("{kind}", body.kind).replace("{links}", body.links.join(", "));
      setRichText(svgElement("text", { class: "free-body-caption", x: cell / 2, y: 22, "text-anchor": "middle" }, layer), caption);
      const at = cells[i];
      const joints = Object.entries(body.points);
      for (let k = 1; k < joints.length; k += 1) {
        const [a, b] = [at(joints[k - 1][1]), at(joints[k][1])];
        setAttributes(svgElement("line", { class: "bar" }, layer), { x1: a[0], y1: a[1], x2: b[0], y2: b[1] });
      }
      for (const [name, p] of joints) {
        pin(layer).update(at(p));
        label(layer, name, [-14, -10]).update(at(p));
      }
      for (const c of parts[i].circles) {
        svgElement("circle", { class: "friction-circle", r: Math.max(2, CIRCLE * c.radius / largestCircle),
          cx: at(c.at)[0], cy: at(c.at)[1] }, layer);
      }
      for (const f of parts[i].forces) {
        const v = [f.force[0] * arrowScale, -f.force[1] * arrowScale];
        forceArrow(layer, classOf(f.kind), f.symbol).update(at(f.at), v, { pushes: f.kind === "reaction" });
      }
      const arcsAt = new Map();           // moments about one point drawn as concentric arcs, not one over another
      for (const m of parts[i].moments) {
        const symbol = m.kind === "balancing" ? t.symbol_balancing_moment : m.symbol;
        const key = at(m.at).map((v) => v.toFixed(1)).join(" ");
        const k = arcsAt.get(key) ?? 0;
        arcsAt.set(key, k + 1);
        const radius = (m.kind === "balancing" ? 1.6 * MOMENT_RADIUS : MOMENT_RADIUS) + ARC_STEP * k;
        momentArc(layer, classOf(m.kind), symbol, radius).update(at(m.at), m.moment);
      }
    });
    const all = (selector) => [...this.svg.querySelectorAll(selector)].filter((node) => node.closest(".force")?.style.display !== "none");
    placeLabels(this.svg, [...all(".free-body-caption"), ...all(".joint-label"), ...all(".moment .force-label"),
      ...all(".force:not(.moment) .force-label")], all(DRAWN_PARTS));
    this.angle.textContent = t.fb_group_angle.replace("{phi}", formatNumber(degrees(freeBody.phi), lang, 1));
    const rows = parts.flatMap((p, i) => [
      ...p.reactions.map((r) => [symbolOf(r.name),
        Array.isArray(r.force) && r.force.every(Number.isFinite) ? formatQuantity(Math.hypot(...r.force), lang, 4) : "—", t.units_N]),
      ...(Number.isFinite(bodies[i].balancing_moment)
        ? [[t.symbol_balancing_moment, formatQuantity(bodies[i].balancing_moment, lang, 4), t.units_N_m]] : []),
    ]);
    this.list.replaceChildren(...rows.flatMap(([symbol, value, unit]) => [
      element("dt", { rich: symbol }), element("dd", { textContent: `${value} ${unit}` })]));
  }
}

/**
 * The largest length (drawing units per N) a force [fx, fy] (N, y down) may be drawn at from point (in a cell of
 * [width, height]) so that the arrow, pulling from the point or pushing into it, ends ROOM inside the cell.
 */
function room(point, force, pushes, [width, height]) {
  const direction = pushes ? [-force[0], -force[1]] : force;
  const limit = (p, d, low, high) => (d > 0 ? (high - ROOM - p) / d : d < 0 ? (low + ROOM - p) / d : Infinity);
  return Math.max(0, Math.min(limit(point[0], direction[0], 0, width), limit(point[1], direction[1], CAPTION, height)));
}
