/**
 * Where a slider's thumb stands for a value. A linear slider's position is its value; a logarithmic one
 * (slider.log, e.g. a stiffness c from 10² to 10⁷ N·m/rad) runs evenly in log10 of the value over
 * LOG_POSITIONS steps, and its values keep LOG_DIGITS significant digits.
 */
const LOG_POSITIONS = 1000;
export const LOG_DIGITS = 3;

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
