/**
 * Where a slider's thumb stands for a value. A linear slider's position is its value; a logarithmic one
 * (slider.log, e.g. a stiffness c from 10² to 10⁷ N·m/rad) runs evenly in log10 of the value over
 * LOG_POSITIONS steps, and its values keep LOG_DIGITS significant digits. From the keyboard a logarithmic
 * slider steps on a grid of KEY_STEPS_PER_DECADE steps per decade (1,00; 1,12; 1,26; … ×10^(1/20), about
 * 12 % a step), PAGE_STEPS of them at a time with PageUp/PageDown (a quarter of a decade, ×1,78).
 */
const LOG_POSITIONS = 1000;
export const LOG_DIGITS = 3;
const KEY_STEPS_PER_DECADE = 20;
const PAGE_STEPS = 5;
const ON_GRID = 0.05;

/** Key → [steps on the grid (signed), or "min"/"max"]. */
const KEYS = {
  ArrowUp: 1, ArrowRight: 1, ArrowDown: -1, ArrowLeft: -1, PageUp: PAGE_STEPS, PageDown: -PAGE_STEPS,
  Home: "min", End: "max",
};

/**
 * The value a logarithmic slider at value takes when key is pressed, or null for a key it does not handle:
 * the next grid point(s) of KEY_STEPS_PER_DECADE a decade in the key's sense (a value between grid points
 * first moves to the neighbouring one), kept within [min, max] and to LOG_DIGITS digits.
 */
export function logKeyValue(slider, value, key) {
  if (!Object.hasOwn(KEYS, key)) return null;
  const steps = KEYS[key];
  if (typeof steps === "string") return slider[steps];
  // a grid value kept to LOG_DIGITS digits lies up to 0,04 of a step off its grid point: it counts as on it
  const grid = Math.log10(value) * KEY_STEPS_PER_DECADE;
  const from = steps > 0 ? Math.floor(grid + ON_GRID) : Math.ceil(grid - ON_GRID);
  const next = Number((10 ** ((from + steps) / KEY_STEPS_PER_DECADE)).toPrecision(LOG_DIGITS));
  return Math.min(slider.max, Math.max(slider.min, next));
}

/** {min, max, step} of the range input and the maps position → value and value → position. */
export function sliderScale(slider) {
  if (!slider.log) {
    return { min: slider.min, max: slider.max, step: slider.step, value: (p) => p, position: (v) => v };
  }
  const [low, high] = [Math.log10(slider.min), Math.log10(slider.max)];
  const clamp = (v) => Math.min(slider.max, Math.max(slider.min, v));
  return {
    min: 0, max: LOG_POSITIONS, step: 1,
    value: (p) => clamp(Number((10 ** (low + (high - low) * p / LOG_POSITIONS)).toPrecision(LOG_DIGITS))),
    position: (v) => (Math.log10(v) - low) / (high - low) * LOG_POSITIONS,
  };
}
