/**
 * The mechanism editor page: the student places the frame's joints and guides, the crank and class-II groups
 * with the mouse; every change asks the server once for the table over the turn (the structure, positions,
 * analogs), once for the special positions and once for the plans at the cursor angle; the animation, traced
 * paths and the plot come from the table. The mechanism lives in the address (?m=…), and in files (export, import).
 */
import { Drawing } from "./view/drawing.js";
import { PointerGestures } from "./view/pointer.js";
import { DirectEdit } from "./view/drag.js";
import { keyboardEditing } from "./view/keyboard_place.js";
import { viewControls } from "./view/view_controls.js";
import { handles } from "./model/handles.js";
import { ElementList } from "./view/elements.js";
import { QuantityPlot } from "./view/plot.js";
import { renderGroupsApart } from "./view/groups_apart.js";
import { renderPlans } from "./view/plans.js";
import { renderSpecial } from "./view/special.js";
import { readiness, renderReadiness } from "./view/readiness.js";
import { renderMasses, renderOpenLinks } from "./view/masses.js";
import { addLoad, dynamicsOf, dynamicsParameter, keptOn, readDynamics, removeLoad, sceneAddress } from "./model/dynamics.js";
import { setPath } from "../common/model/dotted_paths.js";
import { renderStructure } from "./view/structure.js";
import { mechanismQuery, readMechanism } from "./model/address.js";
import { guideShapes, linkShapes, stateAt } from "./model/geometry.js";
import { PICKS, addFrameGuide, addFrameJoint, addGroup, addLinkGuide, addPoint, emptyLinkage, groupNames, guideLabel,
  guides, joints, links, normalised, requestLinkage, setCrank, setSlider, slideLabel } from "./model/linkage.js";
import { animationRow } from "./model/animation.js";
import { EditHistory } from "./model/history.js";
import { LatestRequest, refusalText, refusedGroup } from "./model/service.js";
import { frameOf, planRequest, quantities, specialRequest, tableRequest } from "./model/table.js";
import { formatNumber, plainText } from "../common/view/notation.js";
import { messageText } from "../common/view/messages.js";
import { parseDecimal } from "../common/model/decimal_input.js";

const lang = document.documentElement.lang;
const t = JSON.parse(document.getElementById("interface-texts").textContent);
const presets = JSON.parse(document.getElementById("editor-presets").textContent);
const ownScenes = JSON.parse(document.getElementById("editor-own-scenes").textContent);   // [{scene, variant, title}]
const $ = (id) => document.getElementById(id);
/** The crank's words as the page was served (notation with real subscripts), to put back after a slider. */
const CRANK_LABELS = Object.fromEntries(["editor-phi-label", "editor-omega1-label", "editor-epsilon1-label"]
  .map((id) => [id, [...$(id).childNodes].map((node) => node.cloneNode(true))]));
const DEG = Math.PI / 180;
const TURN_DEGREES = 360;
const SPIN = 60;                               // degrees of crank per second of animation

/**
 * linkage: the mechanism (the API's JSON); mode: what a click places; picked: the elements clicked so far for
 * it; table: the last answer over the turn (361 angles, 1°); refusal: the last 422 ({code, message, loc, ctx});
 * k: the cursor angle in degrees (the table's row); traced: joints whose paths are drawn; plan, special: the
 * last answers for them.
 */
const state = {
  linkage: emptyLinkage(), mode: "select", picked: [], table: null, refusal: null, k: 0, playing: false,
  traced: new Set(), plan: null, special: [], quantities: [], fitPending: false,
  dynamics: null, dynamicsKept: false, places: null, preview: null, handles: [],
};
const tables = new LatestRequest(lang);
const planner = new LatestRequest(lang);
const specials = new LatestRequest(lang);
const estimates = new LatestRequest(lang, "dynamics-estimate");
const editHistory = new EditHistory();
let recorded = null;                 // the mechanism (JSON) as the last step of the edit history left it
const stage = $("editor-drawing");

const HANDLE_WORDS = { joint: "editor_handle_joint", guide: "editor_handle_guide", guide_angle: "editor_handle_angle" };
const drawing = new Drawing(stage, { label: t.drawing, names: (kind, name) => messageText(t[HANDLE_WORDS[kind]],
  { name: kind === "joint" ? name : guideLabel(name, t) }) });
