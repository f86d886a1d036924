/**
 * A study's figure on the measurements page as the server hands it over (data-figure, server/api/bench_pages.py
 * study_figure): the points of the study's own table, every word and written number already in the reader's
 * language; no DOM. Each trace is one method: name, ours (the app's own method), x the run times (ms) and y
 * the errors of its rows (null: a cell that is no finite number), hover each row's tolerance, error and run
 * time as the table writes them. x_title and y_title name the axes.
 */

/** The figure read from its JSON text; an error naming the method whose columns differ in length. */
export function studyFigure(text) {
  const figure = JSON.parse(text);
  for (const trace of figure.traces) {
    if (trace.x.length !== trace.y.length || trace.x.length !== trace.hover.length) {
      throw new Error(`measurements figure: the points of ${trace.name} differ in number`);
    }
  }
  return figure;
}
