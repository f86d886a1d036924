/**
 * The panels of a dynamics scene that are read rather than plotted, as HTML built from an answer:
 *   figures   labelled numbers (M_c0 in both conventions, the friction angle, ω_mean, δ, η, works)
 *   table     rows from a list in the answer (the successive approximations of the friction forces),
 *             with whether the series converges, its ratio and its limit; a column with `words` shows
 *             the interface text words + value instead of the value ("method_" + "merzalov" → "Мерцалов")
 *   numerics  how each result was computed: method and why it was chosen, stiffness ratio, tolerance,
 *             steps (and rejected ones), evaluations of the right-hand side and the Jacobian, LU
 *             decompositions, cycles and Newton iterations, run time, error estimate, energy residual,
 *             and the solver's message — error beside time
 * A number the answer leaves null (M_c0 of a self-locking mechanism) reads "—". Labels, headings and the
 * server's sentences are rich text (subscripts as <sub>, notation.js).
 */
import { pathValue } from "../../common/model/dotted_paths.js";
import { element } from "../../common/view/dom.js";
import { degrees, formatNumber, formatQuantity, plainText, unitText } from "../../common/view/notation.js";

const MISSING = "—";
const TABLE_DIGITS = 5;

/** Headings of the computations a numerics panel may show, by their path in the answer. */
/** Rows of a numerics panel: the key in the answer's numerics, its label, how its value reads. */
const NUMERICS_ROWS = [
  ["method", "numerics_method", (v) => v],
  ["why", "numerics_why", (v) => v],
  ["stiffness_ratio", "numerics_stiffness_ratio", (v, lang) => formatQuantity(v, lang, 3)],
  ["rtol", "numerics_rtol", (v, lang) => formatQuantity(v, lang, 2)],
  ["steps", "numerics_steps", (v, lang) => formatNumber(v, lang, 0)],
  ["rejected", "numerics_rejected", (v, lang) => formatNumber(v, lang, 0)],
  ["nfev", "numerics_nfev", (v, lang) => formatNumber(v, lang, 0)],
  ["njev", "numerics_njev", (v, lang) => formatNumber(v, lang, 0)],
  ["nlu", "numerics_nlu", (v, lang) => formatNumber(v, lang, 0)],
  ["cycles", "numerics_cycles", (v, lang) => formatNumber(v, lang, 0)],
  ["iterations", "numerics_iterations", (v, lang) => formatNumber(v, lang, 0)],
  ["converged", "numerics_converged", (v, lang, t) => t[v ? "numerics_yes" : "numerics_no"]],
  ["runtime_ms", "numerics_runtime", (v, lang, t) => `${formatQuantity(v, lang, 3)} ${unitText("ms", t)}`],
  ["error_estimate", "numerics_error", (v, lang) => formatQuantity(v, lang, 2)],
  ["energy_residual", "numerics_energy", (v, lang) => formatQuantity(v, lang, 2)],
  ["message", "numerics_message", (v) => v],
];

const absent = (value) => value === undefined || value === null || value === "";

/**
 * One labelled number: item.digits significant digits (0: a count, shown whole), times item.scale
 * (100 for %); unit "deg" turns radians into degrees.
 */
function quantity(value, item, { t, lang }) {
  if (value === null) return MISSING;
  const scaled = value * (item.scale ?? 1);
  const shown = item.unit === "deg" ? degrees(scaled) : scaled;
  const number = item.digits ? formatQuantity(shown, lang, item.digits) : formatNumber(shown, lang, 0);
  if (item.unit === "deg") return `${number}°`;
  return item.unit ? `${number} ${unitText(item.unit, t)}` : number;
}

/** A cell of a table: numbers with TABLE_DIGITS digits, words as they are (or as the column's `words` name them). */
function cell(value, lang, column = {}, t = {}) {
  if (absent(value)) return MISSING;
  if (column.words !== undefined) return t[`${column.words}${value}`] ?? String(value);   // "" : the value is the key
  return typeof value === "number" ? formatQuantity(value, lang, TABLE_DIGITS) : String(value);
}

/** True if the answer holds something for a figures, table or numerics panel. */
export function holdsReadings(panel, data) {
  if (panel.kind === "figures") return panel.items.some((item) => pathValue(data, item.path) !== undefined);
  if (panel.kind === "table") return Array.isArray(pathValue(data, panel.path));
  return panel.paths.some((path) => pathValue(data, path));
}

