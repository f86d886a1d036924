/**
 * A plot's data as CSV ("Take the results away"), read from the Plotly graph as drawn, so the
 * file holds exactly the plotted numbers (as sent by the server, every digit) — pinned ghost curves and
 * level lines (their value is in the legend) left out. No DOM beyond the graph's data.
 *
 * Columns: the abscissa (its axis title, "Угол кривошипа φ, °"), then one per curve in the textbook's
 * notation with its unit ("u₃₁, м", "u₃₁ (λ = 3), м"), as plain text (notation.js plainText: subscript
 * digits as glyphs, letters as they are). Curves on another abscissa grid get an abscissa column of their
 * own; a polar curve gives its angle and its radius. Empty cells where a curve has no value (a singular
 * position) or no row. UTF-8 with a byte-order mark (spreadsheets then read the Cyrillic right); the
 * decimal separator is the reader's choice: a comma with ";" between cells, or a point with ",".
 * The abscissa (φ, °; t, s; a polar curve's angle) is written to ABSCISSA_DIGITS significant digits: the
 * server sends angles in radians to 7, and the degrees a plot derives from them carry that rounding
 * ("0,9999998556178845" for 1°), which one digit fewer absorbs.
 */
import { plainText } from "./notation.js";

export const ABSCISSA_DIGITS = 6;

/** An abscissa value to ABSCISSA_DIGITS significant digits (not a number: as it is). */
export function abscissa(value) {
  return typeof value === "number" && Number.isFinite(value) ? Number(value.toPrecision(ABSCISSA_DIGITS)) : value;
}

const ENTITIES = { "&amp;": "&", "&lt;": "<", "&gt;": ">", "&quot;": "\"", "&#39;": "'" };

/** Plotly's pseudo-HTML ("M<sub>с0</sub>") as plain text in the app's notation ("Mс₀"); a superscript of
 * letters keeps its caret, which no glyph can stand for ("M<sub>д</sub><sup>пр</sup>" → "Mд^пр", not "Mдпр"). */
export function plotPlain(html) {
  const markup = String(html ?? "")
    .replace(/<sub>(.*?)<\/sub>/g, "_{$1}")
    .replace(/<sup>(.*?)<\/sup>/g, (whole, run) => (/^[\d+\-−=()/]*$/.test(run) ? `^{${run}}` : `\\^${run}`))
    .replace(/<br\s*\/?>/g, " ").replace(/<[^>]+>/g, "")
    .replace(/&(amp|lt|gt|quot|#39);/g, (entity) => ENTITIES[entity]);
  return plainText(markup).trim();
}

/** "u₃₁ = %{y} м<extra></extra>" → ["u₃₁", "м"]: the curve's name and unit as the hover writes them. */
function hoverNameAndUnit(trace) {
  const match = /^(.*) = %\{y\}(?: ([^<]*))?<extra><\/extra>$/s.exec(trace.hovertemplate ?? "");
  if (!match) return [trace.name ?? "", ""];
  return [match[1].replace(/%\{x\}/g, "k").replace(/^.*<br>/, ""), match[2] ?? ""];
}

const header = (name, unit) => plotPlain(unit ? `${name}, ${unit}` : name);
const sameValues = (a, b) => a === b || (a.length === b.length && a.every((v, i) => v === b[i]));

/** The columns {header, values} of a drawn graph (graph.data and graph.layout as Plotly holds them). */
export function plotColumns(graph) {
  const { data, layout } = graph;
  const groups = [];      // {x, header, columns}: curves sharing one abscissa grid
  for (const trace of data) {
    if (trace.meta?.ghost || trace.hoverinfo === "skip" || trace.visible === false) continue;
    if (trace.type === "scatterpolar") {
      const [angle] = /, (\S+) = %\{theta\}/.exec(trace.hovertemplate ?? "")?.slice(1) ?? ["θ"];
      const radius = layout.polar?.radialaxis?.title?.text ?? "r";
      groups.push({ polar: true, x: trace.theta, header: plotPlain(`${angle} (${trace.name}), °`),
        columns: [{ header: plotPlain(`${trace.name}: ${radius}`), values: trace.r }] });
      continue;
    }
    const [name, unit] = hoverNameAndUnit(trace);
    const column = { header: header(name, unit), values: trace.y };
    const group = groups.find((g) => !g.polar && sameValues(g.x, trace.x));
    if (group) group.columns.push(column);
    else groups.push({ x: trace.x, header: plotPlain(layout.xaxis?.title?.text ?? "x"), columns: [column] });
  }
  return groups.flatMap((g) => [{ header: g.header, values: Array.from(g.x, abscissa) }, ...g.columns]);
}

/** The separators of a CSV file: "comma" → decimal comma, cells split by ";"; "point" → decimal point, ",". */
export function csvSeparators(decimal) {
  return decimal === "comma" ? { decimal: ",", delimiter: ";" } : { decimal: ".", delimiter: "," };
}

function cell(value, { decimal, delimiter }) {
  if (value === null || value === undefined || (typeof value === "number" && !Number.isFinite(value))) return "";
  if (typeof value === "number") return String(value).replace(".", decimal);
  const text = String(value);
  return /["\r\n]/.test(text) || text.includes(delimiter) ? `"${text.replace(/"/g, "\"\"")}"` : text;
}

/** CSV text (with its byte-order mark) of the columns, rows ended by CRLF as RFC 4180 has them. */
export function csvText(columns, decimal) {
  const separators = csvSeparators(decimal);
  const rows = Math.max(0, ...columns.map((c) => c.values.length));
  const lines = [columns.map((c) => cell(c.header, separators)).join(separators.delimiter)];
  for (let i = 0; i < rows; i++) lines.push(columns.map((c) => cell(c.values[i], separators)).join(separators.delimiter));
  return `\uFEFF${lines.join("\r\n")}\r\n`;
}
