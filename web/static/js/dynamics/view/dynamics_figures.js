/**
 * Plotly figures of a dynamics scene's panels, built from an answer of /reduction or /motion; no DOM.
 *   plot   series against x: the crank angle in degrees (x_unit "deg", x in rad) or the time in s;
 *          a scalar series (style "hline", e.g. the mean M_c0) is a dashed level line labelled with its value;
 *          a series with axis 2 is read on a right-hand axis (panel.y2_title), as is the second of two series
 *          whose y_title gives one unit each ("рад; рад/с"); a fast oscillating curve is drawn thin and solid
 *          (dashed it reads as a hatch); a series with `gaps` (a path) has
 *          gaps where the answer's values there are null (ζ where the compliance is infinite); x_unit ""
 *          plots against another series (a phase portrait of the twist), and the nearest point is read;
 *          `series_each: {path, label}` adds one series per key of the answer's object at path (the reactions
 *          of a general mechanism by pair, "magnitudes": {R12, R23, …}), labelled by the template (one for
 *          every language, or {ru, uk, en}) with {key} written as a symbol with its subscript (R12 → R₁₂);
 *          with `words: {word: {ru, uk, en}}` a key that is a word, or whose space-separated words are, is
 *          said in the reader's language word by word ("link 3" → "звено 3", "force E/ram" → "сила E/ram");
 *          style "markers" draws the defined points alone (an operating point on a characteristic)
 *   polar  the phase portrait ω(φ): radius r against angle θ (rad, drawn in degrees), so the start-up
 *          winds round and round onto the closed steady cycle (style "bold"); panel.r_title names the
 *          radius and its unit ("ω, рад/с") on the radial axis and in the hover, theta_symbol the angle
 *          (φ unless named: β around a joint)
 * Every text goes to Plotly through plotText (subscripts as <sub>), every hovered number through the axis'
 * hoverformat, so Plotly writes it with the language's decimal separator and a true minus sign.
 * Series the answer does not hold (no textbook approximation, no steady cycle) are left out; null
 * values (undefined points, e.g. where the mechanism self-locks) are gaps in the curves.
 */
import { pathValue } from "../../common/model/dotted_paths.js";
import { degrees, formatQuantity, plotText } from "../../common/view/notation.js";
import {
  baseLayout, GRID, LEVEL_COLOR, LEVEL_DASH, phiAxis, TRACE_COLORS as COLORS, traceDashes, valueAxis,
} from "../../common/view/plot_style.js";

const DASHES = { solid: "solid", dotted: "dot", dashed: "dash" };
const STARTUP_COLOR = COLORS[2];
const RADIAL_TICKS = 5;      // the most tick labels along a polar plot's radius (Plotly picks a round step)

/** True where the answer holds a value, or a curve with at least one defined point, at path. */
export function holds(data, path) {
  const value = pathValue(data, path);
  if (Array.isArray(value)) return value.some((v) => v !== null);
  return value !== undefined && value !== null;
}

/** A series keeps its colour whatever other series the answer leaves out (link 3 is green in every variant). */
function seriesColor(panel, series) {
  const index = panel.series.indexOf(series);
  return COLORS[(index >= 0 ? index : panel.series.length + series.each) % COLORS.length];
}

/** "R12" → "R_{12}", "R05" → "R_{05}": a key of the answer as notation markup. */
const keySymbol = (key) => key.replace(/^([^\d]+)(\d+)$/, "$1_{$2}");

const LANGUAGES = ["ru", "uk", "en"];

/** A key of the answer as said in lang: the key itself, or its words in series_each.words, or a symbol. */
function keyText(key, words, lang) {
  if (words?.[key]) return words[key][lang];
  const parts = key.split(" ");
  if (!words || !parts.some((part) => words[part])) return keySymbol(key);
  return parts.map((part) => words[part]?.[lang] ?? part).join(" ");
}

