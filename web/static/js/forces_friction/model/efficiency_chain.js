/**
 * Model of the efficiency-chain calculator (POST /api/v1/efficiency-chain), Chaika–Vasylenko (3.39)–(3.40): the
 * mechanisms k = 1…n of a machine, each with its efficiency η_k (0 ≤ η_k ≤ 1) and the driving work A_P,k
 * (J) it receives when the mechanisms share the input in parallel. The server answers both connections:
 *   in series    η = η₁·η₂·…·ηₙ                   (3.39)
 *   in parallel  η = Σ η_k·A_P,k / Σ A_P,k         (3.40), none when no branch receives work
 * No DOM.
 *
 * Events:
 *   "mechanisms"  the list or a value changed: a new request is due (when every value is valid)
 *   "result"      the answer for the current list arrived
 */
import { Emitter } from "../../common/model/emitter.js";

const FIRST = [{ efficiency: 0.9, work: 100 }, { efficiency: 0.8, work: 100 }];

export class EfficiencyChain extends Emitter {
  mechanisms = FIRST.map((mechanism) => ({ ...mechanism }));

  /** Append a mechanism like the last one. */
  add() {
    this.mechanisms.push({ ...this.mechanisms[this.mechanisms.length - 1] });
    this.emit("mechanisms");
  }

  /** Take mechanism index out of the chain; the last one stays. */
  remove(index) {
    if (this.mechanisms.length < 2) return;
    this.mechanisms.splice(index, 1);
    this.emit("mechanisms");
  }

  /** Set the efficiency or the work of mechanism index (a number; NaN for an empty field). */
  set(index, key, value) {
    this.mechanisms[index][key] = value;
    this.emit("mechanisms");
  }

  /** True if value is allowed for key: an efficiency from 0 to 1, a work not negative. */
  static accepts(key, value) {
    return Number.isFinite(value) && value >= 0 && (key !== "efficiency" || value <= 1);
  }

  /** True if every value can be sent. */
  valid() {
    return this.mechanisms.every(({ efficiency, work }) =>
      EfficiencyChain.accepts("efficiency", efficiency) && EfficiencyChain.accepts("work", work));
  }

  request() {
    return { efficiencies: this.mechanisms.map((m) => m.efficiency), works: this.mechanisms.map((m) => m.work) };
  }

  receive(answer) {
    this.emit("result", answer);
  }
}