const readout = viewControls(drawing, { t, lang, onView: () => draw() });
/** Dragging a handle: the drawing follows the pointer, the table asked as it goes (view/drag.js). */
const direct = new DirectEdit({
  read: () => {
    const table = state.refusal ? null : state.table;
    return { linkage: state.linkage, table, k: state.k, s: stateAt(state.linkage, table, state.k),
      shown: table?.phi[state.k] ?? state.k * DEG };
  },
  ask: (linkage, onAnswer) => {
    if (linkage.input) tables.submit(tableRequest(linkage), onAnswer);
    else queueMicrotask(() => onAnswer({ ok: false, error: { code: null, message: "", loc: [], ctx: {} } }));
  },
  show: (linkage, table, preview, answered) => {
    Object.assign(state, { linkage, table, preview, refusal: null });
    if (answered) list.render(linkage, state.traced);
    if (preview?.stop) $("editor-prompt").textContent = t.editor_drag_stopped;
    else prompt();
    draw();
  },
  commit: (linkage, table) => {
    Object.assign(state, { linkage, preview: null });
    prompt();
    changed(true, false, table);
  },
  snapping: () => drawing.snap,
});
new PointerGestures(drawing, {
  canDrag: () => state.mode === "select" && !state.playing,
  dragStart: (id) => {
    const handle = state.handles.find((h) => h.id === id);
    return Boolean(handle) && direct.start(handle);
  },
  drag: (at) => direct.move(at),
  dragEnd: () => direct.end(),
  dragCancel: () => direct.cancel(),
  joint: (name, at) => pickJoint(name, at),
  guide: (name, at) => pickGuide(name, at),
  place: (at) => place(at),
  hover: (at) => readout.pointer(at),
  view: () => draw(),
});
keyboardEditing(drawing, { t, lang, on: { joint: (name, at) => pickJoint(name, at), guide: (name, at) => pickGuide(name, at),
  place: (at) => place(at), handle: (id) => state.handles.find((h) => h.id === id), nudge: (h, step) => direct.nudge(h, step) } });
const list = new ElementList($("editor-elements"), {
  t, lang, onEdit: (continuing) => changed(false, continuing), onStructure: () => changed(true),
  onTrace: (name, on) => {
    if (on) state.traced.add(name);
    else state.traced.delete(name);
    draw();
  },
});
const plot = new QuantityPlot($("editor-plot"), { t, lang });

/* ---- what the student does in the drawing ---- */

function setMode(mode) {
  state.mode = mode;
  state.picked = [];
  for (const button of document.querySelectorAll("[data-mode]")) button.setAttribute("aria-pressed", String(button.dataset.mode === mode));
  const onLink = mode === "point" || mode === "link_guide";
  $("editor-point-link-label").hidden = !onLink;
  if (onLink) {
    const select = $("editor-point-link");
    const keep = select.value;
    select.replaceChildren(...links(state.linkage).map(([link]) => new Option(`${t.editor_link} ${link}`, String(link))));
    if (keep) select.value = keep;
  }
  prompt();
  draw();
}

function prompt() {
  const { mode, picked, linkage } = state;
  let text = t[`editor_prompt_${mode}`] ?? "";
  if (mode === "crank" && picked.length) text = t.editor_prompt_crank_pin;
  if (mode === "slider" && picked.length) text = t.editor_prompt_slider_joint;
  if (PICKS[mode]) {
    const next = PICKS[mode][picked.length];
    text = `${mode}: ${messageText(t[`editor_prompt_pick_${next}`], { n: picked.length + 1 })}`;
    if (picked.length) text += ` (${picked.join(", ")})`;
  }
  if (mode !== "select" && mode !== "joint" && mode !== "guide" && !linkage.input && mode !== "crank" && mode !== "slider") {
    text = t.editor_prompt_crank_first;
  }
  $("editor-prompt").textContent = text;
}

function current() {
  return stateAt(state.linkage, state.table, state.k);
}

