/**
 * Free-body diagrams of the crank-slider's links from an answer of POST /api/v1/forces, at the crank
 * angle φ: the crank 1 about its frame pivot O, the rod 2 about its centre of mass S₂ and the slider 3 on
 * its guide, side by side, each turned as in the mechanism at φ and drawn to one length scale, so that
 * each link carries only the loads that act on it:
 *   crank   R₂₁ = −R₁₂ at A, R₁₄ from the frame at O, the balancing moment
 *   rod     R₁₂ at A, R₃₂ = −R₂₃ at B, its weight G₂ and inertia force Φ₂ at S₂, the inertia moment
 *   slider  R₂₃ at B, the guide's normal reaction R₃₄ and friction F₃₄ at the contact, the force P₃ on
 *           the piston, its weight G₃ and inertia force Φ₃
 * Forces share one scale (set by the 90th percentile over the cycle, so a reaction that grows without
 * bound near self-locking does not shrink the others to nothing; longer arrows are cut to 1.6 times it,
 * or where they would leave the picture, and drawn dashed). The friction circles of radius ρ = f·r are drawn magnified, and each reaction in a
 * revolute pair touches its circle on the side where its moment opposes the relative rotation (3.3):
 * the sense of rotation of crank and rod is read from the answer's joint paths. Below the drawing the
 * values at φ; where the successive approximations diverge (self-locking) the answer has no reactions
 * and the panel says so.
 * On a narrow screen (a phone) the links are drawn one below the other, the drawing's units being CSS
 * pixels, so that the symbols keep their size; in every layout the symbols are moved where they would
 * cover each other, a pin, the block, a bar or an arrow, or leave the drawing (label_placement.js); a preview
 * (while a slider moves) keeps each symbol's offset from its part, and the exact answer places them anew.
 */
import { crankPlace } from "../../common/view/crank_drag.js";
import { DRAWN_PARTS, keepPlaces, placeLabels } from "../../common/view/label_placement.js";
import { element } from "../../common/view/dom.js";
import { forceArrow, momentArc, roundDown } from "./force_parts.js";
import { bar, block, drawing, framePivot, guide, label, pin } from "../../common/view/linkage_parts.js";
import { degrees, formatNumber, formatQuantity, setRichText, unitText } from "../../common/view/notation.js";
import { gridPosition, sampleAt } from "../../common/model/phi_samples.js";
import { setAttributes, svgElement } from "../../common/view/svg.js";

const WIDTH = 960;
const PAD = [80, 80];              // drawing units around the links: room for the arrows
const GAP = 64;                    // drawing units between the links' regions
const LEGEND = 34;                 // drawing units below the picture for the scale bars
const EDGE = 16;                   // drawing units an arrow's far end keeps from the picture's edge (its symbol)
const SLIDER = [56, 30];           // slider block, drawing units
const REFERENCE_ARROW = 90;        // drawing units of the force at the 90th percentile
const LONGEST_ARROW = 1.6 * REFERENCE_ARROW;
const FRICTION_CIRCLE = 14;        // drawing units: the largest friction circle is magnified to about this
const MOMENT_RADIUS = 18;
const CAPTION = 20;                // drawing units from the top to the links' names
const LETTERS = { O: [-22, 16], A: [-4, -12], B: [-4, -16] };
const LABEL_SCALE_LIMIT = 1.6;
const NARROW = 620;                // CSS px: a narrower panel draws the links one below the other
const STACKED = { pad: 56, row: 30, reference: 64, legendRow: 24, widest: 520 };   // drawing units (CSS px) of that layout

const MISSING = "—";

/** The angle (rad, counter-clockwise +) the line a → b turns through from grid row i to i + 1. */
function turning(a, b, i) {
  const angle = (k) => Math.atan2(b[k][1] - a[k][1], b[k][0] - a[k][0]);
  const step = angle(i + 1) - angle(i);
  return Math.atan2(Math.sin(step), Math.cos(step));
}

const minus = (v) => (v ? [-v[0], -v[1]] : null);
const size = (v) => (v ? Math.hypot(v[0], v[1]) : null);

