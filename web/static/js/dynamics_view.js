/**
 * The panels of a dynamics scene's variant, in the variant's order, and above them what the answer says
 * in words. Plot and polar panels are Plotly graphs redrawn by a PanelScheduler (one per animation
 * frame, only those in view); figures, tables and numerics are HTML, rebuilt with every answer.
 *
 * A panel the answer holds nothing for is hidden: when the machine stalls or self-locks, or has no
 * steady cycle, the answer leaves those results out and its warnings say why — they are shown first,
 * under a heading that says there is no steady motion. A refused request (HTTP 422) says why instead.
 */
import { element } from "./dom.js";
import { heldCurves, heldSeries, holds, plotFigure, polarFigure } from "./dynamics_figures.js";
import { refusalMessage } from "./messages.js";
import { PanelScheduler } from "./panel_scheduler.js";
import { holdsReadings, readings } from "./readings_view.js";

const PLOTLY_CONFIG = { displayModeBar: false, responsive: true };
const GRAPH_KINDS = ["plot", "polar"];
const READING_KINDS = ["figures", "table", "numerics"];

/** True if the answer's data holds what the panel shows. */
function holdsPanel(panel, data) {
  if (panel.kind === "plot") return holds(data, panel.x) && heldSeries(panel, data).length > 0;
  if (panel.kind === "polar") return heldCurves(panel, data).length > 0;
  return holdsReadings(panel, data);
}

export class DynamicsView {
  constructor(container, notices, { scene, t, lang }) {
    this.container = container;
    this.notices = notices;
    this.scene = scene;
    this.texts = { t, lang };
    this.panels = [];
    this.scheduler = new PanelScheduler((panel) => this.#draw(panel));
  }

  /** One panel per graph or reading of the variant, hidden until an answer fills it. */
  build(variant) {
    for (const panel of this.panels) if (panel.graph) Plotly.purge(panel.graph);
    this.panels = variant.panels.map((id) => [id, this.scene.panels[id]])
      .filter(([, spec]) => [...GRAPH_KINDS, ...READING_KINDS].includes(spec.kind))
      .map(([id, spec]) => this.#panel(id, spec));
    this.container.replaceChildren(...this.panels.map((panel) => panel.figure));
    this.notices.replaceChildren();
    this.scheduler.track(this.panels.filter((panel) => panel.graph));
  }

  /** Show the answer: the panels it holds data for, its warnings; or why the request was refused. */
  show(answer) {
    const { t } = this.texts;
    const data = answer.ok ? answer.data : null;
    const missing = [];
    for (const panel of this.panels) {
      const held = Boolean(data) && holdsPanel(panel.spec, data);
      panel.figure.hidden = !held;
      if (data && !held) missing.push(panel);
      if (!held) continue;
      if (panel.graph) panel.stale = true;
      else panel.body.replaceChildren(...readings(panel.spec, data, this.texts));
    }
    if (!answer.ok) {
      this.notices.replaceChildren(refusalMessage(t.computation_refused, answer.error, t));
    } else if (data.warnings.length) {
      const noMotion = missing.length > 0;
      this.notices.replaceChildren(element("section", { className: noMotion ? "warnings no-motion" : "warnings" },
        element("h2", { textContent: noMotion ? t.no_motion : t.warnings }),
        element("ul", {}, ...data.warnings.map((warning) => element("li", { textContent: warning })))));
    } else {
      this.notices.replaceChildren();
    }
    this.data = data;
    this.scheduler.refresh();
  }

  #panel(id, spec) {
    const graphic = GRAPH_KINDS.includes(spec.kind);
    const content = element("div", { className: graphic ? "graph" : `readings ${spec.kind}-readings` });
    const figure = element("figure", { className: `panel panel-${spec.kind}`, id: `panel-${id}`, hidden: true },
      ...(spec.title ? [element("h3", { textContent: spec.title[this.texts.lang] })] : []), content);
    return graphic ? { id, spec, figure, graph: content, stale: false } : { id, spec, figure, body: content };
  }

  #draw(panel) {
    if (!this.data) return;
    const figure = panel.spec.kind === "polar" ? polarFigure(panel.spec, this.data, this.texts)
      : plotFigure(panel.spec, this.data, this.texts);
    Plotly.react(panel.graph, figure.data, figure.layout, PLOTLY_CONFIG);
  }
}