/** What the tool picks next, if it is an element: "joint" or "guide" (a click on the plane makes a new one there). */
function pickWanted() {
  const { mode, picked } = state;
  if (mode === "crank" && !picked.length) return "joint";
  if (mode === "slider" && !picked.length) return "guide";
  const next = PICKS[mode]?.[picked.length];
  return next === "joint" || next === "guide" ? next : null;
}

/** A new frame joint or guide (along x) at p, picked for the tool. */
function pickNew(kind, p) {
  state.picked.push(kind === "joint" ? addFrameJoint(state.linkage, p) : addFrameGuide(state.linkage, p));
  if (PICKS[state.mode]?.length !== state.picked.length) changed(true);       // (a complete group: added below)
  afterPick();
}

function place(p) {
  const { mode, linkage } = state;
  const wanted = pickWanted();
  if (wanted) return pickNew(wanted, p);
  if (mode === "joint") addFrameJoint(linkage, p);
  else if (mode === "guide") addFrameGuide(linkage, p);
  else if (mode === "crank" && state.picked.length === 1) setCrank(linkage, state.picked[0], p);
  else if (mode === "slider" && state.picked.length === 1) setSlider(linkage, state.picked[0], p, current().guideAt(state.picked[0]));
  else if (PICKS[mode]?.[state.picked.length] === "place") {
    const s = current();
    addGroup(linkage, mode, state.picked, p, (name) => s.joints[name], (name) => s.guideAt(name));
  } else if (mode === "point" || mode === "link_guide") {
    const link = Number($("editor-point-link").value);
    const frame = current().frameOf(link);
    if (!frame) return;
    (mode === "point" ? addPoint : addLinkGuide)(linkage, link, p, frame);
  } else return;
  finishPick();
}

function finishPick() {
  setMode("select");
  changed(true);
}

/** The next click places something (a frame element, the crank's pin, a group's inner joint, a point). */
function placing() {
  const { mode, picked } = state;
  return ["joint", "guide", "point", "link_guide"].includes(mode) || ((mode === "crank" || mode === "slider") && picked.length === 1)
    || PICKS[mode]?.[picked.length] === "place";
}

function pickJoint(name, at) {
  const { mode, picked, linkage } = state;
  if (placing() || pickWanted() === "guide") return place(at);
  if (mode === "select") {
    if (state.traced.has(name)) state.traced.delete(name);
    else if (!(name in linkage.frame.joints)) state.traced.add(name);
    list.render(linkage, state.traced);
    draw();
    return;
  }
  if (mode === "crank" && !picked.length) {
    if (!(name in linkage.frame.joints)) return;
    picked.push(name);
  } else if (PICKS[mode]?.[picked.length] === "joint" && !picked.includes(name)) {
    picked.push(name);
  } else return;
  afterPick();
}

function pickGuide(name, at) {
  const { mode, picked } = state;
  if (placing() || pickWanted() === "joint") place(at);
  else if (mode === "slider" && !picked.length && name in state.linkage.frame.guides) {
    picked.push(name);
    afterPick();
  } else if (PICKS[mode]?.[picked.length] === "guide" && !picked.includes(name)) {
    picked.push(name);
    afterPick();
  }
}

function afterPick() {
  const { mode, picked, linkage } = state;
  if (PICKS[mode] && picked.length === PICKS[mode].length) {
    const s = current();
    addGroup(linkage, mode, picked, null, (n) => s.joints[n], (n) => s.guideAt(n));
    finishPick();
    return;
  }
  prompt();
  draw();
}

/* ---- the table, the plans, the address ---- */

function writeAddress() {
  const query = mechanismQuery(state.linkage, lang);
  if (state.dynamics) query.set("d", dynamicsParameter(state.dynamics));
  history.replaceState(null, "", `?${query}`);
  const reason = !state.linkage.input || sliderInput() ? t.editor_dynamics_needs_crank
    : !turnsFully() ? t.editor_project_needs_turn : !state.dynamics ? t.editor_project_needs_dynamics : "";
  const hrefs = reason ? null
    : Object.fromEntries(ownScenes.map((own) => [own.scene, sceneAddress(own, query.get("m"), state.dynamics, lang)]));
  renderOpenLinks($("editor-open-dynamics"), hrefs, ownScenes);
  $("editor-open-dynamics-reason").textContent = reason;
  writeProjectLink(query);
  for (const link of document.querySelectorAll("a[data-lang]")) {
    query.set("lang", link.dataset.lang);
    link.href = `?${query}`;
  }
}

