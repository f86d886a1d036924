/**
 * The scene's parameters as a sheet at the bottom of a phone's or tablet's screen (app.css, "Phones and
 * tablets"): the controls are wrapped with a title bar that folds and unfolds them (aria-expanded). The
 * sheet is fixed only on narrow screens; there the page keeps room below its end for it, --sheet-height,
 * measured whenever the sheet changes size. On wide screens the wrapper is a plain column and the bar is
 * not shown.
 */
import { element } from "./dom.js";

/** Wrap controls (the #controls section) in the sheet; title: what the bar says ("Parameters"). */
export function controlsSheet(controls, title) {
  const toggle = element("button", {
    type: "button", className: "sheet-toggle", textContent: title, "aria-expanded": "true",
    "aria-controls": controls.id });
  const sheet = element("div", { className: "controls-sheet" });
  controls.before(sheet);
  sheet.append(toggle, controls);
  toggle.addEventListener("click", () => {
    const folded = sheet.classList.toggle("folded");
    toggle.setAttribute("aria-expanded", String(!folded));
  });
  const measure = () => {
    const fixed = getComputedStyle(sheet).position === "fixed";
    document.documentElement.style.setProperty("--sheet-height", `${fixed ? sheet.offsetHeight : 0}px`);
  };
  new ResizeObserver(measure).observe(sheet);
  return sheet;
}
