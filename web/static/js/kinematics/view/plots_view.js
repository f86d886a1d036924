/**
 * The plot panels of the variant: one Plotly graph per panel, its title, caption (largest error of an
 * approximation) and note. A cursor line (PlotCursor) over each φ-plot follows the animation.
 * Plots are redrawn by a PanelScheduler: one per animation frame, only those in view; a preview (an answer
 * interpolated from a slider's family) redraws every plot in view at once, moving the curves in place where
 * it can (family_plot.js): while the reader holds a slider whose family is here, the exact answer too is drawn
 * with axes that hold every member of the family, so that the first preview after it moves the curves only.
 * Captions and the cursors'
 * values are numbers: they always come from the last exact answer.
 * Every plot has its toolbar (plot_tools.js: zoom, export) and is drawn explorable (plot_explore.js: hover
 * readouts with units, zoom, the pinned ghost curves of ghost_curves.js under its own).
 */
import { drawFigure } from "../../common/view/plot_style.js";
import { element } from "../../common/view/dom.js";
import { familyExtents, moveCurves, roomy, withFamily } from "../../common/view/family_plot.js";
import { approximationErrors, exactOutputs, harmonicClaim, isSpectrum, panelFigure } from "./figures.js";
import { geometryMessage } from "../../common/view/messages.js";
import { formatNumber, symbol } from "../../common/view/notation.js";
import { PanelScheduler } from "../../common/view/panel_scheduler.js";
import { PlotCursor } from "../../common/view/plot_cursor.js";
import { explorable } from "../../common/view/plot_explore.js";
import { plotToolbar } from "../../common/view/plot_tools.js";
import { valueAt } from "../../common/model/positions_table.js";


export class PlotsView {
  /** The family of the slider the reader holds (family_preview.js held()), or null: set before show(). */
  family = null;
  #spans = new Map();      // panel id → the family's extents in its plot (familyExtents), of #spansOf
  #spansOf = null;

