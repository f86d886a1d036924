/**
 * What every Plotly graph of a scene offers the reader besides its curves ("Explore"): hover
 * readouts in the textbook's notation with units, zoom and pan, and the pinned ("ghost") curves under the
 * current ones. One function applied to each figure before Plotly draws it, so the figure builders
 * (figures.js, dynamics_figures.js) stay about the physics.
 *
 * Hover: a graph against the crank angle or the time shows one box ("x unified") titled with the abscissa
 * in notation and unit ("φ = 123,5°", "t = 0,25 с") and a line per curve, "u₃₁ = 0,0866 м", the unit read
 * from the curve's axis title ("u₃₁, u′₃₁, м"; "Δω, рад/с; ε, рад/с²" gives each curve its own part, in
 * order). Plotly writes the numbers through the axis' hoverformat: the language's decimal separator and a
 * true minus sign, as the ticks.
 *
 * Zoom and pan: Plotly's own (drag a box to zoom, double-click to go back), with our toolbar instead of its
 * modebar (plot_tools.js: the modebar's tooltips are English only and its buttons are not reachable from
 * the keyboard). On a touch screen the plot does not take a drag until the reader picks zoom or pan, so a
 * finger on a plot still scrolls the page. A zoom survives new answers (uirevision) until it is reset.
 */

const SUFFIX = "%{y}<extra></extra>";
const X_FORMATS = { "°": ".1f" };      // the crank angle to a tenth of a degree, as the animation's readout
const coarse = () => window.matchMedia?.("(pointer: coarse)").matches ?? false;

/** Plotly's pseudo-HTML ("M<sub>с0</sub>, Н·м") as the text it shows, for comparisons. */
const shownText = (html) => String(html ?? "").replace(/<[^>]+>/g, "");

/**
 * The unit of a curve from its axis title: "u₃₁, u′₃₁, м" → "м"; "рад; рад/с" → the index-th part; a part
 * without a comma is a unit ("Н·м") unless it names a quantity (a subscript, or the curve's own symbol: "ζ").
 */
export function unitFromTitle(title, index, label) {
  const parts = String(title ?? "").split("; ");
  const part = parts.length > 1 ? parts[Math.min(index, parts.length - 1)] : parts[0];
  const comma = part.lastIndexOf(", ");
  if (comma >= 0) return part.slice(comma + 2);
  const named = part.includes("<sub>") || part.includes("_") || shownText(part)[0] === shownText(label)[0];
  return named || !part ? "" : part;
}

/**
 * An axis title's quantity and unit: "Угол кривошипа φ, °" → ["φ", "°"] (words naming a symbol: the symbol),
 * "t, с" → ["t", "с"], "X от ВМТ, м" → ["X от ВМТ", "м"], "φ<sub>д</sub> − φ₁, рад" → the whole difference.
 */
function symbolAndUnit(title) {
  const text = String(title ?? "");
  const comma = text.lastIndexOf(", ");
  if (comma < 0) return [text, ""];
  const quantity = text.slice(0, comma);
  const [, words, symbol] = /^([\p{L}\s]+)\s(\S+)$/u.exec(quantity) ?? [];
  const named = words && shownText(symbol).length <= 2 && /\p{Ll}{3}/u.test(words);
  return [named ? symbol : quantity, text.slice(comma + 2)];
}

const axisKeys = (layout) => Object.keys(layout).filter((key) => /^[xy]axis\d*$/.test(key));
const titleOf = (axis) => axis?.title?.text ?? "";
const spaced = (unit) => (!unit ? "" : unit === "°" ? "°" : ` ${unit}`);

/** The curve's hover line with its unit: "u₃₁ = %{y}" → "u₃₁ = %{y} м". */
function withUnit(trace, layout, index) {
  if (typeof trace.hovertemplate !== "string" || !trace.hovertemplate.endsWith(SUFFIX)) return trace;
  const axis = layout[trace.yaxis && trace.yaxis !== "y" ? `yaxis${trace.yaxis.slice(1)}` : "yaxis"];
  const unit = unitFromTitle(titleOf(axis), index, trace.name);
  const head = trace.hovertemplate.slice(0, -SUFFIX.length);
  if (layout.hovermode === "closest") {
    const [xName, xUnit] = symbolAndUnit(titleOf(layout.xaxis));
    const [yName, yUnit] = symbolAndUnit(titleOf(axis));
    return { ...trace, hovertemplate: `${xName} = %{x}${spaced(xUnit)}<br>${yName} = %{y}${spaced(yUnit)}<extra></extra>` };
  }
  return { ...trace, hovertemplate: `${head}%{y}${spaced(unit)}<extra></extra>` };
}

/**
 * The figure as drawn: ghosts (faded traces, plotted first so that they lie under the curves) added, every
 * axis zoomable, the hover readouts with units. The axes' ranges as built are kept in layout.meta.ranges for
 * the toolbar's "reset zoom".
 */
export function explorable({ data, layout }, ghosts = []) {
  const drawn = { ...layout, uirevision: "explore", dragmode: coarse() ? false : "zoom",
    showlegend: Boolean(layout.showlegend) || ghosts.length > 0 };
  const ranges = {};
  for (const key of axisKeys(layout)) {
    drawn[key] = { ...layout[key], fixedrange: false };
    ranges[key] = layout[key].autorange === false && layout[key].range ? [...layout[key].range] : null;
  }
  drawn.meta = { ...(layout.meta ?? {}), ranges };
  const cartesian = data.every((trace) => trace.type === "scatter" || trace.type === "bar");
  if (cartesian && layout.hovermode === "x") {
    drawn.hovermode = "x unified";
    const [name, unit] = symbolAndUnit(titleOf(layout.xaxis));
    const x = `%{x:${X_FORMATS[unit] ?? ".4~g"}}`;      // the title's own format: it is not the axis'
    const title = unit ? `${name} = ${x}${spaced(unit)}` : `${titleOf(layout.xaxis)}: ${x}`;
    drawn.xaxis = { ...drawn.xaxis, unifiedhovertitle: { text: title }, hoverformat: drawn.xaxis.hoverformat ?? ".4g" };
  }
  const counts = new Map();
  const traces = data.map((trace) => {
    const axis = trace.yaxis ?? "y";
    const index = counts.get(axis) ?? 0;
    if (trace.hoverinfo !== "skip") counts.set(axis, index + 1);
    const named = trace.name || !ghosts.length ? trace : { ...trace, showlegend: false };   // a legend for the ghosts only
    return withUnit(named, drawn, index);
  });
  return { data: [...ghosts, ...traces], layout: drawn };
}

/** Plotly.relayout's argument that puts the graph's axes back to the ranges it was built with. */
export function resetZoom(graph) {
  const ranges = graph.layout?.meta?.ranges ?? {};
  const update = {};
  for (const [key, range] of Object.entries(ranges)) {
    if (range) update[`${key}.range`] = range;
    else update[`${key}.autorange`] = true;
  }
  if (graph.layout?.polar) update["polar.radialaxis.autorange"] = true;
  return update;
}
