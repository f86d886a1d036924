/**
 * The scene as a printed report: print.css lays the page out as a report; the plots are first
 * drawn again at the printed page's width (class "printing": the plot column as wide as A4 between its
 * margins), so that no plot is cut at the page's edge, and put back after the print dialog closes.
 */
const graphs = () => [...document.querySelectorAll(".js-plotly-plot")];
const resize = () => Promise.all(graphs().map((graph) => Plotly.Plots.resize(graph)));

export async function printReport() {
  document.body.classList.add("printing");
  if (window.Plotly) await resize();
  window.print();
  document.body.classList.remove("printing");
  if (window.Plotly) await resize();
}
