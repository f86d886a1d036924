/**
 * The mechanism drawn at one input position, in an SVG whose mapping from metres is the view
 * (model/viewport.js: X = (x − x₀)k, Y = (y₀ − y)k), written on the <svg> as data-view="x₀ y₀ k". The view
 * changes only when the student zooms, pans or asks for a fit: adding an element never moves it. Under the
 * mechanism a grid of round lengths (its step is the snapping step); over it the handles the student may
 * drag. Joints and guides are focusable and carry data-joint, data-guide (a click or Enter picks them);
 * a draggable one also data-drag (its handle's id, model/handles.js). Traced paths are polylines over the
 * whole turn. A drag that stopped where the mechanism no longer assembles is marked: the stopped joint
 * ringed and a dashed line to the pointer.
 */
import { svgElement } from "../../common/view/svg.js";
import { setRichText } from "../../common/view/notation.js";
import { DEFAULT_VIEW, HEIGHT, WIDTH, fitView, gridStep, majorStep, snapPoint, toScreen, toWorld, zoomAbout }
  from "../model/viewport.js";

const GUIDE_HALF = 3;                                     // m: a frame guide is drawn across the whole view
const BLOCK = [34, 17];                                    // a slider block's length and width, drawing units
const LINK_COLORS = ["#1f4e79", "#b5442f", "#2e7d4f", "#6a4c93", "#c07400", "#5d6978"];
const GRID_PIXELS = 10;                                    // the grid's step on the screen, CSS px at least
const ANGLE_HANDLE_PIXELS = 46;                            // a guide's angle handle from its point, CSS px
const LABEL_ALONG = [-70, 70, -130, 130, -200, 200, -30];   // CSS px along a guide where its name may go
const LABEL_CLEAR = 34;                                    // CSS px from any joint a guide's name keeps

export class Drawing {
  /** names(kind, name): the words a handle is read by ("joint C", "guide g1: angle"). */
  constructor(host, { label, names }) {
    this.view = { ...DEFAULT_VIEW };
    this.grid = true;
    this.snap = false;
    this.names = names;
    this.scene = null;
    this.svg = svgElement("svg", { viewBox: `0 0 ${WIDTH} ${HEIGHT}`, role: "group", "aria-label": label,
      class: "editor-svg" });
    host.append(this.svg);
    // the SVG's width in CSS px, kept as it changes: read during a draw it would force a layout of the page
    this.width = this.svg.clientWidth;
    new ResizeObserver(([entry]) => {
      const resized = Math.abs(entry.contentRect.width - this.width) > 1;
      this.width = entry.contentRect.width;
      if (resized && this.scene) this.draw(this.scene);        // the grid's step and the targets follow the size
    }).observe(this.svg);
    this.#writeView();
  }

  /** Drawing units per CSS pixel (the SVG is as wide as its box). */
  get unit() {
    return this.width > 0 ? WIDTH / this.width : 1;
  }

  /** The grid's step (m) at this view and screen: a round length at least GRID_PIXELS apart. */
  get step() {
    return gridStep(this.view, GRID_PIXELS * this.unit);
  }

  /** How far from its guide's point the angle handle is drawn, in metres at this view. */
  get handleReach() {
    return (ANGLE_HANDLE_PIXELS * this.unit) / this.view.k;
  }

  /** The world point p on the grid when snapping is on, else p. */
  snapped(p) {
    return this.snap ? snapPoint(p, this.step) : p;
  }

