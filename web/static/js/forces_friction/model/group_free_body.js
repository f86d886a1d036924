/**
 * The free bodies of a general mechanism's kinetostatics (POST /api/v1/forces, mechanism "general"), read from
 * the answer's free_body: {phi, bodies: [{group, kind, links, points, loads, reactions, friction,
 * friction_circles, balancing_moment?}]}, one body per Assur group (in reverse order of attachment) and the
 * crank last. No DOM: what each body carries, as symbols, points (m) and vectors (N), and the free bodies at
 * the cursor's angle, asked for anew (free_body_phi) once the cursor rests.
 *
 * Symbols (notation markup): a reaction "R34" (link 3 on link 4, 0 the frame) → R₃₄; a friction moment
 * "M34" → M_f34, a friction force "F05" → F_f05; gravity "G4" → G₄; an inertia force "F_in4" → Φ₄, an inertia
 * moment "M_in4" → M_Φ4; a useful load "F_E/ram" → P (on E/ram).
 */
import { ApiClient } from "../../common/model/api.js";

const REST_MS = 250;          // the cursor rests this long before the bodies at its angle are asked for

/** "R34" → "R_{34}": a name of the answer as a symbol with its subscript. */
export function symbolOf(name, kind = "") {
  if (kind === "gravity") return `G_{${name.slice(1)}}`;
  if (kind === "inertia") return name.startsWith("M_in") ? `M_{Φ${name.slice(4)}}` : `Φ_{${name.slice(4)}}`;
  if (kind === "useful") return "P";
  const [, letters, digits] = name.match(/^([A-Za-z]+?)(\d+)$/) ?? [];
  if (!letters) return name;
  return kind === "friction" ? `${letters}_{f${digits}}` : `${letters}_{${digits}}`;
}

/**
 * The parts of one free body: forces {symbol, at, force, kind}, moments {symbol, at, moment, kind}
 * (at: where it is drawn, the link's first point for an inertia moment), friction circles {at, radius}.
 * A reaction on the body is drawn at its pair; the same pair's reaction on the group's other link (R54 beside
 * R45) is inner to the group and left out of the group's picture (it is the readings' business).
 */
export function bodyParts(body) {
  const links = new Set(body.links);
  const first = Object.values(body.points)[0];
  const forces = [];
  const moments = [];
  for (const load of body.loads) {
    if (isVector(load.force)) forces.push({ symbol: symbolOf(load.name, load.kind), at: load.at, force: load.force, kind: load.kind });
    else if (Number.isFinite(load.moment) && load.moment !== 0) moments.push({ symbol: symbolOf(load.name, load.kind), at: first, moment: load.moment, kind: load.kind });
  }
  const outer = body.reactions.filter((r) => !innerReaction(r.name, links));
  for (const r of outer.filter((reaction) => isVector(reaction.force))) forces.push({ symbol: symbolOf(r.name), at: r.at, force: r.force, kind: "reaction", name: r.name });
  for (const f of body.friction) {
    if (innerReaction(f.name, links)) continue;
    if (isVector(f.force)) forces.push({ symbol: symbolOf(f.name, "friction"), at: f.at, force: f.force, kind: "friction" });
    else if (Number.isFinite(f.moment) && f.moment !== 0) moments.push({ symbol: symbolOf(f.name, "friction"), at: f.at, moment: f.moment, kind: "friction" });
  }
  if (Number.isFinite(body.balancing_moment)) {
    const pivot = body.reactions.find((r) => r.name.startsWith("R0"))?.at ?? first;
    moments.push({ symbol: "balancing", at: pivot, moment: body.balancing_moment, kind: "balancing" });
  }
  const circles = Object.entries(body.friction_circles ?? {})
    .map(([pair, radius]) => ({ pair, at: body.points[pair], radius })).filter((c) => c.at && c.radius > 0);
  return { forces, moments, circles, reactions: outer };
}

/** A force the answer gives (where the mechanism self-locks its reactions are null). */
const isVector = (v) => Array.isArray(v) && v.length === 2 && v.every(Number.isFinite);

/** A reaction between two links of the same group (R45 and R54 inside the group 4–5) is not an outer load. */
function innerReaction(name, links) {
  const digits = name.match(/(\d)(\d)$/);
  return Boolean(digits) && links.has(Number(digits[1])) && links.has(Number(digits[2]));
}

/** The free bodies of the latest whole-cycle answer, then those at the cursor's angle once it rests there. */
export class GroupFreeBody {
  /** model: the scene's DynamicsModel (its request); onBodies(freeBody) runs with each free_body to draw. */
  constructor(model, lang, onBodies) {
    this.model = model;
    this.onBodies = onBodies;
    this.api = new ApiClient("forces", lang, () => {});
    this.timer = null;
    this.shown = null;
  }

  /** The whole-cycle answer's free bodies (at its free_body_phi). */
  take(data) {
    this.grid = data.phi;
    this.shown = data.free_body;
    this.onBodies(data.free_body);
  }

  /** The cursor is at phi (rad): once it rests there, ask for the bodies at that angle (unless shown already). */
  at(phi) {
    clearTimeout(this.timer);
    if (!this.shown || this.#near(phi, this.shown.phi)) return;
    this.timer = setTimeout(() => {
      const body = { ...this.model.request(), free_body_phi: phi };
      this.api.submit("free_body", body, (answer) => {
        if (!answer.ok || !answer.data.free_body) return;
        this.shown = answer.data.free_body;
        this.onBodies(this.shown);
      });
    }, REST_MS);
  }

  /** Within half a grid step of the angle shown (the answer draws the bodies at the nearest grid angle). */
  #near(phi, shownPhi) {
    const step = this.grid?.length > 1 ? (this.grid[this.grid.length - 1] - this.grid[0]) / (this.grid.length - 1) : 0.01;
    const turn = 2 * Math.PI;
    const d = ((phi - shownPhi) % turn + 1.5 * turn) % turn - turn / 2;
    return Math.abs(d) <= step / 2;
  }
}
