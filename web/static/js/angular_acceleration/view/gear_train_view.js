/**
 * The instantaneous gear train of the coupler (POST /api/v1/angular-acceleration), drawn to scale at the
 * crank angle φ: the crank-slider (O, A, B) or the elliptic trammel (A the middle of BD, sliders B and D),
 * the instantaneous centre P of the coupler where the line OA meets the normals to the guides, and two
 * "wheels" touching at A: the circle of radius OA about O and the circle of radius |AP| about P. Beside
 * the drawing: ω_AB, ε*, ε**, ε_AB = ε* + ε** and AP at φ.
 *
 * P lies on the line OA at the signed distance 1/inv_AP beyond A (away from O when positive); it is taken
 * from the answer's 1/AP, which passes smoothly through 0 where AP is infinite. When |AP| is too large to
 * draw as a circle, or P is at infinity (OA parallel to the normal at B, e.g. φ = 90° for the crank-slider),
 * the circle about P is drawn as its limit, the straight line through A perpendicular to OA. The drawing
 * is bounded by the mechanism; whatever reaches farther is clipped.
 */
import { crankPlace } from "../../common/view/crank_drag.js";
import { element } from "../../common/view/dom.js";
import { bar, block, drawing, framePivot, guide, label, pin } from "../../common/view/linkage_parts.js";
import { degrees, formatNumber, formatQuantity, unitText } from "../../common/view/notation.js";
import { sampleAt } from "../../common/model/phi_samples.js";
import { fitScale, setAttributes, svgElement } from "../../common/view/svg.js";

const WIDTH = 560;
const HEIGHTS = [300, 480];           // drawing units: the height follows the mechanism's shape within these
const PAD = 34;
const SLIDER = [36, 20];              // slider block, drawing units
const GUIDE_MARGIN = 0.35;            // × OA: guide beyond the slider's stroke
const NEAR = 3;                      // × OA: the drawing holds the circle about P if |AP| never exceeds this
const LARGEST_RADIUS = 1e5;           // drawing units: a larger circle about P is drawn as the straight line
const FAR = 4 * (WIDTH + HEIGHTS[1]); // drawing units: half-length of lines that cross the whole drawing
const LABELS = { O: [-22, 16], A: [9, -10], B: [-4, -16], D: [10, -6], P: [8, -8] };

const JOINTS = ["O", "A", "B", "D"];

export class GearTrainView {
  constructor(body, spec, { t, lang }) {
    this.t = t;
    this.lang = lang;
    this.svg = drawing(WIDTH, HEIGHTS[0], spec.title[lang]);
    const clip = svgElement("clipPath", { id: "gear-train-area" }, this.svg.querySelector("defs"));
    this.area = svgElement("rect", { x: 0, y: 0, width: WIDTH, height: HEIGHTS[0] }, clip);
    this.picture = svgElement("g", { "clip-path": "url(#gear-train-area)" }, this.svg);
    this.rows = {};
    const list = element("dl", { className: "figures-list gear-train-readings" });
    for (const [key, name] of [["phi", "φ"], ["omega", "ω_AB"], ["star", "ε*"], ["star2", "ε**"],
      ["epsilon", "ε_AB = ε* + ε**"], ["OA", "OA"], ["AP", "AP"]]) {
      this.rows[key] = element("dd");
      list.append(element("dt", { rich: name }), this.rows[key]);
    }
    this.infinity = element("p", { className: "note instant-centre-note", textContent: t.instant_centre_at_infinity });
    body.append(element("div", { className: "drawing-with-readings" }, this.svg,
      element("div", { className: "drawing-readings" }, list, this.infinity)));
    /** The crank OA turns by hand (crank_drag.js) about O, where the drawing puts it. */
    this.turnable = { svg: this.svg, name: spec.title[lang], crank: () => this.#crankPlace() };
  }

  #crankPlace() {
    if (!this.data) return null;
    const point = (name, phi) => this.scale.point(sampleAt(this.data.phi, this.data.points[name], phi));
    return crankPlace(point("O", 0), (phi) => point("A", phi));
  }

