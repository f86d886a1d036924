/**
 * The readiness line above the drawing: what the mechanism is now and what to do next, always in view. W
 * (Chebyshev's formula), whether the crank turns fully (the input slider runs its whole travel) or where each
 * group assembles, between its limits of assembly as the server found them exactly (GroupSpecial
 * limit_of_assembly, with `assembles_after`), a group close to a dead position, and the next step; or why the
 * mechanism is refused. Results that need the whole turn (the dynamics, the course project) wait for
 * `readiness(…).turns`.
 */
import { element } from "../../common/view/dom.js";
import { formatNumber } from "../../common/view/notation.js";
import { messageText } from "../../common/view/messages.js";
import { groupNames } from "../model/linkage.js";

const DEG = 180 / Math.PI;
const TURN = 2 * Math.PI;
const NEAR_DEAD = Math.sin(10 / DEG);       // |sin| between a group's links below sin 10°: the four-bar module's warning

/**
 * Where a group assembles, from its limits [{phi, assembles_after}] over the input's range [start, end]:
 * [[from, to], …]; over a crank's turn a stretch may run on through 0 (from > to). null: everywhere.
 */
export function assemblyRanges(limits, [start, end], periodic) {
  const sorted = [...limits].sort((a, b) => a.phi - b.phi);
  if (!sorted.length) return null;
  if (periodic) {
    return sorted.flatMap((limit, k) => (limit.assembles_after ? [[limit.phi, sorted[(k + 1) % sorted.length].phi]] : []));
  }
  const ranges = [];
  let from = sorted[0].assembles_after ? null : start;
  for (const limit of sorted) {
    if (limit.assembles_after) from = limit.phi;
    else if (from !== null) ranges.push([from, limit.phi]);
  }
  if (sorted.at(-1).assembles_after) ranges.push([from, end]);
  return ranges;
}

/**
 * What the page shows (state) and whether results over the whole turn may be asked (turns):
 * empty (no frame joint), no_input, waiting (no answer yet), refused, partial (a group does not assemble
 * everywhere: `groups` [{name, ranges}], each with other limits than the group before it), ready; with W, the
 * groups near a dead position (`near` [{name, phi, angle}]), the input's kind and pin, and whether it has no
 * group yet (bare).
 */
export function readiness({ linkage, table, refusal, special }) {
  const slider = linkage.input?.kind === "slider";
  const base = { slider, mobility: null, groups: [], near: [], turns: false, pin: linkage.input?.joint ?? null,
    bare: !linkage.groups.length };
  const frame = Object.keys(linkage.frame.joints ?? {}).length + Object.keys(linkage.frame.guides ?? {}).length;
  if (!frame) return { ...base, state: "empty" };
  if (!linkage.input) return { ...base, state: "no_input" };
  if (refusal) return { ...base, state: "refused" };
  if (!table) return { ...base, state: "waiting" };
  const names = groupNames(linkage);
  const mobility = table.outputs.structure?.W ?? null;
  const turns = Object.values(table.outputs.joints).every((rows) => rows.every(([x]) => x !== null));
  const range = slider ? linkage.input.travel : [0, TURN];
  const groups = [];
  let before = "";
  names.forEach((name, k) => {
    const limits = (special ?? []).filter((sp) => sp.kind === "limit_of_assembly" && sp.group === k);
    const key = limits.map((sp) => sp.phi.toPrecision(12)).join();
    const ranges = limits.length && key !== before ? assemblyRanges(limits, range, !slider) : null;
    if (ranges?.length) groups.push({ name, ranges });
    if (limits.length) before = key;
  });
  const near = turns ? (special ?? []).filter((sp) => sp.kind === "smallest_determinant" && sp.value < NEAR_DEAD)
    .map((sp) => ({ name: names[sp.group], phi: sp.phi, angle: Math.asin(Math.min(sp.value, 1)) * DEG })) : [];
  return { ...base, state: turns ? "ready" : "partial", mobility, groups, near, turns };
}

/** A stretch of the input in words: "φ from 221.22° through 0° to 143.90°", "s from 0.1 to 0.15 m". */
function rangeText([from, to], slider, t, lang) {
  if (slider) {
    return messageText(t.editor_ready_range_s, { from: formatNumber(from, lang, 4), to: formatNumber(to, lang, 4),
      unit: t.units_m });
  }
  const [a, b] = [from, to].map((phi) => `${formatNumber(phi * DEG, lang, 2)}°`);
  return messageText(from > to ? t.editor_ready_range_wraps : t.editor_ready_range, { from: a, to: b });
}

/** The sentences of a readiness (readiness()) in the reader's language; `reason`: a refusal's, said already. */
export function readinessText(ready, reason, t, lang) {
  const { state, slider } = ready;
  const said = { mobility: ready.mobility === null ? "" : `W = ${ready.mobility}.`, turn: "", next: "" };
  if (state === "empty") said.next = messageText(t.editor_next_frame, { tool: t.editor_mode_joint });
  else if (state === "no_input") said.next = messageText(t.editor_next_crank, { tool: t.editor_mode_crank });
  else if (state === "waiting") said.next = t.editor_next_wait;
  else if (state === "refused") {
    said.turn = `${t.editor_refused} ${reason}`;
    said.next = t.editor_next_refused;
  } else if (state === "partial") {
    said.turn = [slider ? t.editor_ready_no_full_travel : t.editor_ready_no_full_turn,
      ...ready.groups.map(({ name, ranges }) => messageText(t.editor_ready_group_assembles,
        { group: name, ranges: ranges.map((r) => rangeText(r, slider, t, lang)).join(` ${t.editor_and} `) }))].join(" ");
    said.next = t.editor_next_turn;
  } else {
    said.turn = [slider ? t.editor_ready_full_travel : t.editor_ready_full_turn,
      ...ready.near.map(({ name, phi, angle }) => messageText(t.editor_ready_near_dead,
        { group: name, phi: `${formatNumber(phi * DEG, lang, 1)}°`, angle: `${formatNumber(angle, lang, 1)}°` }))].join(" ");
    said.next = ready.bare ? messageText(t.editor_next_group, { pin: ready.pin }) : t.editor_next_ready;
  }
  return said;
}

/** The line into host (its data-state: the readiness' state, for styles and tests). */
export function renderReadiness(host, ready, reason, t, lang) {
  const said = readinessText(ready, reason, t, lang);
  host.dataset.state = ready.state;
  host.replaceChildren(
    ...(said.mobility ? [element("strong", { "data-q": "mobility", textContent: said.mobility }), " "] : []),
    ...(said.turn ? [element("span", { "data-q": "turn", textContent: said.turn }), " "] : []),
    element("span", { "data-q": "next", textContent: said.next }));
}
