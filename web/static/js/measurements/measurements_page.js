/**
 * The measurements page (/measurements): each study's figure drawn into its graph from the data the server
 * put there (data-figure). A drawn graph is marked data-drawn.
 */
import { drawFigure } from "../common/view/plot_style.js";
import { studyFigure } from "./model/study_figure.js";
import { studyPlot } from "./view/study_plot.js";

const lang = document.documentElement.lang;

for (const graph of document.querySelectorAll(".measurements [data-figure]")) {
  drawFigure(graph, studyPlot(studyFigure(graph.dataset.figure), lang)).then(() => { graph.dataset.drawn = ""; });
}
