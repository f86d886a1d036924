/**
 * The student's side of an assignment page: their data (the variant's values, read from the scene the
 * server embedded), and the questions with an answer field each. Answers go to
 * POST /api/v1/assignments/{id}/submissions; the server says right or wrong at once and, only once a
 * question is closed (right, or no attempt left), what the correct value was.
 */
import { element } from "../../common/view/dom.js";
import { formatQuantity, labelledValue } from "../../common/view/notation.js";
import { byId, lang, scene, t } from "../../common/view/page_data.js";
import { decimalMessage, parseDecimal } from "../../common/model/decimal_input.js";

const assignment = JSON.parse(byId("assignment-data").textContent);
const base = `/api/v1/assignments/${encodeURIComponent(assignment.id)}`;
const SHOWN_DIGITS = 6;
const BUSY_TRIES = 6;               // a busy server (503 or 429 with Retry-After) is asked again this often

/** A number typed with a decimal comma (ru, uk) or point, digit groups spaced ("1 234,5"); null if it is
 * not one or is ambiguous ("1,234.5", "2,5,1"; decimal_input.js). */
export function parseAnswer(text) {
  return parseDecimal(text, lang).value ?? null;
}

/** Why a typed answer is not read as a number, in the page's language. */
function numberRefusal(text) {
  const { error } = parseDecimal(text, lang);
  return error === "empty" ? t.assignment_not_a_number : decimalMessage(error, text, t);
}

// --- kinds of question beyond one readout (at_angle, prediction): kept apart from the common panel ------

const degreesText = (x) => formatQuantity(x, lang, 6);

function angleRangeText(grid) {
  return t.assignment_angle_hint.replace("{min}", degreesText(grid.min)).replace("{max}", degreesText(grid.max))
    .replace("{step}", degreesText(grid.step));
}

/** The hint under a question of another kind: the angles offered, or that the plots open afterwards. */
function kindHint(state) {
  if (state.kind === "at_angle") return element("p", { className: "hint angle-hint", textContent: angleRangeText(state.angle) });
  if (state.kind === "prediction") return element("p", { className: "hint prediction-hint", textContent: t.assignment_prediction_hint });
  return null;
}

/** The angle field of an at_angle question (null for the other kinds). */
function angleField(state) {
  if (state.kind !== "at_angle") return null;
  return element("input", { type: "text", inputMode: "decimal", id: `angle-${state.id}`, className: "angle",
    autocomplete: "off", size: 6, "aria-label": t.assignment_angle, placeholder: t.assignment_angle });
}

/** What the submission adds for the question's kind: { body } or { message } when the angle is refused. */
function kindPart(state, angleInput) {
  if (!angleInput) return { body: {} };
  const angle = parseAnswer(angleInput.value);
  const { min, max, step } = state.angle;
  const k = angle === null ? NaN : (angle - min) / step;
  if (angle === null || angle < min - 1e-9 || angle > max + 1e-9 || Math.abs(k - Math.round(k)) > 1e-9) {
    return { message: angleRangeText(state.angle) };
  }
  return { body: { angle } };
}

/** A prediction once closed: its plots open, so the page is asked again (the server now sends them). */
function openLockedPanels(state, feedback) {
  if (state.kind !== "prediction" || !state.locks?.length || !(state.right || state.attempts_left === 0)) return;
  feedback.textContent += ` · ${t.assignment_prediction_open}`;
  setTimeout(() => location.reload(), 1200);
}

function showValues() {
  const variant = scene.variants[0];
  const parts = variant.sliders.map((slider) => labelledValue(slider.label[lang], formatQuantity(slider.default, lang, 6)));
  for (const toggle of variant.toggles) parts.push(`${toggle.label[lang]}: ${toggle.option_labels[0][lang]}`);
  const line = byId("assignment-values");
  line.textContent = `${t.assignment_your_data}: ${parts.join("; ")}`;
  if (variant.sliders.some((slider) => !slider.locked)) {       // the student may explore: a way back
    const mine = new URLSearchParams({ lang, student: assignment.student });
    line.append(" · ", element("a", { id: "back-to-variant", href: `${location.pathname}?${mine}`,
      textContent: t.assignment_back_to_mine }));
  }
}