/**
 * The course project's link (/project with the same m and d), disabled with the reason while the mechanism has
 * no crank, cannot turn fully (a joint undefined somewhere over the turn) or has no masses and loads yet.
 */
function writeProjectLink(query) {
  const link = $("editor-course-project");
  const turns = turnsFully();
  const reason = !state.linkage.input || sliderInput() ? t.editor_project_needs_crank
    : !turns ? t.editor_project_needs_turn : !state.dynamics ? t.editor_project_needs_dynamics : "";
  const project = new URLSearchParams({ lang, m: query.get("m") });
  if (state.dynamics) project.set("d", dynamicsParameter(state.dynamics));
  if (reason) link.removeAttribute("href");
  else link.href = `/project?${project}`;
  link.setAttribute("aria-disabled", String(Boolean(reason)));
  link.classList.toggle("disabled", Boolean(reason));
  $("editor-course-project-reason").textContent = reason;
}

/** Whether every joint is defined over the whole turn (travel): results over a cycle may be asked. */
function turnsFully() {
  return Boolean(state.table && !state.refusal && Object.values(state.table.outputs.joints)
    .every((rows) => rows.every(([x]) => x !== null)));
}

/**
 * A change of the mechanism as a step of the edit history (model/history.js): the mechanism as the last step
 * left it is recorded, unless nothing changed or the change goes on (`continuing`: a slider still dragged; its
 * release makes the step). A drag of the drawing shows its frames without changed() and calls it once at the end.
 */
function remember(continuing = false) {
  const json = JSON.stringify(state.linkage);
  if (!continuing && recorded !== null && json !== recorded) editHistory.record(recorded);
  if (!continuing) recorded = json;
  $("editor-undo").disabled = !editHistory.canUndo;
  $("editor-redo").disabled = !editHistory.canRedo;
}

/** Undo (back) or redo the last step: the mechanism it left is shown, and written in the address, again. */
function step(back) {
  const json = back ? editHistory.undo(recorded) : editHistory.redo(recorded);
  if (json === null) return;
  recorded = json;
  state.linkage = normalised(JSON.parse(json));
  setMode("select");
  changed(true);
}

/** known: the table already answered for this very mechanism (a drag's last answer), shown without asking again. */
function changed(structural, continuing = false, known = null) {
  remember(continuing);
  writeAddress();
  if (structural) list.render(state.linkage, state.traced);
  const linkage = requestLinkage(state.linkage);
  stage.dataset.state = "waiting";
  if (!linkage) {
    state.table = null;
    state.refusal = null;
    showAnswer();
    return;
  }
  const asked = JSON.stringify(linkage);
  specials.submit(specialRequest(linkage), (answer) => {
    state.special = answer.ok ? answer.data.outputs.special : [];
    state.specialOf = asked;           // the readiness line takes the limits of this mechanism only
    showSpecial();
  });
  const answered = (answer) => {
    if (answer.ok) {
      state.table = answer.data;
      state.refusal = null;
    } else {
      state.refusal = answer.error;
    }
    showAnswer();
    writeAddress();
    askEstimate(linkage);                // once the table tells whether the crank turns fully
  };
  if (known) answered({ ok: true, data: known });
  else tables.submit(tableRequest(linkage), answered);
}

/* ---- masses and loads ---- */

/**
 * The estimate for the mechanism as it is now: the whole table, or (kept values) rows for new links only. Not
 * asked for a crank that cannot turn fully (the table says so; the server would refuse it, as every dynamics
 * endpoint does): the masses say why instead.
 */
