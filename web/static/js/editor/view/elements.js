/**
 * The list of the mechanism's elements in the order they are attached (frame, crank, groups) with their
 * sizes typed or dragged (a length's slider runs from a quarter to two and a half times the length it had
 * when the list was drawn), the assembly branch, points of interest, the joints' names (the student may rename
 * them), and a refusal's reason beside the group it concerns; each group under its name in the structural
 * formula (II₁(2,3)), each guide under its label in the reader's language. Editing a value calls
 * onEdit(continuing) (the list is not redrawn, so a drag goes on; continuing: a slider is still being dragged,
 * the step ends with its release); adding, removing or renaming calls onStructure(). Every field is named for
 * a screen reader in words ("length C D"), its visible label keeps the textbook's subscripts.
 */
import { element } from "../../common/view/dom.js";
import { formatNumber } from "../../common/view/notation.js";
import { messageText } from "../../common/view/messages.js";
import { parseDecimal, decimalMessage } from "../../common/model/decimal_input.js";
import { groupName, guideLabel, joints, renameJoint } from "../model/linkage.js";

const DEG = 180 / Math.PI;

export class ElementList {
  constructor(host, { t, lang, onEdit, onStructure, onTrace }) {
    Object.assign(this, { host, t, lang, onEdit, onStructure, onTrace });
    this.refusals = new Map();
    this.fields = [];
  }

