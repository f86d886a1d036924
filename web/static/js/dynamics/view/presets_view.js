/**
 * The scene's presets of a slider (content/scenes "presets": the lecture's table of permissible [δ] by
 * machine type, each {slider, label, min, max}): a select under the slider that puts the slider at the
 * preset's upper bound, and a check of each design's achieved δ (the exact answer and Merzalov's, from
 * the answer's `methods`) against the chosen range: ✓ within it, ✓ below it (smoother than required,
 * the flywheel larger than needed), ✗ above it.
 */
import { element } from "../../common/view/dom.js";
import { formatQuantity, plainText } from "../../common/view/notation.js";

/** Designs checked, by their `method` in the answer, and their names in the interface texts. */
const CHECKED = [["exact", "method_exact"], ["merzalov", "method_merzalov"]];
const DIGITS = 4;
const TOLERANCE = 1e-6;     // relative: the exact method meets its target δ to about 1e-12

/** Where δ stands against a preset's range: "within", "below" (smoother than required) or "above". */
export function verdict(delta, { min, max }) {
  if (delta > max * (1 + TOLERANCE)) return "above";
  return delta < min * (1 - TOLERANCE) ? "below" : "within";
}

export class PresetsView {
  /** controls: the element holding the sliders (ControlsView's), rebuilt before this view with each variant. */
  constructor(controls, model, { t, lang }) {
    this.controls = controls;
    this.model = model;
    this.t = t;
    this.lang = lang;
    this.answer = null;
    model.on("variant", () => this.build());
    model.on("result", (answer) => {
      this.answer = answer;
      this.showCheck();
    });
  }

  build() {
    const sliders = this.model.variant.sliders.map((s) => s.id);
    this.presets = (this.model.scene.presets ?? []).filter((p) => sliders.includes(p.slider));
    this.chosen = null;
    this.check = null;
    if (!this.presets.length) return;
    const { t, lang } = this;
    const range = (p) => `${this.#number(p.min)}…${this.#number(p.max)}`;
    const select = element("select", { id: "preset" },
      element("option", { value: "", textContent: t.preset_none }),
      ...this.presets.map((p, i) => element("option", { value: i, textContent: plainText(`${p.label[lang]}: ${range(p)}`) })));
    const all = this.model.scene.presets;
    const kept = this.presets.indexOf(all[this.model.preset]);      // chosen before (the page address)
    if (kept >= 0) {
      select.value = String(kept);
      this.chosen = this.presets[kept];
    }
    select.addEventListener("change", () => {
      this.chosen = select.value === "" ? null : this.presets[Number(select.value)];
      this.model.choosePreset(this.chosen ? all.indexOf(this.chosen) : null);
      if (this.chosen) this.model.setValue(this.chosen.slider, this.chosen.max);
      this.showCheck();
    });
    this.check = element("ul", { className: "preset-check", "aria-live": "polite" });
    const box = element("div", { className: "presets" },
      element("label", { className: "field" }, element("span", { textContent: t.preset_label }), select), this.check);
    this.controls.querySelector(`#slider-${this.presets[0].slider}`).closest(".slider").after(box);
  }

  /** One line per checked design: "✓ точный расчёт: δ = 0,0125 — в пределах 0,005…0,015". */
  showCheck() {
    if (!this.check) return;
    const methods = this.answer?.ok ? this.answer.data.methods ?? [] : [];
    const preset = this.chosen;
    const lines = preset ? CHECKED.map(([name, label]) => [methods.find((m) => m.method === name), label])
      .filter(([design]) => design) : [];
    this.check.replaceChildren(...lines.map(([design, label]) => {
      const where = verdict(design.delta_achieved, preset);
      return element("li", { className: `preset-${where}`,
        rich: `${where === "above" ? "✗" : "✓"} ${this.t[label]}: δ = ${this.#number(design.delta_achieved)} — `
          + this.#phrase(where, preset) });
    }));
  }

  #phrase(where, { min, max }) {
    const { t } = this;
    if (where === "above") return `${t.preset_above} ${this.#number(max)}`;
    if (where === "below") return `${t.preset_below} ${this.#number(min)}: ${t.preset_below_note}`;
    return `${t.preset_within} ${this.#number(min)}…${this.#number(max)}`;
  }

  #number(value) {
    return formatQuantity(value, this.lang, DIGITS);
  }
}