function askEstimate(linkage) {
  if (sliderInput()) {
    showMasses();
    return;
  }
  if (!turnsFully()) {
    estimates.cancel();
    state.places = null;
    $("editor-masses-status").textContent = state.refusal
      ? refusalText(state.refusal, t, groupNames(state.linkage)) : t.editor_project_needs_turn;
    showMasses();
    writeAddress();
    return;
  }
  estimates.submit({ linkage }, (answer) => {
    if (answer.ok) {
      const estimate = dynamicsOf(answer.data);
      state.places = answer.data.load_places;
      state.dynamics = state.dynamics && state.dynamicsKept ? keptOn(state.dynamics, estimate, state.places) : estimate;
      $("editor-masses-status").textContent = state.dynamicsKept ? "" : t.editor_masses_estimated;
    } else {
      state.places = null;
      $("editor-masses-status").textContent = refusalText(answer.error, t, groupNames(state.linkage));
    }
    showMasses();
    writeAddress();
    const shown = $("editor-masses");
    shown.dataset.estimates = String(Number(shown.dataset.estimates ?? 0) + 1);    // answers taken (tests wait on it)
  });
}

function showMasses() {
  const edited = (redraw) => {
    state.dynamicsKept = true;
    $("editor-masses-status").textContent = "";
    if (redraw) showMasses();
    writeAddress();
  };
  renderMasses($("editor-masses"), sliderInput() ? null : state.dynamics, {
    t, lang, places: state.places,
    onEdit: (path, value) => {
      setPath(state.dynamics, path, value);
      edited(false);
    },
    onAddLoad: (key) => {
      addLoad(state.dynamics, state.places, key);
      edited(true);
    },
    onRemoveLoad: (list, index) => {
      removeLoad(state.dynamics, list, index);
      edited(true);
    },
  });
}

/** The input's words: the crank's angle φ and ω₁, ε₁, or the input slider's s and v₁, a₁. */
function inputLabels() {
  const slider = sliderInput();
  const words = { "editor-phi-label": t.editor_travel_s, "editor-omega1-label": t.editor_v1, "editor-epsilon1-label": t.editor_a1 };
  $("editor-plot-heading").textContent = slider ? t.editor_plot_s : t.editor_plot;
  for (const [id, text] of Object.entries(words)) {
    if (slider) $(id).textContent = text;
    else $(id).replaceChildren(...CRANK_LABELS[id].map((node) => node.cloneNode(true)));
  }
  $("editor-play").textContent = state.playing ? t.editor_pause : slider ? t.editor_play_slider : t.editor_play;
}

function showAnswer() {
  inputLabels();
  const { table, refusal } = state;
  const reason = refusal ? refusalText(refusal, t, groupNames(state.linkage)) : null;
  const refusals = new Map(refusal && refusedGroup(refusal) !== null ? [[refusedGroup(refusal), reason]] : []);
  if (JSON.stringify([...refusals]) !== JSON.stringify([...list.refusals])) {    // not during a drag that closes
    list.refusals = refusals;
    list.render(state.linkage, state.traced);
  }
  renderStructure($("editor-structure"), refusal || !table ? null : table.outputs.structure, reason, t);
  renderGroupsApart($("editor-apart"), state.linkage, refusal ? null : table, current(), t);
  showSpecial();
  fillQuantities();
  if (state.fitPending && table) {
    state.fitPending = false;
    fit();
  }
  draw();
  stage.dataset.state = refusal ? "refused" : table ? "ready" : "empty";
  stage.dataset.answers = String(Number(stage.dataset.answers ?? 0) + 1);
  askPlan();
}

function showSpecial() {
  const shown = state.refusal || !state.table;
  renderSpecial($("editor-special"), shown ? [] : state.special ?? [], lang, (phi) => setAngle(frameOf(state.table, phi)),
    sliderInput(), t.units_m);
  showReadiness();
}

/** The readiness line above the drawing (view/readiness.js): W, the turn or where each group assembles, what next. */
function showReadiness() {
  const { linkage, table, refusal } = state;
  const special = state.specialOf === JSON.stringify(linkage) ? state.special : null;
  renderReadiness($("editor-readiness"), readiness({ linkage, table, refusal, special }),
    refusal ? refusalText(refusal, t, groupNames(linkage)) : "", t, lang);
}

