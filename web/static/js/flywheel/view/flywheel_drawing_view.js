/**
 * Panel view of the machine with its flywheel, to scale: the scene's linkage (joints from
 * POST /api/v1/kinematics for the request's mechanism and lengths) and the flywheel disk of the answer's
 * diameter on the crank axis, both in metres on one scale; the disk's spokes turn with the crank.
 * Below the drawing the disk's diameter, width and mass. When the answer needs no flywheel (its inertia is 0) the
 * linkage is drawn alone and the panel says so.
 */
import { ApiClient } from "../../common/model/api.js";
import { pathValue } from "../../common/model/dotted_paths.js";
import { element } from "../../common/view/dom.js";
import { DRAWINGS } from "../../common/view/linkage_drawings.js";
import { LinkageView } from "../../common/view/linkage_view.js";
import { formatQuantity, setRichText, unitText } from "../../common/view/notation.js";
import { svgElement } from "../../common/view/svg.js";

const JOINT_POINTS = 361;     // a grid step of 1° of crank angle
const SPOKES = 4;
const HUB = 0.08;             // × disk radius
const DIMENSION_GAP = 16;     // drawing units from the disk's rim to its dimension line

/**
 * The drawing of mechanism with a disk of radius (m) on its crank axis: the disk under the frame, spokes on top.
 * Once drawn, resize(radius) redraws the disk in place on the same scale (a preview's disk).
 */
function withFlywheel(base, radius) {
  const [pivot, crankPin] = base.crank;
  let r = 0;                  // the disk's radius in drawing units
  return {
    ...base,
    extent: (params, table) => {
      const [x, y] = table.outputs.joints[pivot][0];
      return [...base.extent(params, table), [x - radius, y - radius], [x + radius, y + radius]];
    },
    frame(layer, scale, params, table) {
      const [cx, cy] = scale.point(table.outputs.joints[pivot][0]);
      const disk = svgElement("circle", { class: "flywheel-disk", cx, cy }, layer);
      const hub = svgElement("circle", { class: "flywheel-hub", cx, cy }, layer);
      const line = svgElement("line", { class: "dimension", "marker-start": "url(#arrow)", "marker-end": "url(#arrow)" }, layer);
      const label = svgElement("text", { class: "dimension-label", x: cx }, layer);
      label.textContent = "D";
      this.resize = (metres) => {
        r = metres * scale.k;
        const y = cy + r + DIMENSION_GAP;
        disk.setAttribute("r", r);
        hub.setAttribute("r", HUB * r);
        for (const [name, value] of [["x1", cx - r], ["y1", y], ["x2", cx + r], ["y2", y]]) line.setAttribute(name, value);
        label.setAttribute("y", y - 4);
        for (const mark of [line, label]) mark.setAttribute("visibility", r > 0 ? "visible" : "hidden");
      };
      this.resize(radius);
      base.frame?.(layer, scale, params, table);
    },
    parts(layer, scale, params) {
      const spokes = Array.from({ length: SPOKES }, () => svgElement("line", { class: "flywheel-spoke" }, layer));
      const baseParts = base.parts?.(layer, scale, params);
      return (points) => {
        const [cx, cy] = points[pivot];
        const turn = Math.atan2(points[crankPin][1] - cy, points[crankPin][0] - cx);
        spokes.forEach((spoke, i) => {
          const angle = turn + (i + 0.5) * 2 * Math.PI / SPOKES;
          const [c, s] = [Math.cos(angle), Math.sin(angle)];
          spoke.setAttribute("x1", cx + HUB * r * c);
          spoke.setAttribute("y1", cy + HUB * r * s);
          spoke.setAttribute("x2", cx + r * c);
          spoke.setAttribute("y2", cy + r * s);
        });
        baseParts?.(points);
      };
    },
  };
}

export class FlywheelDrawingView {
  /** model: the scene's DynamicsModel, whose request names the mechanism and its lengths. */
  constructor(body, spec, { t, lang }, model) {
    this.spec = spec;
    this.model = model;
    this.t = t;
    this.lang = lang;
    const stage = element("div", { className: "linkage" });
    this.numbers = element("p", { className: "flywheel-numbers" });
    body.append(stage, this.numbers);
    this.linkage = new LinkageView(stage, { t, lang });
    this.turnable = this.linkage;             // its crank turns by hand (crank_drag.js)
    this.kinematics = new ApiClient("kinematics", lang, (busy) => body.classList.toggle("busy", busy));
    this.joints = null;
    this.phi = 0;
  }

  holds(data) {
    return Boolean(pathValue(data, this.spec.disk));
  }

  /** Take the answer: ask for the linkage's joints (once per set of lengths) and draw. */
  show(data) {
    const request = this.model.request();
    this.disk = pathValue(data, this.spec.disk);
    this.inertia = pathValue(data, this.spec.inertia);
    this.kinematics.submit("joints", {
      mechanism: request.mechanism, params: request.params, n: JOINT_POINTS, outputs: ["joints"] }, (answer) => {
      this.joints = answer;
      this.#draw();
    });
    if (this.joints) this.#draw();
  }

  /** A preview's disk (an answer interpolated from a slider's family) redrawn in place; the numbers stay. */
  preview(data) {
    const diameter = pathValue(data, this.spec.disk)?.diameter;
    if (!this.drawing?.resize || !(diameter >= 0)) return;     // no disk drawn: the preview leaves the drawing
    this.drawing.resize(diameter / 2);
    this.linkage.drawAt(this.phi);
  }

  drawAt(phi) {
    this.phi = phi;
    this.linkage.drawAt(phi);
  }

  #draw() {
    const { t, lang } = this;
    const needed = this.inertia > 0 && this.disk.diameter > 0;
    const base = this.joints.ok ? DRAWINGS[this.joints.data.mechanism] : null;
    this.drawing = needed && base ? withFlywheel(base, this.disk.diameter / 2) : base;
    this.linkage.show(this.joints, this.phi, this.drawing);
    const number = (value, unit) => `${formatQuantity(value, lang, 4)} ${unitText(unit, t)}`;
    this.numbers.classList.toggle("no-flywheel", !needed);
    setRichText(this.numbers, needed ? [`D = ${number(this.disk.diameter, "m")}`,
      `b = ${number(this.disk.width, "m")}`, `m = ${number(this.disk.mass, "kg")}`].join(" · ") : t.flywheel_not_needed);
  }
}
