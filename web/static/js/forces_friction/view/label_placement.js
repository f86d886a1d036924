/**
 * Labels of a drawing that do not cover each other: each label in turn, if its box meets one of the labels
 * already placed, moves to the nearest free place around where its part put it (rings of CANDIDATE_ANGLES
 * directions at growing distances); a label with no free place within reach stays where it covers least.
 * Boxes are the texts' getBBox() in drawing units (their layer must have no transform of its own); a
 * label also keeps inside the drawing's edges where it can.
 */
const RINGS = [5, 10, 16, 23, 31, 40];                  // drawing units from where the part put the label
const CANDIDATE_ANGLES = 12;
const MARGIN = 1;                                       // drawing units kept between two labels

function overlap(a, b) {
  const w = Math.min(a.x + a.width, b.x + b.width) - Math.max(a.x, b.x) + MARGIN;
  const h = Math.min(a.y + a.height, b.y + b.height) - Math.max(a.y, b.y) + MARGIN;
  return w > 0 && h > 0 ? w * h : 0;
}

const covered = (box, placed) => placed.reduce((sum, other) => sum + overlap(box, other), 0);
const shifted = (box, dx, dy) => ({ x: box.x + dx, y: box.y + dy, width: box.width, height: box.height });

const FAR = 1e5;                                        // drawing units: "everything beyond the edge"

/** Boxes that cover everything outside the drawing's box {x, y, width, height}, so labels stay within it. */
function outside({ x, y, width, height }) {
  return [{ x: x - FAR, y: y - FAR, width: FAR, height: 2 * FAR + height },
    { x: x + width, y: y - FAR, width: FAR, height: 2 * FAR + height },
    { x: x - FAR, y: y - FAR, width: 2 * FAR + width, height: FAR },
    { x: x - FAR, y: y + height, width: 2 * FAR + width, height: FAR }];
}

/**
 * Place texts (SVG <text> nodes with x and y attributes, shown ones only, most important first) so that
 * their boxes do not intersect, and stay inside bounds (the drawing's box in drawing units) if given.
 */
export function separateLabels(texts, bounds = null) {
  const placed = bounds ? outside(bounds) : [];
  for (const text of texts) {
    const box = text.getBBox();
    if (!box.width) continue;
    let best = { dx: 0, dy: 0, cover: covered(box, placed) };
    for (const radius of RINGS) {
      if (best.cover === 0) break;
      for (let i = 0; i < CANDIDATE_ANGLES && best.cover > 0; i += 1) {
        const angle = Math.PI / 2 + 2 * Math.PI * i / CANDIDATE_ANGLES;       // below first, then round
        const [dx, dy] = [radius * Math.cos(angle), radius * Math.sin(angle)];
        const cover = covered(shifted(box, dx, dy), placed);
        if (cover < best.cover) best = { dx, dy, cover };
      }
    }
    if (best.dx || best.dy) {
      text.setAttribute("x", Number(text.getAttribute("x")) + best.dx);
      text.setAttribute("y", Number(text.getAttribute("y")) + best.dy);
    }
    placed.push(shifted(box, best.dx, best.dy));
  }
}
