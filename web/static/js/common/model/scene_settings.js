/**
 * What the reader has chosen in a scene (content/scenes/*.json): the variant (a mechanism set-up) and
 * the values of its sliders and toggles. No DOM. The kinematics and the dynamics models extend it with
 * the request they build from these values and the answers they receive.
 *
 * Events:
 *   "variant"   the variant changed: controls and panels are rebuilt
 *   "params"    a value changed: a new request is due
 *   "grab"      the reader took hold of a slider (pointer down or keyboard focus): its slider
 *   "rest"      the held slider came to rest (released, its keys at rest, or let go)
 */
import { Emitter } from "./emitter.js";

export class SceneSettings extends Emitter {
  /** initial: {variant, values} from the page address; values that do not fit the variant are ignored. */
  constructor(scene, initial = {}) {
    super();
    this.scene = scene;
    this.useVariant(scene.variants.find((v) => v.id === initial.variant) ?? scene.variants[0]);
    for (const [id, value] of Object.entries(initial.values ?? {})) {
      if (this.accepts(id, value)) this.values[id] = value;
    }
  }

  /** Announce the initial state to the listeners. */
  start() {
    this.emit("variant", this.variant);
    this.emit("params");
  }

  selectVariant(id) {
    const variant = this.scene.variants.find((v) => v.id === id);
    if (!variant || variant === this.variant) return;
    this.useVariant(variant);
    this.emit("variant", variant);
    this.emit("params");
  }

  setValue(id, value) {
    if (!this.accepts(id, value) || this.values[id] === value) return;
    this.values[id] = value;
    this.emit("params");
  }

  /** The reader took hold of slider id; it stays grabbed until let go. */
  grab(id) {
    const slider = this.variant.sliders.find((s) => s.id === id);
    if (!slider || slider.locked) return;
    this.grabbed = slider;
    this.emit("grab", slider);
  }

  /** The held slider came to rest. */
  rest() {
    if (this.grabbed) this.emit("rest");
  }

  /** The reader let go of the slider (it lost the focus). */
  letGo() {
    this.rest();
    this.grabbed = null;
  }

  /** Back to the variant's defaults (the variant stays): every value, and what the models keep besides. */
  reset() {
    this.useVariant(this.variant);
    this.emit("variant", this.variant);
    this.emit("params");
  }

  /** True if value is allowed for the slider (a number in its range) or the toggle (one of its options) id. */
  accepts(id, value) {
    const slider = this.variant.sliders.find((s) => s.id === id);
    if (slider?.locked) return value === slider.default;     // fixed by an assignment
    if (slider) return Number.isFinite(value) && value >= slider.min && value <= slider.max;
    const toggle = this.variant.toggles.find((t) => t.id === id);
    return Boolean(toggle?.options.includes(value));
  }

  /** Make variant the current one, its sliders and toggles at their defaults. */
  useVariant(variant) {
    this.variant = variant;
    this.grabbed = null;      // the slider the reader holds, if any
    this.values = Object.fromEntries([...variant.sliders, ...variant.toggles].map((c) => [c.id, c.default]));
  }
}
