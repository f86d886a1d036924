/**
 * Model of a dynamics scene (endpoint /reduction or /motion): the reader's choices (SceneSettings) and
 * the request body built from them. No DOM.
 *
 * The body is the variant's `request` with the mechanism added; each toggle puts its option at its
 * dotted path (toggle.param, e.g. "load.convention"); each slider puts value × to_si × (the value at
 * slider.scale, if given) at slider.param and at each of its slider.also paths, e.g. λ sets
 * params.l2 = λ·params.l1 in metres, a slider in degrees has to_si = π/180, and one f sets the friction
 * coefficient of every pair; values the reader edited in a panel (the indicator diagram's points, a free
 * law's table) go to their paths; outputs are whatever the variant's panels need.
 *
 * The chosen preset of a slider (presets_view.js) is kept here as its index in the scene's presets, so that
 * the page address holds it (url_state.js).
 *
 * Events, besides those of SceneSettings:
 *   "result"    the answer for the current values arrived (the results, or why there are none)
 *   "preset"    a preset was chosen or dropped
 */
import { pathValue, setPath } from "../../common/model/dotted_paths.js";
import { SceneSettings } from "../../common/model/scene_settings.js";
import { isFreeLaw } from "./free_law_table.js";

export class DynamicsModel extends SceneSettings {
  /** initial: as SceneSettings', plus the edits (Map path → list) and the preset's index from the address. */
  constructor(scene, initial = {}) {
    super(scene, initial);
    const edits = new Map(initial.edits ?? []);
    for (const [path, values] of edits) if (this.#editable(path, values, edits)) this.edits.set(path, values);
    this.choosePreset(initial.preset ?? null);
  }

  /** Choose preset number index of the scene's presets (null: none); one for a slider of another variant is dropped. */
  choosePreset(index) {
    const preset = this.scene.presets?.[index];
    this.preset = preset && this.variant.sliders.some((s) => s.id === preset.slider) ? index : null;
    this.emit("preset", this.preset);
  }

  /** The SI value slider sets in the request (l₂ in metres for λ = l₂/l₁). */
  setting(slider) {
    return pathValue(this.request(), slider.param);
  }

  /** What slider sets, as the family request's vary: value × to_si × (value at scale) at each of its paths. */
  familyVary(slider) {
    const factor = slider.to_si * (slider.scale ? pathValue(this.request(), slider.scale) : 1);
    return [slider.param, ...slider.also].map((path) => ({ path, factor }));
  }

  /** Body of the request for the current values. */
  request() {
    const variant = this.variant;
    const body = { ...structuredClone(variant.request), mechanism: variant.mechanism };
    for (const toggle of variant.toggles) setPath(body, toggle.param, this.values[toggle.id]);
    for (const [path, value] of this.edits) setPath(body, path, value);
    for (const slider of variant.sliders) {
      const scale = slider.scale ? pathValue(body, slider.scale) : 1;
      const value = this.values[slider.id] * slider.to_si * scale;
      for (const path of [slider.param, ...slider.also]) setPath(body, path, value);
    }
    return { ...body, outputs: this.outputs() };
  }

  /** What the variant's panels need ("resisting", "friction_iteration", "steady", "startup", …). */
  outputs() {
    return [...new Set(this.variant.panels.flatMap((id) => this.scene.panels[id]?.needs ?? []))];
  }

  /** Put value at path of the request body (a list edited in a panel, e.g. "motor.expansion"). */
  edit(path, value) {
    this.edits.set(path, value);
    this.emit("params");
  }

  useVariant(variant) {
    super.useVariant(variant);
    this.edits = new Map();
    this.preset = null;
  }

  /**
   * Whether a list of the address (edits: all of them) is one a panel of the variant edits (spec.paths): finite
   * numbers, as many as the variant's own list; a free law's table (a panel of kind "free_law_table": its angles
   * and moments, the variant's own list where the address has none) of any length the server accepts.
   */
  #editable(path, values, edits) {
    const panel = this.variant.panels.map((id) => this.scene.panels[id])
      .find((spec) => Object.values(spec?.paths ?? {}).includes(path));
    const own = pathValue(this.variant.request, path);
    if (!panel || !Array.isArray(own) || !values.every(Number.isFinite)) return false;
    if (panel.kind !== "free_law_table") return values.length === own.length;
    const list = (key) => edits.get(panel.paths[key]) ?? pathValue(this.variant.request, panel.paths[key]);
    return isFreeLaw(list("phi"), list("moment"));
  }

  /** Take the answer to the latest request. */
  receive(answer) {
    this.emit("result", answer);
  }
}
