/**
 * A preview frame's fast path for a Plotly graph: the curves (scatter, scatterpolar: lines, markers, text) of
 * a figure of the same shape as the one drawn are moved in place — each line's SVG path, marker and label is
 * placed anew through the axes Plotly laid out — with
 * no Plotly.react (whose full replot, axes and annotations included, takes several frames for a scene's
 * plots). Only what a preview needs: the axes, titles, special-position marks and hover data stay those
 * of the last drawing until the next Plotly.react (the exact answer). Where that would mislead or cannot
 * be done — a curve leaving the drawn axes' range, a trace of another kind or mode, a different number
 * of traces, gaps or points — it answers false and the caller draws with Plotly.react.
 * So that the first preview after an exact answer fits too, a view holding the family of the slider the reader
 * holds draws the exact answer with axes that hold every member of the family (familyExtents, withFamily).
 */

const SLACK = 1e-3;      // a point this fraction of its axis's span beyond it is in (under a pixel: a φ grid
                        // interpolated between members may end a rounding error past the cycle)
const within = (value, [a, b]) => {
  const slack = SLACK * Math.abs(b - a);
  return value >= Math.min(a, b) - slack && value <= Math.max(a, b) + slack;
};
const linear = (...axes) => axes.every((axis) => axis?.range && axis.type === "linear");

/**
 * How a laid-out trace maps its points to pixels: (u, v) → [x, y], or null when a point leaves the drawn
 * axes (unless clipped: a straight line that Plotly clips to the plot area, in a preview as in the exact
 * drawing); null for a trace this fast path does not draw. A cartesian trace's (x, y) go through its axes
 * ("y2" → layout.yaxis2); a polar trace's (θ in degrees, r) through the polar subplot's angular and radial
 * axes to the plane and then its x and y axes, as Plotly's scatterpolar draws them.
 */
function pixels(graph, trace, clipped) {
  const layout = graph._fullLayout;
  if (trace.type === "scatter") {
    const [xa, ya] = [layout[`xaxis${trace.xaxis.slice(1)}`], layout[`yaxis${trace.yaxis.slice(1)}`]];
    if (!linear(xa, ya)) return null;
    return (x, y) => (clipped || (within(x, xa.range) && within(y, ya.range)) ? [xa.c2p(x), ya.c2p(y)] : null);
  }
  const polar = trace.type === "scatterpolar" ? layout[trace.subplot]?._subplot : null;
  const [xa, ya] = [trace._xA, trace._yA];
  if (!polar || !linear(polar.radialAxis, xa, ya) || polar.angularAxis?.type !== "linear"
    || trace.thetaunit !== "degrees") return null;
  return (theta, r) => {      // a linear angular axis computes in radians
    if (!within(r, polar.radialAxis.range)) return null;
    const [g, angle] = [polar.radialAxis.c2g(r), polar.angularAxis.c2g(theta * Math.PI / 180)];
    return [xa.c2p(g * Math.cos(angle)), ya.c2p(g * Math.sin(angle))];
  };
}

/** Pieces of a curve between its gaps (null values) as SVG path data, or null if a point leaves the range. */
function segments(us, vs, toPixels) {
  const pieces = [];
  let current = "";
  for (let i = 0; i < vs.length; i++) {
    const [u, v] = [us[i], vs[i]];
    if (u === null || v === null || u === undefined || v === undefined) {
      if (current) pieces.push(current);
      current = "";
      continue;
    }
    const point = toPixels(u, v);
    if (!point) return null;
    current += `${current ? "L" : "M"}${point[0].toFixed(2)},${point[1].toFixed(2)}`;
  }
  if (current) pieces.push(current);
  return pieces;
}

/**
 * The points of (us, vs) that have both values, in pixels (Plotly draws no marker for a point without one: an
 * operating point among nulls), or null if one of them leaves the range.
 */
function points(us, vs, toPixels) {
  const given = (x) => x !== null && x !== undefined;
  const placed = [];
  for (let i = 0; i < vs.length; i++) if (given(us[i]) && given(vs[i])) placed.push(toPixels(us[i], vs[i]));
  return placed.every(Boolean) ? placed : null;
}

const MODES = new Set(["lines", "markers", "lines+markers", "markers+text", "lines+markers+text"]);

/**
 * The moves that draw trace (as Plotly laid it out, in its group) with next's data: [element, attribute,
 * value] for its line pieces, its markers (transform) and its text (x, y); null if that cannot be done.
 */
function moves(graph, group, trace, next) {
  if (!next || next.type !== trace.type || next.mode !== trace.mode || !MODES.has(trace.mode)) return null;
  const [us, vs] = trace.type === "scatter" ? [next.x, next.y] : [next.theta, next.r];
  const straight = trace.type === "scatter" && trace.mode === "lines" && us.length === 2;    // a tangent, a level
  const toPixels = pixels(graph, trace, straight);
  if (!toPixels) return null;
  const out = [];
  if (trace.mode.includes("lines")) {
    const paths = group.querySelectorAll("path.js-line");
    const pieces = segments(us, vs, toPixels);
    if (!pieces || pieces.length !== paths.length) return null;
    paths.forEach((path, i) => out.push([path, "d", pieces[i]]));
  }
  if (trace.mode.includes("markers") || trace.mode.includes("text")) {
    const placed = points(us, vs, toPixels);
    const markers = trace.mode.includes("markers") ? group.querySelectorAll(".points path.point") : [];
    const texts = trace.mode.includes("text") ? group.querySelectorAll(".text text") : [];
    if (!placed || (markers.length && markers.length !== placed.length) || (texts.length && texts.length !== placed.length)) return null;
    markers.forEach((marker, i) => out.push([marker, "transform", `translate(${placed[i][0]},${placed[i][1]})`]));
    texts.forEach((text, i) => out.push([text, "x", placed[i][0]], [text, "y", placed[i][1]]));
  }
  return out;
}

