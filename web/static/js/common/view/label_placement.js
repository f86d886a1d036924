/**
 * The labels of a drawing placed where they can be read: each label in turn (most important first) stays where
 * its part put it if its box meets no label already placed, no drawn part it would hide (pins, blocks, bars,
 * arrows: the obstacles) and no edge of the drawing; otherwise it moves to the nearest place around that is
 * free (rings of CANDIDATE_ANGLES directions at growing distances), or, with no free place within reach,
 * to the place where it covers least, a label counting far more than a part and an edge most.
 * Boxes are measured on the screen (client pixels), so that labels of layers moved by a transform (the cells
 * of a group drawing) are compared as they are seen; a move is written back in the text's own units. Every box
 * is measured before any label moves (one layout of the page, not one per label), and each label is compared
 * only with the boxes of the cells of a grid it reaches.
 * A drawing that moves many times a second (a preview while a slider moves) may instead keep each label at the
 * offset from where its part put it that the last placement gave it (keepPlaces), measuring nothing.
 */
const RINGS = [4, 8, 13, 19, 26, 34, 43, 53];           // drawing units from where the part put the label
const CANDIDATE_ANGLES = 16;
const MARGIN = 1.5;                                     // px kept between two labels
const LABEL_WEIGHT = 50;                                // a label covered costs this many times a part covered
const EDGE_WEIGHT = 200;
const SAMPLE = 6;                                       // px between the boxes that stand for a line

const box = (r) => ({ left: r.left, top: r.top, right: r.right, bottom: r.bottom });
const moved = (b, dx, dy) => ({ left: b.left + dx, top: b.top + dy, right: b.right + dx, bottom: b.bottom + dy });

/** The area (px²) two boxes share, each grown by margin / 2. */
function shared(a, b, margin) {
  const w = Math.min(a.right, b.right) - Math.max(a.left, b.left) + margin;
  const h = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top) + margin;
  return w > 0 && h > 0 ? w * h : 0;
}

/** The area (px²) of a box beyond the frame. */
function beyond(b, frame) {
  const area = (b.right - b.left) * (b.bottom - b.top);
  const w = Math.max(0, Math.min(b.right, frame.right) - Math.max(b.left, frame.left));
  const h = Math.max(0, Math.min(b.bottom, frame.bottom) - Math.max(b.top, frame.top));
  return area - w * h;
}

/**
 * Boxes (px) that stand for a drawn element: a line or a straight path by small boxes along it (its own box
 * would cover the whole rectangle it spans diagonally), anything else by its box.
 */
function obstacleBoxes(node) {
  const r = node.getBoundingClientRect();
  if (!r.width && !r.height) return [];
  if (node.tagName !== "line") return [box(r)];
  const matrix = node.getScreenCTM();
  if (!matrix) return [];
  const [x1, y1, x2, y2] = ["x1", "y1", "x2", "y2"].map((name) => Number(node.getAttribute(name)));
  const a = new DOMPoint(x1, y1).matrixTransform(matrix);
  const b = new DOMPoint(x2, y2).matrixTransform(matrix);
  const steps = Math.max(1, Math.ceil(Math.hypot(b.x - a.x, b.y - a.y) / SAMPLE));
  const half = Math.max(1.5, Number.parseFloat(getComputedStyle(node).strokeWidth) / 2 || 1.5);
  return Array.from({ length: steps + 1 }, (_, i) => {
    const [x, y] = [a.x + (b.x - a.x) * i / steps, a.y + (b.y - a.y) * i / steps];
    return { left: x - half, top: y - half, right: x + half, bottom: y + half };
  });
}

/** Boxes filed by the cells (CELL px squares) they touch, to find those near a box without looking at all. */
class BoxGrid {
  #cells = new Map();

  #keys(b, each) {
    for (let i = Math.floor(b.left / CELL); i <= Math.floor(b.right / CELL); i += 1) {
      for (let j = Math.floor(b.top / CELL); j <= Math.floor(b.bottom / CELL); j += 1) each(`${i} ${j}`);
    }
  }

  add(b) {
    this.#keys(b, (key) => {
      if (!this.#cells.has(key)) this.#cells.set(key, []);
      this.#cells.get(key).push(b);
    });
  }

  /** The boxes in the cells that region touches (each once). */
  near(region) {
    const found = new Set();
    this.#keys(region, (key) => this.#cells.get(key)?.forEach((b) => found.add(b)));
    return [...found];
  }
}

