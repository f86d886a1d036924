/**
 * Model of the live work–precision study of the scene's machine (POST /api/v1/work-precision/motion or
 * /work-precision/elastic): the same computation by several methods at a few tolerances, each timed and
 * compared with a reference at a much tighter tolerance. It costs seconds of server time, so it runs only
 * when asked, for the request body of the values at that moment, and remembers which body its answer
 * belongs to. No DOM.
 *
 * An answer is ApiClient's: {ok: true, data} with data = {study: {rows, skipped, reference, quantity},
 * warnings}, each row {method, rtol, runtime_ms (ms), error (relative error against the reference)}, or
 * {ok: false, error} when the study was refused (a machine without a speed-dependent moment has no
 * steady-cycle solvers to compare).
 *
 * Events:
 *   "running"   true when the study starts, false when its answer has arrived
 *   "result"    the answer arrived
 */
import { ApiClient } from "../../common/model/api.js";
import { Emitter } from "../../common/model/emitter.js";

const KEY = "study";

export class WorkPrecisionStudy extends Emitter {
  #client;
  #answeredFor = null;      // the body the answer was computed for, as JSON text

  /** endpoint: "work-precision/motion" or "work-precision/elastic"; lang: language of the answer. */
  constructor(endpoint, lang) {
    super();
    this.answer = null;
    this.running = false;
    this.#client = new ApiClient(endpoint, lang, (running) => {
      this.running = running;
      this.emit("running", running);
    });
  }

  /** Run the study for the request body; a run for the same body again measures the times again. */
  run(body) {
    const text = JSON.stringify(body);
    this.#client.forget(KEY);
    this.#client.submit(KEY, body, (answer) => {
      this.answer = answer;
      this.#answeredFor = text;
      this.emit("result", answer);
    });
  }

  /** True if there is an answer and it was computed for another body than this one. */
  answersEarlier(body) {
    return this.answer !== null && this.#answeredFor !== JSON.stringify(body);
  }
}
