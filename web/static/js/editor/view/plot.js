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

  /** Against φ (rad, drawn in degrees), or against the input slider's s (m) when `slider`. */
  draw(phi, quantity, cursor, slider = false) {
    const { t, lang } = this;
    if (!window.Plotly || !quantity) {
      this.host.replaceChildren();
      return;
    }
    const x = slider ? phi : phi.map((p) => p * DEG);
    const at = slider ? cursor : cursor * DEG;
    const unit = unitText(quantity.unit, t);
    const title = `${plotText(quantity.label)}${quantity.unit === "1" ? "" : `, ${unit}`}`;
    const layout = { ...baseLayout({ lang }, 300), xaxis: slider ? valueAxis(`s, ${unitText("m", t)}`) : phiAxis(2 * Math.PI, { t }), yaxis: valueAxis(title),
      showlegend: false,
      shapes: [{ type: "line", xref: "x", yref: "paper", x0: at, x1: at, y0: 0, y1: 1,
        line: { color: "#5d6978", width: 1, dash: "dot" } }] };
    const trace = { x, y: quantity.values, type: "scatter", mode: "lines", name: plotText(quantity.label),
      line: { color: TRACE_COLORS[0], width: 2 }, hovertemplate: "%{y}<extra></extra>" };
    window.Plotly.react(this.host, [trace], layout, { displaylogo: false, responsive: true,
      modeBarButtonsToRemove: ["lasso2d", "select2d"] });
  }
}
