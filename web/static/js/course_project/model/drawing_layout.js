/**
 * The course project's drawings on paper, without a DOM: millimetres from a quantity at its scale factor μ,
 * the size of a label's text, labels placed so that they do not cover each other, the A1 sheet with its
 * frame and title block (ESKD, GOST 2.301 and 2.104), the drawings laid out on it, and round ticks.
 *
 * Paper coordinates are millimetres with y pointing down (as in SVG); a quantity's plane (metres, m/s, m/s²,
 * N) has y pointing up. A scale factor μ is the quantity per millimetre of paper (μ_l in m/mm, μ_v in m/s per
 * mm, μ_a in m/s² per mm, μ_F in N/mm), so a value q is drawn q/μ mm long.
 */
import { notationParts } from "../../common/view/notation.js";

/** Paper sizes, mm (GOST 2.301): A1 landscape. */
export const A1 = { width: 841, height: 594 };
/** The frame's distance from the sheet's edges, mm: the binding margin on the left (GOST 2.104). */
const FRAME_MARGINS = { left: 20, top: 5, right: 5, bottom: 5 };
/** The title block (GOST 2.104, form 1), mm, in the frame's bottom right corner. */
const TITLE_BLOCK = { width: 185, height: 55 };
/** Font sizes of the drawings, mm (GOST 2.304: 2.5, 3.5, 5, 7). */
export const FONT = { small: 2.5, label: 3.5, caption: 5, title: 7 };
/** The mantissas of standard scale factors: 1, 2, 2.5, 4, 5 × 10ᵏ (the ESKD scales 1:1, 1:2, 1:2.5, 1:4, 1:5). */
const STANDARD_MANTISSAS = [1, 2, 2.5, 4, 5];

/** The smallest standard scale factor (1, 2, 2.5, 4, 5 × 10ᵏ per mm) at which extent fits into millimetres. */
export function standardScale(extent, millimetres) {
  if (!(extent > 0) || !(millimetres > 0)) return 1;
  const raw = extent / millimetres;
  const power = 10 ** Math.floor(Math.log10(raw));
  for (const m of [...STANDARD_MANTISSAS, 10]) {
    if (m * power >= raw * (1 - 1e-12)) return m * power;
  }
  return 10 * power;
}

/**
 * The ESKD scale of a length drawing at μ_l (m/mm): 1 mm of paper stands for 1000 μ_l mm of the machine, so
 * μ_l = 0.002 m/mm is "1:2" and μ_l = 0.0005 m/mm is "2:1"; the ratio's number as written in lang.
 */
export function eskdScale(muL, format = String) {
  const ratio = 1000 * muL;
  const rounded = (x) => Number(x.toPrecision(6));
  return ratio >= 1 ? `1:${format(rounded(ratio))}` : `${format(rounded(1 / ratio))}:1`;
}

/**
 * The placement of a quantity's plane on paper at scale mu: the points' box, margin mm around it; at(p)
 * gives a point's paper position [X, Y] (mm, y down), width and height the paper size of the box with margins.
 */
export function paperPlacement(points, mu, margin = 0) {
  const finite = points.filter((p) => p && Number.isFinite(p[0]) && Number.isFinite(p[1]));
  const xs = finite.map((p) => p[0]);
  const ys = finite.map((p) => p[1]);
  const [x0, x1] = xs.length ? [Math.min(...xs), Math.max(...xs)] : [0, 0];
  const [y0, y1] = ys.length ? [Math.min(...ys), Math.max(...ys)] : [0, 0];
  return {
    mu,
    width: (x1 - x0) / mu + 2 * margin,
    height: (y1 - y0) / mu + 2 * margin,
    at: ([x, y]) => [margin + (x - x0) / mu, margin + (y1 - y) / mu],
  };
}

