/**
 * Redraws the plot panels that are out of date, one per animation frame, and only those in (or near)
 * the window; a panel scrolled into view later is drawn then. A slider drag therefore never blocks the
 * page for long and redraws only what is seen.
 *
 * A panel is any object {figure, stale} whose figure is its element on the page; the scheduler keeps
 * panel.visible up to date and calls draw(panel) with panel.stale already cleared.
 */
export class PanelScheduler {
  #panels = [];
  #frameRequested = false;

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

  /** Draw the stale panels that are in view, from the next animation frame on. */
  refresh() {
    if (this.#frameRequested) return;
    this.#frameRequested = true;
    requestAnimationFrame(this.#drawNext);
  }

  #drawNext = () => {
    this.#frameRequested = false;
    const panel = this.#panels.find((p) => p.stale && p.visible);
    if (!panel) return;
    panel.stale = false;
    this.draw(panel);
    this.refresh();
  };
}
