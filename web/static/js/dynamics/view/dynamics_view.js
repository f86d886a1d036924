/**
 * The panels of a dynamics scene's variant, in the variant's order, and above them what the answer says
 * in words. Plot and polar panels are Plotly graphs redrawn by a PanelScheduler (one per animation
 * frame, only those in view); figures, tables and numerics are HTML, rebuilt with every answer; other
 * kinds have views of their own (PANEL_VIEWS).
 *
 * A variant with a drawing (a panel view with drawAt) is animated: the drawings and a cursor over each
 * plot against φ follow the crank angle, interpolating in the one answer of the current values.
 *
 * A panel the answer holds nothing for is hidden: when the machine stalls or self-locks, or has no
 * steady cycle, the answer leaves those results out and its warnings say why — they are shown first,
 * under a heading that says there is no steady motion. A refused request (HTTP 422) says why instead.
 * A panel that needs nothing from the answer ("needs": [], e.g. a calculator) is always shown. A panel
 * of a kind this page has no view for is left out, so new content never breaks an older page.
 *
 * While the reader holds a slider whose family is here, an exact answer's graphs are drawn with axes that hold
 * every member of the family (family_plot.js), so that a preview moves their curves only.
 *
 * Every graph has its toolbar (plot_tools.js: zoom, export) and is drawn explorable (plot_explore.js: hover
 * readouts with units, zoom, the pinned ghost curves of ghost_curves.js under its own).
 *
 * A panel view's module is loaded (import()) only when a variant has such a panel: a scene fetches the
 * code it shows and no more. Its panel stays hidden until the view has arrived, then takes the latest answer.
 */
import { drawFigure } from "../../common/view/plot_style.js";
import { element } from "../../common/view/dom.js";
import { pathValue } from "../../common/model/dotted_paths.js";
import { heldCurves, heldSeries, holds, plotFigure, polarFigure } from "./dynamics_figures.js";
import { familyExtents, moveCurves, roomy, withFamily } from "../../common/view/family_plot.js";
import { refusalMessage } from "../../common/view/messages.js";
import { formatQuantity } from "../../common/view/notation.js";
import { PanelScheduler } from "../../common/view/panel_scheduler.js";
import { sampleAt } from "../../common/model/phi_samples.js";
import { PlotCursor } from "../../common/view/plot_cursor.js";
import { explorable } from "../../common/view/plot_explore.js";
import { plotToolbar } from "../../common/view/plot_tools.js";
import { holdsReadings, readings } from "./readings_view.js";

const GRAPH_KINDS = ["plot", "polar"];
const READING_KINDS = ["figures", "table", "numerics"];

/**
 * Panel kinds drawn by views of their own, each loaded on first use: load() gives the class View, and
 * new View(body, spec, {t, lang}, model) (model: the scene's DynamicsModel, for views that read or edit the
 * request) has
 *   holds(data)   true if the answer's data holds what the panel shows
 *   show(data)    take the answer's data
 *   drawAt(phi)   drawings (and diagrams that follow the crank angle): show them at crank angle phi (rad);
 *                 such a view is marked drawing: true here (the page shows the crank-angle clock for it)
 *   paramsChanged()  optional: a value changed (a view with results of its own marks them as earlier)
 *   turnable      optional, a drawing view's: the drawing whose crank turns by hand, {svg, crank(), name?}
 *                 (crank_drag.js), handed to the page's turn(turnable) once the view is made
 *   useFamily(family)  optional: the family of the slider the reader holds (or null), for a diagram whose axes
 *                 should hold every member's (family_plot.js); the view redraws itself if it must
 * A view without holds needs nothing from the answer (as a panel with "needs": []): always shown, never given show.
 */
