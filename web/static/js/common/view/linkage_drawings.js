/**
 * How each mechanism is drawn from its joints table (joint names of POST /api/v1/kinematics):
 *   crank   crank pivot and crank pin (for the crank circle and the special-position marks)
 *   pivots  joints fixed to the frame, drawn with a hatched support
 *   links   bars between joints; labels: letters and their offsets in drawing units
 *   extent  points (metres) the drawing needs besides the joints' paths
 *   frame   fixed parts other than pivots (guides, bearings)
 *   parts   moving parts other than bars (blocks, the yoke), drawn under the bars: returns their update
 */
import { bar, block, guide, screenAngle } from "./linkage_parts.js";

const YOKE_HALF_SLOT = 1.25;        // × l₁: the yoke's slot reaches beyond the crank pin
const YOKE_ROD = 3.4;               // × l₁: rod length from the yoke to its free end
const YOKE_BEARING = [1.6, 2.2];    // × l₁: frame bearing of the yoke rod, always around the rod
const ROD_GAP = 5;                  // drawing units from the rod's axis to its bearing
const SLIDER = [40, 22];            // slider block, drawing units
const GUIDE_MARGIN = 0.3;           // × l₁: guide beyond the slider's stroke

export const DRAWINGS = {
  sine: {
    crank: ["O", "A"],
    pivots: ["O"],
    links: [["O", "A"]],
    labels: { O: [-24, 14], A: [9, -10] },
    extent: ({ l1 }) => [[-l1, -YOKE_HALF_SLOT * l1], [(1 + YOKE_ROD) * l1, YOKE_HALF_SLOT * l1]],
    frame(layer, scale, { l1 }) {
      const [x0, y] = scale.point([YOKE_BEARING[0] * l1, 0]);
      const [x1] = scale.point([YOKE_BEARING[1] * l1, 0]);
      guide(layer, x0, x1, y - ROD_GAP, -1);
      guide(layer, x0, x1, y + ROD_GAP, 1);
    },
    parts(layer, scale, { l1 }) {
      const rod = block(layer, YOKE_ROD * l1 * scale.k, 2 * ROD_GAP - 2, "rod");
      const yoke = block(layer, 18, 2 * YOKE_HALF_SLOT * l1 * scale.k, "slot");
      const stone = block(layer, 12, 18);
      return (points) => {
        const [x, y] = points.yoke;
        rod.update([x + YOKE_ROD * l1 * scale.k / 2, y]);
        yoke.update(points.yoke);
        stone.update(points.A);
      };
    },
  },

  slider_crank: {
    crank: ["O", "A"],
    pivots: ["O"],
    links: [["O", "A"], ["A", "B"]],
    labels: { O: [-24, 14], A: [9, -10], B: [-4, -18] },
    extent({ l1, e }, table) {
      const xs = table.outputs.joints.B.map((p) => p[0]);
      return [[Math.min(...xs) - GUIDE_MARGIN * l1, e], [Math.max(...xs) + GUIDE_MARGIN * l1, e]];
    },
    frame(layer, scale, params, table) {
      const [[x0, y], [x1]] = this.extent(params, table).map(scale.point);
      guide(layer, x0, x1, y + SLIDER[1] / 2);
    },
    parts(layer) {
      const slider = block(layer, ...SLIDER);
      return (points) => slider.update(points.B);
    },
  },

  slotted_link: {
    crank: ["A", "B"],
    pivots: ["A", "C"],
    links: [["A", "B"]],
    labels: { A: [-24, 14], B: [10, -10], C: [-24, 14] },
    extent: () => [],
    parts(layer) {
      const lever = bar(layer, "bar lever");     // from C through the block B
      const stone = block(layer, 28, 16);
      return (points) => {
        lever.update(points.C, points.lever_end);
        stone.update(points.B, screenAngle(points.C, points.lever_end));
      };
    },
  },

  four_bar: {
    crank: ["A", "B"],
    pivots: ["A", "D"],
    links: [["A", "B"], ["B", "C"], ["D", "C"]],
    labels: { A: [-24, 14], B: [-6, -12], C: [8, -12], D: [13, 14] },
    extent: () => [],
  },
};
