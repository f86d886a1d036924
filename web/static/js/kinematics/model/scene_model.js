/**
 * Model of a kinematics scene: the reader's choices (SceneSettings), the overlay switch, and the
 * kinematics answers for them. No DOM.
 *
 * A slider sets params[param] = value × params[scale] (lengths in metres, e.g. λ = l₂/l₁ sets l₂ = λ·l₁);
 * a toggle sets params[param] to one of its options (assembly ±1, stroke limiter 0/1).
 *
 * Events, besides those of SceneSettings:
 *   "overlay"   the overlay switch changed
 *   "result"    the answer for the current parameters arrived (a table, or the reason there is none)
 *   "overlays"  the overlay tables changed
 */
import { SceneSettings } from "../../common/model/scene_settings.js";

const TURN = 2 * Math.PI;
const POINTS_PER_TURN = 360;            // a grid step of 1° of crank angle
/** Outputs drawn for the overlay values of λ (the textbook's Figs. 2.3, 2.5). */
const OVERLAY_OUTPUTS = ["s", "s2", "u31", "du31", "u21", "du21"];

/** Points of the grid over one cycle, ends included: 361 for 2π, 721 for a 4π change-point cycle. */
function gridPoints(cycle) {
  return 1 + Math.round(POINTS_PER_TURN * cycle / TURN);
}

export class SceneModel extends SceneSettings {
  #cycles = new Map();     // cycle length last answered, by variant and toggle values

  /** initial: {variant, values, overlay} from the page address. */
  constructor(scene, initial = {}) {
    super(scene, initial);
    this.overlay = Boolean(initial.overlay) && this.variant.overlay_values.length > 0;
  }

  reset() {
    this.overlay = false;
    super.reset();
  }

  setOverlay(on) {
    this.overlay = on && this.variant.overlay_values.length > 0;
    if (!this.overlay) this.overlays.clear();
    this.emit("overlay", this.overlay);
    this.emit("overlays");
  }

  /** The length in metres that slider sets (l₂ for λ = l₂/l₁). */
  setting(slider) {
    return this.params()[slider.param];
  }

  /** What slider sets, as the family request's vary: params[param] = value × params[scale]. */
  familyVary(slider) {
    return [{ path: `params.${slider.param}`, factor: slider.scale ? this.params()[slider.scale] : 1 }];
  }

  /** Mechanism parameters (metres and switches) for the given slider and toggle values. */
  params(values = this.values) {
    const params = { ...this.variant.fixed };
    for (const toggle of this.variant.toggles) params[toggle.param] = values[toggle.id];
    for (const slider of this.variant.sliders) {
      params[slider.param] = values[slider.id] * (slider.scale ? params[slider.scale] : 1);
    }
    return params;
  }

  /** Every output the variant's panels show, plus the drawing's joints, special positions and info. */
  outputs() {
    const names = new Set(this.scene.outputs);
    for (const id of this.variant.panels) {
      for (const name of this.scene.panels[id].outputs ?? []) names.add(name);
    }
    return [...names];
  }

  /** Body of the kinematics request for the current (or given) values. */
  request(values = this.values, outputs = this.outputs()) {
    const cycle = this.#cycles.get(this.#cycleKey()) ?? TURN;
    return { mechanism: this.variant.mechanism, params: this.params(values), n: gridPoints(cycle), outputs };
  }

  /** One request per overlay value of the first slider (λ), the other values as they are now. */
  overlayRequests() {
    if (!this.overlay) return [];
    const slider = this.variant.sliders[0];
    return this.variant.overlay_values.map((lambda) => ({
      lambda, body: this.request({ ...this.values, [slider.id]: lambda }, OVERLAY_OUTPUTS) }));
  }

  /** Take the answer to request body; ask again when the table's cycle needs a different grid. */
  receive(body, answer) {
    this.answer = answer;
    this.emit("result", answer);
    if (!answer.ok) return;
    this.#cycles.set(this.#cycleKey(), answer.data.cycle);
    if (gridPoints(answer.data.cycle) !== body.n) this.emit("params");
  }

  receiveOverlay(lambda, answer) {
    if (!this.overlay) return;
    this.overlays.set(lambda, answer);
    this.emit("overlays");
  }

  useVariant(variant) {
    super.useVariant(variant);
    this.overlay = Boolean(this.overlay) && variant.overlay_values.length > 0;
    this.answer = null;
    this.overlays = new Map();   // λ → answer, for the overlay values of the first slider
  }

  #cycleKey() {
    return JSON.stringify([this.variant.id, this.variant.toggles.map((t) => this.values[t.id])]);
  }
}