function feedbackText(state) {
  if (state.right) return `✓ ${t.assignment_right}`;
  const last = state.answers.length ? `✗ ${t.assignment_wrong}. ` : "";
  return state.attempts_left > 0 ? `${last}${t.assignment_attempts_left}: ${state.attempts_left}`
    : `${last}${t.assignment_no_attempts}`;
}

function questionItem(state) {
  const input = element("input", { type: "text", inputMode: "decimal", id: `answer-${state.id}`,
    autocomplete: "off", "aria-label": state.label });
  const button = element("button", { type: "submit", className: "button", textContent: t.assignment_check });
  const feedback = element("p", { className: "feedback", id: `feedback-${state.id}`, role: "status" });
  const correct = element("p", { className: "correct-value", id: `correct-${state.id}` });
  const angleInput = angleField(state);
  const form = element("form", { className: "answer-form", noValidate: true },
    ...(angleInput ? [element("span", { textContent: "φ =" }), angleInput,
      element("span", { className: "unit", textContent: "°" })] : []), input,
    element("span", { className: "unit", textContent: state.unit }), button);
  const item = element("li", { className: "question", id: `question-${state.id}` },
    element("p", { className: "question-label", textContent: state.label }),
    element("p", { className: "hint", textContent: `${t.assignment_tolerance}: ±${formatQuantity(state.tolerance * 100, lang)} %` }),
    ...[kindHint(state)].filter(Boolean), form, feedback, correct);

  function show(next) {
    item.classList.toggle("right", next.right);
    item.classList.toggle("wrong", !next.right && next.answers.length > 0);
    feedback.textContent = feedbackText(next);
    const closed = next.right || next.attempts_left === 0 || !assignment.info.open;
    input.disabled = button.disabled = closed;
    if (angleInput) angleInput.disabled = closed;
    if (next.correct_value !== null && next.correct_value !== undefined) {
      correct.textContent = `${t.assignment_correct_value}: ${formatQuantity(next.correct_value, lang, SHOWN_DIGITS)} ${state.unit}`;
    }
  }

  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    const answer = parseAnswer(input.value);
    if (answer === null) {
      feedback.textContent = numberRefusal(input.value);
      return;
    }
    const extra = kindPart(state, angleInput);
    if (extra.message) {
      feedback.textContent = extra.message;
      return;
    }
    button.disabled = true;
    try {
      const response = await submitted(JSON.stringify(
        { student: assignment.student, question: state.id, answer, ...extra.body }), feedback);
      const payload = await response.json().catch(() => null);
      if (response.ok) {
        state.answers.push(answer);
        Object.assign(state, { right: payload.right, attempts_left: payload.attempts_left,
          correct_value: payload.correct_value });
        show(state);
        openLockedPanels(state, feedback);
      } else {
        const detail = Array.isArray(payload?.detail) ? payload.detail[0] : null;
        feedback.textContent = t[`assignment_error_${detail?.type}`] ?? detail?.msg ?? `HTTP ${response.status}`;
        button.disabled = false;
      }
    } catch (error) {
      feedback.textContent = `${t.assignment_failed}: ${error}`;
      button.disabled = false;
    }
  });
  show(state);
  return item;
}

/**
 * POST the submission; while the server answers "busy" (503: this variant's answers are being computed; 429:
 * too many at once) with Retry-After, say so and send it again after that wait: such an answer counted no
 * attempt, so sending it again is safe.
 */
async function submitted(body, feedback) {
  for (let tries = 1; ; tries += 1) {
    const response = await fetch(`${base}/submissions`, {
      method: "POST", headers: { "Content-Type": "application/json" }, body });
    const wait = Number.parseFloat(response.headers.get("Retry-After") ?? "");
    if (![503, 429].includes(response.status) || !Number.isFinite(wait) || tries === BUSY_TRIES) return response;
    feedback.textContent = t.busy_retrying;
    await new Promise((resolve) => setTimeout(resolve, 1000 * Math.min(Math.max(wait, 0.5), 30)));
  }
}

async function start() {
  showValues();
  const response = await fetch(`${base}/me?lang=${lang}`);
  if (!response.ok) {
    byId("questions").replaceChildren(element("li", { textContent: `${t.assignment_failed} (HTTP ${response.status})` }));
    return;
  }
  const variant = await response.json();
  byId("questions").replaceChildren(...variant.questions.map(questionItem));
}

start();
