/**
 * Keys on a slider are a hold, as a drag is: a run of key presses (arrows, PageUp/PageDown, Home/End, a key held
 * down and repeating) moves the slider like a drag and comes to rest once, when the keys are released and none is
 * pressed for REST_MS. While the keys move it, each value is drawn from the slider's family (family_preview.js)
 * like a drag's, and the exact answer is asked for at rest, not at every key (a range input says "change" at
 * every key; the controls ignore it while a run is on).
 *
 * A run starts with the first key (the slider is grabbed if it is not held: its family is asked for, as on a
 * pointer down); a pointer put on the slider ends it without rest (the pointer holds it now, and rests it when
 * released); the focus leaving the slider rests it at once (the controls let it go).
 */
const REST_MS = 250;      // the keys rest this long after the last one is released
const SLIDER_KEYS = new Set(["ArrowUp", "ArrowRight", "ArrowDown", "ArrowLeft", "PageUp", "PageDown", "Home", "End"]);

export class SliderKeys {
  #timer = null;
  #down = new Set();        // slider keys pressed and not yet released

  /** running: a run of keys is on (from its first key until it rests or a pointer takes the slider). */
  running = false;

  /** input: the range input; grab(): take hold of its slider if it is not held; rest(): the keys came to rest. */
  constructor(input, { grab, rest }) {
    this.grab = grab;
    this.rest = rest;
    input.addEventListener("keydown", (event) => this.#keyDown(event));
    input.addEventListener("keyup", (event) => this.#keyUp(event));
    input.addEventListener("pointerdown", () => this.#stop());
    input.addEventListener("blur", () => this.#stop());
  }

  /** True if key moves a slider (a key this module takes for a run). */
  static moves(key) {
    return SLIDER_KEYS.has(key);
  }

  #keyDown(event) {
    if (!SliderKeys.moves(event.key)) return;
    clearTimeout(this.#timer);
    this.#timer = null;
    this.#down.add(event.key);
    if (!this.running) {
      this.running = true;
      this.grab();
    }
  }

  #keyUp(event) {
    if (!this.#down.delete(event.key) || this.#down.size || !this.running) return;
    this.#timer = setTimeout(() => {
      this.#stop();
      this.rest();
    }, REST_MS);
  }

  /** End the run without rest. */
  #stop() {
    clearTimeout(this.#timer);
    this.#timer = null;
    this.#down.clear();
    this.running = false;
  }
}
