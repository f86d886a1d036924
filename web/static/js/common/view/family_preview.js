/**
 * Dragging is a lookup: when the reader grabs a slider (pointer down or keyboard focus) the page asks once
 * for the slider's family (POST /api/v1/family: the scene's answer at values across the slider's range,
 * every other value as it is now). While that slider moves and its family covers the value, the views are
 * given an answer interpolated from the family (family_model.js), at most once per animation frame and
 * without a request; the page asks for the exact answer when the slider comes to rest.
 *
 * Two stages: the page first asks for the coarse family ("stage": "coarse", the 9 start members, answered
 * at once, in the server's lane of answers) and, when it has arrived, for the full one (queued behind other
 * students' full families; asked together, the full family would take the CPU the coarse one needs first).
 * The preview is drawn from the best family there is: the full one replaces the coarse one
 * when it arrives (and redraws a preview on the screen). A server that refuses "stage" (an older one, 422)
 * gets one request without it, the full family, for the rest of the page's life.
 *
 * A grab of another slider (or of the same one at other values) gives up the families still on their way:
 * their requests are aborted, so that the server stops computing them (server/runtime/heavy.py, LaneQueue) and
 * its CPU goes to the family now held. A coarse family already there is kept; grabbing its slider again asks
 * for the full one anew.
 *
 * The request names the answer's leaves the variant's panels draw in a preview ("fields", family_fields.js):
 * the server sends only those, packed ("packed": true: the arrays equal in every member once, in "shared",
 * every array as integer steps in a quantum of at most 0.01 % of its span), unpacked and merged on arrival
 * (family_model.js received).
 *
 * The model is the scene's SceneSettings (a SceneModel or a DynamicsModel): request() is the body sent
 * now, familyVary(slider) the paths the slider sets with their factors, grabbed the slider held, scene and
 * variant what the page shows.
 *
 * Events:
 *   "preview"  {ok: true, data, preview: true}: draw this interpolated answer (plots, drawings, cursors);
 *              numbers in tables and readouts stay those of the last exact answer
 *   "family"   the family of the slider held, at the values shown, has arrived (or a better one): held()
 *
 * Performance marks (bench/browser.py): family-requested (the grab), family-arrived (the first family the
 * preview can draw from), family-coarse-arrived, family-full-arrived; a family asked for ends with exactly one of
 * family-full-arrived, family-unrefined (the busy server answered the full stage with its coarse family),
 * family-failed (no family: the page drags without one) and family-given-up (aborted by the next grab);
 * preview-coarse or preview-full for each preview frame, by the family it is drawn from.
 */
import { ApiClient } from "../model/api.js";
import { element } from "./dom.js";
import { messageText } from "./messages.js";
import { Emitter } from "../model/emitter.js";
import { previewFields } from "../model/family_fields.js";
import { familyKey, interpolate, memberInterval, received } from "../model/family_model.js";

const KEPT = 4;     // families kept on the page: the latest asked (a family may hold several MB)
const STAGES = ["coarse", "full"];
const NOT_REFUSED = new Set(["network", "server"]);    // failures that say nothing of whether stages are taken

export class FamilyPreview extends Emitter {
  #families = new Map();     // familyKey → the family, or null while it is on its way
  #due = null;               // the family and value of the next frame's preview
  #frameRequested = false;
  #staged = true;            // the server takes "stage" (until it refuses it)
  #pending = new Set();      // keys whose full family is on its way (its coarse or full stage in flight)

  /** showing: a preview is on the screen (or due) and no exact answer has replaced it yet. */
  showing = false;

