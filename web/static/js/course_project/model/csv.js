/**
 * A report table as a CSV file: its rows as the page shows them (the same columns, the numbers rounded to the
 * digits the page shows, angles in degrees), for a spreadsheet: in ru and uk a decimal comma with ";" between
 * cells, in en a decimal point with ","; every text cell quoted (RFC 4180: a quote inside doubled), the headers
 * and names as plain text (notation.js plainText: u₃₁, F_in4 → "Fin4"); UTF-8 with a byte-order mark, rows
 * ended by CRLF. No DOM.
 */
import { csvSeparators } from "../../common/view/export_csv.js";
import { plainText } from "../../common/view/notation.js";

export const SIGNIFICANT = 4;                    // digits of a number in the report's tables
export const ANGLE_DECIMALS = 1;                 // decimals of an angle in degrees

/** The number a cell shows, as a plain number: rounded as the page rounds it (angles in degrees). */
export function shownValue(value, kind) {
  if (value === null || value === undefined || !Number.isFinite(value)) return null;
  if (kind === "int") return value;
  if (kind === "angle") return Number((value * 180 / Math.PI).toFixed(ANGLE_DECIMALS));
  return Number(value.toPrecision(SIGNIFICANT));
}

const quoted = (text) => `"${String(text).replace(/"/g, "\"\"")}"`;

function csvCell(value, kind, decimal) {
  if (kind === "text") return value === null || value === undefined ? "" : quoted(plainText(String(value)));
  const shown = shownValue(value, kind);
  if (shown === null) return "";
  return String(shown).replace("e", "E").replace(".", decimal);
}

/** The CSV text of a table (model/report_tables.js) for the page's language. */
export function tableCsv(table, lang) {
  const { decimal, delimiter } = csvSeparators(lang === "en" ? "point" : "comma");
  const lines = [table.columns.map((c) => quoted(plainText(c.header))).join(delimiter)];
  for (const row of table.rows) {
    lines.push(row.cells.map((value, k) => csvCell(value, table.columns[k].kind, decimal)).join(delimiter));
  }
  return `\uFEFF${lines.join("\r\n")}\r\n`;
}
