/**
 * Turn the crank by hand: press anywhere on the linkage drawing and the crank angle follows the
 * pointer, φ = sense · (atan2 of the pointer about the crank's pivot − the pin's direction at φ = 0), taken
 * the short way round from where the crank stands (a 4π change-point cycle goes on into its second turn).
 * The animation clock is put there (it pauses), so the drawing and the plots' cursors follow as they follow
 * the clock. From the keyboard the focused drawing is a slider: arrows ±1°, Page Up/Down ±15°, Home 0°.
 *
 * The drawing tells where its crank is: a target {svg, crank()} whose crank() gives the pivot in drawing
 * units, the pin's direction at φ = 0 and the sense in which φ grows on the screen (crankPlace below), or
 * null while nothing is drawn. The LinkageView is one (kinematics, the flywheel's machine); the dynamics
 * scenes' panel views that draw the crank (the free-body diagram, the gear train) give theirs as `turnable`,
 * and the dynamics page turns every one with its one clock, so every plot cursor and per-angle readout follows.
 */
import { degrees, formatNumber, plainText } from "./notation.js";

const TURN = 2 * Math.PI;
const STEP = Math.PI / 180;
const PAGE_STEP = 15 * STEP;
const KEYS = { ArrowRight: STEP, ArrowUp: STEP, ArrowLeft: -STEP, ArrowDown: -STEP, PageUp: PAGE_STEP, PageDown: -PAGE_STEP };

const SENSE_STEP = Math.PI / 3;     // rad of crank angle over which the sense on the screen is read

/** a wrapped into (−π, π]. */
const shortest = (a) => a - TURN * Math.ceil((a - Math.PI) / TURN);

/**
 * Where a crank turns on the screen: centre the pivot and pinAt(phi) the crank pin at crank angle phi (rad),
 * both in drawing units; gives {centre, start, sense}: the pin's direction at φ = 0 (rad, the drawing's
 * axes) and ±1, the sense in which φ grows there (a drawing with y down turns a counter-clockwise φ clockwise).
 */
export function crankPlace(centre, pinAt) {
  const direction = (phi) => {
    const [x, y] = pinAt(phi);
    return Math.atan2(y - centre[1], x - centre[0]);
  };
  const start = direction(0);
  return { centre, start, sense: Math.sign(shortest(direction(SENSE_STEP) - start)) || 1 };
}

export class CrankDrag {
  /**
   * target: the drawing, {svg, crank()}, and its name if it is not the linkage drawing (a free-body diagram:
   * "its name: drag the crank …"); animation: the page's CrankAnimation.
   */
  constructor(target, animation, { t, lang }) {
    this.target = target;
    this.animation = animation;
    const svg = target.svg;
    const label = target.name ? `${target.name}: ${t.crank_turn}` : t.crank_drag;
    Object.entries({ tabindex: 0, role: "slider", "aria-label": plainText(label), "aria-valuemin": 0 })
      .forEach(([name, value]) => svg.setAttribute(name, value));
    svg.classList.add("turnable");
    const show = (phi) => {
      svg.setAttribute("aria-valuemax", Math.round(degrees(animation.cycle)));
      svg.setAttribute("aria-valuenow", Math.round(degrees(phi)));
      svg.setAttribute("aria-valuetext", `φ = ${formatNumber(degrees(phi), lang, 1)}°`);
    };
    animation.on("phi", (phi) => svg.isConnected && show(phi));     // a drawing of another variant: gone
    show(animation.phi);
    svg.addEventListener("pointerdown", (event) => {
      if (!target.crank() || event.button !== 0) return;
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
    const place = this.target.crank();
    if (!place) return;
    const { centre, start, sense } = place;
    const point = new DOMPoint(event.clientX, event.clientY).matrixTransform(this.target.svg.getScreenCTM().inverse());
    const pointer = Math.atan2(point.y - centre[1], point.x - centre[0]);
    const target = sense * (pointer - start);
    this.animation.seek(this.animation.phi + shortest(target - this.animation.phi));
  }
}