function askPlan() {
  if (state.playing || !state.table || state.refusal) {
    if (!state.table || state.refusal) renderPlans($("editor-plans"), null, t, lang);
    return;
  }
  const read = (id, fallback) => {
    const value = parseDecimal($(id).value, lang);
    return value.error ? fallback : value.value;
  };
  const phi = state.table.phi[state.k];
  $("editor-plans").dataset.state = "waiting";
  planner.submit(planRequest(state.linkage, phi, read("editor-omega1", 10), read("editor-epsilon1", 0)), (answer) => {
    state.plan = answer.ok ? answer.data.outputs.plan : null;
    showPlans();
    $("editor-plans").dataset.state = answer.ok ? "ready" : "refused";
  });
}

/** The plans with the scales the student typed (empty: chosen to fit). */
function showPlans() {
  const scale = (id) => {
    const read = parseDecimal($(id).value, lang);
    return read.error ? null : read.value;
  };
  renderPlans($("editor-plans"), state.plan, t, lang, { velocity: scale("editor-mu-v"), acceleration: scale("editor-mu-a") },
    sliderInput());
}

function fillQuantities() {
  const select = $("editor-quantity");
  const all = state.table && !state.refusal ? quantities(state.table, (pair) => slideLabel(pair, t)) : [];
  const keep = select.value || all.find((q) => q.id.startsWith("slides:"))?.id || all[0]?.id;
  select.replaceChildren(...all.map((q) => new Option(plainText(q.label), q.id)));
  if (keep && all.some((q) => q.id === keep)) select.value = keep;
  state.quantities = all;
  drawPlot();
}

function drawPlot() {
  const q = state.quantities?.find((item) => item.id === $("editor-quantity").value);
  plot.draw(state.table?.phi ?? [], q, sliderInput() ? state.table.phi[state.k] : state.k * DEG, sliderInput());
}

/* ---- drawing and animation ---- */

function draw() {
  const { linkage, table, preview } = state;
  const s = current();
  Object.assign(s.joints, preview?.joints);            // a dragged joint where the pointer has it
  state.handles = state.mode === "select" && !state.playing ? handles(linkage, s, drawing.handleReach) : [];
  const clickable = PICKS[state.mode]?.[state.picked.length]
    ?? ({ crank: "joint", slider: state.picked.length ? null : "guide" }[state.mode] ?? null);
  const jointNames = [...joints(linkage).keys()];
  const traces = table && !state.refusal ? [...state.traced].filter((n) => table.outputs.joints[n])
    .map((n) => table.outputs.joints[n].map(([x, y]) => (x === null ? null : [x, y]))) : [];
  drawing.draw({
    frameJoints: linkage.frame.joints,
    joints: Object.fromEntries(jointNames.map((n) => [n, s.joints[n] ?? null])),
    guides: guideShapes(s, [...guides(linkage).keys()]).map((g) => ({ ...g, label: guideLabel(g.name, t) })),
    links: table && !state.refusal ? linkShapes(linkage, table, s) : [],
    traces, picked: new Set(state.picked), clickable, handles: state.handles, stop: preview?.stop ?? null,
  });
  const travel = sliderInput() && state.table ? state.table.phi[state.k] : undefined;
  $("editor-phi-value").textContent = travel === undefined ? `φ = ${formatNumber(state.k, lang, 0)}°`
    : `s = ${formatNumber(travel, lang, 3)} ${t.units_m}`;
}

/** Whether the input link is a slider: the table's rows are then its travel s (m), not the crank's degrees. */
function sliderInput() {
  return state.linkage.input?.kind === "slider";
}

function setAngle(k) {
  state.k = ((k % TURN_DEGREES) + TURN_DEGREES) % TURN_DEGREES;
  $("editor-phi").value = String(state.k);
  draw();
  if (!state.playing) {
    drawPlot();
    askPlan();
    if (!state.refusal) renderGroupsApart($("editor-apart"), state.linkage, state.table, current(), t);
  }
}

let started = null;
function frame(now) {
  if (!state.playing) return;
  started ??= now - (state.k / SPIN) * 1000;
  setAngle(animationRow(Math.floor(((now - started) / 1000) * SPIN), TURN_DEGREES, sliderInput()));
  requestAnimationFrame(frame);
}

function play(on) {
  state.playing = on;
  started = null;
  $("editor-play").setAttribute("aria-pressed", String(on));
  inputLabels();
  if (on) requestAnimationFrame(frame);
  else setAngle(state.k);
}

