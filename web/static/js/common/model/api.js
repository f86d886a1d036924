/**
 * Client of one computing endpoint (POST /api/v1/kinematics, /reduction, /motion, …) that coalesces requests.
 *
 * Requests are grouped by a key ("main", "overlay 1.5", …). Per key at most one request is in flight;
 * a request submitted meanwhile waits, replacing any older waiting one, and the answer of a request
 * that has been superseded is dropped. A slider drag therefore costs one request per server round
 * trip, and the screen always ends on the latest parameters.
 *
 * An answer is {ok: true, data} with the response body, or {ok: false, error: {code, message, field}} where
 * code is the error code of the 422 answer (content/i18n has err_<code>; null when the answer names none,
 * and its message is shown), "network" or "server".
 *
 * A request asked while a slider is dragged (submit's `drag`, the scene's slider held and no family to draw
 * from) says so (X-MDL-Drag: 1): the server serves it after every answer at rest, a preview of a value the slider
 * passes (server/runtime/admission.py). The same question asked again at rest and not yet sent goes unmarked;
 * one already in flight is left to finish (aborted and sent again, it would briefly count twice against the
 * server's limit of this browser's computations in flight, and be refused).
 *
 * A server that has as many of this browser's computations in flight as it admits answers 429 with
 * Retry-After (seconds): the client waits that long (plus up to half again, so that a class does not come
 * back all at once), then sends the latest request for the key. Meanwhile the page says "busy, retrying";
 * the student never sees the 429 as an error.
 */
const RETRY_JITTER = 0.5;
const MAX_RETRY_AFTER_S = 10;
let retrying = 0;                      // requests of this page waiting to be sent again

/** Show or hide the page's "busy, retrying" note (one for every client on the page). */
function noteRetrying(delta) {
  retrying += delta;
  let note = document.getElementById("busy-retrying");
  if (!note) {
    const texts = JSON.parse(document.getElementById("interface-texts")?.textContent ?? "{}");
    note = Object.assign(document.createElement("p"), {
      id: "busy-retrying", className: "retry-note", textContent: texts.busy_retrying ?? "…" });
    note.setAttribute("role", "status");
    document.body.append(note);
  }
  note.hidden = retrying === 0;
}

/** Milliseconds to wait before sending again, from the answer's Retry-After (delta-seconds). */
function retryDelay(response) {
  const seconds = Number.parseInt(response.headers.get("Retry-After") ?? "", 10);
  const base = Number.isFinite(seconds) ? Math.min(Math.max(seconds, 0), MAX_RETRY_AFTER_S) : 1;
  return 1000 * Math.max(base, 0.25) * (1 + RETRY_JITTER * Math.random());
}

const pause = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

export class ApiClient {
  #slots = new Map();
  #active = 0;

  /**
   * endpoint: "kinematics", "reduction", "motion", …; lang: language of the warnings;
   * onBusy(busy) is told when the first request starts and the last ends.
   */
  constructor(endpoint, lang, onBusy) {
    this.url = `/api/v1/${endpoint}?lang=${encodeURIComponent(lang)}`;
    this.onBusy = onBusy;
  }

  /**
   * Ask for body under key; onAnswer(answer) runs only if no newer request for key arrives first. drag: asked
   * while a slider is dragged (a preview; see above).
   */
  submit(key, body, onAnswer, { drag = false } = {}) {
    const text = JSON.stringify(body);
    const slot = this.#slots.get(key) ?? { latest: null, waiting: null, busy: false };
    this.#slots.set(key, slot);
    if (slot.latest?.text === text) {                // the same question is already asked
      if (!drag) slot.latest.drag = false;           // asked at rest: sent unmarked if still waiting
      return;
    }
    slot.latest = { text, onAnswer, drag };
    slot.waiting = slot.latest;
    if (!slot.busy) this.#drain(slot);
  }

  /** Drop whatever is waiting or in flight under key. */
  forget(key) {
    const slot = this.#slots.get(key);
    if (slot) slot.latest = slot.waiting = null;
  }

  /**
   * Drop whatever is waiting under key and abort its request in flight: the server, seeing the request
   * gone, stops computing it (a slider's family the student no longer holds).
   */
  cancel(key) {
    this.forget(key);
    this.#slots.get(key)?.controller?.abort();
  }

  async #drain(slot) {
    slot.busy = true;
    if (this.#active++ === 0) this.onBusy(true);
    while (slot.waiting) {
      const request = slot.waiting;
      slot.waiting = null;
      slot.controller = new AbortController();
      const answer = await this.#post(request, slot.controller.signal);
      slot.controller = null;
      if (answer.retryAfter !== undefined) {
        if (!slot.waiting && slot.latest === request) slot.waiting = request;   // else a newer one goes
        if (slot.waiting) {
          noteRetrying(+1);
          await pause(answer.retryAfter);
          noteRetrying(-1);
        }
      } else if (slot.latest === request) {
        request.onAnswer(answer);
      }
    }
    slot.busy = false;
    if (--this.#active === 0) this.onBusy(false);
  }

  /** The answer to one POST; {retryAfter: ms} when the server is busy with this browser's requests. */
  async #post({ text, drag }, signal) {
    const headers = { "Content-Type": "application/json" };
    if (drag) headers["X-MDL-Drag"] = "1";
    try {
      const response = await fetch(this.url, { method: "POST", headers, body: text, signal });
      if (response.status === 429) return { retryAfter: retryDelay(response) };
      const payload = await response.json().catch(() => null);
      if (response.ok && payload) return { ok: true, data: payload };
      const detail = Array.isArray(payload?.detail) ? payload.detail[0] : null;
      if (!detail) return { ok: false, error: { code: "server", message: `HTTP ${response.status}` } };
      const field = Array.isArray(detail.loc) && detail.loc[0] === "body" ? detail.loc.slice(1).join(".") : null;
      return { ok: false, error: { code: detail.ctx?.code ?? null, message: detail.msg, ctx: detail.ctx ?? {}, field } };
    } catch (error) {
      return { ok: false, error: { code: "network", message: String(error) } };
    }
  }
}
