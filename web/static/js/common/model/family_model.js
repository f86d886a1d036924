/**
 * A slider's family (POST /api/v1/family): the scene's answer at several values of one slider, every other
 * value fixed, and the answer between them by the contract's interpolation rule. No DOM.
 *
 * Rule (the server checks its families with the same rule): for a value v between members k and k+1
 * (positions in log v for a logarithmic slider) with weight w = (v − v_k)/(v_{k+1} − v_k),
 *   a number in both                  → (1 − w)·a + w·b
 *   null in either                    → null
 *   arrays of equal length            → element by element (numbers, [x, y] joints, lists of objects; two
 *                                        objects whose texts differ, e.g. a special position's kind, are not
 *                                        the same quantity: the nearer member's object)
 *   objects                           → key by key (the nearer member's keys)
 *   anything else (strings, booleans, arrays of different length) and everything under
 *   "warnings", "numerics" and "study" → the nearer member's leaf.
 * A cubic interval (the family's orders[k] = 3) draws each number that the 4 members of its stencil
 * (k − 1 … k + 2, moved inside the range at its ends) all hold, at the same place of the same structure, as
 * Lagrange's cubic through them, Σ ℓᵢ·fᵢ (in the same coordinate as w); where one of the 4 lacks it or holds
 * null, the number is linear as above. A nearest interval (orders[k] = 0: a coarse family's interval not shown
 * within the tolerance) gives the nearer member's answer whole: a true answer of a nearby value.
 * A value equal to a member's gives that member's answer as it is; an array the two members share (the same
 * object: a family's "shared" arrays, withShared) is passed through as it is.
 *
 * Families are kept by the request with the slider's paths removed (familyKey): the same other values
 * give the same family, whichever value the slider had when it was asked for.
 */
import { setPath } from "./dotted_paths.js";

const NEAREST_ONLY = new Set(["warnings", "numerics", "study"]);

/** The strings of an object, as one text (its identity: a special position's kind); "" for anything else. */
function texts(item) {
  if (item === null || typeof item !== "object" || Array.isArray(item)) return "";
  return JSON.stringify(Object.entries(item).filter(([, value]) => typeof value === "string"));
}

const number = (x) => typeof x === "number";

/**
 * Mix of two members' leaves a and b at weight w (0 → a, 1 → b); outer (a cubic interval): {trees, weights},
 * the 4 stencil members' leaves at the same place and their Lagrange weights, or undefined (linear).
 */
export function blend(a, b, w, outer) {
  if (a === b) return a;
  if (number(a) && number(b)) return outer && outer.trees.every(number) ? cubic(outer, (t) => t) : (1 - w) * a + w * b;
  if (a === null || b === null) return null;
  if (Array.isArray(a)) {
    if (!Array.isArray(b) || a.length !== b.length) return w < 0.5 ? a : b;
    const trees = outer && outer.trees.every((t) => Array.isArray(t) && t.length === a.length) ? outer.trees : null;
    const mixed = new Array(a.length);
    for (let i = 0; i < a.length; i++) {
      const [x, y] = [a[i], b[i]];
      if (number(x) && number(y)) {
        mixed[i] = trees && trees.every((t) => number(t[i])) ? cubic(outer, (t) => t[i]) : (1 - w) * x + w * y;
      } else if (texts(x) === texts(y)) {
        const inner = trees && trees.every((t) => t[i] !== null && t[i] !== undefined && texts(t[i]) === texts(x))
          ? { trees: trees.map((t) => t[i]), weights: outer.weights } : undefined;
        mixed[i] = blend(x, y, w, inner);
      } else {
        mixed[i] = w < 0.5 ? x : y;
      }
    }
    return mixed;
  }
  if (typeof a === "object" && typeof b === "object" && !Array.isArray(b)) {
    const [near, far] = w < 0.5 ? [a, b] : [b, a];
    const objects = outer && outer.trees.every((t) => t !== null && typeof t === "object" && !Array.isArray(t));
    const mixed = {};
    for (const [key, value] of Object.entries(near)) {
      if (NEAREST_ONLY.has(key) || !(key in far)) {
        mixed[key] = value;
        continue;
      }
      const inner = objects && outer.trees.every((t) => key in t)
        ? { trees: outer.trees.map((t) => t[key]), weights: outer.weights } : undefined;
      mixed[key] = blend(a[key], b[key], w, inner);
    }
    return mixed;
  }
  return w < 0.5 ? a : b;
}

/** Σ ℓᵢ·fᵢ over the 4 stencil leaves (pick: the number of each). */
function cubic({ trees, weights }, pick) {
  return weights[0] * pick(trees[0]) + weights[1] * pick(trees[1])
    + weights[2] * pick(trees[2]) + weights[3] * pick(trees[3]);
}

/** The first of the 4 members whose cubic draws interval k of count members (server/families/family.py, stencils). */
export function stencilStart(k, count) {
  return Math.min(Math.max(k - 1, 0), Math.max(count - 4, 0));
}

