/**
 * A plot of the quantity the student picks against the crank angle φ (plotly, served by our server), with a
 * vertical line at the cursor angle.
 */
import { baseLayout, phiAxis, valueAxis, TRACE_COLORS } from "../../common/view/plot_style.js";
import { plotText, unitText } from "../../common/view/notation.js";

const DEG = 180 / Math.PI;

export class QuantityPlot {
  constructor(host, { t, lang }) {
    Object.assign(this, { host, t, lang });
  }

  draw(phi, quantity, cursor) {
    const { t, lang } = this;
    if (!window.Plotly || !quantity) {
      this.host.replaceChildren();
      return;
    }
    const x = phi.map((p) => p * DEG);
    const unit = unitText(quantity.unit, t);
    const title = `${plotText(quantity.label)}${quantity.unit === "1" ? "" : `, ${unit}`}`;
    const layout = { ...baseLayout({ lang }, 300), xaxis: phiAxis(2 * Math.PI, { t }), yaxis: valueAxis(title),
      showlegend: false,
      shapes: [{ type: "line", xref: "x", yref: "paper", x0: cursor * DEG, x1: cursor * DEG, y0: 0, y1: 1,
        line: { color: "#5d6978", width: 1, dash: "dot" } }] };
    const trace = { x, y: quantity.values, type: "scatter", mode: "lines", name: plotText(quantity.label),
      line: { color: TRACE_COLORS[0], width: 2 }, hovertemplate: "%{y}<extra></extra>" };
    window.Plotly.react(this.host, [trace], layout, { displaylogo: false, responsive: true,
      modeBarButtonsToRemove: ["lasso2d", "select2d"] });
  }
}