/** The panel's series with those its series_each makes from the answer's keys. */
function panelSeries(panel, data) {
  const each = panel.series_each;
  const object = each ? pathValue(data, each.path) : null;
  if (!object || typeof object !== "object") return panel.series;
  const template = (lang) => (typeof each.label === "string" ? each.label : each.label[lang]);
  const made = Object.keys(object).map((key, i) => {
    const label = Object.fromEntries(LANGUAGES.map((lang) =>
      [lang, template(lang).replaceAll("{key}", keyText(key, each.words, lang))]));
    return { y: `${each.path}.${key}`, each: i, label };
  });
  return [...panel.series, ...made];
}

const toDegrees = (values) => values.map((v) => (v === null ? null : degrees(v)));

/** The series of a plot panel that the answer holds. */
export function heldSeries(panel, data) {
  return panelSeries(panel, data).filter((series) => holds(data, series.y));
}

/** The series of a polar panel that the answer holds. */
export function heldCurves(panel, data) {
  return panel.series.filter((series) => holds(data, series.theta) && holds(data, series.r));
}

const UNITS_APART = /\s*;\s*/;     // a y_title "рад; рад/с": one unit per series
const FAST_TURNS = 30;             // a curve turning more often than this across the plot is a fast oscillation

/**
 * The panel with each series on its own axis when its y_title lists one unit per series ("рад; рад/с", two
 * series and no right-hand axis of their own): the first on the left, the second on the right, each axis
 * titled by its series' symbol and unit; otherwise the panel itself.
 */
function unitsApart(panel, held, lang) {
  const units = panel.y_title[lang].split(UNITS_APART);
  if (units.length !== 2 || held.length !== 2 || panel.y2_title || held.some((series) => series.axis)) return panel;
  const title = (series, unit) => Object.fromEntries(LANGUAGES.map((l) =>
    [l, `${series.label[l]}, ${panel.y_title[l].split(UNITS_APART)[held.indexOf(series)] ?? unit}`]));
  const series = [held[0], { ...held[1], axis: 2 }];
  return { ...panel, series, y_title: title(held[0], units[0]), y2_title: title(held[1], units[1]) };
}

/** How many times a curve turns (its slope changes sign): a measure of how fast it oscillates. */
function turns(values) {
  let count = 0;
  let last = 0;
  for (let i = 1; i < values.length; i += 1) {
    const step = Math.sign((values[i] ?? 0) - (values[i - 1] ?? 0));
    if (step && last && step !== last) count += 1;
    if (step) last = step;
  }
  return count;
}

/**
 * The dashes of the held series: as asked, the others told apart by traceDashes; a fast oscillating curve
 * (more than FAST_TURNS turns) asked for no dash is drawn solid, a dash on it would read as a hatch.
 */
function seriesDashes(held, data) {
  const asked = held.map((series) => (series.style === "hline" ? LEVEL_DASH : DASHES[series.style] ?? null));
  const dashes = traceDashes(asked);
  const counts = held.map((series, i) => (asked[i] === null && Array.isArray(pathValue(data, series.y))
    ? turns(pathValue(data, series.y)) : -1));
  const fast = counts.indexOf(Math.max(...counts));
  const solid = dashes.indexOf("solid");
  if (counts[fast] > FAST_TURNS && solid >= 0 && solid !== fast && asked[solid] === null) {
    [dashes[solid], dashes[fast]] = [dashes[fast], dashes[solid]];
  }
  return { dashes, fast: counts[fast] > FAST_TURNS ? fast : -1 };
}

