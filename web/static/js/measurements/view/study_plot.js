/**
 * A study's work–precision figure (model/study_figure.js) as a Plotly figure; no DOM. Run time (ms) along x
 * and error along y, both logarithmic, so lower left is better; one line with markers per method through
 * its tolerances in the table's order, the app's own method drawn bold as on the scenes' live studies
 * (dynamics/view/work_precision_figure.js). Nothing is computed here: names, titles and hover texts come
 * written from the server, the axes' numbers are written by Plotly with the language's separators.
 */
import { baseLayout, LEVEL_COLOR, TRACE_COLORS, traceDashes, valueAxis } from "../../common/view/plot_style.js";

const OURS_COLOR = TRACE_COLORS[1];
const COLORS = [TRACE_COLORS[0], TRACE_COLORS[3], TRACE_COLORS[2], TRACE_COLORS[4], LEVEL_COLOR];   // 3:1 and more
const SYMBOLS = ["circle", "square", "diamond", "triangle-up", "cross", "x", "star", "hexagon"];
const HEIGHT = 480;
const LINE = 30;       // characters: a longer legend name is written on several lines (a phone shows it whole)

/** A method's name as the legend writes it: a long one broken before its parenthesis and after its commas. */
function legendName(name) {
  return name.length > LINE ? name.replace(" (", "<br>(").replaceAll(", ", ",<br>") : name;
}

/** Plotly figure {data, layout} of a study's figure in lang. */
export function studyPlot({ traces, x_title: xTitle, y_title: yTitle }, lang) {
  const dashes = traceDashes(traces.map((trace) => (trace.ours ? "solid" : null)));   // told apart without colours
  let others = 0;
  const data = traces.map((trace, i) => {
    const color = trace.ours ? OURS_COLOR : COLORS[others++ % COLORS.length];
    return {
      type: "scatter", mode: "lines+markers", name: trace.ours ? `<b>${legendName(trace.name)}</b>` : legendName(trace.name),
      x: trace.x, y: trace.y, text: trace.hover, hovertemplate: `${trace.name}<br>%{text}<extra></extra>`,     // the name on one line
      line: { color, width: trace.ours ? 4 : 1.6, dash: dashes[i] },
      marker: { color, size: trace.ours ? 10 : 7, symbol: SYMBOLS[i % SYMBOLS.length] },
    };
  });
  return {
    data,
    layout: {
      ...baseLayout({ lang }, HEIGHT), hovermode: "closest", showlegend: true,
      xaxis: valueAxis(xTitle, { type: "log" }), yaxis: valueAxis(yTitle, { type: "log" }),
    },
  };
}