const PANEL_VIEWS = {
  efficiency_chain: { load: () => import("../../forces_friction/view/efficiency_chain_view.js").then((m) => m.EfficiencyChainView) },
  flywheel_drawing: { load: () => import("../../flywheel/view/flywheel_drawing_view.js").then((m) => m.FlywheelDrawingView), drawing: true },
  free_body: { load: () => import("../../forces_friction/view/free_body_view.js").then((m) => m.FreeBodyView), drawing: true },
  group_free_body: { load: () => import("../../forces_friction/view/group_free_body_view.js").then((m) => m.GroupFreeBodyView), drawing: true },
  free_law_table: { load: () => import("./free_law_editor_view.js").then((m) => m.FreeLawEditorView) },
  gear_train: { load: () => import("../../angular_acceleration/view/gear_train_view.js").then((m) => m.GearTrainView), drawing: true },
  indicator_diagram: { load: () => import("../../flywheel/view/indicator_diagram_view.js").then((m) => m.IndicatorDiagramView) },
  mass_model: { load: () => import("./mass_model_view.js").then((m) => m.MassModelView) },
  merzalov_sheet: { load: () => import("../../flywheel/view/merzalov_sheet_view.js").then((m) => m.MerzalovSheetView) },
  reference_table: { load: () => import("./reference_table_view.js").then((m) => m.ReferenceTableView) },
  toggle_drawings: { load: () => import("./toggle_drawings_view.js").then((m) => m.ToggleDrawingsView), drawing: true },
  wittenbauer: { load: () => import("../../flywheel/view/wittenbauer_view.js").then((m) => m.WittenbauerView), drawing: true },
  work_precision: { load: () => import("./work_precision_view.js").then((m) => m.WorkPrecisionView) },
};
const loadedViews = new Map();          // kind → promise of its view class, one import per kind

/** The view entry of a panel kind, or null (also for names such as "constructor" that every object has). */
const panelView = (kind) => (Object.hasOwn(PANEL_VIEWS, kind) ? PANEL_VIEWS[kind] : null);
const isShown = (spec) => [...GRAPH_KINDS, ...READING_KINDS].includes(spec?.kind) || panelView(spec?.kind) !== null;
const isDrawing = (spec) => panelView(spec.kind)?.drawing === true;

function loadView(kind) {
  if (!loadedViews.has(kind)) loadedViews.set(kind, panelView(kind).load());
  return loadedViews.get(kind);
}

/** True if the answer's data holds what the panel shows. */
function holdsPanel(panel, data) {
  if (panel.view) return panel.view.holds(data);
  if (panel.spec.kind === "plot") return holds(data, panel.spec.x) && heldSeries(panel.spec, data).length > 0;
  if (panel.spec.kind === "polar") return heldCurves(panel.spec, data).length > 0;
  return holdsReadings(panel.spec, data);
}

export class DynamicsView {
  /** The family of the slider the reader holds (family_preview.js held()), or null: set before show(). */
  family = null;
  #spans = new Map();      // panel id → the family's extents in its graph (familyExtents), of #spansOf
  #spansOf = null;
  // exact answers shown: the container's data-answers; a graph's data-answer is the one it has drawn (a panel out
  // of view is drawn in an idle period, so a page captured, printed or read by a test waits for it)
  #shown = 0;