const CELL = 48;                                        // px: the grid's cells
const REACH = RINGS.at(-1);                             // drawing units a label may move

const where = new WeakMap();        // text → {from: [x, y] where its part put it, to: [x, y] where it was placed}

/**
 * Place texts (SVG <text>s with x and y attributes, most important first; hidden ones are left alone) inside
 * the svg's box, off each other and off the obstacles (SVG elements). Returns nothing; moves the texts.
 */
export function placeLabels(svg, texts, obstacles = []) {
  const frameRect = svg.getBoundingClientRect();
  const ctm = svg.getScreenCTM();
  if (!frameRect.width || !ctm) return;
  const frame = box(frameRect);
  const unit = Math.hypot(ctm.a, ctm.b) || 1;           // px per drawing unit
  const parts = new BoxGrid();
  for (const part of obstacles.flatMap(obstacleBoxes)) parts.add(part);
  const starts = texts.map((text) => text.getBoundingClientRect());     // measured before anything moves
  const placed = new BoxGrid();
  const moves = [];
  texts.forEach((text, index) => {
    const start = starts[index];
    if (!start.width) return;
    const own = box(start);
    const reach = REACH * unit + MARGIN + 2;            // px: every candidate place and its margin
    const region = { left: own.left - reach, top: own.top - reach, right: own.right + reach, bottom: own.bottom + reach };
    const [near, others] = [parts.near(region), placed.near(region)];
    const cost = (b) => EDGE_WEIGHT * beyond(b, frame)
      + LABEL_WEIGHT * others.reduce((sum, other) => sum + shared(b, other, MARGIN), 0)
      + near.reduce((sum, part) => sum + shared(b, part, 0), 0);
    let best = { dx: 0, dy: 0, cost: cost(own) };
    for (const radius of RINGS) {
      if (best.cost === 0) break;
      for (let i = 0; i < CANDIDATE_ANGLES; i += 1) {
        const angle = Math.PI / 2 + 2 * Math.PI * i / CANDIDATE_ANGLES;     // below first, then round
        const [dx, dy] = [radius * unit * Math.cos(angle), radius * unit * Math.sin(angle)];
        const c = cost(moved(own, dx, dy));
        if (c < best.cost - 1e-9) best = { dx, dy, cost: c };
        if (best.cost === 0) break;
      }
    }
    moves.push([text, best.dx / unit, best.dy / unit]);
    placed.add(moved(own, best.dx, best.dy));
  });
  for (const [text, dx, dy] of moves) {
    const from = [Number(text.getAttribute("x")), Number(text.getAttribute("y"))];
    const to = [from[0] + dx, from[1] + dy];
    if (dx || dy) {
      text.setAttribute("x", to[0]);
      text.setAttribute("y", to[1]);
    }
    where.set(text, { from, to });
  }
}

/**
 * Each text placed before (placeLabels) and put by its part somewhere else since is moved by the offset its
 * last placement gave it; a text its part has not moved since stays; a text never placed stays where it is.
 */
export function keepPlaces(texts) {
  for (const text of texts) {
    const last = where.get(text);
    if (!last) continue;
    const [x, y] = [Number(text.getAttribute("x")), Number(text.getAttribute("y"))];
    if (x === last.to[0] && y === last.to[1]) continue;
    const to = [x + last.to[0] - last.from[0], y + last.to[1] - last.from[1]];
    text.setAttribute("x", to[0]);
    text.setAttribute("y", to[1]);
    where.set(text, { from: [x, y], to });
  }
}

/** Everything a label of a linkage or force drawing should leave visible. */
export const DRAWN_PARTS = "circle.pin, rect.block, .frame-pivot, line.ground, line.bar, line.slot, line.force-shaft, path.force-head, .moment path.force-shaft";
