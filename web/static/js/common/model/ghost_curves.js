/**
 * Pinned runs ("compare runs", PhET's ghosts): the curves of every plot as they are now, kept
 * faded under the curves of later values until cleared. They live in the page only: nothing is asked of
 * the server, and a reload forgets them. Keyed by panel id, so a pinned u₃₁ stays under u₃₁ when the
 * mechanism changes; a panel pinned with nothing drawn has no ghosts.
 *
 * Events: "change" (pinned or cleared).
 */
import { Emitter } from "./emitter.js";

const OPACITY = 0.3;
const KEPT = ["type", "mode", "x", "y", "theta", "r", "xaxis", "yaxis", "subplot", "connectgaps"];

export class GhostCurves extends Emitter {
  #pinned = new Map();      // panel id → faded copies of its traces

  /** label: the legend's name of the pinned curves ("закреплено"). */
  constructor(label) {
    super();
    this.label = label;
  }

  get count() {
    return this.#pinned.size;
  }

  /** Pin the curves now drawn in graphs (Map panel id → Plotly graph element); earlier pins are replaced. */
  pin(graphs) {
    this.#pinned.clear();
    for (const [id, graph] of graphs) {
      const traces = (graph.data ?? []).filter((trace) => !trace.meta?.ghost && trace.hoverinfo !== "skip");
      if (traces.length) this.#pinned.set(id, traces.map((trace, i) => this.#ghost(trace, i === 0)));
    }
    this.emit("change");
  }

  clear() {
    if (!this.#pinned.size) return;
    this.#pinned.clear();
    this.emit("change");
  }

  /** The ghost traces of panel id ([] if none). */
  traces(id) {
    return this.#pinned.get(id) ?? [];
  }

  #ghost(trace, first) {
    const ghost = Object.fromEntries(KEPT.filter((key) => trace[key] !== undefined).map((key) => [key, trace[key]]));
    const color = trace.line?.color ?? trace.marker?.color;
    return { ...ghost, name: this.label, legendgroup: "pinned", showlegend: first, hoverinfo: "skip",
      opacity: OPACITY, meta: { ghost: true },
      ...(trace.type === "bar" ? { marker: { color } }
        : { line: { color, width: Math.max(1.5, (trace.line?.width ?? 2)), dash: trace.line?.dash } }) };
  }
}
