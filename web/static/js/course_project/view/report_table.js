/**
 * A report table (model/report_tables.js) as HTML: its caption, the column headers with real subscripts, each
 * cell written in the page's language (4 significant digits, a decimal comma in ru/uk, a true minus, powers of
 * ten written out; angles in degrees; "—" where the answer has no value), the chosen position's row marked, and
 * a button that downloads the same rows as CSV (model/csv.js). Also the download of any text as a file.
 */
import { element } from "../../common/view/dom.js";
import { formatNumber, formatQuantity } from "../../common/view/notation.js";
import { ANGLE_DECIMALS, SIGNIFICANT, tableCsv } from "../model/csv.js";

const NONE = "—";

/** A cell's text as the page writes it. */
export function cellText(value, kind, lang) {
  if (kind === "text") return value ?? NONE;
  if (value === null || value === undefined || !Number.isFinite(value)) return NONE;
  if (kind === "int") return String(value);
  if (kind === "angle") return formatNumber(value * 180 / Math.PI, lang, ANGLE_DECIMALS);
  return formatQuantity(value, lang, SIGNIFICANT);
}

/** Offer text as a file named name (type: its MIME type). */
export function download(name, text, type) {
  const link = element("a", { href: URL.createObjectURL(new Blob([text], { type })), download: name });
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
}

/** The table's element: tools (CSV), the scrolling frame and the table itself (id: the table's id). */
export function renderTable(table, { t, lang }) {
  const button = element("button", { type: "button", className: "csv-download", "data-table": table.id,
    textContent: t.project_csv, title: t.project_csv_title });
  button.addEventListener("click", () => download(`${table.id}.csv`, tableCsv(table, lang), "text/csv;charset=utf-8"));
  const head = element("tr", {}, ...table.columns.map((c) => element("th", { scope: "col", rich: c.header })));
  const rows = table.rows.map((row) => element("tr", row.chosen ? { className: "chosen" } : {},
    ...row.cells.map((value, k) => {
      const kind = table.columns[k].kind;
      const text = cellText(value, kind, lang);
      return kind === "text" ? element("td", { className: "text", rich: text }) : element("td", { textContent: text });
    })));
  return element("div", { className: "report-table-block" },
    element("div", { className: "report-tools" }, button),
    element("div", { className: "table-scroll" }, element("table", { className: "report-table", id: table.id },
      element("caption", { rich: table.caption }), element("thead", {}, head), element("tbody", {}, ...rows))));
}