/** Lagrange's weights of the cubic through the nodes (4 coordinates) at x. */
function lagrange(nodes, x) {
  return nodes.map((xi, i) => nodes.reduce((product, xj, j) => (j === i ? product : product * (x - xj) / (xi - xj)), 1));
}

/**
 * Where value falls among the family's members: {k, w} with w ∈ [0, 1] towards member k + 1 (and, inside a
 * cubic interval, stencil: {trees, weights}, its 4 members and their Lagrange weights at value), or null
 * when it is outside the family or a neighbour was refused (no answer to interpolate from).
 */
export function memberInterval(family, value) {
  const { values, answers } = family;
  const position = family.log ? Math.log : (v) => v;
  if (!(value >= values[0] && value <= values.at(-1)) || (family.log && value <= 0)) return null;
  let k = 0;
  while (k < values.length - 2 && value > values[k + 1]) k++;
  if (values.length === 1) return answers[0] ? { k: 0, w: 0 } : null;
  const [low, high] = [position(values[k]), position(values[k + 1])];
  const along = Math.min(1, Math.max(0, (position(value) - low) / (high - low)));
  const w = family.orders?.[k] === 0 ? Math.round(along) : along;     // 0: the nearer member, a true answer
  const needed = w === 0 ? [k] : w === 1 ? [k + 1] : [k, k + 1];
  if (!needed.every((i) => answers[i])) return null;
  if (w > 0 && w < 1 && family.orders?.[k] === 3) {
    const first = stencilStart(k, values.length);
    const members = answers.slice(first, first + 4);
    if (members.length === 4 && members.every(Boolean)) {
      const nodes = values.slice(first, first + 4).map(position);
      return { k, w, stencil: { trees: members, weights: lagrange(nodes, position(value)) } };
    }
  }
  return { k, w };
}

/** The answer the family gives for value (see the rule above), or null where it gives none. */
export function interpolate(family, value) {
  const at = memberInterval(family, value);
  if (!at) return null;
  const { answers } = family;
  if (at.w === 0) return answers[at.k];
  if (at.w === 1) return answers[at.k + 1];
  return blend(answers[at.k], answers[at.k + 1], at.w, at.stencil);
}

/** Key of the family of the slider that sets these paths (and of the fields asked): the request body with them removed. */
export function familyKey(body, paths, fields = []) {
  const rest = structuredClone(body);
  for (const path of paths) setPath(rest, path, undefined);
  return JSON.stringify([paths, rest, fields]);
}

/**
 * A packed array's values (server/families/family.py, Packed): the integers k as differences of its order along the
 * first axis, column by column; x = 10^exp10 · k, null where the step is null (order 1 only).
 */
function unpackedArray({ exp10, order, deltas }) {
  const scale = exp10 < 0 ? (k) => k / 10 ** -exp10 : (k) => k * 10 ** exp10;     // 10^|e| exact: a decimal's double
  const step = (sum, d) => (Array.isArray(d) ? d.map((x, i) => step(sum?.[i], x)) : d === null ? sum : (sum ?? 0) + d);
  const value = (sum, d) => (Array.isArray(d) ? d.map((x, i) => value(sum[i], x)) : d === null ? null : scale(sum));
  let steps = deltas;
  if (order === 2) {         // first differences: d_0 = e_0, d_1 = e_1, d_i = d_(i−1) + e_i
    let sum;
    steps = deltas.map((e, i) => (i === 0 ? e : (sum = step(sum, e))));
  }
  let sum;
  return steps.map((d) => {
    sum = step(sum, d);
    return value(sum, d);
  });
}

const isObject = (x) => x !== null && typeof x === "object" && !Array.isArray(x);
const isPacked = (x) => isObject(x) && Array.isArray(x.deltas) && typeof x.exp10 === "number" && Object.keys(x).length === 3;

/** A tree with its packed arrays as arrays of numbers (and nulls). */
function unpacked(tree) {
  if (isPacked(tree)) return unpackedArray(tree);
  if (!isObject(tree)) return tree;
  return Object.fromEntries(Object.entries(tree).map(([key, value]) => [key, unpacked(value)]));
}

/** shared merged into own, object by object (a new object wherever something is added; arrays by reference). */
function merged(shared, own) {
  const whole = { ...own };
  for (const [key, value] of Object.entries(shared)) {
    whole[key] = isObject(value) ? merged(value, isObject(own[key]) ? own[key] : {}) : value;
  }
  return whole;
}

/**
 * A family as sent (POST /api/v1/family) with each member's answer whole: a packed family's arrays unpacked
 * and its "shared" arrays merged into every answered member (the same array objects in each: the rule
 * passes them through). A family sent unpacked is returned as it is.
 */
export function received(family) {
  const { shared, ...rest } = family;
  if (!shared) return rest;
  const common = unpacked(shared);
  return { ...rest, answers: family.answers.map((own) => (own ? merged(common, unpacked(own)) : own)) };
}
