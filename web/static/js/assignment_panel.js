/**
 * The student's side of an assignment page: their data (the variant's values, read from the scene the
 * server embedded), and the questions with an answer field each. Answers go to
 * POST /api/v1/assignments/{id}/submissions; the server says right or wrong at once and, only once a
 * question is closed (right, or no attempt left), what the correct value was.
 */
import { element } from "./dom.js";
import { formatQuantity, labelledValue } from "./notation.js";
import { byId, lang, scene, t } from "./page_data.js";

const assignment = JSON.parse(byId("assignment-data").textContent);
const base = `/api/v1/assignments/${encodeURIComponent(assignment.id)}`;
const SHOWN_DIGITS = 6;

/** A number typed with a decimal comma or point, spaces allowed ("1 234,5"); null if it is not one. */
export function parseAnswer(text) {
  const cleaned = String(text).replace(/[\s\u00a0]/g, "").replace(",", ".");
  const value = Number(cleaned);
  return cleaned !== "" && Number.isFinite(value) ? value : null;
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
  const form = element("form", { className: "answer-form", noValidate: true }, input,
    element("span", { className: "unit", textContent: state.unit }), button);
  const item = element("li", { className: "question", id: `question-${state.id}` },
    element("p", { className: "question-label", textContent: state.label }),
    element("p", { className: "hint", textContent: `${t.assignment_tolerance}: ±${formatQuantity(state.tolerance * 100, lang)} %` }),
    form, feedback, correct);

  function show(next) {
    item.classList.toggle("right", next.right);
    item.classList.toggle("wrong", !next.right && next.answers.length > 0);
    feedback.textContent = feedbackText(next);
    const closed = next.right || next.attempts_left === 0 || !assignment.info.open;
    input.disabled = button.disabled = closed;
    if (next.correct_value !== null && next.correct_value !== undefined) {
      correct.textContent = `${t.assignment_correct_value}: ${formatQuantity(next.correct_value, lang, SHOWN_DIGITS)} ${state.unit}`;
    }
  }

  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    const answer = parseAnswer(input.value);
    if (answer === null) {
      feedback.textContent = t.assignment_not_a_number;
      return;
    }
    button.disabled = true;
    try {
      const response = await fetch(`${base}/submissions`, {
        method: "POST", headers: { "Content-Type": "application/json" },
        body: JSON.stringify({ student: assignment.student, question: state.id, answer }) });
      const payload = await response.json().catch(() => null);
      if (response.ok) {
        state.answers.push(answer);
        Object.assign(state, { right: payload.right, attempts_left: payload.attempts_left,
          correct_value: payload.correct_value });
        show(state);
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
