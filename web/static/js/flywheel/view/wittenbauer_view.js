/**
 * Panel view of Wittenbauer's energy–mass diagram (wittenbauer_figure.js): the Plotly graph, a point that
 * runs round the closed curve with the crank angle of the animation, and below it where the tangents
 * meet and what the segment ab gives: I_I = ab/(ω²_mean [δ]), Wittenbauer's flywheel inertia.
 * The point is a positioned element moved with a CSS transform, placed through Plotly's axis maps
 * measured after every redraw, so animation frames never ask Plotly to lay out again. While the reader holds a
 * slider whose family is here (useFamily), the axes hold the diagram of every member, so that a preview only
 * moves the curves.
 */
import { drawFigure } from "../../common/view/plot_style.js";
import { pathValue } from "../../common/model/dotted_paths.js";
import { element } from "../../common/view/dom.js";
import { degrees, formatNumber, formatQuantity, setRichText, unitText } from "../../common/view/notation.js";
import { sampleAt } from "../../common/model/phi_samples.js";
import { familyExtents, moveCurves, withFamily } from "../../common/view/family_plot.js";
import { energyMass, originInView, wittenbauerFigure } from "./wittenbauer_figure.js";


export class WittenbauerView {
  constructor(body, spec, { t, lang }) {
    this.spec = spec;
    this.t = t;
    this.lang = lang;
    this.graph = element("div", { className: "graph" });
    this.point = element("div", { className: "energy-mass-point", hidden: true });
    this.readout = element("p", { className: "point-readout" });
    this.caption = element("p", { className: "caption" });
    body.append(element("div", { className: "graph-frame" }, this.graph, this.point), this.readout, this.caption);
    this.maps = null;
    this.listening = false;
    this.phi = 0;
    this.family = null;
    this.spans = null;        // the family's extents in the diagram (familyExtents)
  }

  /** The family of the slider the reader holds (or null): the next drawing's axes hold its members. */
  useFamily(family) {
    if (family === this.family) return;
    this.family = family;
    this.spans = null;
    if (this.data && this.drawn === this.diagram) this.show(this.data);
  }

  /** The diagram's figure for data, its axes holding the family's members if one is held. */
  #figure(data) {
    const figureOf = (answer) => wittenbauerFigure(this.spec, answer, { t: this.t, lang: this.lang });
    const figure = figureOf(data);
    if (!this.family) return figure;
    this.spans ??= familyExtents({ answers: this.family.answers.filter((a) => a && this.holds(a)) }, figureOf);
    return withFamily(figure, this.spans);
  }

  holds(data) {
    const curve = pathValue(data, this.spec.x);
    return Array.isArray(curve) && curve.length > 1 && Boolean(pathValue(data, this.spec.diagram));
  }

  show(data) {
    this.data = data;
    this.diagram = energyMass(this.spec, data);
    this.drawn = this.diagram;
    const figure = this.#figure(data);
    setRichText(this.caption, this.#caption(data));
    drawFigure(this.graph, figure).then(() => {
      if (!this.listening) {
        this.listening = true;
        this.graph.on("plotly_afterplot", () => this.#measure());
      }
      this.#measure();
    });
  }

  /**
   * Draw a preview's diagram (an answer interpolated from a slider's family): curve, tangents and points
   * moved in place where they fit the drawn axes, else laid out again; the caption and the readout keep the
   * numbers of the last answer shown.
   */
  preview(data) {
    this.drawn = energyMass(this.spec, data);
    const figure = this.#figure(data);
    if (moveCurves(this.graph, figure.data)) {
      this.drawAt(this.phi);
      return Promise.resolve();
    }
    return drawFigure(this.graph, figure);    // afterplot places the point
  }

  /** Put the point at the drawn curve's place for crank angle phi (rad); the readout from the answer shown. */
  drawAt(phi) {
    this.phi = phi;
    if (!this.maps || !this.data) return;
    const at = (diagram) => [sampleAt(this.data.phi, diagram.x, phi), sampleAt(this.data.phi, diagram.y, phi)];
    const [px, py] = at(this.drawn);
    const [x, y] = at(this.diagram);
    this.point.hidden = [x, y, px, py].includes(null);
    if (this.point.hidden) return;
    this.point.style.transform = `translate(${this.maps.x(px)}px, ${this.maps.y(py)}px)`;
    const energy = unitText("J", this.t);
    setRichText(this.readout, `φ = ${formatNumber(degrees(phi), this.lang, 1)}°: ${this.t.symbol_inertia_group_II} = `
      + `${formatQuantity(x, this.lang, 3)} ${unitText("kg·m²", this.t)}, A_Σ = ${formatQuantity(y, this.lang, 3)} ${energy}`);
  }

  /** Pixel maps of both axes inside the graph frame, from Plotly's laid-out axes. */
  #measure() {
    const { xaxis, yaxis, _size: size } = this.graph._fullLayout;
    this.maps = { x: (v) => size.l + xaxis.l2p(v), y: (v) => size.t + yaxis.l2p(v) };
    this.drawAt(this.phi);
  }

  /** "Касательные пересекаются в O′ (…) · ab = 1145 Дж · I_I = ab/(ω_ср²[δ]) = 41,26 кг·м²" (markup, notation.js). */
  #caption(data) {
    const { t, lang } = this;
    const { origin_inertia: ox, origin_energy: oy, b_up: up, b_low: low } = this.diagram.diagram;
    const inertia = unitText("kg·m²", t);
    const energy = unitText("J", t);
    const parts = [`${t.wittenbauer_origin} O′: ${t.symbol_inertia_group_II} = ${formatQuantity(ox, lang, 4)} ${inertia}, `
      + `A_Σ = ${formatQuantity(oy, lang, 4)} ${energy}${originInView(this.diagram) ? "" : ` (${t.wittenbauer_off_plot})`}`,
    `ab = ${formatQuantity(up - low, lang, 4)} ${energy}`];
    const wittenbauer = (data.methods ?? []).find((m) => m.method === "wittenbauer");
    if (wittenbauer) parts.push(`${t.symbol_inertia_group_I} = ab/(${t.symbol_mean_speed}²·[δ]) = ${formatQuantity(wittenbauer.inertia, lang, 4)} ${inertia}`);
    return parts.join(" · ");
  }
}
