/**
 * Redraws the plot panels that are out of date, those in (or near) the window first. An exact answer is
 * drawn one panel per animation frame, so a new answer never blocks the page for long, and then the panels
 * out of view, one per idle period, so that the whole page holds the answer (a page printed or captured
 * whole shows every plot). A preview (an answer interpolated from a family while a slider is dragged) is
 * drawn in one go, every stale panel in view within the same frame (drawNow); panels out of view wait
 * until they are scrolled into view or the next exact answer, so that nothing slows the drag.
 *
 * A panel is any object {figure, stale} whose figure is its element on the page; the scheduler keeps
 * panel.visible up to date and calls draw(panel) with panel.stale already cleared; draw returns a promise
 * that settles when the panel is drawn (Plotly.react's).
 */
const IDLE_MS = 50;     // where the browser has no requestIdleCallback: a panel out of view every 50 ms
/** Out of date, out of view, and not a figure the answer left out (hidden). */
const hiddenStale = (panel) => panel.stale && !panel.visible && !panel.figure.hidden;

export class PanelScheduler {
  #panels = [];
  #frameRequested = false;
  #waiting = [];       // resolvers of drawn(): told when no panel in view is stale
  #lastDraw = null;
  #previewing = false;
  #idleRequested = false;

  constructor(draw) {
    this.draw = draw;
    this.visibility = new IntersectionObserver((entries) => {
      for (const entry of entries) {
        const panel = this.#panels.find((p) => p.figure === entry.target);
        if (panel) panel.visible = entry.isIntersecting;
      }
      this.#drawSoon();
    }, { rootMargin: "100px" });
  }

  /** Watch these panels instead of the previous ones. */
  track(panels) {
    this.visibility.disconnect();
    this.#panels = panels;
    for (const panel of panels) {
      panel.visible = false;
      this.visibility.observe(panel.figure);
    }
  }

  /** An exact answer: draw the stale panels in view, one per animation frame from the next on, then the rest. */
  refresh() {
    this.#previewing = false;
    this.#drawSoon();
  }

  #drawSoon() {
    if (this.#frameRequested) return;
    this.#frameRequested = true;
    requestAnimationFrame(this.#drawNext);
  }

  /** Draw every stale panel in view now; resolves when they are all drawn. */
  drawNow() {
    this.#previewing = true;
    const due = this.#panels.filter((p) => p.stale && p.visible);
    for (const panel of due) panel.stale = false;
    return Promise.all(due.map((panel) => this.draw(panel)));
  }

  /** Resolves once no panel in view is stale and the last one drawn is on the page. */
  drawn() {
    return new Promise((resolve) => {
      this.#waiting.push(resolve);
      this.#drawSoon();
    });
  }

  #drawNext = () => {
    this.#frameRequested = false;
    const panel = this.#panels.find((p) => p.stale && p.visible);
    if (!panel) {
      const waiting = this.#waiting.splice(0);
      Promise.resolve(this.#lastDraw).catch(() => {}).then(() => waiting.forEach((resolve) => resolve()));
      this.#drawHiddenSoon();
      return;
    }
    panel.stale = false;
    this.#lastDraw = this.draw(panel);
    this.#drawSoon();
  };

  #drawHiddenSoon() {
    if (this.#idleRequested || this.#previewing || !this.#panels.some(hiddenStale)) return;
    this.#idleRequested = true;
    (window.requestIdleCallback ?? ((then) => setTimeout(then, IDLE_MS)))(this.#drawHidden);
  }

  /** One stale panel out of view, drawn in an idle period (after an exact answer, not during a preview). */
  #drawHidden = () => {
    this.#idleRequested = false;
    const panel = this.#previewing ? null : this.#panels.find(hiddenStale);
    if (!panel) return;
    panel.stale = false;
    Promise.resolve(this.draw(panel)).catch(() => {}).then(() => this.#drawHiddenSoon());
  };
}
