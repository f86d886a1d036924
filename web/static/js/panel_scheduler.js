/**
 * Redraws the plot panels that are out of date, and only those in (or near) the window; a panel scrolled
 * into view later is drawn then. An exact answer is drawn one panel per animation frame, so a new answer
 * never blocks the page for long; a preview (an answer interpolated from a family while a slider is
 * dragged) is drawn in one go, every stale panel in view within the same frame (drawNow).
 *
 * A panel is any object {figure, stale} whose figure is its element on the page; the scheduler keeps
 * panel.visible up to date and calls draw(panel) with panel.stale already cleared; draw returns a promise
 * that settles when the panel is drawn (Plotly.react's).
 */
export class PanelScheduler {
  #panels = [];
  #frameRequested = false;
  #waiting = [];       // resolvers of drawn(): told when no panel in view is stale
  #lastDraw = null;

  constructor(draw) {
    this.draw = draw;
    this.visibility = new IntersectionObserver((entries) => {
      for (const entry of entries) {
        const panel = this.#panels.find((p) => p.figure === entry.target);
        if (panel) panel.visible = entry.isIntersecting;
      }
      this.refresh();
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

  /** Draw the stale panels that are in view, one per animation frame from the next on. */
  refresh() {
    if (this.#frameRequested) return;
    this.#frameRequested = true;
    requestAnimationFrame(this.#drawNext);
  }

  /** Draw every stale panel in view now; resolves when they are all drawn. */
  drawNow() {
    const due = this.#panels.filter((p) => p.stale && p.visible);
    for (const panel of due) panel.stale = false;
    return Promise.all(due.map((panel) => this.draw(panel)));
  }

  /** Resolves once no panel in view is stale and the last one drawn is on the page. */
  drawn() {
    return new Promise((resolve) => {
      this.#waiting.push(resolve);
      this.refresh();
    });
  }

  #drawNext = () => {
    this.#frameRequested = false;
    const panel = this.#panels.find((p) => p.stale && p.visible);
    if (!panel) {
      const waiting = this.#waiting.splice(0);
      Promise.resolve(this.#lastDraw).catch(() => {}).then(() => waiting.forEach((resolve) => resolve()));
      return;
    }
    panel.stale = false;
    this.#lastDraw = this.draw(panel);
    this.refresh();
  };
}