  /** Every other field shown again from the mechanism: a length and its ratio λ show the same change. */
  #refresh(except) {
    for (const field of this.fields) {
      if (field === except) continue;
      field.input.value = field.shown();
      if (field.range) field.range.value = field.get();
    }
  }

  /** "length C D": a length's name as a screen reader says it (the letters apart, no subscript markup). */
  #length(from, to) {
    return messageText(this.t.editor_say_length, { from, to });
  }

  /**
   * A number field: label (notation, shown), spoken (its name in words, for a screen reader), value in SI
   * (shown in degrees when degrees), a slider for positive lengths.
   */
  #number(label, spoken, get, set, { degrees = false, slider = false, unit = "", symbol = true } = {}) {
    const { t, lang } = this;
    const shown = () => formatNumber(degrees ? get() * DEG : get(), lang, degrees ? 1 : 3);
    const input = element("input", { type: "text", inputmode: "decimal", size: 6, value: shown(), "aria-label": spoken });
    const note = element("span", { className: "field-error", role: "alert" });
    const parts = [element("span", { rich: label, ...(symbol ? { translate: false } : {}) }), input, unit];
    let range = null;
    if (slider) {
      const base = get();
      range = element("input", { type: "range", min: base * 0.25, max: base * 2.5, step: base / 400, value: base,
        "aria-label": spoken });
    }
    const field = { input, range, shown, get };
    this.fields.push(field);
    range?.addEventListener("input", () => {
      set(Number(Number(range.value).toFixed(4)));
      input.value = shown();
      this.#refresh(field);
      this.onEdit(true);
    });
    range?.addEventListener("change", () => this.onEdit(false));      // released: the drag is one step
    input.addEventListener("change", () => {
      const read = parseDecimal(input.value, lang);
      if (read.error) {
        note.textContent = decimalMessage(read.error, input.value, t);
        return;
      }
      note.textContent = "";
      set(degrees ? read.value / DEG : read.value);
      input.value = shown();
      if (range) range.value = get();
      this.#refresh(field);
      this.onEdit();
    });
    return element("label", { className: "field" }, ...parts, ...(range ? [range] : []), note);
  }

  #branch(group) {
    const { t } = this;
    const select = element("select", { "aria-label": t.editor_branch },
      element("option", { value: "1", textContent: "+1" }), element("option", { value: "-1", textContent: "−1" }));
    select.value = String(group.branch ?? 1);
    select.addEventListener("change", () => {
      group.branch = Number(select.value);
      this.onEdit();
    });
    return element("label", { className: "field" }, t.editor_branch, select);
  }

  #remove(label, action) {
    return element("button", { type: "button", className: "remove", textContent: "×", title: label,
      "aria-label": label, onclick: () => {
        action();
        this.onStructure();
      } });
  }

  /** The joint's name as a field: a new name renames it wherever the mechanism refers to it. */
  #name(linkage, name, what) {
    const { t } = this;
    const input = element("input", { type: "text", size: 3, value: name, className: "joint-name", "data-name": name,
      "aria-label": `${t.editor_name}: ${what} ${name}`, spellcheck: false });
    input.addEventListener("change", () => {
      if (renameJoint(linkage, name, input.value)) this.onStructure();
      else input.value = name;
    });
    return element("label", { className: "name-field" }, t.editor_name, input);
  }

  #points(owner, linkage) {
    const { t } = this;
    return Object.entries(owner.points ?? {}).map(([name, p]) => {
      const said = `${t.editor_point} ${name}`;
      return element("div", { className: "point-row" },
        element("span", { rich: `${t.editor_point} ${name} (${t.editor_link} ${p.link ?? owner.links?.[0] ?? owner.link})` }),
        this.#name(linkage, name, t.editor_point),
        this.#number(t.editor_along, `${said}: ${t.editor_along}`, () => p.along ?? 0, (v) => { p.along = v; },
          { unit: t.units_m, symbol: false }),
        this.#number(t.editor_across, `${said}: ${t.editor_across}`, () => p.across ?? 0, (v) => { p.across = v; },
          { unit: t.units_m, symbol: false }),
        this.#remove(`${t.editor_remove} ${name}`, () => { delete owner.points[name]; }));
    }).concat(Object.entries(owner.new_guides ?? {}).map(([name, g]) => {
      const said = `${t.editor_link_guide} ${guideLabel(name, t)}`;
      return element("div", { className: "point-row" },
        element("span", { textContent: `${said} (${t.editor_link} ${g.link ?? owner.links?.[0] ?? owner.link})` }),
        this.#number(t.editor_along, `${said}: ${t.editor_along}`, () => g.along ?? 0, (v) => { g.along = v; },
          { unit: t.units_m, symbol: false }),
        this.#number(t.editor_across, `${said}: ${t.editor_across}`, () => g.across ?? 0, (v) => { g.across = v; },
          { unit: t.units_m, symbol: false }),
        this.#number("α", `${said}: ${t.editor_say_guide_angle}`, () => g.angle ?? 0, (v) => { g.angle = v; },
          { degrees: true, unit: "°" }),
        this.#remove(`${t.editor_remove} ${said}`, () => { delete owner.new_guides[name]; }));
    }));
  }

  /**
   * A group hinged to the crank's pin by its link of length l₂: the ratio beside the absolute length in both
   * of the textbook's conventions, λ = l₂/l₁ and r/l = l₁/l₂ (as the crank-slider's sliders), each editable.
   */
  #ratios(linkage, group, get, set) {
    const crank = linkage.input;
    if (crank?.kind === "slider" || !crank || group.outer?.[0] !== crank.joint) return [];
    const rod = `l_{${group.outer[0]}${group.inner}}`;
    const r = `l_{${crank.pivot}${crank.joint}}`;
    const [rodSaid, rSaid] = [[group.outer[0], group.inner], [crank.pivot, crank.joint]].map((ends) => ends.join(" "));
    return [this.#number(`λ = ${rod}/${r}`, messageText(this.t.editor_say_ratio, { symbol: "λ", a: rodSaid, b: rSaid }),
      () => get() / crank.length, (v) => set(v * crank.length), { slider: true }),
    this.#number(`r/l = ${r}/${rod}`, messageText(this.t.editor_say_ratio, { symbol: "r/l", a: rSaid, b: rodSaid }),
      () => crank.length / get(), (v) => set(crank.length / v), { slider: true })];
  }

  render(linkage, traced) {
    const { t } = this;
    const rows = [];
    this.fields = [];
    for (const [name, p] of Object.entries(linkage.frame.joints)) {
      const said = `${t.editor_frame_joint} ${name}`;
      rows.push(element("div", { className: "element-row", "data-element": name },
        element("strong", { textContent: said }),
        this.#name(linkage, name, t.editor_frame_joint),
        this.#number("x", `${said}: x`, () => p[0], (v) => { p[0] = v; }, { unit: t.units_m }),
        this.#number("y", `${said}: y`, () => p[1], (v) => { p[1] = v; }, { unit: t.units_m }),
        this.#remove(`${t.editor_remove} ${said}`, () => {
          delete linkage.frame.joints[name];
          if (linkage.input?.pivot === name) linkage.input = null;
        })));
    }
    for (const [name, g] of Object.entries(linkage.frame.guides)) {
      const through = Array.isArray(g.through) ? g.through : null;
      const said = `${t.editor_frame_guide} ${guideLabel(name, t)}`;
      rows.push(element("div", { className: "element-row", "data-element": name },
        element("strong", { textContent: said }),
        ...(through ? [this.#number("x", `${said}: x`, () => through[0], (v) => { through[0] = v; }, { unit: t.units_m }),
          this.#number("y", `${said}: y`, () => through[1], (v) => { through[1] = v; }, { unit: t.units_m })] : []),
        this.#number(t.editor_angle, `${said}: ${t.editor_angle}`, () => g.angle ?? 0, (v) => { g.angle = v; },
          { degrees: true, unit: "°", symbol: false }),
        this.#remove(`${t.editor_remove} ${said}`, () => {
          delete linkage.frame.guides[name];
          if (linkage.input?.guide === name) linkage.input = null;
        })));
    }
    const crank = linkage.input;
    if (crank?.kind === "slider") {
      rows.push(element("div", { className: "element-row", "data-element": "crank" },
        element("strong", {}, `${t.editor_input_slider} ${crank.link}: `,
          element("span", { translate: false, textContent: `${crank.joint} (${t.editor_guide_word} ${guideLabel(crank.guide, t)})` })),
        this.#name(linkage, crank.joint, t.editor_input_slider),
        this.#number("s_min", t.editor_say_s_min, () => crank.travel[0], (v) => { crank.travel[0] = v; },
          { slider: true, unit: t.units_m }),
        this.#number("s_max", t.editor_say_s_max, () => crank.travel[1], (v) => { crank.travel[1] = v; },
          { slider: true, unit: t.units_m }),
        ...this.#points(crank, linkage),
        this.#remove(`${t.editor_remove} ${t.editor_input_slider}`, () => { linkage.input = null; })));
    } else if (crank) {
      const sense = element("select", { "aria-label": t.editor_sense },
        element("option", { value: "1", textContent: t.editor_ccw }), element("option", { value: "-1", textContent: t.editor_cw }));
      sense.value = String(crank.sense ?? 1);
      sense.addEventListener("change", () => { crank.sense = Number(sense.value); this.onEdit(); });
      rows.push(element("div", { className: "element-row", "data-element": "crank" },
        element("strong", {}, `${t.editor_crank} ${crank.link}: `,
          element("span", { translate: false, textContent: `${crank.pivot}${crank.joint}` })),
        this.#name(linkage, crank.joint, t.editor_crank_pin),
        this.#number(`l_{${crank.pivot}${crank.joint}}`, this.#length(crank.pivot, crank.joint), () => crank.length,
          (v) => { crank.length = v; }, { slider: true, unit: t.units_m }),
        this.#number("θ_0", t.editor_say_theta0, () => crank.angle0 ?? 0, (v) => { crank.angle0 = v; },
          { degrees: true, unit: "°" }),
        element("label", { className: "field" }, t.editor_sense, sense),
        ...this.#points(crank, linkage),
        this.#remove(`${t.editor_remove} ${t.editor_crank}`, () => { linkage.input = null; })));
    }
    linkage.groups.forEach((group, k) => {
      const on = [...(group.outer ?? []), ...(group.guides ?? (group.guide ? [group.guide] : [])).map((g) => guideLabel(g, t))]
        .join(", ");
      const name = groupName(group);
      const fields = group.kind === "RPR" ? [] : [this.#name(linkage, group.inner, `${t.editor_group} ${name}`)];
      if (group.kind === "RRR") {
        const [b, d] = group.outer;
        fields.push(this.#number(`l_{${b}${group.inner}}`, this.#length(b, group.inner), () => group.lengths[0],
          (v) => { group.lengths[0] = v; }, { slider: true, unit: t.units_m }),
        this.#number(`l_{${d}${group.inner}}`, this.#length(d, group.inner), () => group.lengths[1],
          (v) => { group.lengths[1] = v; }, { slider: true, unit: t.units_m }), this.#branch(group),
        ...this.#ratios(linkage, group, () => group.lengths[0], (v) => { group.lengths[0] = v; }));
      } else if (group.kind === "RRP") {
        fields.push(this.#number(`l_{${group.outer[0]}${group.inner}}`, this.#length(group.outer[0], group.inner),
          () => group.length, (v) => { group.length = v; }, { slider: true, unit: t.units_m }), this.#branch(group),
        ...this.#ratios(linkage, group, () => group.length, (v) => { group.length = v; }));
      } else if (group.kind === "RPR") {
        fields.push(this.#number("e", t.editor_say_offset, () => group.offset ?? 0, (v) => { group.offset = v; },
          { unit: t.units_m }), this.#branch(group));
      } else if (group.kind === "RPP") {
        fields.push(this.#number("α", t.editor_say_slot_angle, () => group.angle ?? Math.PI / 2, (v) => { group.angle = v; },
          { degrees: true, unit: "°" }));
      }
      const refusal = this.refusals.get(k);
      rows.push(element("div", { className: `element-row group-row${refusal ? " refused" : ""}`, "data-group": k },
        element("strong", { textContent: `${name} ${group.kind}: ${t.editor_links} ${group.links.join(", ")} — ${t.editor_on} ${on}` }),
        ...fields, ...this.#points(group, linkage),
        this.#remove(`${t.editor_remove}: ${t.editor_group} ${name}`, () => { linkage.groups.splice(k, 1); }),
        ...(refusal ? [element("p", { className: "refusal-reason", role: "alert", textContent: refusal })] : [])));
    });
    if (!rows.length) rows.push(element("p", { className: "hint", textContent: t.editor_empty }));
    const moving = [...joints(linkage)].filter(([, on]) => !on.includes(0)).map(([name]) => name);
    const traces = element("fieldset", { className: "traces" }, element("legend", { textContent: t.editor_traces }),
      ...moving.map((name) => {
        const box = element("input", { type: "checkbox", checked: traced.has(name), "data-trace": name });
        box.addEventListener("change", () => this.onTrace(name, box.checked));
        return element("label", {}, box, name);
      }));
    this.host.replaceChildren(...rows, ...(moving.length ? [traces] : []));
  }
}
