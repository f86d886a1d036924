/**
 * The instructor's assignment form: reads the rows (fixed value, or a per-student range; whether the
 * student may move the slider), the toggles, the questions with their tolerances (and, by kind, the angles a
 * student may choose or the expression over readouts), attempts and deadline, posts them to
 * /api/v1/assignments and shows the students' link and the private results link. Numbers are typed in text
 * fields and read by decimal_input.js (a decimal comma in ru/uk; what is ambiguous is refused, in the page's
 * language, before anything is sent). A 422 answer names the field and the reason, shown beside the form.
 */
import { decimalMessage, parseDecimal } from "../../common/model/decimal_input.js";
import { element } from "../../common/view/dom.js";

const form = document.getElementById("assignment-form");
const t = JSON.parse(document.getElementById("interface-texts").textContent);
const errorLine = document.getElementById("builder-error");
const lang = form.dataset.lang;
let problems = [];            // the fields refused while the form is read: [{ input, message }]

const shown = (x) => (lang === "en" ? String(x) : String(x).replace(".", ","));

/** Why a number field's text is refused (null: it is fine), and its value. */
function judge(input) {
  const parsed = parseDecimal(input.value, lang);
  if (parsed.error === "empty" && input.classList.contains("optional")) return { value: null, message: null };
  if (parsed.error) return { value: null, message: decimalMessage(parsed.error, input.value, t) };
  const { min, max } = input.dataset;
  if (input.classList.contains("whole") && !Number.isInteger(parsed.value)) {
    return { value: null, message: t.number_not_whole };
  }
  if (min !== undefined && max !== undefined && (parsed.value < Number(min) || parsed.value > Number(max))) {
    return { value: null, message: t.number_out_of_range.replace("{text}", input.value.trim())
      .replace("{min}", shown(min)).replace("{max}", shown(max)) };
  }
  return { value: parsed.value, message: null };
}

function mark(input, message) {
  input.setCustomValidity(message ?? "");
  if (message) input.setAttribute("aria-invalid", "true");
  else input.removeAttribute("aria-invalid");
}

/** The number in a field; a refused one is marked and remembered in `problems`, and reads as null. */
function number(input) {
  const { value, message } = judge(input);
  mark(input, message);
  if (message) problems.push({ input, message });
  return value;
}

const problemText = (list) => list.map(({ input, message }) => `${input.dataset.label}: ${message}`).join("; ");

function sliderRule(row) {
  const field = (name) => row.querySelector(`[name="${name}"]`);
  const rule = {};
  if (field("vary").checked) {
    rule.vary = { min: number(field("vary_min")), max: number(field("vary_max")) };
    const step = number(field("vary_step"));
    if (step !== null) rule.step = step;
  } else {
    rule.value = number(field("value"));
  }
  if (field("free").checked) {
    const span = rule.vary ?? { min: Number(row.dataset.min), max: Number(row.dataset.max) };
    rule.free = { min: span.min, max: span.max };
  }
  return rule;
}

function toggles() {
  const chosen = {};
  for (const select of form.querySelectorAll(".toggle-rule")) {
    const options = JSON.parse(form.querySelector(`.toggle-options[data-toggle="${select.dataset.toggle}"]`).textContent);
    chosen[select.dataset.toggle] = options[Number(select.value)];
  }
  return chosen;
}

/** One picked question: its tolerance, and by kind the angles offered or the expression. */
function questionPick(box) {
  const pick = form.querySelector(`.question-pick[data-question="${box.value}"]`);
  const field = (name) => pick.querySelector(`[name="${name}-${box.value}"]`);
  const chosen = { id: box.value };
  const percent = number(field("tolerance"));
  if (percent !== null) chosen.tolerance = percent / 100;
  if (pick.dataset.kind === "at_angle") {
    chosen.angle = { min: number(field("angle_min")), max: number(field("angle_max")), step: number(field("angle_step")) };
  } else if (pick.dataset.kind === "combination") {
    chosen.expression = field("expression").value.trim();
  }
  return chosen;
}

function questions() {
  return [...form.querySelectorAll('input[name="question"]:checked')].map(questionPick);
}

/** The editor's mechanism {m, d} of a variant that takes it from the address (a course project of one's own), or
 * null. */
function ownMechanism() {
  const data = document.getElementById("own-mechanism");
  return data ? JSON.parse(data.textContent) : null;
}

function spec() {
  const sliders = {};
  for (const row of form.querySelectorAll(".slider-rule")) sliders[row.dataset.slider] = sliderRule(row);
  const deadline = form.querySelector("#deadline").value;
  return {
    scene: form.dataset.scene, variant: form.dataset.variant, lang: form.dataset.lang,
    ...(ownMechanism() ? { mechanism: ownMechanism() } : {}),
    title: form.querySelector("#title").value.trim(), sliders, toggles: toggles(), questions: questions(),
    attempts: number(form.querySelector("#attempts")),
    reveal_answers: form.querySelector("#reveal").checked,
    deadline: deadline ? new Date(deadline).toISOString() : null,     // the instructor's local time, sent in UTC
  };
}

