/**
 * Client of one computing endpoint (POST /api/v1/kinematics, /reduction, /motion, …) that coalesces requests.
 *
 * Requests are grouped by a key ("main", "overlay 1.5", …). Per key at most one request is in flight;
 * a request submitted meanwhile waits, replacing any older waiting one, and the answer of a request
 * that has been superseded is dropped. A slider drag therefore costs one request per server round
 * trip, and the screen always ends on the latest parameters.
 *
 * An answer is {ok: true, data} with the response body, or {ok: false, error: {code, message}} where
 * code is the error code of the 422 answer (content/i18n has err_<code>; null when the answer names none,
 * and its message is shown), "network" or "server".
 */
export class ApiClient {
  #slots = new Map();
  #inFlight = 0;

  /**
   * endpoint: "kinematics", "reduction", "motion", …; lang: language of the warnings;
   * onBusy(busy) is told when the first request starts and the last ends.
   */
  constructor(endpoint, lang, onBusy) {
    this.url = `/api/v1/${endpoint}?lang=${encodeURIComponent(lang)}`;
    this.onBusy = onBusy;
  }

  /** Ask for body under key; onAnswer(answer) runs only if no newer request for key arrives first. */
  submit(key, body, onAnswer) {
    const text = JSON.stringify(body);
    const slot = this.#slots.get(key) ?? { latest: null, waiting: null, busy: false };
    this.#slots.set(key, slot);
    if (slot.latest?.text === text) return;          // the same question is already asked
    slot.latest = { text, onAnswer };
    slot.waiting = slot.latest;
    if (!slot.busy) this.#drain(slot);
  }

  /** Drop whatever is waiting or in flight under key. */
  forget(key) {
    const slot = this.#slots.get(key);
    if (slot) slot.latest = slot.waiting = null;
  }

  async #drain(slot) {
    slot.busy = true;
    while (slot.waiting) {
      const request = slot.waiting;
      slot.waiting = null;
      const answer = await this.#post(request.text);
      if (slot.latest === request) request.onAnswer(answer);
    }
    slot.busy = false;
  }

  async #post(text) {
    if (this.#inFlight++ === 0) this.onBusy(true);
    try {
      const response = await fetch(this.url, {
        method: "POST", headers: { "Content-Type": "application/json" }, body: text });
      const payload = await response.json().catch(() => null);
      if (response.ok && payload) return { ok: true, data: payload };
      const detail = Array.isArray(payload?.detail) ? payload.detail[0] : null;
      if (!detail) return { ok: false, error: { code: "server", message: `HTTP ${response.status}` } };
      return { ok: false, error: { code: detail.ctx?.code ?? null, message: detail.msg } };
    } catch (error) {
      return { ok: false, error: { code: "network", message: String(error) } };
    } finally {
      if (--this.#inFlight === 0) this.onBusy(false);
    }
  }
}