function fit() {
  const points = Object.values(state.linkage.frame.joints);
  if (state.table) {
    for (const rows of Object.values(state.table.outputs.joints)) points.push(...rows.filter((p) => p[0] !== null));
  }
  drawing.fit(points);
}

function load(linkage, status = "", dynamics = null) {
  state.linkage = normalised(linkage);
  state.dynamics = dynamicsOf(dynamics);
  state.dynamicsKept = Boolean(dynamics);
  $("editor-masses-status").textContent = dynamics ? t.editor_masses_from_preset : "";
  state.traced = new Set(Object.keys(state.linkage.groups.at(-1)?.points ?? {}).slice(0, 1));
  state.fitPending = Boolean(state.linkage.input);      // a fit once its table is there; the view stays otherwise
  $("editor-file-status").textContent = status;
  setMode("select");
  changed(true);
}

/* ---- tools ---- */

for (const button of document.querySelectorAll("[data-mode]")) button.addEventListener("click", () => setMode(button.dataset.mode));
$("editor-phi").addEventListener("input", () => setAngle(Number($("editor-phi").value)));
$("editor-play").addEventListener("click", () => play(!state.playing));
$("editor-fit").addEventListener("click", () => {
  fit();
  draw();
});
$("editor-quantity").addEventListener("change", drawPlot);
for (const id of ["editor-omega1", "editor-epsilon1"]) $(id).addEventListener("change", askPlan);
for (const id of ["editor-mu-v", "editor-mu-a"]) $(id).addEventListener("change", showPlans);
$("editor-omega1").value = formatNumber(10, lang, 1);
$("editor-epsilon1").value = formatNumber(0, lang, 1);

const presetSelect = $("editor-preset");
presetSelect.append(...presets.map((p) => new Option(p.title, p.name)));
presetSelect.addEventListener("change", () => {
  const preset = presets.find((p) => p.name === presetSelect.value);
  if (preset) load(preset.linkage, preset.source, preset.dynamics);
});
$("editor-new").addEventListener("click", () => {
  presetSelect.value = "";
  load(emptyLinkage());
});
$("editor-undo").addEventListener("click", () => step(true));
$("editor-redo").addEventListener("click", () => step(false));
$("editor-estimate").addEventListener("click", () => {
  state.dynamicsKept = false;
  const linkage = requestLinkage(state.linkage);
  if (linkage) askEstimate(linkage);
});
$("editor-export").addEventListener("click", () => {
  const text = JSON.stringify({ mechanism: "general", linkage: state.linkage,
    ...(state.dynamics ? { dynamics: state.dynamics } : {}) }, null, 1);
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([text], { type: "application/json" }));
  link.download = "mechanism.json";
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
});
$("editor-import").addEventListener("change", async (event) => {
  const file = event.target.files?.[0];
  if (!file) return;
  try {
    const data = JSON.parse(await file.text());
    load(data.linkage ?? data, `${t.editor_imported}: ${file.name}`, data.linkage && data.dynamics?.masses ? data.dynamics : null);
  } catch {
    $("editor-file-status").textContent = t.editor_import_failed;
  }
  event.target.value = "";
});
$("copy-link").addEventListener("click", async () => {
  try {
    await navigator.clipboard.writeText(location.href);
    $("editor-file-status").textContent = t.editor_link_copied;
  } catch {
    $("editor-file-status").textContent = location.href;
  }
});
document.addEventListener("keydown", (event) => {
  if (event.key === "Escape") {
    direct.cancel();
    setMode("select");
  }
  const key = event.key.toLowerCase();        // Ctrl+Z undoes; Ctrl+Shift+Z and Ctrl+Y redo
  if ((key === "z" || key === "y") && (event.ctrlKey || event.metaKey) && !event.target.closest("input, select")) {
    event.preventDefault();
    step(key === "z" && !event.shiftKey);
  }
});

const fromAddress = readMechanism();
if (fromAddress) {
  try {
    load(fromAddress, "", readDynamics());
    $("editor-masses-status").textContent = "";
  } catch {
    load(emptyLinkage());
  }
} else {
  setMode("select");
  changed(true);
}