/** The content of a figures, table or numerics panel for the answer's data. */
export function readings(panel, data, texts) {
  if (panel.kind === "figures") return figuresList(panel, data, texts);
  if (panel.kind === "table") return rowsTable(panel, data, texts);
  return numericsTable(panel, data, texts);
}

function figuresList(panel, data, texts) {
  const items = panel.items.filter((item) => pathValue(data, item.path) !== undefined);
  return [element("dl", { className: "figures-list" }, ...items.flatMap((item) => [
    element("dt", { rich: item.label[texts.lang] }),
    element("dd", { textContent: quantity(pathValue(data, item.path), item, texts) })]))];
}

function rowsTable(panel, data, texts) {
  const rows = pathValue(data, panel.path);
  const columns = panel.columns.filter((column) => rows.some((row) => column.key in row));
  const table = element("table", { className: "rows" },
    element("thead", {}, element("tr", {}, ...columns.map((column) =>
      element("th", { scope: "col", rich: column.label[texts.lang] })))),
    element("tbody", {}, ...rows.map((row) => element("tr", {}, ...columns.map((column) =>
      element("td", { rich: cell(row[column.key], texts.lang, column, texts.t) }))))));
  const series = pathValue(data, panel.path.split(".").slice(0, -1).join("."));
  const summary = series && "converged" in series ? [seriesSummary(series, columns, texts)] : [];
  const note = panel.note ? [element("p", { className: "note", rich: panel.note[texts.lang] })] : [];
  return [...summary, scrollingFrame(table, panel, texts), ...note];
}

/**
 * A table in a box that scrolls (both ways) instead of widening the page on a phone; focusable, so the
 * keyboard scrolls it too, and named by its panel's title for screen readers.
 */
function scrollingFrame(table, panel, { lang }) {
  return element("div", { className: "table-frame", tabIndex: 0, role: "region",
    "aria-label": plainText(panel.title?.[lang] ?? "") }, table);
}

/**
 * "φ = 30,0° · знаменатель ряда 0,0225 < 1 · ряд сходится · предел: R₂₃ = 1,023", or that it diverges
 * (the mechanism self-locks at this angle), for a list of successive approximations; approximations
 * that are not a series (no ratio: the bearings' stiffness) say only whether they converged.
 */
function seriesSummary(series, columns, { t, lang }) {
  const parts = [];
  if (typeof series.phi === "number") parts.push(`φ = ${formatNumber(degrees(series.phi), lang, 1)}°`);
  const ratio = `${t.series_ratio} ${formatQuantity(series.ratio, lang, 3)}`;
  if (typeof series.ratio !== "number") {
    parts.push(series.converged ? t.approximations_converged : t.approximations_stopped);
  } else if (series.converged) {
    parts.push(`${ratio} < 1`, t.series_converges);
    const limit = Object.entries(series.limit ?? {}).map(([key, value]) =>
      `${columns.find((c) => c.key === key)?.label[lang] ?? key} = ${cell(value, lang)}`);
    if (limit.length) parts.push(`${t.series_limit}: ${limit.join(", ")}`);
  } else {
    parts.push(`${ratio} ≥ 1`, t.series_diverges);
  }
  return element("p", { className: `series-summary ${series.converged ? "converges" : "diverges"}`,
    rich: parts.join(" · ") });
}

function numericsTable(panel, data, texts) {
  const { t, lang } = texts;
  const runs = panel.paths.filter((path) => pathValue(data, path)).map((path) => [path, pathValue(data, path)]);
  const rows = NUMERICS_ROWS.filter(([key]) => runs.some(([, numerics]) => !absent(numerics[key])));
  const column = (path) => panel.columns[panel.paths.indexOf(path)][lang];     // the scene names each computation
  const head = runs.length > 1 ? [element("thead", {}, element("tr", {}, element("td"),
    ...runs.map(([path]) => element("th", { scope: "col", rich: column(path) }))))] : [];
  return [scrollingFrame(element("table", { className: "numerics" }, ...head,
    element("tbody", {}, ...rows.map(([key, label, text]) => element("tr", { className: `numerics-${key}` },
      element("th", { scope: "row", rich: t[label] }),
      ...runs.map(([, numerics]) => element("td", {
        rich: absent(numerics[key]) ? MISSING : text(numerics[key], lang, t) })))))), panel, texts)];
}