  /**
   * ghosts: the pinned curves (GhostCurves), drawn under each graph's own; turn(turnable): makes a drawing's
   * crank turn by hand with the page's clock.
   */
  constructor(container, notices, { scene, t, lang }, model, ghosts, turn) {
    this.container = container;
    this.turn = turn;
    this.ghosts = ghosts;
    this.model = model;
    this.notices = notices;
    this.scene = scene;
    this.texts = { t, lang };
    this.panels = [];
    this.phi = 0;
    this.animated = false;
    this.scheduler = new PanelScheduler((panel) => this.#draw(panel));
    model.on("params", () => {
      for (const panel of this.panels) panel.view?.paramsChanged?.();
    });
    ghosts.on("change", () => {
      this.#spans.clear();
      for (const panel of this.panels) if (panel.graph && panel.graph.data) panel.stale = true;
      this.scheduler.refresh();
    });
  }

  /** The graphs drawn now: Map panel id → Plotly graph element. */
  graphs() {
    return new Map(this.panels.filter((p) => p.graph?.data && !p.figure.hidden).map((p) => [p.id, p.graph]));
  }

  /** One panel per graph, reading or panel view of the variant, hidden until an answer fills it. */
  build(variant) {
    for (const panel of this.panels) if (panel.graph) Plotly.purge(panel.graph);
    const specs = variant.panels.map((id) => [id, this.scene.panels[id]]).filter(([, spec]) => isShown(spec));
    this.animated = specs.some(([, spec]) => isDrawing(spec));
    this.answered = false;
    this.panels = specs.map(([id, spec]) => this.#panel(id, spec));
    this.container.replaceChildren(...this.panels.map((panel) => panel.figure));
    this.notices.replaceChildren();
    this.scheduler.track(this.panels.filter((panel) => panel.graph));
  }

  /** No mechanism in the address for an own-mechanism variant: say how to get one, draw nothing. */
  showMissingMechanism() {
    const { t, lang } = this.texts;
    for (const panel of this.panels) this.#fill(panel, null);
    this.notices.replaceChildren(element("section", { className: "warnings own-mechanism-missing" },
      element("h2", { textContent: t.own_mechanism_missing_title }),
      element("p", { rich: t.own_mechanism_missing }),
      element("p", {}, element("a", { className: "button secondary", href: `/editor?lang=${lang}`,
        textContent: t.own_mechanism_open_editor }))));
    this.data = this.plotted = null;
  }

  /** Show the answer: the panels it holds data for, its warnings; or why the request was refused. */
  show(answer) {
    const { t } = this.texts;
    const data = answer.ok ? answer.data : null;
    const missing = [];
    for (const panel of this.panels) if (this.#fill(panel, data) === false && data) missing.push(panel);
    if (!answer.ok) {
      this.notices.replaceChildren(refusalMessage(t.computation_refused, answer.error, t));
    } else if (data.warnings.length) {
      const noMotion = missing.length > 0;
      this.notices.replaceChildren(element("section", { className: noMotion ? "warnings no-motion" : "warnings" },
        element("h2", { textContent: noMotion ? t.no_motion : t.warnings }),
        element("ul", {}, ...data.warnings.map((warning) => element("li", { rich: warning })))));
    } else {
      this.notices.replaceChildren();
    }
    this.data = this.plotted = data;
    this.answered = true;
    this.container.dataset.answers = String(++this.#shown);
    for (const panel of this.panels) panel.view?.useFamily?.(this.family);
    this.drawAt(this.phi);
    this.scheduler.refresh();
  }

  /**
   * Draw an answer's data interpolated from a slider's family (a preview) now: the graphs and drawings that
   * hold it follow it; figures, tables and numerics keep the last exact answer's numbers.
   */
  preview(data) {
    if (!this.data) return Promise.resolve();
    this.plotted = data;
    const drawn = [];
    for (const panel of this.panels) {
      if (panel.figure.hidden || panel.loading) continue;
      if (panel.graph) panel.stale ||= holdsPanel(panel, data);
      else if (panel.view?.drawAt && panel.view.holds?.(data)) drawn.push(panel.view.preview ? panel.view.preview(data) : panel.view.show(data));
    }
    return Promise.all([...drawn, this.scheduler.drawNow()]);
  }

  /**
   * The family of the slider held has arrived (or null: none): the exact answer's graphs are drawn again where
   * their axes do not yet hold the family's members (those in view first, the others when idle).
   */
  useFamily(family) {
    if (family === this.family) return;
    this.family = family;
    if (!this.data || this.plotted !== this.data) return;       // a preview on the screen: the next exact answer
    for (const panel of this.panels) if (!panel.figure.hidden) panel.view?.useFamily?.(family);
    for (const panel of this.panels) {
      const drawn = panel.graph?.layout;
      if (!drawn || panel.figure.hidden) continue;
      const { layout } = this.#figure(panel);
      panel.stale ||= Object.keys(layout).some((key) => /^([xy]axis|polar)/.test(key)
        && JSON.stringify(layout[key].range ?? layout[key].radialaxis?.range)
          !== JSON.stringify(drawn[key]?.range ?? drawn[key]?.radialaxis?.range));
    }
    this.scheduler.refresh();
  }

  /** Resolves once every graph in view shows what it was last given. */
  drawn() {
    return this.scheduler.drawn();
  }

  /** Show or hide one panel for the answer's data (null: refused); whether it holds it, null while loading. */
  #fill(panel, data) {
    if (panel.loading) return null;
    const independent = panel.spec.needs?.length === 0 || (panel.view !== undefined && !panel.view.holds);
    const held = independent || (Boolean(data) && holdsPanel(panel, data));
    panel.figure.hidden = !held;
    if (!held || independent) return held;
    if (panel.graph) panel.stale = true;
    else if (panel.view) panel.view.show(data);
    else panel.body.replaceChildren(...readings(panel.spec, data, this.texts));
    return held;
  }

  /** A panel view has loaded: make it, and give it the answer already shown (and the crank angle). */
  #viewLoaded(panel, View) {
    if (!this.panels.includes(panel)) return;            // another variant was built meanwhile
    panel.view = new View(panel.body, panel.spec, this.texts, this.model);
    panel.loading = false;
    if (panel.view.turnable) this.turn(panel.view.turnable);
    if (this.answered) this.#fill(panel, this.data);
    if (this.data && !panel.figure.hidden) panel.view.drawAt?.(this.phi);
  }

  /** Put the drawings and the plot cursors at crank angle phi (rad). */
  drawAt(phi) {
    this.phi = phi;
    if (!this.data) return;
    for (const panel of this.panels) {
      if (panel.figure.hidden) continue;
      panel.view?.drawAt?.(phi);
      panel.cursor?.move(phi);
    }
  }

  #panel(id, spec) {
    const { lang } = this.texts;
    const graph = GRAPH_KINDS.includes(spec.kind) ? element("div", { className: "graph" }) : null;
    const heading = spec.title ? [element("h2", { rich: spec.title[lang] })] : [];
    const tools = graph ? [plotToolbar(graph, { name: `${this.scene.id}-${id}`, title: spec.title?.[lang] ?? id }, this.texts)] : [];
    const title = heading.length || tools.length ? [element("div", { className: "panel-head" }, ...heading, ...tools)] : [];
    const make = (content, ...more) => element("figure", {
      className: `panel panel-${spec.kind}${isDrawing(spec) ? " panel-drawing" : ""}`, id: `panel-${id}`, hidden: true },
    ...title, content, ...more);
    if (panelView(spec.kind)) {
      const body = element("div", { className: `${spec.kind}-body` });
      const panel = { id, spec, figure: make(body), body, loading: true };
      loadView(spec.kind).then((View) => this.#viewLoaded(panel, View));
      return panel;
    }
    if (graph) {
      const cursor = this.animated && spec.kind === "plot" && spec.x_unit === "deg"
        ? new PlotCursor((phi) => this.#values(spec, phi), this.phi) : null;
      const frame = element("div", { className: "graph-frame" }, graph, ...(cursor ? [cursor.element] : []));
      const note = spec.note ? [element("p", { className: "note", rich: spec.note[lang] })] : [];   // under the plot
      return { id, spec, figure: make(frame, ...note), graph, cursor, stale: false };
    }
    const body = element("div", { className: `readings ${spec.kind}-readings` });
    return { id, spec, figure: make(body), body };
  }

  /**
   * "ε* = 0,0604", "ε** = −0,141", … one line each: the plot's series at crank angle phi, each named by the
   * first word of its label (its symbol); level lines left out, "—" where the answer has no value.
   */
  #values(spec, phi) {
    if (!this.data) return "";
    const { lang } = this.texts;
    const phis = pathValue(this.data, spec.x);
    return heldSeries(spec, this.data).filter((series) => series.style !== "hline").map((series) => {
      const value = sampleAt(phis, pathValue(this.data, series.y), phi);
      return `${series.label[lang].split(" ")[0]} = ${value === null ? "—" : formatQuantity(value, lang, 3)}`;
    }).join("\n");
  }

  /** The graph's figure for what is plotted, its axes holding the family's members if one is held. */
  #figure(panel) {
    const figureOf = (data) => explorable(panel.spec.kind === "polar" ? polarFigure(panel.spec, data, this.texts)
      : plotFigure(panel.spec, data, this.texts), this.ghosts.traces(panel.id));
    const figure = figureOf(this.plotted);
    if (!this.family) return figure;
    if (this.#spansOf !== this.family) {
      this.#spans.clear();
      this.#spansOf = this.family;
    }
    const held = (data) => holdsPanel(panel, data);
    if (!this.#spans.has(panel.id)) {
      this.#spans.set(panel.id, familyExtents({ answers: this.family.answers.filter((a) => a && held(a)) }, figureOf));
    }
    return withFamily(figure, this.#spans.get(panel.id));
  }

  #draw(panel) {
    if (!this.plotted || !holdsPanel(panel, this.plotted)) return null;   // e.g. a preview of a stalled motor
    let figure = this.#figure(panel);
    if (this.plotted !== this.data) {             // a preview
      if (moveCurves(panel.graph, figure.data)) return Promise.resolve();
      if (!this.family) figure = roomy(figure);     // the family's ranges hold its own data too
    }
    const shown = this.plotted === this.data ? this.#shown : null;
    return drawFigure(panel.graph, figure).then(() => {
      panel.cursor?.follow(panel.graph);
      if (shown !== null) panel.figure.dataset.answer = String(shown);
    });
  }
}