/** Plotly figure {data, layout} of a plot panel (content/scenes "panels" entry) for the answer's data. */
export function plotFigure(shownPanel, data, texts) {
  const { lang } = texts;
  const panel = unitsApart(shownPanel, heldSeries(shownPanel, data), lang);
  const xValues = pathValue(data, panel.x);
  const inDegrees = panel.x_unit === "deg";
  const x = inDegrees ? toDegrees(xValues) : xValues;
  const ends = [x[0], x[x.length - 1]];
  const held = panel === shownPanel ? heldSeries(panel, data) : panel.series;
  const { dashes, fast } = seriesDashes(held, data);
  const traces = held.map((series, i) => {
    const label = plotText(series.label[lang]);
    const y = pathValue(data, series.y);
    if (series.style === "hline") {
      const name = `${label} = ${formatQuantity(y, lang, 4)}`;
      return { type: "scatter", mode: "lines", x: ends, y: [y, y], name, hoverinfo: "skip",
        line: { color: LEVEL_COLOR, width: 1.5, dash: dashes[i] } };
    }
    const gaps = series.gaps ? pathValue(data, series.gaps) : null;
    return { type: "scatter", mode: series.style === "markers" ? "markers" : "lines",
      x, y: gaps ? y.map((v, i) => (gaps[i] === null ? null : v)) : y,
      name: label, connectgaps: false, yaxis: series.axis === 2 ? "y2" : "y", marker: { size: 10 },
      line: { color: seriesColor(panel, series), width: i === fast ? 1.2 : 2, dash: dashes[i] },
      hovertemplate: `${label} = %{y}<extra></extra>` };
  });
  const layout = {
    ...baseLayout(texts, 300), showlegend: traces.length > 1,
    xaxis: inDegrees ? phiAxis(xValues[xValues.length - 1], texts) : timeAxis(panel, texts),
    yaxis: valueAxis(plotText(panel.y_title[lang])),
  };
  if (panel.x_unit === "") layout.hovermode = "closest";
  if (traces.some((trace) => trace.yaxis === "y2")) {
    layout.yaxis2 = valueAxis(plotText(panel.y2_title[lang]), {
      overlaying: "y", side: "right", showgrid: false, zeroline: false, tickmode: "auto" });
    layout.margin = { ...layout.margin, r: 64 };
  }
  return { data: traces, layout };
}

function timeAxis(panel, { lang }) {
  return { title: { text: plotText(panel.x_title[lang]) }, fixedrange: true, ticks: "outside", gridcolor: GRID,
    zeroline: false, rangemode: "tozero", hoverformat: ".4g" };
}

/** Plotly figure {data, layout} of a polar panel (the phase portrait) for the answer's data. */
export function polarFigure(panel, data, texts) {
  const { lang } = texts;
  const radius = plotText(panel.r_title[lang]);
  const angle = panel.theta_symbol ?? "φ";
  const [quantity, unit] = panel.r_title[lang].split(/, (?=[^,]+$)/).map(plotText);
  const curves = heldCurves(panel, data);
  const dashes = traceDashes(curves.map((series) => (series.style === "bold" ? "solid" : null)));
  const traces = curves.map((series, i) => {
    const label = plotText(series.label[lang]);
    const bold = series.style === "bold";
    return { type: "scatterpolar", mode: "lines", name: label,
      theta: toDegrees(pathValue(data, series.theta)), r: pathValue(data, series.r), connectgaps: false,
      line: bold ? { color: COLORS[0], width: 3.5, dash: dashes[i] } : { color: STARTUP_COLOR, width: 1.2, dash: dashes[i] },
      hovertemplate: `${label}: ${quantity} = %{r} ${unit}, ${angle} = %{theta}°<extra></extra>` };
  });
  return {
    data: traces,
    layout: {
      ...baseLayout(texts, 440), hovermode: "closest", showlegend: true, margin: { l: 40, r: 40, t: 40, b: 30 },
      polar: {
        bgcolor: "#ffffff",
        angularaxis: { direction: "counterclockwise", rotation: 0, dtick: 45, ticksuffix: "°", gridcolor: GRID,
          hoverformat: ".1f" },
        // autorange said: under the graph's uirevision Plotly kept an earlier answer's radial range (curves clipped)
        // the radial axis along 0°, its tick labels above it and its title above them: Plotly sets the title off
        // by the axis layer's height, which is the axis's own length for an upright axis (title over the ticks),
        // and below a level axis it leaves the title's box 3 px into the labels' (above it, 2 px clear);
        // at most RADIAL_TICKS ticks: the labels lie side by side along the radius, whose length on a phone
        // (some 150 px) left Plotly's own choice of eight 3-digit labels running together ("100120140")
        radialaxis: { autorange: true, rangemode: "tozero", angle: 0, tickangle: 0, side: "counterclockwise", gridcolor: GRID,
          nticks: RADIAL_TICKS, exponentformat: "power", hoverformat: ".4g", title: { text: radius } },
      },
    },
  };
}