  /** ghosts: the pinned curves (GhostCurves), drawn under each plot's own. */
  constructor(container, { scene, t, lang }, ghosts) {
    this.container = container;
    this.scene = scene;
    this.texts = { t, lang };
    this.panels = [];
    this.phi = 0;
    this.ghosts = ghosts;
    this.scheduler = new PanelScheduler((panel) => this.#render(panel));
    ghosts.on("change", () => {
      this.#spans.clear();
      if (!this.table) return;
      for (const panel of this.panels) panel.stale = true;
      this.scheduler.refresh();
    });
  }

  /** The plots drawn now: Map panel id → Plotly graph element. */
  graphs() {
    return new Map(this.panels.filter((p) => p.graph.data).map((p) => [p.id, p.graph]));
  }

  /** One panel per plot of the variant, in the scene's order. */
  build(variant) {
    for (const panel of this.panels) Plotly.purge(panel.graph);
    this.panels = variant.panels.filter((id) => this.scene.panels[id].kind === "plot")
      .map((id) => this.#panel(id, this.scene.panels[id]));
    this.message = element("div", { className: "plots-message" });
    this.container.replaceChildren(this.message, ...this.panels.map((p) => p.figure));
    this.scheduler.track(this.panels);
  }

  /** Show the answer (and the overlay tables, Map λ → answer), or why there is nothing to plot. */
  show(answer, overlays) {
    this.message.replaceChildren(...(answer.ok ? [] : [geometryMessage(answer.error, this.texts.t)]));
    this.table = answer.ok ? answer.data : null;
    this.plotted = this.table;
    for (const panel of this.panels) {
      panel.figure.hidden = !answer.ok;
      panel.overlays = overlays;
      panel.stale = answer.ok;
      panel.captioned = false;
    }
    this.scheduler.refresh();
  }

  /**
   * The family of the slider held has arrived (or null: none): the exact answer shown is drawn again where its
   * axes do not yet hold the family's members (panels in view first, the others when idle).
   */
  useFamily(family) {
    if (family === this.family) return;
    this.family = family;
    if (!this.table || this.plotted !== this.table) return;       // a preview on the screen: the next exact answer
    for (const panel of this.panels) {
      const drawn = panel.graph.layout;
      if (!drawn) continue;
      const { layout } = this.#figure(panel);
      panel.stale ||= Object.keys(layout).some((key) => /^[xy]axis/.test(key)
        && JSON.stringify(layout[key].range) !== JSON.stringify(drawn[key]?.range));
    }
    this.scheduler.refresh();
  }

  /** Draw the preview answer (and the overlay tables) in every plot in view now; resolves once drawn. */
  preview(answer, overlays) {
    if (!this.table) return Promise.resolve();       // nothing exact shown yet: the panels stay as they are
    this.plotted = answer.data;
    for (const panel of this.panels) {
      panel.overlays = overlays;
      panel.stale = true;
    }
    return this.scheduler.drawNow();
  }

  /** Resolves once every plot in view shows what it was last given. */
  drawn() {
    return this.scheduler.drawn();
  }

  /** Move the cursors to crank angle phi (rad) and show the values there. */
  moveCursor(phi) {
    this.phi = phi;
    for (const panel of this.panels) if (panel.hasCursor) panel.cursor.move(phi);
  }

  /** "u₃₁ = 0,0866  u′₃₁ = 0,05": the panel's outputs at crank angle phi. */
  #values(spec, phi) {
    if (!this.table) return "";
    return exactOutputs(spec).map((name) => {
      const value = valueAt(this.table, this.table.outputs[name], phi);
      return `${symbol(name)} = ${value === null ? "—" : formatNumber(value, this.texts.lang)}`;
    }).join("  ");
  }

  #panel(id, spec) {
    const graph = element("div", { className: "graph" });
    const cursor = new PlotCursor((phi) => this.#values(spec, phi), this.phi);
    const caption = element("p", { className: "caption" });
    const title = spec.title[this.texts.lang];
    const figure = element("figure", { className: "panel", id: `panel-${id}` },
      element("div", { className: "panel-head" }, element("h2", { rich: title }),
        plotToolbar(graph, { name: `${this.scene.id}-${id}`, title }, this.texts)),
      element("div", { className: "graph-frame" }, graph, cursor.element), caption,
      ...(spec.note ? [element("p", { className: "note", rich: spec.note[this.texts.lang] })] : []));
    return { id, spec, graph, cursor, caption, figure, stale: false,
      hasCursor: !spec.outputs.some(isSpectrum) };
  }

  /** The panel's figure for what is plotted, its axes holding the family's members if one is held. */
  #figure(panel) {
    const figureOf = (answer) => explorable(panelFigure(panel.spec, answer, panel.overlays, this.texts),
      this.ghosts.traces(panel.id));
    const figure = figureOf(this.plotted);
    if (!this.family) return figure;
    if (this.#spansOf !== this.family) {
      this.#spans.clear();
      this.#spansOf = this.family;
    }
    if (!this.#spans.has(panel.id)) this.#spans.set(panel.id, familyExtents(this.family, figureOf));
    return withFamily(figure, this.#spans.get(panel.id));
  }

  #render(panel) {
    let { data, layout } = this.#figure(panel);
    if (!panel.captioned) {
      panel.caption.textContent = approximationErrors(panel.spec, this.table, this.texts)
        || harmonicClaim(panel.spec, this.table, this.texts);
    }
    panel.captioned = true;
    if (this.plotted !== this.table) {            // a preview
      if (moveCurves(panel.graph, data)) return Promise.resolve();
      if (!this.family) ({ layout } = roomy({ data, layout }));     // the family's ranges hold its own data too
    }
    return drawFigure(panel.graph, { data, layout }).then(() => {
      if (panel.hasCursor) panel.cursor.follow(panel.graph);
    });
  }
}
