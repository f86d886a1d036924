/**
 * View of the scene's inputs: the variant (mechanism) picker, the sliders with the textbook convention
 * and the English one beside it, the toggles, the overlay switch (kinematics), and the variant's
 * description. The model is a SceneSettings that also tells the length a ratio slider sets (setting).
 * Sliders report on every `input` event, and when the reader takes hold of one (pointer down, keyboard
 * focus), it comes to rest (`change`, pointer up; keys: once they rest, slider_keys.js) and it is let go
 * (blur): dragging, with the pointer or the keys, is drawn from the slider's family (family_preview.js) or,
 * before that arrives, kept cheap by the coalescing client.
 * Every slider tells a screen reader its value as the page writes it (aria-valuetext "δ = 0,02", not the
 * thumb's position); a logarithmic one steps from the keyboard by a fraction of a decade (slider_scale.js).
 * On a phone or tablet the controls are a sheet at the bottom of the screen (controls_sheet.js).
 */
import { choiceSelect } from "./choice_select.js";
import { controlsSheet } from "./controls_sheet.js";
import { element } from "./dom.js";
import {
  formatNumber, formatQuantity, labelledValue, paramSymbol, plainText, richText, setRichText, unitText,
} from "./notation.js";
import { LOG_DIGITS, logKeyValue, sliderScale } from "../model/slider_scale.js";
import { SliderKeys } from "./slider_keys.js";

const POWER_FROM = 1e6;     // a slider value from here on reads "4,4·10⁶", not "4400000"

/** Decimals that show a slider's step: 0.01 → 2. */
function decimalsOf(step) {
  return Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
}

/**
 * A slider's value with the decimals of its step, or with a power of ten when it is large; a logarithmic
 * slider's with its significant digits ("0,0125", "3,16·10⁶").
 */
function sliderValue(value, slider, lang) {
  if (slider.log) return formatQuantity(value, lang, LOG_DIGITS);
  return Math.abs(value) >= POWER_FROM ? formatQuantity(value, lang) : formatNumber(value, lang, decimalsOf(slider.step));
}

/** The English convention beside a slider is the reciprocal ratio ("r/l = 1/λ"): its name and value. */
function reciprocal(english, value, lang) {
  const name = english.replace(/\s*=\s*1\/λ$/, "");
  return name === english ? english : `${name} = ${formatNumber(1 / value, lang)}`;
}

export class ControlsView {
  /** pickerLabel: what the variants are ("Mechanism", "Set-up"). */
  constructor(container, model, { t, lang, pickerLabel }) {
    this.container = container;
    this.model = model;
    this.t = t;
    this.lang = lang;
    this.pickerLabel = pickerLabel;
    controlsSheet(container, t.parameters);
    model.on("variant", () => this.build());
    model.on("params", () => this.showValues());
    model.on("overlay", (on) => { if (this.overlayBox) this.overlayBox.checked = on; });
  }

