/**
 * Panel view of the live work–precision study (model: work_precision_study.js, figure:
 * work_precision_figure.js). It needs nothing from the scene's answer: a button runs the study for the
 * request body of the current values (the body the scene's own request sends), never a slider move, as
 * it takes seconds of server time. The chart then shows error against run time per method, and below it
 * the quantity compared, the reference, the runs that did not finish within the time budget and the
 * panel's note with a link to the full tables (the measurements page, /measurements). Once a value
 * changes, the chart is greyed and said to belong to the earlier values until the study runs again; a
 * refused study says why.
 */
import { drawFigure } from "../../common/view/plot_style.js";
import { element } from "../../common/view/dom.js";
import { refusalMessage } from "../../common/view/messages.js";
import { richText } from "../../common/view/notation.js";
import { plottedRows, workPrecisionFigure } from "./work_precision_figure.js";
import { WorkPrecisionStudy } from "../model/work_precision_study.js";


export class WorkPrecisionView {
  constructor(body, spec, { t, lang }, model) {
    this.t = t;
    this.lang = lang;
    this.model = model;
    this.study = new WorkPrecisionStudy(spec.endpoint, lang);
    this.button = element("button", { type: "button", className: "study-run", textContent: t.study_run });
    this.button.addEventListener("click", () => this.study.run(model.request()));
    this.state = element("p", { className: "study-state", role: "status" });
    this.graph = element("div", { className: "graph", hidden: true });
    this.details = element("div", { className: "study-details" });
    this.result = element("div", { className: "study-result" }, this.graph, this.details);
    const note = spec.note ? [element("p", { className: "note", rich: spec.note[lang] }),
      element("p", { className: "note study-tables" },
        element("a", { href: `/measurements?lang=${lang}`, textContent: t.study_full_tables }))] : [];
    body.append(element("div", { className: "study-bar" }, this.button, this.state), this.result, ...note);
    this.study.on("running", () => this.#mark());
    this.study.on("result", (answer) => this.#show(answer));
  }

  /** A value changed: the study shown, if any, now belongs to the earlier values. */
  paramsChanged() {
    this.#mark();
  }

  /** The button and the sentence beside it: running, results of earlier values, or nothing to say. */
  #mark() {
    const { running } = this.study;
    const earlier = !running && this.study.answersEarlier(this.model.request());
    this.button.disabled = running;
    this.result.classList.toggle("running", running);
    this.result.classList.toggle("earlier", earlier);
    this.state.classList.toggle("earlier", earlier);
    this.state.textContent = running ? this.t.study_running : earlier ? this.t.study_earlier : "";
  }

  #show(answer) {
    const { t } = this;
    if (!answer.ok) {
      this.graph.hidden = true;
      Plotly.purge(this.graph);
      this.details.replaceChildren(refusalMessage(t.study_refused, answer.error, t));
    } else {
      const { study, warnings } = answer.data;
      this.graph.hidden = plottedRows(study.rows).length === 0;
      if (this.graph.hidden) Plotly.purge(this.graph);
      else {
        const figure = workPrecisionFigure(study.rows, { t, lang: this.lang });
        drawFigure(this.graph, figure);
      }
      this.details.replaceChildren(...this.#details(study, warnings));
    }
    this.#mark();
  }

  /** What the chart compares and against what, the runs left out, and the answer's warnings. */
  #details(study, warnings) {
    const { t } = this;
    const line = (label, text, className) => element("p", { className },
      element("span", { className: "study-label", textContent: `${label}: ` }), richText(text));
    const lines = study.reference === null ? [element("p", { className: "study-no-reference", textContent: t.study_no_reference })]
      : [element("p", { className: "study-reading", textContent: t.study_reading }),
        line(t.study_quantity, study.quantity, "study-quantity"),
        line(t.study_reference, study.reference, "study-reference")];
    if (study.skipped.length) lines.push(line(t.study_skipped, study.skipped.join("; "), "study-skipped"));
    if (warnings.length) lines.push(element("ul", { className: "study-warnings" },
      ...warnings.map((warning) => element("li", { rich: warning }))));
    return lines;
  }
}
