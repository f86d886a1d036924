/**
 * The scene's toolbar (scene.html #scene-tools): copy the link of the whole state, reset to the
 * variant's defaults, pin the curves as ghosts and clear them, print the report, and the CSV files' decimal
 * separator. The buttons are in the page's template (translated there); this wires them to the model, the
 * ghosts and the views. graphs() gives the plots drawn now (Map panel id → Plotly graph element).
 */
import { printReport } from "./print_report.js";
import { copyLink } from "./share_link.js";

export function sceneTools(model, ghosts, graphs, { t, lang }) {
  const byId = (id) => document.getElementById(id);
  const clear = byId("clear-pinned");
  const showPinned = () => {
    if (clear) clear.disabled = ghosts.count === 0;
  };
  byId("copy-link").addEventListener("click", () =>
    copyLink(model, lang, { field: byId("share-link"), status: byId("share-status"), t }));
  byId("reset-scene").addEventListener("click", () => model.reset());
  byId("pin-curves")?.addEventListener("click", () => ghosts.pin(graphs()));
  clear?.addEventListener("click", () => ghosts.clear());
  byId("print-report").addEventListener("click", printReport);
  ghosts.on("change", showPinned);
  showPinned();
}
