/**
 * Panel view of the efficiency-chain calculator (model: efficiency_chain.js): a row per mechanism with
 * its η_k and A_P,k, buttons to add and remove mechanisms, and η of the chain in series (3.39) and in
 * parallel (3.40), with (3.40) as printed (the sum of the η_k) beside it. It needs nothing from the scene's answer: its own client asks /efficiency-chain
 * whenever a valid value changes. The fields are text read by decimal_input.js, so "0,9" is 0.9 on a
 * Russian page whatever the browser's locale (an <input type="number"> would follow the browser's).
 */
import { ApiClient } from "../../common/model/api.js";
import { element } from "../../common/view/dom.js";
import { EfficiencyChain } from "../model/efficiency_chain.js";
import { decimalMessage, parseDecimal } from "../../common/model/decimal_input.js";
import { refusalMessage } from "../../common/view/messages.js";
import { formatQuantity, plainText, unitText } from "../../common/view/notation.js";

/** A value as typed back into a field: no grouping, the page's decimal separator (a comma in ru and uk). */
const typed = (value, lang) => (lang === "en" ? String(value) : String(value).replace(".", ","));

export class EfficiencyChainView {
  constructor(body, spec, { t, lang }) {
    this.t = t;
    this.lang = lang;
    this.model = new EfficiencyChain();
    const client = new ApiClient("efficiency-chain", lang, (busy) => body.classList.toggle("busy", busy));
    this.rows = element("tbody");
    this.series = element("output", { className: "chain-series" });
    this.parallel = element("output", { className: "chain-parallel" });
    this.printed = element("output", { className: "chain-parallel-printed" });
    this.message = element("div", { className: "chain-message" });
    const add = element("button", { type: "button", className: "chain-add", textContent: t.chain_add });
    add.addEventListener("click", () => this.model.add());
    body.append(
      element("table", { className: "chain-table" },
        element("thead", {}, element("tr", {},
          element("th", { scope: "col", textContent: "k" }),
          element("th", { scope: "col", rich: "η_k" }),
          element("th", { scope: "col", rich: `A_{P,k}, ${unitText("J", t)}` }),
          element("td"))),
        this.rows),
      add,
      element("dl", { className: "figures-list chain-results" },
        element("dt", { rich: t.chain_series }), element("dd", {}, this.series),
        element("dt", { rich: t.chain_parallel }), element("dd", {}, this.parallel),
        element("dt", { rich: t.chain_parallel_printed }), element("dd", {}, this.printed)),
      this.message);

    this.model.on("mechanisms", () => {
      this.#rows();
      if (this.model.valid()) client.submit("chain", this.model.request(), (answer) => this.model.receive(answer));
      else this.series.textContent = this.parallel.textContent = this.printed.textContent = "—";
    });
    this.model.on("result", (answer) => this.#result(answer));
    this.model.emit("mechanisms");
  }

  /** Rebuild the rows when their number changed; otherwise only mark the invalid fields. */
  #rows() {
    const { mechanisms } = this.model;
    if (this.rows.children.length !== mechanisms.length) {
      this.rows.replaceChildren(...mechanisms.map((mechanism, i) => this.#row(mechanism, i)));
    }
    for (const input of this.rows.querySelectorAll("input")) {
      const key = input.dataset.key;
      input.setAttribute("aria-invalid", String(!EfficiencyChain.accepts(key, this.model.mechanisms[Number(input.dataset.index)][key])));
    }
  }

  #row(mechanism, index) {
    const field = (key) => {
      const input = element("input", {
        type: "text", inputmode: "decimal", size: 6, value: typed(mechanism[key], this.lang), className: `chain-${key}`,
        "aria-label": plainText(key === "efficiency" ? `η_{${index + 1}}` : `A_{P,${index + 1}}`), "data-key": key, "data-index": index });
      input.addEventListener("input", () => {
        const read = parseDecimal(input.value, this.lang);
        input.title = read.error ? decimalMessage(read.error, input.value, this.t) : "";
        this.message.textContent = input.title;
        this.model.set(index, key, read.error ? NaN : read.value);
      });
      return element("td", {}, input);
    };
    const remove = element("button", {
      type: "button", className: "chain-remove", textContent: "×", title: this.t.chain_remove,
      "aria-label": this.t.chain_remove, disabled: this.model.mechanisms.length < 2 });
    remove.addEventListener("click", () => this.model.remove(index));
    return element("tr", {}, element("th", { scope: "row", textContent: String(index + 1) }),
      field("efficiency"), field("work"), element("td", {}, remove));
  }

  #result(answer) {
    const shown = (value) => (value === null || value === undefined ? "—" : formatQuantity(value, this.lang, 4));
    this.message.replaceChildren(...(answer.ok ? [] : [refusalMessage(this.t.computation_refused, answer.error, this.t)]));
    this.series.textContent = answer.ok ? shown(answer.data.series) : "—";
    this.parallel.textContent = answer.ok ? shown(answer.data.parallel) : "—";
    // (3.40) as printed, the sum of the η_k (Chaika–Vasylenko: the total A_P in the numerator), beside the corrected
    this.printed.textContent = answer.ok ? shown(answer.data.errata?.[0]?.printed_value) : "—";
  }
}
