/**
 * POST /api/v1/kinematics (or another endpoint: the dynamics estimate) for the editor, the latest question only: a question asked while another is in
 * flight replaces the waiting one, and an answer to a superseded question is dropped. A refusal (422) keeps
 * the field it names (loc) so that the page can show the reason beside the group it concerns.
 * An answer is {ok: true, data} or {ok: false, error: {code, message, loc, ctx}}.
 */
import { errorReason } from "../../common/view/messages.js";

export class LatestRequest {
  #busy = false;
  #waiting = null;
  #serial = 0;

  constructor(lang, endpoint = "kinematics") {
    this.url = `/api/v1/${endpoint}?lang=${encodeURIComponent(lang)}`;
  }

  submit(body, onAnswer) {
    this.#serial += 1;
    this.#waiting = { body: JSON.stringify(body), onAnswer, serial: this.#serial };
    if (!this.#busy) this.#drain();
  }

  /** Drop the question waiting and the answer to the one in flight: nothing is to be asked now. */
  cancel() {
    this.#serial += 1;
    this.#waiting = null;
  }

  async #drain() {
    this.#busy = true;
    while (this.#waiting) {
      const request = this.#waiting;
      this.#waiting = null;
      const answer = await this.#post(request.body);
      if (answer.retryAfter !== undefined) {
        this.#waiting ??= request;
        await new Promise((resolve) => setTimeout(resolve, answer.retryAfter));
      } else if (request.serial === this.#serial) {
        request.onAnswer(answer);
      }
    }
    this.#busy = false;
  }

  async #post(body) {
    try {
      const response = await fetch(this.url, { method: "POST", headers: { "Content-Type": "application/json" }, body });
      if (response.status === 429) {
        return { retryAfter: 1000 * Math.max(0.25, Number(response.headers.get("Retry-After")) || 1) };
      }
      const payload = await response.json().catch(() => null);
      if (response.ok && payload) return { ok: true, data: payload };
      const detail = Array.isArray(payload?.detail) ? payload.detail[0] : null;
      return { ok: false, error: { code: detail?.ctx?.code ?? (detail ? null : "server"),
        message: detail?.msg ?? `HTTP ${response.status}`, loc: detail?.loc ?? [], ctx: detail?.ctx ?? {} } };
    } catch (error) {
      return { ok: false, error: { code: "network", message: String(error), loc: [], ctx: {} } };
    }
  }
}

/** The group a refusal names (its index), or null: loc ["body", "linkage", "groups", "1", …]. */
export function refusedGroup(error) {
  const loc = error.loc ?? [];
  const at = loc.indexOf("groups");
  if (loc[1] !== "linkage" || at < 0 || loc[at + 1] === undefined) return null;
  const k = Number(loc[at + 1]);
  return Number.isInteger(k) ? k : null;
}

/**
 * The reason of a refusal in the reader's language (the app's one message renderer, errorReason), a group
 * named as in the structural formula where `groups` (its names) is given.
 */
export function refusalText(error, t, groups = null) {
  return errorReason(error, t, { groups });
}
