/**
 * The mechanism drawn at one crank angle, in an SVG whose mapping from metres is fixed until the student asks
 * for a new fit (so that clicking places things where the pointer is): X = (x − x₀)k, Y = (y₀ − y)k,
 * written on the <svg> as data-view="x₀ y₀ k". Joints and guides are clickable (data-joint, data-guide);
 * every click is reported with where it was, in metres. Traced paths are polylines over the whole turn.
 */
import { svgElement } from "../../common/view/svg.js";
import { setRichText } from "../../common/view/notation.js";

const WIDTH = 800;
const HEIGHT = 600;
const DEFAULT_VIEW = { x0: -0.5, y0: 0.5, k: 600 };      // 1.33 m × 1 m around the origin
const GUIDE_HALF = 3;                                     // m: a frame guide is drawn across the whole view
const BLOCK = [34, 17];                                    // a slider block's length and width, drawing units
const LINK_COLORS = ["#1f4e79", "#b5442f", "#2e7d4f", "#6a4c93", "#c07400", "#5d6978"];

export class Drawing {
  constructor(host, { onPlace, onJoint, onGuide, label }) {
    this.view = { ...DEFAULT_VIEW };
    this.svg = svgElement("svg", { viewBox: `0 0 ${WIDTH} ${HEIGHT}`, role: "img", "aria-label": label,
      class: "editor-svg" });
    host.append(this.svg);
    this.svg.addEventListener("click", (event) => {
      const target = event.target.closest("[data-joint], [data-guide]");
      const at = this.toWorld(event.clientX, event.clientY);
      if (target?.dataset.joint) onJoint(target.dataset.joint, at);
      else if (target?.dataset.guide) onGuide(target.dataset.guide, at);
      else onPlace(at);
    });
    this.#writeView();
  }

  #writeView() {
    const { x0, y0, k } = this.view;
    this.svg.dataset.view = `${x0} ${y0} ${k}`;
  }

  /** Fit the view around the points [x, y] (metres), with a margin. */
  fit(points) {
    const finite = points.filter((p) => p && Number.isFinite(p[0]) && Number.isFinite(p[1]));
    if (finite.length < 2) return;
    const xs = finite.map((p) => p[0]);
    const ys = finite.map((p) => p[1]);
    const [xa, xb, ya, yb] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const k = 0.8 * Math.min(WIDTH / Math.max(xb - xa, 0.05), HEIGHT / Math.max(yb - ya, 0.05));
    this.view = { x0: (xa + xb) / 2 - WIDTH / 2 / k, y0: (ya + yb) / 2 + HEIGHT / 2 / k, k };
    this.#writeView();
  }

  toWorld(clientX, clientY) {
    const point = this.svg.createSVGPoint();
    point.x = clientX;
    point.y = clientY;
    const local = point.matrixTransform(this.svg.getScreenCTM().inverse());
    const { x0, y0, k } = this.view;
    return [x0 + local.x / k, y0 - local.y / k];
  }

  xy([x, y]) {
    const { x0, y0, k } = this.view;
    return [(x - x0) * k, (y0 - y) * k];
  }

  /**
   * scene: {frameJoints: {name: [x, y]}, joints: {name: [x, y] | null}, guides: [{name, point, angle, moving}],
   * links: [{link, lines: [[a, b]], blocks: [{at, angle}]}], traces: [[[x, y], …]], picked: Set of names,
   * clickable: "joint" | "guide" | null}
   */
  draw(scene) {
    this.svg.replaceChildren();
    // drawing units per CSS pixel: a finger-sized target (about 14 px round a joint) at any screen width
    const unit = this.svg.clientWidth > 0 ? WIDTH / this.svg.clientWidth : 1;
    const reach = Math.max(11, 14 * unit);
    const layer = (name) => svgElement("g", { class: name }, this.svg);
    const guides = layer("guides");
    const traces = layer("traces");
    const linksLayer = layer("links");
    const joints = layer("joints");
    this.svg.classList.toggle("picking-joint", scene.clickable === "joint");
    this.svg.classList.toggle("picking-guide", scene.clickable === "guide");
    for (const g of scene.guides) {
      const half = g.moving ? 0.25 : GUIDE_HALF;
      const [c, s] = [Math.cos(g.angle), Math.sin(g.angle)];
      const a = this.xy([g.point[0] - half * c, g.point[1] - half * s]);
      const b = this.xy([g.point[0] + half * c, g.point[1] + half * s]);
      const line = { x1: a[0], y1: a[1], x2: b[0], y2: b[1] };
      svgElement("line", { ...line, class: `guide${scene.picked.has(g.name) ? " picked" : ""}` }, guides);
      svgElement("line", { ...line, class: "guide-hit", "data-guide": g.name, "stroke-width": reach }, guides);
      const at = this.xy(g.point);
      svgElement("text", { x: at[0] + 6, y: at[1] - 6, class: "guide-label" }, guides).textContent = g.label ?? g.name;
    }
    for (const path of scene.traces) {
      const points = path.filter(Boolean).map((p) => this.xy(p).map((v) => v.toFixed(1)).join(",")).join(" ");
      svgElement("polyline", { points, class: "trace" }, traces);
    }
    for (const link of scene.links) {
      const color = LINK_COLORS[(link.link - 1) % LINK_COLORS.length];
      const group = svgElement("g", { "data-link": link.link, stroke: color }, linksLayer);
      for (const [a, b] of link.lines) {
        if (!a || !b || ![...a, ...b].every(Number.isFinite)) continue;
        const [p, q] = [this.xy(a), this.xy(b)];
        svgElement("line", { x1: p[0], y1: p[1], x2: q[0], y2: q[1], class: "link" }, group);
      }
      for (const block of link.blocks) {
        if (!block.at || !Number.isFinite(block.angle)) continue;     // a link the table does not have yet
        const [x, y] = this.xy(block.at);
        const [w, h] = BLOCK;
        svgElement("rect", { x: x - w / 2, y: y - h / 2, width: w, height: h, class: "block", fill: "#ffffff",
          transform: `rotate(${(-block.angle * 180) / Math.PI} ${x} ${y})` }, group);
      }
    }
    for (const [name, p] of Object.entries(scene.frameJoints)) {
      const [x, y] = this.xy(p);
      svgElement("path", { d: `M${x},${y} l-10,16 h20 z`, class: "ground" }, joints);
      svgElement("line", { x1: x - 14, y1: y + 16, x2: x + 14, y2: y + 16, class: "ground-line" }, joints);
    }
    for (const [name, p] of Object.entries(scene.joints)) {
      if (!p) continue;
      const [x, y] = this.xy(p);
      svgElement("circle", { cx: x, cy: y, r: 5.5, class: `joint${scene.picked.has(name) ? " picked" : ""}` }, joints);
      svgElement("circle", { cx: x, cy: y, r: reach, class: "joint-hit", "data-joint": name }, joints);
      setRichText(svgElement("text", { x: x + 9, y: y - 9, class: "joint-label" }, joints), name);
    }
  }
}
