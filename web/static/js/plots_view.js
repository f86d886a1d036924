/**
 * The plot panels of the variant: one Plotly graph per panel, its title, caption (largest error of an
 * approximation) and note. A cursor line over each φ-plot follows the animation; it is a positioned
 * element moved with a CSS transform, so animation frames never ask Plotly to lay out again.
 * Plots are redrawn by a PanelScheduler: one per animation frame, only those in view.
 */
import { element } from "./dom.js";
import { approximationErrors, exactOutputs, panelFigure } from "./figures.js";
import { geometryMessage } from "./messages.js";
import { degrees, formatNumber, symbol } from "./notation.js";
import { PanelScheduler } from "./panel_scheduler.js";
import { valueAt } from "./positions_table.js";

const PLOTLY_CONFIG = { displayModeBar: false, responsive: true };

export class PlotsView {
  constructor(container, { scene, t, lang }) {
    this.container = container;
    this.scene = scene;
    this.texts = { t, lang };
    this.panels = [];
    this.phi = 0;
    this.scheduler = new PanelScheduler((panel) => this.#render(panel));
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
    for (const panel of this.panels) {
      panel.figure.hidden = !answer.ok;
      panel.overlays = overlays;
      panel.stale = answer.ok;
    }
    this.scheduler.refresh();
  }

  /** Move the cursors to crank angle phi (rad) and show the values there. */
  moveCursor(phi) {
    this.phi = phi;
    for (const panel of this.panels) {
      if (!panel.axis || !this.table) continue;
      const { left, width, x0, x1 } = panel.axis;
      const x = left + (degrees(phi) - x0) / (x1 - x0) * width;
      panel.cursor.style.transform = `translateX(${x}px)`;
      panel.readout.classList.toggle("before", x > left + 0.6 * width);   // keep the values inside the plot
      panel.readout.textContent = exactOutputs(panel.spec).map((name) => {
        const value = valueAt(this.table, this.table.outputs[name], phi);
        return `${symbol(name)} = ${value === null ? "—" : formatNumber(value, this.texts.lang)}`;
      }).join("  ");
    }
  }

  #panel(id, spec) {
    const graph = element("div", { className: "graph" });
    const readout = element("span", { className: "cursor-readout" });
    const cursor = element("div", { className: "cursor", hidden: true }, readout);
    const caption = element("p", { className: "caption" });
    const figure = element("figure", { className: "panel", id: `panel-${id}` },
      element("h3", { textContent: spec.title[this.texts.lang] }),
      element("div", { className: "graph-frame" }, graph, cursor), caption,
      ...(spec.note ? [element("p", { className: "note", textContent: spec.note[this.texts.lang] })] : []));
    return { id, spec, graph, cursor, readout, caption, figure, stale: false, axis: null,
      hasCursor: !spec.outputs.includes("harmonics") };
  }

  #render(panel) {
    const { data, layout } = panelFigure(panel.spec, this.table, panel.overlays, this.texts);
    panel.caption.textContent = approximationErrors(panel.spec, this.table, this.texts);
    Plotly.react(panel.graph, data, layout, PLOTLY_CONFIG).then(() => {
      if (!panel.hasCursor || panel.listening) return;
      panel.listening = true;
      panel.graph.on("plotly_afterplot", () => this.#measure(panel));
      this.#measure(panel);
    });
  }

  /** Plot area in pixels and the φ range, from Plotly's computed layout (after every (re)draw). */
  #measure(panel) {
    const layout = panel.graph._fullLayout;
    const { l, t, w, h } = layout._size;
    const [x0, x1] = layout.xaxis.range;
    panel.axis = { left: l, width: w, x0, x1 };
    Object.assign(panel.cursor.style, { top: `${t}px`, height: `${h}px` });
    panel.cursor.hidden = false;
    this.moveCursor(this.phi);
  }
}