export class FreeBodyView {
  constructor(body, spec, { t, lang }) {
    this.t = t;
    this.lang = lang;
    this.body = body;
    this.phi = 0;
    this.stacked = null;
    new ResizeObserver(() => {            // a phone turned, a window narrowed: lay out again if it changes
      if (!this.data || this.body.clientWidth === this.shownWidth) return;       // only its height changed
      if (this.#narrow() !== this.stacked) this.show(this.data);
      else this.#scaleLabels();
      this.drawAt(this.phi);
    }).observe(body);
    this.svg = drawing(WIDTH, 300, spec.title[lang]);
    this.picture = svgElement("g", {}, this.svg);
    this.locked = element("p", { className: "note self-locking-note", textContent: t.self_locking_at_angle, hidden: true });
    this.list = element("dl", { className: "figures-list free-body-readings" });
    body.append(this.svg, this.locked, this.list);
    /** The crank 1 turns by hand (crank_drag.js) about O, where the diagram draws it. */
    this.turnable = { svg: this.svg, name: spec.title[lang], crank: () => this.#crankPlace() };
  }

  /** The crank as drawn: pivot O at its anchor, the pin A turned with the answer's OA at φ (y up). */
  #crankPlace() {
    if (!this.data) return null;
    const { data, anchors, k } = this;
    const at = (name, phi) => sampleAt(data.phi, data.points[name], phi);
    const [x, y] = anchors.crank;
    return crankPlace(anchors.crank, (phi) => {
      const [O, A] = [at("O", phi), at("A", phi)];
      return [x + (A[0] - O[0]) * k, y - (A[1] - O[1]) * k];
    });
  }

  holds(data) {
    return Array.isArray(data.points?.A) && Boolean(data.reactions) && Boolean(data.applied);
  }

  /** True if the panel is too narrow for the links side by side. */
  #narrow() {
    const width = this.body.clientWidth;
    return width > 0 && width < NARROW;
  }