/** A 422 answer in words: "sliders → lambda → vary: the range must lie within 1.3 … 6". */
function reason(payload, status) {
  const detail = Array.isArray(payload?.detail) ? payload.detail[0] : null;
  if (!detail) return `${t.assignment_failed} (HTTP ${status})`;
  const where = detail.loc.filter((part) => part !== "body").join(" → ");
  return `${t.assignment_failed}: ${where ? `${where}: ` : ""}${detail.msg}`;
}

function showLinks(created) {
  const links = document.getElementById("assignment-links");
  for (const [id, url] of [["student-link", created.student_url], ["results-link", created.results_url]]) {
    const link = document.getElementById(id);
    link.href = url;
    link.textContent = url;
  }
  document.getElementById("variants-count").textContent = `${t.assignment_variants_count}: ${created.variants}`;
  links.hidden = false;
  links.scrollIntoView({ block: "nearest" });
  showTurning(created.id);
}

/** A course project: how many of a sample of the variants turn fully (only those are handed out). */
async function showTurning(id) {
  const response = await fetch(`/api/v1/assignments/${encodeURIComponent(id)}?lang=${form.dataset.lang}`);
  const turning = response.ok ? (await response.json()).turning : null;
  if (!turning) return;
  document.getElementById("variants-count").append(" ", element("span", { id: "variants-turning",
    textContent: t.assignment_variants_turning.replace("{turn}", turning.turn).replace("{checked}", turning.checked) }));
}

/** A row's range fields are open when "per student" is ticked, its value field when it is not. */
function syncRow(row) {
  const varied = row.querySelector('[name="vary"]').checked;
  for (const name of ["vary_min", "vary_max", "vary_step"]) row.querySelector(`[name="${name}"]`).disabled = !varied;
  row.querySelector('[name="value"]').disabled = varied;
}

for (const row of form.querySelectorAll(".slider-rule")) {
  row.querySelector('[name="vary"]').addEventListener("change", () => syncRow(row));
  syncRow(row);                  // a box ticked before this module ran (or kept by the browser on reload)
}

/** A prediction's plots open once it is closed, unless another picked question hides the same plots: say so. */
function syncPredictionNotes() {
  const picks = [...form.querySelectorAll(".question-pick")];
  const picked = (pick) => pick.querySelector('input[name="question"]').checked;
  const label = (pick) => pick.querySelector("label").textContent.trim();
  for (const prediction of picks.filter((pick) => pick.dataset.kind === "prediction")) {
    const hides = new Set(JSON.parse(prediction.dataset.hides));
    const blocking = picks.filter((pick) => pick !== prediction && pick.dataset.kind !== "prediction" && picked(pick)
      && JSON.parse(pick.dataset.hides).some((name) => hides.has(name)));
    const note = prediction.querySelector(".prediction-conflict");
    note.hidden = !(picked(prediction) && blocking.length);
    note.textContent = t.questions_prediction_conflict.replace("{questions}", blocking.map(label).join("; "));
  }
}

for (const box of form.querySelectorAll('input[name="question"]')) box.addEventListener("change", syncPredictionNotes);
syncPredictionNotes();

/** A number field says on leaving it if its text is refused, and the message goes as soon as the text is
 * mended while typing (not on leaving: the line shrinking under a click could move the button away). */
for (const input of form.querySelectorAll("input.decimal")) {
  input.addEventListener("change", () => {
    const { message } = judge(input);
    mark(input, message);
    if (message) errorLine.textContent = problemText([{ input, message }]);
  });
  input.addEventListener("input", () => {
    if (judge(input).message) return;
    mark(input, null);
    if (!form.querySelector('[aria-invalid="true"]')) errorLine.textContent = "";
  });
}

form.addEventListener("submit", async (event) => {
  event.preventDefault();
  errorLine.textContent = "";
  problems = [];
  const body = spec();
  if (problems.length) {                   // nothing is sent while a number is refused
    errorLine.textContent = problemText(problems);
    problems[0].input.focus();
    return;
  }
  const button = form.querySelector("#create-assignment");
  button.disabled = true;
  try {
    const response = await fetch("/api/v1/assignments", {
      method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
    const payload = await response.json().catch(() => null);
    if (response.ok) showLinks(payload);
    else errorLine.textContent = reason(payload, response.status);
  } catch (error) {
    errorLine.textContent = `${t.assignment_failed}: ${error}`;
  } finally {
    button.disabled = false;
  }
});