  constructor(endpoint, lang, model) {
    super();
    this.endpoint = endpoint;
    this.model = model;
    this.client = new ApiClient("family", lang, () => {});
    model.on("grab", (slider) => this.#ask(slider));
    model.on("variant", () => this.end());
  }

  /**
   * If the grabbed slider's family covers the current values: draw them from it at the next animation
   * frame and return true; else false (the page asks for the exact answer as usual).
   */
  preview() {
    const slider = this.model.grabbed;
    if (!slider) return false;
    const family = this.#families.get(this.#question(slider).key);
    const value = this.model.values[slider.id];
    if (!family || !memberInterval(family, value)) return false;
    this.#due = { family, value };
    this.showing = true;
    if (!this.#frameRequested) {
      this.#frameRequested = true;
      requestAnimationFrame(this.#draw);
    }
    return true;
  }

  /** The family of the slider the reader holds at the other values shown (coarse or full), or null. */
  held() {
    const slider = this.model.grabbed;
    return slider && !slider.locked ? this.#families.get(this.#question(slider).key) ?? null : null;
  }

  /** The exact answer is shown: the preview is over. */
  end() {
    this.showing = false;
    this.#due = null;
  }

  /** The family request for the slider at the current values, and its key. */
  #question(slider) {
    const request = this.model.request();
    const vary = this.model.familyVary(slider);
    const fields = previewFields(this.model.scene, this.model.variant);
    const body = { endpoint: this.endpoint, request, vary, min: slider.min, max: slider.max, log: slider.log,
      ...(fields.length ? { fields } : {}), packed: true };
    return { body, key: familyKey(request, vary.map((v) => v.path), fields) };
  }

  #ask(slider) {
    if (slider.locked) return;
    const { body, key } = this.#question(slider);
    if (body.request.outputs?.length === 0) return;
    this.#giveUpAllBut(key);
    const held = this.#families.get(key);
    if (this.#pending.has(key) || held?.coarse === false) return;       // on its way, or there in full
    if (!held) {
      this.#families.set(key, null);
      for (const old of [...this.#families.keys()].slice(0, -KEPT)) this.#drop(old);
    }
    performance.mark("family-requested");
    this.#pending.add(key);
    this.#send(key, body, held || !this.#staged ? "full" : "coarse");   // a coarse one held: the full one
  }

  /** Abort the families on their way but the one under key; keep the coarse ones that have arrived. */
  #giveUpAllBut(key) {
    for (const other of [...this.#pending]) {
      if (other === key) continue;
      for (const stage of STAGES) this.client.cancel(`${stage} ${other}`);
      this.#pending.delete(other);
      performance.mark("family-given-up");
      if (!this.#families.get(other)) this.#families.delete(other);
    }
  }

  /** Forget the family under key and its answered questions: the same grab later asks the server again (the
   * client does not send a question it has answered already, see ApiClient.submit). */
  #drop(key) {
    this.#families.delete(key);
    for (const stage of STAGES) this.client.forget(`${stage} ${key}`);
  }

  /** Ask for one stage of the family under key (body without "stage"); a coarse one asks next for the full one. */
  #send(key, body, stage) {
    const asked = stage === "coarse" ? { ...body, stage } : body;      // "full" is the server's default
    this.client.submit(`${stage} ${key}`, asked, (answer) => {
      if (stage === "full") this.#pending.delete(key);
      if (!this.#families.has(key)) return;                         // dropped meanwhile
      const coarse = answer.ok && answer.data.numerics?.stage === "coarse";
      if (stage === "coarse" && !answer.ok && !NOT_REFUSED.has(answer.error.code)) this.#staged = false;   // a 422
      if (stage === "coarse" && !(answer.ok && !coarse)) this.#send(key, body, "full");
      if (!answer.ok) {            // no family: dragging stays as without one, the next grab asks again
        if (stage === "full") {
          performance.mark("family-failed");
          if (this.#families.get(key)) this.client.forget(`full ${key}`);   // the coarse one stays
          else this.#drop(key);
        }
        return;
      }
      if (stage === "full" && coarse) {          // the busy server did not refine it: the next grab asks again
        performance.mark("family-unrefined");
        this.client.forget(`full ${key}`);
      }
      if (coarse && this.#families.get(key)) return;                 // the full family came first, or is held
      if (!this.#families.get(key)) performance.mark("family-arrived");
      performance.mark(coarse ? "family-coarse-arrived" : "family-full-arrived");
      this.#families.set(key, { ...received(answer.data), log: body.log, coarse });
      if (this.showing) this.preview();                            // the better family redraws the preview
      this.emit("family", this.#families.get(key));
    });
  }

  #draw = () => {
    this.#frameRequested = false;
    if (!this.showing || !this.#due) return;
    const { family, value } = this.#due;
    performance.mark(family.coarse ? "preview-coarse" : "preview-full");
    for (const describe of badges) describe(family);
    this.emit("preview", { ok: true, data: interpolate(family, value), preview: true });
  };
}

const badges = new Set();    // the page's preview badges: each says how coarse the family drawn from is

/**
 * The mark that says the page shows a preview: a badge in container and the class "preview" on the scene
 * layout, which dims the numbers kept from the last exact answer (app.css). Drawn from a coarse family (the
 * server's numerics.stage: its first members, unrefined, as a busy server sends) the badge says so, and its
 * title gives the family's stated error in % of a quantity's span.
 */
export function previewMark(container, { t }) {
  const layout = container.closest(".scene-layout") ?? container;
  const badge = element("p", { className: "preview-note", role: "status", textContent: t.preview, title: t.preview_hint });
  container.append(badge);
  badges.add((family) => {
    const error = family.interpolation_error;
    badge.textContent = family.coarse ? t.preview_coarse : t.preview;
    badge.title = !family.coarse ? t.preview_hint : Number.isFinite(error)
      ? `${t.preview_hint} ${messageText(t.preview_coarse_error, { error: 100 * error })}` : t.preview_hint;
  });
  return (on) => layout.classList.toggle("preview", on);
}