  /**
   * The symbols' size in drawing units (--label-scale, app.css) such that a drawing shown smaller than its
   * units keeps them at their size in CSS pixels (up to LABEL_SCALE_LIMIT times larger).
   */
  #scaleLabels() {
    const shownWidth = this.svg.clientWidth || this.width;
    const scale = Math.min(LABEL_SCALE_LIMIT, Math.max(1, this.width / shownWidth));
    this.svg.style.setProperty("--label-scale", scale.toFixed(3));
  }

  /** Lay the links out for the answer's cycle, set the force scale, build the parts. */
  show(data) {
    this.data = this.exact = data;
    const { points } = data;
    this.shownWidth = this.body.clientWidth;
    this.stacked = this.#narrow();
    this.width = this.stacked ? Math.max(280, Math.floor(this.body.clientWidth)) : WIDTH;
    const layout = this.stacked ? layOutStacked(points, this.width) : layOut(points);
    this.anchors = layout.anchors;
    this.k = layout.k;
    this.reference = this.stacked ? STACKED.reference : REFERENCE_ARROW;
    this.forceScale = this.reference / referenceForce(data);
    const circles = data.friction_circles ?? { O: 0, A: 0, B: 0 };
    const largest = Math.max(circles.O, circles.A, circles.B);
    this.magnify = largest > 0 ? Math.max(1, roundDown(FRICTION_CIRCLE / (largest * this.k))) : 0;
    this.rho = Object.fromEntries(Object.entries(circles).map(([name, r]) => [name, r * this.k * this.magnify]));
    this.height = layout.height;
    this.svg.setAttribute("viewBox", `0 0 ${this.width} ${layout.height}`);
    this.#scaleLabels();

    const frame = svgElement("g", { class: "frame" });
    const links = svgElement("g", { class: "moving" });
    const forces = svgElement("g", { class: "forces" });
    const legendTop = layout.height - (this.stacked ? 3 * STACKED.legendRow - 10 : 14);
    const legend = svgElement("g", { class: "scale-legend", transform: `translate(12 ${legendTop})` });
    this.picture.replaceChildren(frame, links, forces, legend);
    this.layers = [frame, links, forces];
    framePivot(frame, this.anchors.crank);
    for (const [name, key] of [["crank", "fb_link_crank"], ["rod", "fb_link_rod"], ["slider", "fb_link_slider"]]) {
      svgElement("text", { class: "link-name", x: this.anchors[name][0], y: layout.captions[name] }, frame).textContent = this.t[key];
    }
    const [bx, by] = this.anchors.slider;
    guide(frame, bx - 1.2 * SLIDER[0], bx + 1.2 * SLIDER[0], by + SLIDER[1] / 2);
    this.parts = this.#links(links);
    this.arrows = this.#arrows(forces);
    this.#legend(legend);
    this.rows = this.#readings();
  }

  /**
   * Draw a preview's answer (interpolated from a slider's family) in the layout of the exact answer shown: the
   * same anchors and scales, the friction circles resized; the symbols keep the places the last placement gave
   * them beside their parts (placed anew with the exact answer), and the readings the exact answer's numbers.
   * With no exact drawing, another layout (a phone turned) or friction circles where it has none: drawn whole.
   */
  preview(data) {
    const circles = data.friction_circles ?? { O: 0, A: 0, B: 0 };
    if (!this.exact || this.#narrow() !== this.stacked || (!this.magnify && Math.max(circles.O, circles.A, circles.B) > 0)) {
      const exact = this.exact;
      this.show(data);
      this.exact = exact ?? data;
      this.drawAt(this.phi);
      return Promise.resolve();
    }
    this.data = data;
    this.rho = Object.fromEntries(Object.entries(circles).map(([name, r]) => [name, r * this.k * this.magnify]));
    this.#drawState(this.#state(this.phi), false);
    return Promise.resolve();
  }

  drawAt(phi) {
    this.phi = phi;
    const state = this.#state(phi);
    const exact = this.data === this.exact;
    this.#drawState(state, exact);
    const shown = exact ? state : this.#state(phi, this.exact);        // numbers: the exact answer's
    this.locked.hidden = !shown.locked;
    for (const [cell, text] of this.rows) setRichText(cell, text(shown));
  }

  /** Links, friction circles and loads at state; their symbols placed (place) or kept beside their parts. */
  #drawState(state, place) {
    const at = (anchor, origin) => ([x, y]) =>
      [anchor[0] + (x - origin[0]) * this.k, anchor[1] - (y - origin[1]) * this.k];
    const map = { crank: at(this.anchors.crank, state.O), rod: at(this.anchors.rod, state.S2),
      slider: at(this.anchors.slider, state.B) };
    this.parts(state, map);
    this.arrows(state, map);
    this.#separateLabels(place);
  }

  /**
   * The symbols shown move off each other, off the parts and arrows and inside the drawing: links' names,
   * letters, moments, forces, in that order; or (place false) each keeps its last offset from its part.
   */
  #separateLabels(place) {
    const shown = (node) => node.style.display !== "none" && node.closest(".force")?.style.display !== "none";
    const all = (selector) => this.layers.flatMap((layer) => [...layer.querySelectorAll(selector)]).filter(shown);
    const texts = [...all(".link-name"), ...all(".joint-label"), ...all(".moment .force-label"),
      ...all(".force:not(.moment) .force-label")];
    if (place) placeLabels(this.svg, texts, all(DRAWN_PARTS));
    else keepPlaces(texts);
  }

  /**
   * Everything drawn at phi: positions (m), forces (N), moments (N·m, counter-clockwise +), and the turning
   * of crank (w1) and rod (w2) over the grid step there (rad, counter-clockwise +: their senses of rotation).
   */
  #state(phi, data = this.data) {
    const at = (values) => sampleAt(data.phi, values, phi);
    const [O, A, B, S2] = ["O", "A", "B", "S2"].map((name) => at(data.points[name]));
    const R12 = at(data.reactions.R12);
    const locked = R12 === null;
    const reaction = (values) => (locked ? null : at(values));
    const { i } = gridPosition(data.phi, phi);
    const moment = at(data.balancing_moment);
    return {
      phi, O, A, B, S2, locked, R12, R23: reaction(data.reactions.R23), R41: reaction(data.reactions.R41),
      N: locked ? null : at(data.reactions.R34)?.[1] ?? null,
      F34: locked ? null : at(data.friction.F34),
      balancing: moment, Mb: moment === null ? null : -moment,       // the answer's is along ω₁ (clockwise)
      G2: at(data.applied.G2), G3: at(data.applied.G3), F_in2: at(data.applied.F_in2),
      F_in3: at(data.applied.F_in3), P: at(data.applied.F_3p), M_in2: at(data.applied.M_in2),
      w1: turning(data.points.O, data.points.A, i), w2: turning(data.points.A, data.points.B, i),
    };
  }

  /** Bars, the slider block, pins, letters and friction circles; returns their update(state, map). */
  #links(layer) {
    const circles = svgElement("g", { class: "friction-circles" }, layer);
    const circle = (body, joint) => {
      const node = svgElement("circle", { class: "friction-circle" }, circles);
      return (state, map) => {
        const [cx, cy] = map[body](state[joint]);
        setAttributes(node, { cx, cy, r: this.rho[joint] });      // a preview's f resizes it
      };
    };
    const frictionCircles = this.magnify ? [circle("crank", "O"), circle("crank", "A"), circle("rod", "A"),
      circle("rod", "B"), circle("slider", "B")] : [];
    const crank = bar(layer);
    const rod = bar(layer);
    const slider = block(layer, ...SLIDER);
    const joints = [["crank", "O"], ["crank", "A"], ["rod", "A"], ["rod", "B"], ["slider", "B"]];
    const pins = joints.map(() => pin(layer));
    const letters = joints.map(([, name]) => label(layer, name, LETTERS[name]));
    return (state, map) => {
      const at = (body, name) => map[body](state[name]);
      crank.update(at("crank", "O"), at("crank", "A"));
      rod.update(at("rod", "A"), at("rod", "B"));
      slider.update(at("slider", "B"));
      joints.forEach(([body, name], i) => {
        pins[i].update(at(body, name));
        letters[i].update(at(body, name));
      });
      for (const update of frictionCircles) update(state, map);
    };
  }

  /** The force arrows and moment arcs of the three links; returns their update(state, map). */
  #arrows(layer) {
    const arrow = (className, symbol) => forceArrow(layer, className, symbol);
    const t = this.t;
    const parts = {
      R41: arrow("reaction", "R₁₄"), R21: arrow("reaction", "R₂₁"), Mb: momentArc(layer, "balancing", t.symbol_balancing_moment, MOMENT_RADIUS),
      R12: arrow("reaction", "R₁₂"), R32: arrow("reaction", "R₃₂"), G2: arrow("gravity", "G₂"), F_in2: arrow("inertia", "Φ₂"),
      M_in2: momentArc(layer, "inertia", "M_Φ₂", MOMENT_RADIUS),
      R23: arrow("reaction", "R₂₃"), R34: arrow("reaction guide", "R₃₄"), F34: arrow("friction", "F₃₄"),
      P: arrow("load", "P₃"), F_in3: arrow("inertia", "Φ₃"), G3: arrow("gravity", "G₃"),
    };
    return (state, map) => {
      const { w1, w2 } = state;
      /**
       * A load at point (m) of body, shifted by offset (drawing units); given an outward direction, the
       * arrow lies on that side of the point, pulling away from it or pushing into it.
       */
      const drawn = (name, body, point, force, offset = [0, 0], outward = null) => {
        const [x, y] = map[body](point);
        const [vector, beyondScale] = this.#vector(force);
        const pushes = Boolean(vector && outward) && vector[0] * outward[0] + vector[1] * outward[1] < 0;
        const at = [x + offset[0], y + offset[1]];
        const [inside, cut] = this.#inside(at, vector, pushes);
        parts[name].update(at, inside, { pushes, beyondScale: beyondScale || cut });
      };
      /**
       * A reaction in a revolute pair: its line touches the friction circle, its moment against the relative
       * turning; drawn outside the body, on the side of the joint away from inner (a point of the body, m).
       */
      const reaction = (name, body, joint, force, relative, inner) => {
        const offset = force ? tangent(force, Math.sign(relative) * this.rho[joint]) : [0, 0];
        const [from, to] = [map[body](state[joint]), map[body](inner)];
        drawn(name, body, state[joint], force, offset, [from[0] - to[0], from[1] - to[1]]);
      };
      reaction("R41", "crank", "O", state.R41, w1, state.A);
      reaction("R21", "crank", "A", minus(state.R12), w1 - w2, state.O);
      parts.Mb.update(map.crank(state.O), state.Mb);
      reaction("R12", "rod", "A", state.R12, w2 - w1, state.B);
      reaction("R32", "rod", "B", minus(state.R23), w2, state.A);
      drawn("G2", "rod", state.S2, state.G2);
      drawn("F_in2", "rod", state.S2, state.F_in2);
      parts.M_in2.update(map.rod(state.S2), state.M_in2);
      // the slider's loads spread over the block so that collinear ones do not hide each other: the rod's
      // on the rod's side of B (away from B's mirror of A), the guide's at the bottom face, the piston
      // force on the face it pushes
      const [bx, by] = map.slider(state.B);
      reaction("R23", "slider", "B", state.R23, -w2, [2 * state.B[0] - state.A[0], 2 * state.B[1] - state.A[1]]);
      const contact = [SLIDER[0] / 4, SLIDER[1] / 2];
      drawn("R34", "slider", state.B, state.N === null ? null : [0, state.N], contact, [0, 1]);
      drawn("F34", "slider", state.B, state.F34 === null ? null : [state.F34, 0], contact);
      drawn("F_in3", "slider", state.B, state.F_in3, [0, -SLIDER[1] / 2]);
      drawn("G3", "slider", state.B, state.G3);
      const [pushing, beyondScale] = this.#vector(state.P);
      const face = pushing ? [bx - Math.sign(pushing[0]) * SLIDER[0] / 2, by + SLIDER[1] / 4] : [bx, by];
      const [inside, cut] = this.#inside(face, pushing, true);
      parts.P.update(face, inside, { pushes: true, beyondScale: beyondScale || cut });
    };
  }

  /** [vector in drawing units, beyond scale] of a force (N, y up), or [null, false] for none. */
  #vector(force) {
    if (!force) return [null, false];
    const length = Math.hypot(force[0], force[1]) * this.forceScale;
    const cut = Math.min(1, (LONGEST_ARROW / REFERENCE_ARROW) * this.reference / Math.max(length, 1e-300));
    return [[force[0] * this.forceScale * cut, -force[1] * this.forceScale * cut], cut < 1];
  }

  /**
   * The arrow of vector (drawing units) at point, pulling from it or pushing into it, shortened if needed so
   * that its far end stays EDGE inside the picture (above the scale bars): [vector, shortened].
   */
  #inside(point, vector, pushes) {
    if (!vector) return [vector, false];
    const [dx, dy] = pushes ? [-vector[0], -vector[1]] : vector;
    const limit = (p, d, low, high) => (d > 0 ? (high - EDGE - p) / d : d < 0 ? (low + EDGE - p) / d : Infinity);
    const share = Math.min(1, limit(point[0], dx, 0, this.width), limit(point[1], dy, 0,
      this.height - (this.stacked ? 3 * STACKED.legendRow : LEGEND)));
    return share < 1 ? [[vector[0] * Math.max(share, 0), vector[1] * Math.max(share, 0)], true] : [vector, false];
  }

  /** Scale bars: a round length, a round force, and the magnification of the friction circles. */
  #legend(layer) {
    const { t, lang } = this;
    const length = roundDown(0.25 * (this.width - 2 * PAD[0]) / this.k);
    const units = length * this.k;
    svgElement("path", { class: "scale-bar", d: `M0 -4 V4 M0 0 H${units} M${units} -4 V4` }, layer);
    text(layer, units + 8, 0, `${formatNumber(length, lang)} ${unitText("m", t)}`);
    const force = roundDown(this.reference / this.forceScale);
    // side by side on a wide drawing, one below the other on a narrow one
    const [start, forceRow] = this.stacked ? [0, STACKED.legendRow] : [Math.max(units + 110, 180), 0];
    forceArrow(layer, "reaction", "").update([start, forceRow], [force * this.forceScale, 0]);
    text(layer, start + force * this.forceScale + 8, forceRow, `${formatNumber(force, lang)} ${unitText("N", t)}`);
    if (!this.magnify) return;
    const [circleAt, circleRow] = this.stacked ? [7, 2 * STACKED.legendRow] : [start + force * this.forceScale + 120, 0];
    svgElement("circle", { class: "friction-circle", cx: circleAt, cy: circleRow, r: 7 }, layer);
    text(layer, circleAt + 14, circleRow, this.magnify > 1
      ? t.friction_circles_scale.replace("{k}", formatNumber(this.magnify, lang)) : t.friction_circles_to_scale);
  }

  /** Rows below the drawing: [value cell, text(state)]. */
  #readings() {
    const { t, lang } = this;
    const value = (v, unit) => (v === null || v === undefined ? MISSING
      : `${formatQuantity(v, lang, 4)} ${unitText(unit, t)}`);
    const rows = [
      [t.crank_angle, "", (s) => `${formatNumber(degrees(s.phi), lang, 1)}°`],
      ["|R₁₂| = |R₂₁|", t.fb_joint_A, (s) => value(size(s.R12), "N")],
      ["|R₂₃| = |R₃₂|", t.fb_joint_B, (s) => value(size(s.R23), "N")],
      ["|R₁₄|", t.fb_joint_O, (s) => value(size(s.R41), "N")],
      ["R₃₄", t.fb_guide_normal, (s) => value(s.N, "N")],
      ["F₃₄", t.fb_guide_friction, (s) => value(s.F34, "N")],
      [t.symbol_balancing_moment, t.fb_balancing_moment, (s) => value(s.balancing, "N·m")],
      ["P₃", t.fb_piston_force, (s) => value(s.P?.[0] ?? null, "N")],
      ["|Φ₂|", t.fb_inertia_rod, (s) => value(size(s.F_in2), "N")],
      ["M_{Φ2}", t.fb_inertia_moment_rod, (s) => value(s.M_in2, "N·m")],
      ["Φ₃", t.fb_inertia_slider, (s) => value(s.F_in3?.[0] ?? null, "N")],
      ["G₂, G₃", t.fb_weights, (s) => [size(s.G2), size(s.G3)].map((g) => value(g, "N")).join("; ")],
    ];
    this.list.replaceChildren();
    const cells = rows.map(([symbol, words, text]) => {
      const cell = element("dd");
      this.list.append(element("div", {},
        element("dt", {}, element("span", { className: "symbol", rich: symbol }), words && ` ${words}`), cell));
      return [cell, text];
    });
    return cells;
  }
}

