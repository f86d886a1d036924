/**
 * A cursor line over a Plotly graph whose x axis is the crank angle in degrees, with the values at that
 * angle beside it. It is a positioned element moved with a CSS transform, so animation frames never ask
 * Plotly to lay out again; the plot area is measured from Plotly's layout after every (re)draw.
 * The graph and cursor.element share a positioned frame (.graph-frame).
 */
import { element } from "./dom.js";
import { degrees, setRichText } from "./notation.js";

export class PlotCursor {
  /** readout(phi): the text shown beside the line at crank angle phi (rad); phi: where the line starts. */
  constructor(readout, phi = 0) {
    this.readout = readout;
    this.text = element("span", { className: "cursor-readout" });
    this.element = element("div", { className: "cursor", hidden: true }, this.text);
    this.axis = null;
    this.graph = null;
    this.phi = phi;
  }

  /** Measure graph's plot area now and after each of its redraws; call once Plotly has drawn it. */
  follow(graph) {
    if (this.graph !== graph) {
      this.graph = graph;
      graph.on("plotly_afterplot", () => this.#measure());
    }
    this.#measure();
  }

  /** Put the line at crank angle phi (rad) and show the values there. */
  move(phi) {
    this.phi = phi;
    if (!this.axis) return;
    const { left, width, x0, x1 } = this.axis;
    const x = left + (degrees(phi) - x0) / (x1 - x0) * width;
    this.element.style.transform = `translateX(${x}px)`;
    this.element.style.visibility = x < left - 0.5 || x > left + width + 0.5 ? "hidden" : "";   // zoomed away
    this.text.classList.toggle("before", x > left + 0.6 * width);   // keep the values inside the plot
    setRichText(this.text, this.readout(phi));
  }

  #measure() {
    const layout = this.graph._fullLayout;
    const { l, t, w, h } = layout._size;
    const [x0, x1] = layout.xaxis.range;
    this.axis = { left: l, width: w, x0, x1 };
    Object.assign(this.element.style, { top: `${t}px`, height: `${h}px` });
    this.element.hidden = false;
    this.move(this.phi);
  }
}