  holds(data) {
    return Array.isArray(data.points?.A) && Array.isArray(data.inv_AP);
  }

  /** Scale the drawing to the mechanism of the answer and build its parts. */
  show(data) {
    this.data = data;
    const { points } = data;
    const names = JOINTS.filter((name) => points[name]);
    const trammel = names.includes("D");
    this.crank = crankLength(points);
    const bounds = extent(data, names, this.crank);
    const height = drawingHeight(bounds);
    this.svg.setAttribute("viewBox", `0 0 ${WIDTH} ${height}`);
    this.area.setAttribute("height", height);
    this.scale = fitScale(bounds, WIDTH, height, PAD);
    const frame = svgElement("g", { class: "frame" });
    const construction = svgElement("g", { class: "construction" });
    const wheels = svgElement("g", { class: "wheels" });
    const moving = svgElement("g", { class: "moving" });
    this.picture.replaceChildren(frame, construction, wheels, moving);

    this.#guides(frame, points, trammel);
    const [cx, cy] = this.scale.point(points.O[0]);
    framePivot(frame, [cx, cy]);
    this.lines = {
      centres: svgElement("line", { class: "construction-line" }, construction),
      normalB: svgElement("line", { class: "construction-line" }, construction),
      normalD: trammel ? svgElement("line", { class: "construction-line" }, construction) : null,
    };
    svgElement("circle", { class: "pitch-circle crank-wheel", cx, cy, r: this.crank * this.scale.k }, wheels);
    this.couplerWheel = svgElement("circle", { class: "pitch-circle coupler-wheel" }, wheels);
    this.couplerLine = svgElement("line", { class: "pitch-circle coupler-wheel" }, wheels);
    const blocks = { B: block(moving, ...SLIDER), ...(trammel ? { D: block(moving, ...SLIDER) } : {}) };
    const bars = [bar(moving), bar(moving)];
    const pins = names.map(() => pin(moving));
    const letters = names.map((name) => label(moving, name, LABELS[name]));
    this.centre = svgElement("g", { class: "instant-centre" }, moving);
    const centreDot = svgElement("circle", { r: 5 }, this.centre);
    const centreLetter = label(this.centre, "P", LABELS.P);
    this.moveCentre = (P) => {
      setAttributes(centreDot, { cx: P[0], cy: P[1] });
      centreLetter.update(P);
    };
    this.moveParts = (at) => {
      blocks.B.update(at.B);
      blocks.D?.update(at.D, 90);
      bars[0].update(at.O, at.A);
      bars[1].update(trammel ? at.B : at.A, trammel ? at.D : at.B);
      names.forEach((name, i) => {
        pins[i].update(at[name]);
        letters[i].update(at[name]);
      });
    };
  }

  drawAt(phi) {
    const { data, scale } = this;
    const sample = (values) => sampleAt(data.phi, values, phi);
    const at = Object.fromEntries(JOINTS.filter((name) => data.points[name])
      .map((name) => [name, scale.point(sample(data.points[name]))]));
    this.moveParts(at);

    const [O, A] = [at.O, at.A];
    const crankRadius = Math.hypot(A[0] - O[0], A[1] - O[1]);
    const u = [(A[0] - O[0]) / crankRadius, (A[1] - O[1]) / crankRadius];     // along OA, drawing units
    setAttributes(this.lines.centres, line(O, u));
    setAttributes(this.lines.normalB, line(at.B, [0, 1]));
    if (this.lines.normalD) setAttributes(this.lines.normalD, line(at.D, [1, 0]));

    const inverse = sample(data.inv_AP);                   // 1/AP, m⁻¹, AP signed from A towards O
    const radius = inverse === null ? Infinity : scale.k / Math.abs(inverse);
    const atInfinity = !(radius < LARGEST_RADIUS);
    this.couplerWheel.style.display = atInfinity ? "none" : "";
    this.couplerLine.style.display = atInfinity ? "" : "none";
    this.centre.style.display = atInfinity ? "none" : "";
    this.infinity.hidden = !atInfinity;
    if (atInfinity) {
      setAttributes(this.couplerLine, line(A, [-u[1], u[0]]));
    } else {
      const along = -Math.sign(inverse) * radius;        // u points from O to A
      const P = [A[0] + u[0] * along, A[1] + u[1] * along];
      setAttributes(this.couplerWheel, { cx: P[0], cy: P[1], r: radius });
      this.moveCentre(P);
    }
    this.#read(phi, sample, atInfinity ? null : 1 / Math.abs(inverse));
  }