/**
 * Where the links go: the crank turns about O, the rod about S₂, the slider sits still on its guide; the
 * boxes their joints sweep about these anchors over the cycle lie side by side, GAP apart, and the length
 * scale k (drawing units per metre) makes them fill the width. anchors: drawing points of O, S₂ and B.
 */
function layOut(points) {
  const about = (anchor, names) => names.flatMap((name) => points[name].map(([x, y], i) =>
    [x - points[anchor][i][0], y - points[anchor][i][1]]));
  const box = (offsets) => {
    const [xs, ys] = [offsets.map((p) => p[0]), offsets.map((p) => p[1])];
    return { x: [Math.min(...xs), Math.max(...xs)], y: [Math.min(...ys), Math.max(...ys)] };
  };
  const boxes = { crank: box(about("O", ["A", "O"])), rod: box(about("S2", ["A", "B", "S2"])), slider: box([[0, 0]]) };
  const widths = boxes.crank.x[1] - boxes.crank.x[0] + boxes.rod.x[1] - boxes.rod.x[0];
  const k = (WIDTH - 2 * PAD[0] - 2 * GAP - SLIDER[0]) / widths;
  const top = Math.max(...Object.values(boxes).map((b) => b.y[1])) * k;
  const bottom = Math.min(...Object.values(boxes).map((b) => b.y[0])) * k;
  const y = PAD[1] + top;
  let left = PAD[0];
  const anchors = {};
  for (const [name, { x }] of Object.entries(boxes)) {
    const width = name === "slider" ? SLIDER[0] : (x[1] - x[0]) * k;
    anchors[name] = [name === "slider" ? left + width / 2 : left - x[0] * k, y];
    left += width + GAP;
  }
  const captions = { crank: CAPTION, rod: CAPTION, slider: CAPTION };
  return { anchors, k, captions, height: Math.round(2 * PAD[1] + top - bottom + LEGEND) };
}