/** Redraw graph's curves for the figure's data in place; false if it must be drawn by Plotly.react. */
export function moveCurves(graph, data) {
  const drawn = graph._fullData;
  if (!drawn || drawn.length !== data.length || !graph._fullLayout) return false;
  const updates = [];
  const groups = graph.querySelectorAll(".scatterlayer .trace");
  if (groups.length !== data.length) return false;
  for (const group of groups) {
    const trace = group.__data__?.[0]?.trace;
    const traceMoves = trace && moves(graph, group, trace, data[trace.index]);
    if (!traceMoves) return false;
    updates.push(...traceMoves);
  }
  for (const [node, attribute, value] of updates) node.setAttribute(attribute, value);
  return true;
}

const ROOM = 0.2;     // a preview drawn by Plotly.react leaves this fraction of its data's span free each side
const FAMILY_ROOM = 0.05;     // a family's ranges: this fraction of the members' span free each side (interpolation's swing)

/** The extent [low, high] of the data on each axis Plotly would range itself: Map layout key → [low, high]. */
function extents({ data, layout }, into = new Map()) {
  const widen = (key, values) => {
    let [low, high] = into.get(key) ?? [Infinity, -Infinity];
    for (const value of values ?? []) {
      if (!Number.isFinite(value)) continue;
      if (value < low) low = value;
      if (value > high) high = value;
    }
    if (low <= high) into.set(key, [low, high]);
  };
  for (const trace of data) {
    if (trace.type === "scatter") {
      widen(`xaxis${(trace.xaxis ?? "x").slice(1)}`, trace.x);
      widen(`yaxis${(trace.yaxis ?? "y").slice(1)}`, trace.y);
    } else if (trace.type === "scatterpolar" && layout.polar) {
      widen("polar", trace.r);
    }
  }
  for (const [key, axis] of Object.entries(layout)) {       // an axis the figure ranges itself: its range
    if (/^[xy]axis\d*$/.test(key) && Array.isArray(axis?.range)) widen(`fixed ${key}`, axis.range);
  }
  return into;
}

/** A round step of a tenth to a twentieth of span: ranges rounded out to it stay the same for slightly different data. */
function roundStep(span) {
  const power = 10 ** Math.floor(Math.log10(span));
  return [1, 2, 5, 10].map((m) => m * power / 10).find((step) => span / step <= 20) ?? power;
}

/**
 * The figure with every axis Plotly would range itself fixed to its extent (Map layout key → [low, high]) with
 * room (a fraction of the span) each side, rounded out to a round step; an axis the figure ranges itself (φ,
 * Wittenbauer's diagram) gets the union of the ranges in spans ("fixed xaxis"), without room.
 */
function ranged({ data, layout }, spans, room) {
  const fixed = { ...layout };
  for (const [key, [low, high]] of spans) {
    if (key.startsWith("fixed ")) {         // ranged by the figure: the union of its ranges as it is
      const name = key.slice(6);
      const reversed = layout[name]?.range[0] > layout[name]?.range[1];
      if (layout[name]) fixed[name] = { ...layout[name], range: reversed ? [high, low] : [low, high], autorange: false };
      continue;
    }
    const extra = (high - low) * room || Math.abs(high) * room || 1;
    const step = roundStep(high - low + 2 * extra);
    const [from, to] = [Math.floor((low - extra) / step) * step, Math.ceil((high + extra) / step) * step];
    if (key === "polar") {
      fixed.polar = { ...layout.polar, radialaxis: { ...layout.polar.radialaxis, range: [0, to], autorange: false } };
      continue;
    }
    const axis = layout[key] ?? {};
    if (axis.autorange === false || axis.range) continue;         // a fixed axis (φ) stays as it is
    fixed[key] = { ...axis, range: [axis.rangemode === "tozero" ? Math.min(0, from) : from, to], autorange: false };
  }
  return { data, layout: fixed };
}

/**
 * The figure for a preview that Plotly.react must draw (a curve left the axes) without a family's ranges:
 * every axis Plotly would range automatically gets a fixed range with ROOM around the data, so the next
 * preview frames fit and are moved in place again.
 */
export function roomy(figure) {
  return ranged(figure, extents(figure), ROOM);
}

/**
 * The extents of a slider's family in one plot: figureOf(answer) → the plot's figure for a member's answer,
 * over every answered member (Map layout key → [low, high]). Drawn with these (withFamily), the exact answer's
 * axes already hold every preview the family gives, so that a preview only moves the curves (moveCurves).
 */
export function familyExtents(family, figureOf) {
  const spans = new Map();
  for (const answer of family.answers) if (answer) extents(figureOf(answer), spans);
  return spans;
}

/** The figure with its free axes fixed to the family's extents (familyExtents) and its own data, with room. */
export function withFamily(figure, spans) {
  const both = extents(figure, new Map([...spans].map(([key, span]) => [key, [...span]])));
  return ranged(figure, both, FAMILY_ROOM);
}