  /** The readings at phi; AP in metres, null at infinity. */
  #read(phi, sample, AP) {
    const { t, lang } = this;
    const value = (v, unit) => (v === null ? "—" : `${formatQuantity(v, lang, 3)} ${unitText(unit, t)}`);
    this.rows.phi.textContent = `${formatNumber(degrees(phi), lang, 1)}°`;
    this.rows.omega.textContent = value(sample(this.data.omega_coupler), "rad/s");
    this.rows.star.textContent = value(sample(this.data.epsilon_star), "rad/s²");
    this.rows.star2.textContent = value(sample(this.data.epsilon_star2), "rad/s²");
    this.rows.epsilon.textContent = value(sample(this.data.epsilon), "rad/s²");
    this.rows.OA.textContent = value(this.crank, "m");
    this.rows.AP.textContent = AP === null ? "∞" : value(AP, "m");
  }

  /** The frame's guides under the sliders' strokes: B along x; for the trammel also D along y. */
  #guides(layer, points, trammel) {
    const { scale, crank } = this;
    const span = (values) => [Math.min(...values) - GUIDE_MARGIN * crank, Math.max(...values) + GUIDE_MARGIN * crank];
    const [x0, x1] = span(points.B.map((p) => p[0]));
    const [left, y] = scale.point([x0, points.B[0][1]]);
    guide(layer, left, scale.point([x1, 0])[0], y + SLIDER[1] / 2);
    if (!trammel) return;
    const [y0, y1] = span(points.D.map((p) => p[1]));
    const [x, bottom] = scale.point([points.D[0][0], y0]);
    const top = scale.point([0, y1])[1];
    const turned = svgElement("g", { transform: `rotate(90 ${x} ${top})` }, layer);
    guide(turned, x, x + (bottom - top), top + SLIDER[1] / 2);
  }
}

/**
 * The points (metres) the drawing must hold: the joints' paths, the crank circle, and the circle about P
 * when P stays near (|AP| ≤ NEAR·OA at every angle: the trammel, where AP = OA).
 */
function extent(data, names, crank) {
  const { points } = data;
  const paths = names.flatMap((name) => points[name]);
  const [ox, oy] = points.O[0];
  const box = [[ox - crank, oy - crank], [ox + crank, oy + crank]];
  if (!data.inv_AP.every((v) => v !== null && Math.abs(v) * crank * NEAR >= 1)) return [...paths, ...box];
  const wheels = points.P.flatMap(([x, y], i) => {
    const r = 1 / Math.abs(data.inv_AP[i]);
    return [[x - r, y - r], [x + r, y + r]];
  });
  return [...paths, ...box, ...wheels];
}

/** OA in metres. */
function crankLength({ O, A }) {
  return Math.hypot(A[0][0] - O[0][0], A[0][1] - O[0][1]);
}

/** Height of the drawing in drawing units: the extent's shape at the drawing's width, within HEIGHTS. */
function drawingHeight(points) {
  const span = (k) => Math.max(...points.map((p) => p[k])) - Math.min(...points.map((p) => p[k]));
  const height = (WIDTH - 2 * PAD) * span(1) / span(0) + 2 * PAD;
  return Math.round(Math.min(Math.max(height, HEIGHTS[0]), HEIGHTS[1]));
}

/** Attributes of a line through point p along the unit vector u, long enough to cross the drawing. */
function line([x, y], [ux, uy]) {
  return { x1: x - ux * FAR, y1: y - uy * FAR, x2: x + ux * FAR, y2: y + uy * FAR };
}