/** Joints' sweeps about a body's anchor (m): the box {x: [min, max], y: [min, max]} of the offsets. */
function sweep(points, anchor, names) {
  const offsets = names.flatMap((name) => points[name].map(([x, y], i) =>
    [x - points[anchor][i][0], y - points[anchor][i][1]]));
  const [xs, ys] = [offsets.map((p) => p[0]), offsets.map((p) => p[1])];
  return { x: [Math.min(...xs), Math.max(...xs)], y: [Math.min(...ys), Math.max(...ys)] };
}

/**
 * The narrow layout: crank, rod and slider one below the other, each centred in a row headed by its name,
 * one length scale k for all that lets the wider of crank and rod fill the width less the margins.
 */
function layOutStacked(points, width) {
  const boxes = { crank: sweep(points, "O", ["A", "O"]), rod: sweep(points, "S2", ["A", "B", "S2"]),
    slider: { x: [0, 0], y: [0, 0] } };
  const k = (Math.min(width, STACKED.widest) - 2 * STACKED.pad) / Math.max(...["crank", "rod"].map((name) => boxes[name].x[1] - boxes[name].x[0]));
  const anchors = {};
  const captions = {};
  let y = 0;
  for (const [name, box] of Object.entries(boxes)) {
    captions[name] = y + CAPTION;
    const above = name === "slider" ? SLIDER[1] : box.y[1] * k;
    const below = name === "slider" ? SLIDER[1] : -box.y[0] * k;
    anchors[name] = [width / 2 - (box.x[0] + box.x[1]) / 2 * k, y + STACKED.row + STACKED.pad + above];
    y = anchors[name][1] + below + STACKED.pad;
  }
  return { anchors, k, captions, height: Math.round(y + 3 * STACKED.legendRow) };
}

