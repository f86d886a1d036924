/**
 * View of the crank-angle clock: play/pause, a scrub slider for φ in degrees, the φ readout and the
 * speed. Moving the scrub slider pauses the animation.
 */
import { element } from "./dom.js";
import { degrees, formatNumber } from "./notation.js";

const SPEEDS = [0.25, 0.5, 1, 2];

export class AnimationControls {
  constructor(container, animation, { t, lang }) {
    this.animation = animation;
    this.lang = lang;
    this.button = element("button", { type: "button", className: "play", textContent: t.play });
    this.scrub = element("input", {
      type: "range", min: 0, max: 360, step: 0.5, value: 0, id: "crank-angle", "aria-label": t.crank_angle });
    this.readout = element("output", { className: "phi-readout", htmlFor: "crank-angle" });
    const speed = element("select", { id: "animation-speed" },
      ...SPEEDS.map((s) => element("option", { value: s, textContent: `${formatNumber(s, lang)}×`, selected: s === 1 })));
    container.append(this.button, this.scrub, this.readout,
      element("label", { className: "speed" }, `${t.speed} `, speed));

    this.button.addEventListener("click", () => animation.toggle());
    this.scrub.addEventListener("input", () => {
      animation.pause();
      animation.seek(Number(this.scrub.value) * Math.PI / 180);
    });
    speed.addEventListener("change", () => animation.setSpeed(Number(speed.value)));
    animation.on("playing", (playing) => {
      this.button.textContent = playing ? t.pause : t.play;
      this.button.setAttribute("aria-pressed", String(playing));
    });
    animation.on("phi", (phi) => this.show(phi));
    this.show(animation.phi);
  }

  show(phi) {
    this.scrub.max = degrees(this.animation.cycle);
    this.scrub.value = degrees(phi);
    this.readout.textContent = `φ = ${formatNumber(degrees(phi), this.lang, 1)}°`;
  }
}