  #writeView() {
    const { x0, y0, k } = this.view;
    this.svg.dataset.view = `${x0} ${y0} ${k}`;
    this.svg.dataset.step = String(this.step);
  }

  /** Show `view` from the next draw on (the page draws again). */
  setView(view) {
    this.view = view;
    this.#writeView();
  }

  /** Fit the view around the points [x, y] (metres), with a margin. */
  fit(points) {
    this.setView(fitView(points, this.view));
  }

  /** Zoom by factor about the drawing's centre (the view's buttons). */
  zoom(factor) {
    this.setView(zoomAbout(this.view, [WIDTH / 2, HEIGHT / 2], factor));
  }

  /** The drawing point [X, Y] under the client point (CSS px of the window). */
  toDrawing(clientX, clientY) {
    const point = this.svg.createSVGPoint();
    point.x = clientX;
    point.y = clientY;
    const local = point.matrixTransform(this.svg.getScreenCTM().inverse());
    return [local.x, local.y];
  }

  /** The world point (m) under the client point. */
  toWorld(clientX, clientY) {
    return toWorld(this.view, this.toDrawing(clientX, clientY));
  }

  xy(p) {
    return toScreen(this.view, p);
  }

  #grid(layer) {
    const { x0, y0, k } = this.view;
    const defs = svgElement("defs", {}, layer);
    const steps = [["minor", this.step], ["major", majorStep(this.step)]];
    for (const [kind, step] of steps) {
      const size = step * k;
      const pattern = svgElement("pattern", { id: `editor-grid-${kind}`, patternUnits: "userSpaceOnUse", width: size,
        height: size, x: (-x0 * k) % size, y: (y0 * k) % size }, defs);
      svgElement("path", { d: `M0,0 H${size} M0,0 V${size}`, class: `grid-${kind}` }, pattern);
      svgElement("rect", { width: WIDTH, height: HEIGHT, fill: `url(#editor-grid-${kind})` }, layer);
    }
    const [ox, oy] = this.xy([0, 0]);
    svgElement("path", { d: `M${ox},0 V${HEIGHT} M0,${oy} H${WIDTH}`, class: "grid-axes" }, layer);
  }

  /**
   * Where a guide's name is written: along the guide from its point, on the first of a few places (nearer
   * first, either way) that keeps LABEL_CLEAR drawing units from every joint (the joints' own names sit by them),
   * and inside the drawing; beside the point if none does. A guide whose point is out of view is named from the
   * point of its line nearest the drawing's centre.
   */
  #guideLabelAt(g, marks) {
    const [c, s] = [Math.cos(g.angle), -Math.sin(g.angle)];        // the guide's direction on the drawing (Y down)
    let [x, y] = this.xy(g.point);
    if (x < 0 || x > WIDTH || y < 0 || y > HEIGHT) {                 // its point out of view: from the line's point
      const along = (WIDTH / 2 - x) * c + (HEIGHT / 2 - y) * s;      // nearest to the drawing's centre
      [x, y] = [x + along * c, y + along * s];
    }
    const scale = this.unit;
    for (const along of LABEL_ALONG) {
      const at = [x + along * scale * c + 6 * scale * s, y + along * scale * s - 6 * scale * c];
      const clear = marks.every(([mx, my]) => Math.hypot(mx - at[0], my - at[1]) >= LABEL_CLEAR * scale);
      if (clear && at[0] > 0 && at[0] < WIDTH - 30 && at[1] > 15 && at[1] < HEIGHT) return at;
    }
    return [x + 6, y - 6];
  }

  #focusable(attributes, label) {
    return { ...attributes, tabindex: 0, role: "button", "aria-label": label };
  }

  /**
   * scene: {frameJoints: {name: [x, y]}, joints: {name: [x, y] | null}, guides: [{name, point, angle, moving}],
   * links: [{link, lines: [[a, b]], blocks: [{at, angle}]}], traces: [[[x, y], …]], picked: Set of names,
   * clickable: "joint" | "guide" | null, handles: [{id, kind, name, at}] (draggable now), stop: {at, pointer}
   * | null (a drag stopped at `at`, the pointer at `pointer`)}
   */
  draw(scene) {
    this.scene = scene;
    const focused = this.svg.contains(document.activeElement) ? document.activeElement.dataset.key : null;
    this.svg.replaceChildren();
    // drawing units per CSS pixel: a finger-sized target (about 14 px round a joint) at any screen width
    const reach = Math.max(11, 14 * this.unit);
    const layer = (name) => svgElement("g", { class: name }, this.svg);
    const grid = layer("grid");
    const guides = layer("guides");
    const traces = layer("traces");
    const linksLayer = layer("links");
    const joints = layer("joints");
    const handles = layer("handles");
    if (this.grid) this.#grid(grid);
    this.svg.classList.toggle("picking-joint", scene.clickable === "joint");
    this.svg.classList.toggle("picking-guide", scene.clickable === "guide");
    const drags = new Map(scene.handles.map((h) => [h.id, h]));
    const marks = Object.values(scene.joints).filter(Boolean).map((p) => this.xy(p));
    const dragOf = (kinds, name) => kinds.map((kind) => drags.get(`${kind}:${name}`)).find(Boolean);
    for (const g of scene.guides) {
      const half = g.moving ? 0.25 : GUIDE_HALF;
      const [c, s] = [Math.cos(g.angle), Math.sin(g.angle)];
      const a = this.xy([g.point[0] - half * c, g.point[1] - half * s]);
      const b = this.xy([g.point[0] + half * c, g.point[1] + half * s]);
      const line = { x1: a[0], y1: a[1], x2: b[0], y2: b[1] };
      const drag = dragOf(["guide"], g.name);
      svgElement("line", { ...line, class: `guide${scene.picked.has(g.name) ? " picked" : ""}` }, guides);
      svgElement("line", this.#focusable({ ...line, class: `guide-hit${drag ? " draggable" : ""}`, "data-guide": g.name,
        "data-key": `guide:${g.name}`, "stroke-width": reach, ...(drag ? { "data-drag": drag.id } : {}) },
      this.names("guide", g.name)), guides);
      const [lx, ly] = this.#guideLabelAt(g, marks);
      svgElement("text", { x: lx, y: ly, class: "guide-label" }, guides).textContent = g.label ?? g.name;
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
    for (const p of Object.values(scene.frameJoints)) {
      const [x, y] = this.xy(p);
      svgElement("path", { d: `M${x},${y} l-10,16 h20 z`, class: "ground" }, joints);
      svgElement("line", { x1: x - 14, y1: y + 16, x2: x + 14, y2: y + 16, class: "ground-line" }, joints);
    }
    for (const [name, p] of Object.entries(scene.joints)) {
      if (!p) continue;
      const [x, y] = this.xy(p);
      const drag = dragOf(["frame", "crank", "input_slider", "RRR", "RRP", "point"], name);
      svgElement("circle", { cx: x, cy: y, r: 5.5, class: `joint${scene.picked.has(name) ? " picked" : ""}` }, joints);
      svgElement("circle", this.#focusable({ cx: x, cy: y, r: reach, class: `joint-hit${drag ? " draggable" : ""}`,
        "data-joint": name, "data-key": `joint:${name}`, ...(drag ? { "data-drag": drag.id } : {}) },
      this.names("joint", name)), joints);
      setRichText(svgElement("text", { x: x + 9, y: y - 9, class: "joint-label" }, joints), name);
    }
    for (const h of scene.handles.filter((item) => item.kind === "guide_angle")) {
      const [x, y] = this.xy(h.at);
      svgElement("circle", this.#focusable({ cx: x, cy: y, r: 6, class: "angle-handle draggable", "data-drag": h.id,
        "data-key": h.id }, this.names("guide_angle", h.name)), handles);
    }
    if (scene.stop) {
      const [x, y] = this.xy(scene.stop.at);
      const [px, py] = this.xy(scene.stop.pointer);
      svgElement("line", { x1: x, y1: y, x2: px, y2: py, class: "stop-line" }, handles);
      svgElement("circle", { cx: x, cy: y, r: 13, class: "stop-ring" }, handles);
    }
    if (focused) this.svg.querySelector(`[data-key="${CSS.escape(focused)}"]`)?.focus({ preventScroll: true });
  }
}
