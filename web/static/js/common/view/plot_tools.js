/**
 * The small toolbar on every plot: zoom back, pan or zoom by dragging, and the plot taken away
 * as PNG, SVG (Plotly.toImage, drawn by the page itself, nothing fetched) or CSV (export_csv.js). Buttons
 * with words in the reader's language, reachable from the keyboard; Plotly's modebar stays off.
 *
 * The image is the graph as shown (pinned curves included) on a white page with the panel's title above it;
 * the CSV holds the plotted data only. The decimal separator of the CSV is the page's choice (the select
 * #csv-decimal of the scene's toolbar; a comma in ru and uk, a point in en by default).
 */
import { element } from "./dom.js";
import { csvText, plotColumns } from "./export_csv.js";
import { plotText } from "./notation.js";
import { resetZoom } from "./plot_explore.js";

const IMAGE_SCALE = 2;       // PNG pixels per CSS pixel: sharp in a printed lab report

/** The reader's decimal separator for CSV files: "comma" or "point". */
export function csvDecimal(lang) {
  const choice = document.getElementById("csv-decimal")?.value;
  return choice || (lang === "en" ? "point" : "comma");
}

function save(href, fileName) {
  const link = element("a", { href, download: fileName, hidden: true });
  document.body.append(link);
  link.click();
  link.remove();
}

/** The graph drawn again on a white page with its title, as a data URL of format "png" or "svg". */
function image(graph, title, format) {
  const { width, height } = graph._fullLayout;
  const layout = { ...graph.layout, paper_bgcolor: "#ffffff", title: { text: plotText(title), x: 0.01, xanchor: "left" },
    margin: { ...graph.layout.margin, t: Math.max(graph.layout.margin?.t ?? 0, 64) }, height: height + 34, width };
  return Plotly.toImage({ data: graph.data, layout, config: { staticPlot: true } },
    { format, width, height: height + 34, scale: format === "png" ? IMAGE_SCALE : 1 });
}

/**
 * A toolbar for graph (a Plotly graph's element): name is the file name without extension ("flywheel-speed"),
 * title the panel's title (interface text with notation markup).
 */
export function plotToolbar(graph, { name, title }, { t, lang }) {
  const button = (text, label, action, extra = {}) => {
    const node = element("button", { type: "button", className: "plot-tool", textContent: text,
      title: label, "aria-label": label, ...extra });
    node.addEventListener("click", () => action(node));
    return node;
  };
  // the accessible name starts with the visible word (WCAG 2.5.3, label in name), then says what it does
  const pan = button(t.plot_pan, `${t.plot_pan}: ${t.plot_pan_title}`, (node) => {
    const on = node.getAttribute("aria-pressed") !== "true";
    node.setAttribute("aria-pressed", String(on));
    Plotly.relayout(graph, { dragmode: on ? "pan" : "zoom" });
  }, { "aria-pressed": "false" });
  return element("div", { className: "plot-tools", role: "group", "aria-label": t.plot_tools },
    button("⟲", t.plot_zoom_reset, () => Plotly.relayout(graph, resetZoom(graph))),
    pan,
    button("PNG", t.export_png, () => image(graph, title, "png").then((url) => save(url, `${name}.png`))),
    button("SVG", t.export_svg, () => image(graph, title, "svg").then((url) => save(url, `${name}.svg`))),
    button("CSV", t.export_csv, () => {
      const blob = new Blob([csvText(plotColumns(graph), csvDecimal(lang))], { type: "text/csv;charset=utf-8" });
      const url = URL.createObjectURL(blob);
      save(url, `${name}.csv`);
      setTimeout(() => URL.revokeObjectURL(url), 1000);
    }));
}