/** The force (N) the arrows are scaled to: the 90th percentile over φ of the largest force at each angle. */
function referenceForce(data) {
  const { reactions, applied, friction } = data;
  const vectors = [reactions.R12, reactions.R23, reactions.R41, applied.G2, applied.G3, applied.F_in2,
    applied.F_in3, applied.F_3p];
  const largest = data.phi.map((_, i) => Math.max(0,
    ...vectors.map((values) => size(values[i]?.[0] === null ? null : values[i]) ?? 0),
    ...(reactions.R12[i]?.[0] === null ? [] : [Math.abs(reactions.R34[i][1] ?? 0), Math.abs(friction.F34[i] ?? 0)])));
  const sorted = largest.sort((a, b) => a - b);
  return sorted[Math.floor(0.9 * (sorted.length - 1))] || 1;
}

/**
 * The offset (drawing units) from a joint's centre to the line of force that touches the circle of radius
 * |signedRadius| so that the force's moment about the centre has the sign opposite to signedRadius's.
 */
function tangent(force, signedRadius) {
  const length = Math.hypot(force[0], force[1]);
  if (!length || !signedRadius) return [0, 0];
  // counter-clockwise normal (y up) scaled by the radius; the screen's y points down
  return [-force[1] / length * signedRadius, -force[0] / length * signedRadius];
}

function text(layer, x, y, content) {
  setRichText(svgElement("text", { class: "scale-label", x, y }, layer), content);
}
