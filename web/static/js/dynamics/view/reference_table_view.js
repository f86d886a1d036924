/**
 * Panel view of a reference table of the sources (content/tables/<name>.json's "reference", written into the
 * panel by the server): its columns and rows, a range column ([low, high]) as "low … high" in the page's
 * number format, texts in the page's language, the note under it. It needs nothing from the answer.
 */
import { element } from "../../common/view/dom.js";
import { formatQuantity, plainText } from "../../common/view/notation.js";

const cellText = (value, column, lang) => {
  if (column.range && Array.isArray(value)) return value.map((v) => formatQuantity(v, lang, 3)).join(" … ");
  if (value && typeof value === "object") return value[lang] ?? "";
  return typeof value === "number" ? formatQuantity(value, lang, 3) : String(value ?? "");
};

export class ReferenceTableView {
  constructor(body, spec, { lang }) {
    const columns = spec.columns ?? [];
    const table = element("table", { className: "rows reference-table" },
      element("thead", {}, element("tr", {}, ...columns.map((column) =>
        element("th", { scope: "col", rich: column.label[lang] })))),
      element("tbody", {}, ...(spec.rows ?? []).map((row) => element("tr", {}, ...columns.map((column) =>
        element("td", { rich: cellText(row[column.key], column, lang) }))))));
    const note = spec.note ? [element("p", { className: "note", rich: spec.note[lang] })] : [];
    body.append(element("div", { className: "table-frame", tabIndex: 0, role: "region",
      "aria-label": plainText(spec.title?.[lang] ?? "") }, table), ...note);
  }
}