  build() {
    const { model, t, lang } = this;
    const variant = model.variant;
    const picker = element("select", { id: "variant" }, ...model.scene.variants.map((v) =>
      element("option", { value: v.id, textContent: plainText(v.label[lang]), selected: v === variant })));
    picker.addEventListener("change", () => model.selectVariant(picker.value));
    this.readouts = new Map();
    this.overlayBox = null;
    this.container.replaceChildren(
      element("label", { className: "field" }, element("span", { textContent: this.pickerLabel }), picker),
      ...variant.sliders.map((slider) => this.#slider(slider)),
      ...variant.toggles.map((toggle) => this.#toggle(toggle)),
      ...(variant.overlay_values.length ? [this.#overlay(variant)] : []),
      element("p", { className: "variant-text", rich: variant.text[lang] }));
    this.showValues();
  }

  /**
   * Slider readouts: "λ = l₂/l₁ = 3,00 · r/l = 0,333", "P_с (нагрузка) = 2000 Н" (P with subscript с); a slider with a scale is
   * a ratio of lengths and also shows the length it sets, "l₂ = 0,300 м". A thumb that does not stand
   * for the value (the value was set elsewhere, e.g. by a preset) moves to it.
   */
  showValues() {
    for (const slider of this.model.variant.sliders) {
      const value = this.model.values[slider.id];
      const named = labelledValue(slider.label[this.lang], sliderValue(value, slider, this.lang));
      const parts = [named];
      if (slider.english) parts.push(reciprocal(slider.english[this.lang], value, this.lang));
      const { main, length, input, scale } = this.readouts.get(slider.id);
      if (scale.value(Number(input.value)) !== value) input.value = scale.position(value);
      input.setAttribute("aria-valuetext", plainText(named));
      setRichText(main, parts.join(" · "));
      length.textContent = slider.scale ? `${paramSymbol(slider.param)} = `
        + `${formatNumber(this.model.setting(slider), this.lang, 3)} ${unitText("m", this.t)}` : "";
    }
  }

  #slider(slider) {
    const scale = sliderScale(slider);
    const input = element("input", {
      type: "range", id: `slider-${slider.id}`, min: scale.min, max: scale.max, step: scale.step,
      value: scale.position(this.model.values[slider.id]), disabled: slider.locked });
    const main = element("span", { className: "readout" });
    const length = element("span", { className: "length" });
    this.readouts.set(slider.id, { main, length, input, scale });
    input.addEventListener("input", () => {
      performance.mark("slider-input");
      this.model.setValue(slider.id, scale.value(Number(input.value)));
    });
    for (const type of ["pointerdown", "focus"]) input.addEventListener(type, () => this.model.grab(slider.id));
    const keys = new SliderKeys(input, {
      grab: () => { if (this.model.grabbed?.id !== slider.id) this.model.grab(slider.id); },
      rest: () => this.model.rest() });
    // "change" when the value moved (at every key too: keys rest when they stop); pointerup also when the thumb
    // was put back where it was taken from
    input.addEventListener("change", () => { if (!keys.running) this.model.rest(); });
    input.addEventListener("pointerup", () => this.model.rest());
    input.addEventListener("blur", () => this.model.letGo());
    if (slider.log) input.addEventListener("keydown", (event) => this.#logKey(slider, event));
    return element("label", { className: slider.locked ? "slider locked" : "slider", htmlFor: input.id },
      element("span", { className: "slider-text" }, main, length), input);
  }

  /** A key on a logarithmic slider: the next value on its grid of fractions of a decade (at rest with the keys). */
  #logKey(slider, event) {
    const value = logKeyValue(slider, this.model.values[slider.id], event.key);
    if (value === null || event.altKey || event.ctrlKey || event.metaKey) return;
    event.preventDefault();
    if (value === this.model.values[slider.id]) return;
    performance.mark("slider-input");
    this.model.setValue(slider.id, value);
  }

  #toggle(toggle) {
    if (toggle.display === "select") return choiceSelect(toggle, this.model, this.lang);
    const name = `toggle-${toggle.id}`;
    const options = toggle.options.map((option, i) => {
      const radio = element("input", {
        type: "radio", name, value: option, checked: option === this.model.values[toggle.id] });
      radio.addEventListener("change", () => this.model.setValue(toggle.id, option));
      return element("label", { className: "option" }, radio, " ", richText(toggle.option_labels[i][this.lang]));
    });
    return element("fieldset", { className: "toggle", id: name },
      element("legend", { rich: toggle.label[this.lang] }), ...options);
  }

  #overlay(variant) {
    const values = variant.overlay_values.map((v) => formatNumber(v, this.lang)).join("; ");
    this.overlayBox = element("input", { type: "checkbox", id: "overlay", checked: this.model.overlay });
    this.overlayBox.addEventListener("change", () => this.model.setOverlay(this.overlayBox.checked));
    return element("label", { className: "option overlay" }, this.overlayBox, ` ${this.t.overlay} = ${values}`);
  }
}