// Advance widths of a sans-serif face in em, rounded up over DejaVu Sans and Arial (the faces a browser takes for
// "sans-serif"), so that a label's estimated box holds its drawn one.
const WIDE = /[A-ZА-ЯЁІЇЄҐΑ-ΩmwшщжюмфыМШЩЖЮФЫmMWω]/u;
const NARROW = /[ilj.,:;'|!Iі()\[\]]/u;
const EM = { wide: 0.86, narrow: 0.36, space: 0.34, other: 0.66 };
const ASCENT = 0.96;            // em above the base line (DejaVu Sans' ascender 0.93)
const DESCENT = 0.26;           // em below it
const SUB = { size: 0.75, drop: 0.3, rise: 0.5 };   // notation.js: a lowered run at 75 %, 0.3 em down; a raised one 0.5 em up

function advance(text) {
  let width = 0;
  for (const c of text) {
    if (c === " ") width += EM.space;
    else if (NARROW.test(c)) width += EM.narrow;
    else if (WIDE.test(c)) width += EM.wide;
    else width += EM.other;
  }
  return width;
}

/**
 * The box of a label's text (notation markup: "R_12", "μ_l = 0,002 м/мм") of font size fontSize (mm) whose
 * anchor is [x, y] on its base line, text-anchor "start", "middle" or "end": {x, y, width, height}, mm.
 * The widths are an upper estimate of a sans-serif face's, so that the drawn text lies inside the box.
 */
export function textBox(text, [x, y], fontSize, anchor = "middle") {
  let width = 0;
  let top = ASCENT;
  let bottom = DESCENT;
  for (const part of notationParts(text)) {
    if (!part.shift) {
      width += advance(part.text);
      continue;
    }
    width += SUB.size * advance(part.text);
    if (part.shift === "sub") bottom = Math.max(bottom, SUB.drop + SUB.size * DESCENT);
    else top = Math.max(top, SUB.rise + SUB.size * ASCENT);
  }
  const w = width * fontSize;
  const left = anchor === "start" ? x : anchor === "end" ? x - w : x - w / 2;
  return { x: left, y: y - top * fontSize, width: w, height: (top + bottom) * fontSize };
}

/** The area two boxes share with gap added around each (0 if they are apart by more than gap). */
function boxOverlap(a, b, gap = 0) {
  const w = Math.min(a.x + a.width, b.x + b.width) - Math.max(a.x, b.x) + gap;
  const h = Math.min(a.y + a.height, b.y + b.height) - Math.max(a.y, b.y) + gap;
  return w > 0 && h > 0 ? w * h : 0;
}

/**
 * Whether the segment [[x1, y1], [x2, y2]] passes through the box: apart if their boxes are, else by
 * Liang–Barsky clipping against the box's four edges (indices, not destructuring: it runs ~10⁵ times a drawing).
 */
function segmentCrossesBox(segment, box) {
  const x1 = segment[0][0];
  const y1 = segment[0][1];
  const x2 = segment[1][0];
  const y2 = segment[1][1];
  const right = box.x + box.width;
  const bottom = box.y + box.height;
  if ((x1 < box.x && x2 < box.x) || (x1 > right && x2 > right) || (y1 < box.y && y2 < box.y)
    || (y1 > bottom && y2 > bottom)) return false;
  const dx = x2 - x1;
  const dy = y2 - y1;
  let t0 = 0;
  let t1 = 1;
  const clip = (p, q) => {
    if (p === 0) return q >= 0;
    const r = q / p;
    if (p < 0) t0 = Math.max(t0, r);
    else t1 = Math.min(t1, r);
    return t0 <= t1;
  };
  return clip(-dx, x1 - box.x) && clip(dx, right - x1) && clip(-dy, y1 - box.y) && clip(dy, bottom - y1);
}

const NEAR_RINGS = [0, 1.2, 2.4, 3.6, 5, 6.5, 8, 10, 12.5, 15, 18];   // mm from where the drawing put the label
const FAR_RING_STEP = 3;        // mm: beyond the near rings, rings this far apart …
const FARTHEST = 90;            // … up to this distance, until a free place is found
const DIRECTIONS = 16;          // places on a near ring; a far ring has one every 2 mm of its length
const LABEL_GAP = 0.4;          // mm kept between two labels
const COVERS = 1e6;             // cost of a label covering another label, a mark or the edge (and of each mm² of it)
const CROSSES = 20;             // cost of a line of the drawing through a label

const RINGS = [...NEAR_RINGS];
for (let radius = NEAR_RINGS.at(-1) + FAR_RING_STEP; radius <= FARTHEST; radius += FAR_RING_STEP) RINGS.push(radius);
const directions = (radius) => (radius === 0 ? 1 : Math.max(DIRECTIONS, Math.ceil(Math.PI * radius)));

const shifted = (box, dx, dy) => ({ x: box.x + dx, y: box.y + dy, width: box.width, height: box.height });

/**
 * Labels placed so that no two of their boxes meet: each label in turn (most important first) takes, of the
 * places on rings around where its drawing put it, the one that covers no label placed before it, no mark
 * (boxes: pins, poles, arrowheads, fixed texts) and stays inside bounds, crossed by the fewest lines (segments),
 * nearest to where it was put; the near rings (to 18 mm) are searched whole, the far ones (to 90 mm) only
 * until a place covers nothing. labels: [{text, at: [x, y], fontSize, anchor}], at the anchor on the base
 * line; returns [{...label, x, y, box, moved}] in the same order (moved: the distance from at, mm).
 */
export function placeLabels(labels, { marks = [], segments = [], bounds = null } = {}) {
  const placed = [];
  const out = [];
  const grid = segmentGrid(segments);
  for (const label of labels) {
    const box = textBox(label.text, label.at, label.fontSize, label.anchor);
    let best = null;
    let reach = -1;
    let lines = [];
    let blockers = [];
    for (const radius of RINGS) {
      if (radius > reach) {              // the lines and boxes within reach of this ring and the next ones
        reach = radius + 2 * FAR_RING_STEP;
        lines = near(grid, segments, box, reach);
        blockers = [...placed, ...marks].filter((b) => boxOverlap(b, box, reach + LABEL_GAP) > 0);
      }
      const count = directions(radius);
      for (let i = 0; i < count; i += 1) {
        const angle = -Math.PI / 2 + 2 * Math.PI * i / count;            // above first, then clockwise
        const [dx, dy] = [radius * Math.cos(angle), radius * Math.sin(angle)];
        const candidate = shifted(box, dx, dy);
        let cost = radius;
        for (const other of blockers) {
          const shared = boxOverlap(candidate, other, LABEL_GAP);
          if (shared > 0) cost += COVERS * (1 + shared);                 // any overlap costs more than any free place
        }
        if (bounds && !inside(candidate, bounds)) cost += COVERS * (1 + outsideArea(candidate, bounds));
        for (const segment of lines) if (segmentCrossesBox(segment, candidate)) cost += CROSSES;
        if (!best || cost < best.cost) best = { dx, dy, cost };
      }
      if (best.cost <= radius || (radius >= NEAR_RINGS.at(-1) && best.cost < COVERS)) break;
    }
    const final = shifted(box, best.dx, best.dy);
    placed.push(final);
    out.push({ ...label, x: label.at[0] + best.dx, y: label.at[1] + best.dy, box: final,
      moved: Math.hypot(best.dx, best.dy) });
  }
  return out;
}

const CELL = 10;                 // mm: the side of a cell of the segments' grid

/** The segments by the grid cells their boxes cover: Map "i,j" → [indices]. */
function segmentGrid(segments) {
  const cells = new Map();
  segments.forEach(([[x1, y1], [x2, y2]], k) => {
    for (let i = Math.floor(Math.min(x1, x2) / CELL); i <= Math.floor(Math.max(x1, x2) / CELL); i += 1) {
      for (let j = Math.floor(Math.min(y1, y2) / CELL); j <= Math.floor(Math.max(y1, y2) / CELL); j += 1) {
        const key = `${i},${j}`;
        if (!cells.has(key)) cells.set(key, []);
        cells.get(key).push(k);
      }
    }
  });
  return cells;
}

/** The segments in the grid's cells within reach (mm) of the box, each once. */
function near(grid, segments, box, reach) {
  const found = new Set();
  for (let i = Math.floor((box.x - reach) / CELL); i <= Math.floor((box.x + box.width + reach) / CELL); i += 1) {
    for (let j = Math.floor((box.y - reach) / CELL); j <= Math.floor((box.y + box.height + reach) / CELL); j += 1) {
      for (const k of grid.get(`${i},${j}`) ?? []) found.add(k);
    }
  }
  return [...found].map((k) => segments[k]);
}

function inside(box, bounds) {
  return box.x >= bounds.x && box.y >= bounds.y && box.x + box.width <= bounds.x + bounds.width
    && box.y + box.height <= bounds.y + bounds.height;
}

function outsideArea(box, bounds) {
  return box.width * box.height - boxOverlap(box, bounds);
}

/** The box {x, y, width, height} of boxes and points ([x, y]), grown by pad. */
export function unionBox(items, pad = 0) {
  const xs = [];
  const ys = [];
  for (const item of items) {
    if (Array.isArray(item)) {
      if (!Number.isFinite(item[0]) || !Number.isFinite(item[1])) continue;
      xs.push(item[0]);
      ys.push(item[1]);
    } else {
      xs.push(item.x, item.x + item.width);
      ys.push(item.y, item.y + item.height);
    }
  }
  if (!xs.length) return { x: 0, y: 0, width: 2 * pad, height: 2 * pad };
  const [x0, y0] = [Math.min(...xs) - pad, Math.min(...ys) - pad];
  return { x: x0, y: y0, width: Math.max(...xs) + pad - x0, height: Math.max(...ys) + pad - y0 };
}

/**
 * The sheet's frame and title block, mm: {width, height, frame, titleBlock, area}; area is the frame's inside
 * where drawings go (the title block cut out of it when they are laid out).
 */
export function sheetFrame(paper = A1) {
  const frame = { x: FRAME_MARGINS.left, y: FRAME_MARGINS.top,
    width: paper.width - FRAME_MARGINS.left - FRAME_MARGINS.right,
    height: paper.height - FRAME_MARGINS.top - FRAME_MARGINS.bottom };
  const titleBlock = { x: frame.x + frame.width - TITLE_BLOCK.width, y: frame.y + frame.height - TITLE_BLOCK.height,
    width: TITLE_BLOCK.width, height: TITLE_BLOCK.height };
  return { width: paper.width, height: paper.height, frame, titleBlock };
}

/**
 * The title block's cells (GOST 2.104, form 1, simplified to what a course project fills in), relative to its
 * top left corner, mm: [{name, x, y, width, height, caption}]; caption: the cell holds a printed heading
 * (a text key) rather than a value. Left: the changes' header and the rows of the developer (the student and
 * the date), the group, the variant and the checker; right: the document's designation, the sheet's name, the
 * letter, mass and scale, the sheet's number and count, and the maker (the app).
 */
export function titleBlockCells() {
  const row = 5;
  const left = [7, 10, 23, 15, 10];                         // Изм., Лист, № докум., Подп., Дата
  const x = left.reduce((xs, w) => [...xs, xs.at(-1) + w], [0]);
  const cells = [];
  const cell = (name, cx, cy, width, height, caption = false) => cells.push({ name, x: cx, y: cy, width, height, caption });
  for (let r = 0; r < 6; r += 1) for (let c = 0; c < 5; c += 1) cell(`change_${r}_${c}`, x[c], r * row, left[c], row);
  ["tb_change", "tb_sheet", "tb_document", "tb_signature", "tb_date"].forEach((key, c) => cell(key, x[c], 6 * row, left[c], row, true));
  const people = [["tb_developed", "student", "date"], ["tb_group", "group", null], ["tb_variant", "variant", null],
    ["tb_checked", "checker", null]];
  people.forEach(([heading, value, date], i) => {
    const y = (7 + i) * row;
    cell(heading, 0, y, left[0] + left[1], row, true);
    cell(value, x[2], y, left[2], row);
    cell(`signature_${i}`, x[3], y, left[3], row);
    cell(date ?? `date_${i}`, x[4], y, left[4], row);
  });
  const right = 65;
  cell("designation", right, 0, 120, 15);
  cell("sheet_name", right, 15, 70, 25);
  cell("tb_letter", right + 70, 15, 15, row, true);
  cell("tb_mass", right + 85, 15, 17, row, true);
  cell("tb_scale", right + 102, 15, 18, row, true);
  cell("letter", right + 70, 20, 15, 15);
  cell("mass", right + 85, 20, 17, 15);
  cell("scale", right + 102, 20, 18, 15);
  cell("sheet_number", right + 70, 35, 25, row);
  cell("sheet_count", right + 95, 35, 25, row);
  cell("maker", right + 70, 40, 50, 15);
  cell("work_kind", right, 40, 70, 15);
  return cells;
}

/**
 * Drawings of sizes [{width, height}] (mm) laid out on a sheet in rows, in their order, gap mm apart, inside
 * the frame with pad mm to it and clear of the title block: {placed: [{x, y, oversize}] (null for one that did
 * not fit), overflow: [indices]}. A row is as high as its highest drawing; a drawing that would reach into the
 * title block starts the next row; one that fits no row is left for the next sheet, except that the first
 * drawing of a sheet is placed in its top left corner even if it is larger than the sheet (oversize: no other
 * sheet would take it).
 */
export function layOutSheet(sizes, { paper = A1, gap = 10, pad = 8 } = {}) {
  const { frame, titleBlock } = sheetFrame(paper);
  const area = { x: frame.x + pad, y: frame.y + pad, width: frame.width - 2 * pad, height: frame.height - 2 * pad };
  const block = { x: titleBlock.x - gap, y: titleBlock.y - gap, width: titleBlock.width + gap, height: titleBlock.height + gap };
  const placed = [];
  const overflow = [];
  let [x, y, rowHeight] = [area.x, area.y, 0];
  for (const [i, size] of sizes.entries()) {
    let spot = null;
    for (let tries = 0; tries < 2 && !spot; tries += 1) {
      if (x > area.x && x + size.width > area.x + area.width) [x, y, rowHeight] = [area.x, y + rowHeight + gap, 0];
      const box = { x, y, width: size.width, height: size.height };
      const fits = x + size.width <= area.x + area.width + 1e-9 && y + size.height <= area.y + area.height + 1e-9
        && boxOverlap(box, block) === 0;
      if (fits) spot = { x, y };
      else if (x > area.x) [x, y, rowHeight] = [area.x, y + rowHeight + gap, 0];
      else break;
    }
    if (!spot && !placed.some(Boolean)) {
      spot = { x: area.x, y: area.y, oversize: true };
      [x, y] = [area.x, area.y];
    }
    if (!spot) {
      placed.push(null);
      overflow.push(i);
      continue;
    }
    placed.push(spot);
    x += size.width + gap;
    rowHeight = Math.max(rowHeight, size.height);
  }
  return { placed, overflow };
}

/**
 * Round tick values over [min, max] at most every `spacing` mm of a scale mu (the value per mm): a standard
 * step (1, 2, 2.5, 4, 5 × 10ᵏ) of at least spacing·mu, the ticks at its multiples.
 */
export function roundTicks(min, max, mu, spacing = 10) {
  const step = standardScale(spacing * mu, 1);
  const first = Math.ceil(min / step - 1e-9);
  const last = Math.floor(max / step + 1e-9);
  const ticks = [];
  for (let k = first; k <= last; k += 1) ticks.push(Number((k * step).toPrecision(12)));
  return { step, ticks };
}

/**
 * A text that fits width mm: at font size, or smaller down to smallest (mm), else cut with "…" at smallest:
 * {text, size}.
 */
export function fittedText(text, width, size, smallest = FONT.small * 0.8) {
  const widthAt = (candidate, fontSize) => textBox(candidate, [0, 0], fontSize, "start").width;
  const natural = widthAt(text, size);
  if (natural <= width) return { text, size };
  const scaled = size * width / natural;
  if (scaled >= smallest) return { text, size: scaled };
  let cut = text;
  while (cut.length > 1 && widthAt(`${cut}…`, smallest) > width) cut = cut.slice(0, -1);
  return { text: `${cut}…`, size: smallest };
}
