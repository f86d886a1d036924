/**
 * Which row of the table the animation shows at a step of its clock. A crank turns on and on: the rows
 * follow one another and the last is followed by the first. A slider input runs its travel out and back:
 * its first and last rows are the ends of the travel, so after the last row the rows go back down to the
 * first instead of jumping there. No DOM.
 */
export function animationRow(step, rows, outAndBack) {
  const last = rows - 1;
  if (!outAndBack || last < 1) return ((step % rows) + rows) % rows;
  const phase = ((step % (2 * last)) + 2 * last) % (2 * last);
  return phase <= last ? phase : 2 * last - phase;
}
