/**
 * The picture of an elastic machine's dynamic model, drawn from the panel's spec (content/scenes) for the
 * model the variant's request names (request.model: "two_mass", "kinematic_drive", "three_mass"): along one
 * shaft, the discs (their inertias J and angles φ, and what each stands for: motor, middle shaft, mechanism),
 * between them the elastic links as springs (stiffness c) with the dampers beside them (damping b), the
 * driving moment M_д on the first disc (or on the driven end of a shaft turned at φ₁ = ωt) and the
 * resisting moment M_с on the last. The spec:
 *   models   {model: {drive?: {angle, name}, masses: [{J, angle, name}], springs: [{c, b?}]}}: symbols in the
 *            scene's notation ("J_2(φ_2)"), names in three languages; springs[i] joins mass i − 1 (or the drive)
 *            and mass i
 *   moments  {driving, resisting}: the moments' symbols in three languages
 * The picture depends on nothing the answer holds: the panel needs nothing and is always shown.
 */
import { DRAWN_PARTS, placeLabels } from "../../common/view/label_placement.js";
import { drawing } from "../../common/view/linkage_parts.js";
import { setRichText } from "../../common/view/notation.js";
import { setAttributes, svgElement } from "../../common/view/svg.js";

const WIDTH = 470;
const HEIGHT = 220;
const AXIS = 104;                   // drawing units from the top to the shaft's axis
const DISC = [16, 84];              // a disc seen from the side: thickness and diameter
const DRIVE = [26, 46];             // the driven end of the shaft (kinematic drive)
const END = 58;                     // drawing units from the edges to the first and last disc
const SPRING_Y = -18;               // the spring above the axis, the damper below it (drawing units)
const DAMPER_Y = 18;
const COILS = 7;
const MOMENT = [11, 30];            // the moment arrow: half-width and half-height of its arc

export class MassModelView {
  constructor(body, spec, { t, lang }, model) {
    this.spec = spec;
    this.lang = lang;
    this.svg = drawing(WIDTH, HEIGHT, spec.title[lang]);
    this.svg.classList.add("mass-model");
    body.append(this.svg);
    const chain = spec.models[model.variant.request?.model];
    if (chain) this.#draw(chain);
    else this.svg.style.display = "none";
    /** Laid out once shown: the labels' places need the drawing's size on the screen. */
    new ResizeObserver(() => this.#placeLabels()).observe(this.svg);
  }

  #draw(chain) {
    const { lang, svg } = this;
    const parts = svgElement("g", { class: "model-parts" }, svg);
    const labels = svgElement("g", { class: "model-labels" }, svg);
    const text = (x, y, content, className = "model-symbol") =>
      setRichText(svgElement("text", { class: className, x, y, "text-anchor": "middle" }, labels), content);
    const bodies = [...(chain.drive ? [{ drive: true, ...chain.drive }] : []), ...chain.masses];
    const step = (WIDTH - 2 * END) / Math.max(1, bodies.length - 1);
    const xs = bodies.map((_, i) => (bodies.length === 1 ? WIDTH / 2 : END + i * step));
    svgElement("line", { class: "model-axis", x1: 18, x2: WIDTH - 18, y1: AXIS, y2: AXIS }, parts);
    bodies.forEach((item, i) => {
      const x = xs[i];
      const [w, h] = item.drive ? DRIVE : DISC;
      svgElement("rect", { class: item.drive ? "block model-drive" : "block model-disc",
        x: x - w / 2, y: AXIS - h / 2, width: w, height: h }, parts);
      if (item.J) text(x, AXIS - h / 2 - 12, item.J);
      text(x, AXIS + h / 2 + 20, item.angle);
      text(x, AXIS + h / 2 + 40, item.name[lang], "model-name");
    });
    chain.springs.forEach((link, i) => {
      const [a, b] = [xs[i] + halfWidth(bodies[i]), xs[i + 1] - halfWidth(bodies[i + 1])];
      spring(parts, a, b, AXIS + SPRING_Y);
      text((a + b) / 2, AXIS + SPRING_Y - 16, link.c);
      if (link.b) {
        damper(parts, a, b, AXIS + DAMPER_Y);
        text((a + b) / 2, AXIS + DAMPER_Y + 26, link.b);
      }
    });
    const first = xs[0] - halfWidth(bodies[0]) - 16;
    const last = xs.at(-1) + halfWidth(bodies.at(-1)) + 16;
    moment(parts, first, 1);
    text(first - MOMENT[0] - 20, AXIS - MOMENT[1] + 4, this.spec.moments.driving[lang]);
    moment(parts, last, -1);
    text(last + MOMENT[0] + 20, AXIS - MOMENT[1] + 4, this.spec.moments.resisting[lang]);
  }

  #placeLabels() {
    if (this.svg.style.display === "none") return;
    placeLabels(this.svg, [...this.svg.querySelectorAll(".model-labels text")],
      [...this.svg.querySelectorAll(`.model-parts :is(${DRAWN_PARTS}, .model-spring, .model-damper, .model-moment)`)]);
  }
}

const halfWidth = (item) => (item.drive ? DRIVE[0] : DISC[0]) / 2;

/** A coil spring from x0 to x1 at height y (drawing units): short straight ends, a zigzag between. */
function spring(layer, x0, x1, y) {
  const lead = 0.15 * (x1 - x0);
  const pitch = (x1 - x0 - 2 * lead) / COILS;
  const points = [[x0, y], [x0 + lead, y]];
  for (let k = 0; k < COILS; k += 1) {
    points.push([x0 + lead + (k + 0.25) * pitch, y - 8], [x0 + lead + (k + 0.75) * pitch, y + 8]);
  }
  points.push([x1 - lead, y], [x1, y]);
  svgElement("polyline", { class: "model-spring", points: points.map((p) => p.join(",")).join(" ") }, layer);
}

/** A dashpot from x0 to x1 at height y: a rod with a piston in an open cylinder. */
function damper(layer, x0, x1, y) {
  const middle = (x0 + x1) / 2;
  const group = svgElement("g", { class: "model-damper" }, layer);
  svgElement("path", { d: `M${x0} ${y} H${middle - 4} M${middle - 4} ${y - 7} V${y + 7}` }, group);
  svgElement("path", { d: `M${middle - 12} ${y - 10} H${middle + 10} V${y + 10} H${middle - 12} M${middle + 10} ${y} H${x1}` }, group);
}

/** A moment about the shaft seen from the side: an arc round the axis at x, its arrow turning by sense. */
function moment(layer, x, sense) {
  const [rx, ry] = MOMENT;
  const path = svgElement("path", { class: "model-moment", "marker-end": "url(#arrow)" }, layer);
  setAttributes(path, { d: sense > 0 ? `M${x} ${AXIS + ry} A${rx} ${ry} 0 1 1 ${x} ${AXIS - ry}`
    : `M${x} ${AXIS - ry} A${rx} ${ry} 0 1 1 ${x} ${AXIS + ry}` });
}
