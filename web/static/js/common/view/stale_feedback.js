/**
 * Immediate feedback: a computation that takes longer than DELAY shows a progress bar and dims
 * what is on the screen (class "stale": the old curves and drawing stay, visibly old, never silently so)
 * until the answer arrives. Shorter ones change nothing, so a quick answer does not flicker. The bar is
 * fixed at the top of the window, so it is seen wherever the page is scrolled (a phone shows one column).
 */
import { element } from "./dom.js";

const DELAY = 300;     // ms

export class StaleFeedback {
  /** containers: the elements whose content goes stale (plots, drawing); label: the progress bar's words. */
  constructor(containers, label) {
    this.containers = containers;
    this.timer = null;
    this.bar = element("div", { className: "progress", role: "progressbar", "aria-label": label, hidden: true },
      element("span", { className: "progress-text", textContent: label }));
    document.body.append(this.bar);
  }

  /** A request started (true) or the last one ended (false): ApiClient's onBusy. */
  busy(on) {
    clearTimeout(this.timer);
    this.timer = on ? setTimeout(() => this.#mark(true), DELAY) : null;
    if (!on) this.#mark(false);
  }

  #mark(stale) {
    for (const container of this.containers) {
      container.classList.toggle("stale", stale);
      container.setAttribute("aria-busy", String(stale));
    }
    this.bar.hidden = !stale;
  }
}
