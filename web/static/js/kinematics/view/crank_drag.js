/**
 * Turn the crank by hand (issue 16): press anywhere on the linkage drawing and the crank angle follows the
 * pointer, φ = sense · (atan2 of the pointer about the crank's pivot − the pin's direction at φ = 0), taken
 * the short way round from where the crank stands (a 4π change-point cycle goes on into its second turn).
 * The animation clock is put there (it pauses), so the drawing and the plots' cursors follow as they follow
 * the clock. From the keyboard the focused drawing is a slider: arrows ±1°, Page Up/Down ±15°, Home 0°.
 *
 * The LinkageView tells where the crank is (crank(): the pivot in drawing units, the pin's direction at
 * φ = 0 and the sense in which φ grows on the screen), rebuilt with every answer.
 */
import { degrees, formatNumber, plainText } from "../../common/view/notation.js";

const TURN = 2 * Math.PI;
const STEP = Math.PI / 180;
const PAGE_STEP = 15 * STEP;
const KEYS = { ArrowRight: STEP, ArrowUp: STEP, ArrowLeft: -STEP, ArrowDown: -STEP, PageUp: PAGE_STEP, PageDown: -PAGE_STEP };

/** a wrapped into (−π, π]. */
const shortest = (a) => a - TURN * Math.ceil((a - Math.PI) / TURN);

export class CrankDrag {
  constructor(linkage, animation, { t, lang }) {
    this.linkage = linkage;
    this.animation = animation;
    const svg = linkage.svg;
    Object.entries({ tabindex: 0, role: "slider", "aria-label": plainText(t.crank_drag), "aria-valuemin": 0 })
      .forEach(([name, value]) => svg.setAttribute(name, value));
    svg.classList.add("turnable");
    const show = (phi) => {
      svg.setAttribute("aria-valuemax", Math.round(degrees(animation.cycle)));
      svg.setAttribute("aria-valuenow", Math.round(degrees(phi)));
      svg.setAttribute("aria-valuetext", `φ = ${formatNumber(degrees(phi), lang, 1)}°`);
    };
    animation.on("phi", show);
    show(animation.phi);
    svg.addEventListener("pointerdown", (event) => {
      if (!linkage.crank() || event.button !== 0) return;
      svg.setPointerCapture(event.pointerId);
      svg.classList.add("turning");
      animation.pause();
      this.#follow(event);
    });
    svg.addEventListener("pointermove", (event) => {
      if (svg.hasPointerCapture(event.pointerId)) this.#follow(event);
    });
    svg.addEventListener("lostpointercapture", () => svg.classList.remove("turning"));
    svg.addEventListener("keydown", (event) => {
      const step = KEYS[event.key];
      if (step === undefined && event.key !== "Home") return;
      event.preventDefault();
      animation.pause();
      animation.seek(step === undefined ? 0 : animation.phi + step);
    });
  }

  /** Put the crank where the pointer is, seen from the pivot. */
  #follow(event) {
    const { centre, start, sense } = this.linkage.crank();
    const point = new DOMPoint(event.clientX, event.clientY).matrixTransform(this.linkage.svg.getScreenCTM().inverse());
    const pointer = Math.atan2(point.y - centre[1], point.x - centre[0]);
    const target = sense * (pointer - start);
    this.animation.seek(this.animation.phi + shortest(target - this.animation.phi));
  }
}
