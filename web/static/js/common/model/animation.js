/**
 * The crank-angle clock of the animation: φ (rad) runs through one kinematic cycle (2π, or 4π for a
 * change-point four-bar without limiter), one crank revolution every SECONDS_PER_TURN / speed seconds.
 * Views read positions for φ from the one kinematics table of the current parameters.
 *
 * Events: "phi" (φ changed), "playing" (started or paused).
 */
import { Emitter } from "./emitter.js";

const TURN = 2 * Math.PI;
const SECONDS_PER_TURN = 4;
const LONGEST_FRAME = 0.1;     // s; a background tab or a slow frame does not make the crank jump

export class CrankAnimation extends Emitter {
  phi = 0;
  cycle = TURN;
  speed = 1;
  playing = false;
  #lastTime = null;

  setCycle(cycle) {
    if (cycle === this.cycle) return;
    this.cycle = cycle;
    this.seek(this.phi);
  }

  /** Put the crank at phi (rad), wrapped into the cycle. */
  seek(phi) {
    this.phi = ((phi % this.cycle) + this.cycle) % this.cycle;
    this.emit("phi", this.phi);
  }

  setSpeed(speed) {
    this.speed = speed;
  }

  play() {
    if (this.playing) return;
    this.playing = true;
    this.#lastTime = null;
    requestAnimationFrame(this.#tick);
    this.emit("playing", true);
  }

  pause() {
    if (!this.playing) return;
    this.playing = false;
    this.emit("playing", false);
  }

  toggle() {
    if (this.playing) this.pause();
    else this.play();
  }

  #tick = (time) => {
    if (!this.playing) return;
    if (this.#lastTime !== null) {
      const seconds = Math.min((time - this.#lastTime) / 1000, LONGEST_FRAME);
      this.seek(this.phi + TURN * this.speed * seconds / SECONDS_PER_TURN);
    }
    this.#lastTime = time;
    requestAnimationFrame(this.#tick);
  };
}
