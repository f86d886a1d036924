/**
 * The instructor's assignment form: reads the rows (fixed value, or a per-student range; whether the
 * student may move the slider), the toggles, the questions with their tolerances, attempts and deadline,
 * posts them to /api/v1/assignments and shows the students' link and the private results link. A 422
 * answer names the field and the reason, shown beside the form.
 */
const form = document.getElementById("assignment-form");
const t = JSON.parse(document.getElementById("interface-texts").textContent);
const errorLine = document.getElementById("builder-error");

/** A number typed with a decimal comma or a point; null when it is not one. */
function number(text) {
  const value = Number(String(text).trim().replace(",", "."));
  return String(text).trim() !== "" && Number.isFinite(value) ? value : null;
}

function sliderRule(row) {
  const field = (name) => row.querySelector(`[name="${name}"]`);
  const rule = {};
  if (field("vary").checked) {
    rule.vary = { min: number(field("vary_min").value), max: number(field("vary_max").value) };
    const step = number(field("vary_step").value);
    if (step !== null) rule.step = step;
  } else {
    rule.value = number(field("value").value);
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

function questions() {
  return [...form.querySelectorAll('input[name="question"]:checked')].map((box) => {
    const percent = number(form.querySelector(`[name="tolerance-${box.value}"]`).value);
    return percent === null ? { id: box.value } : { id: box.value, tolerance: percent / 100 };
  });
}

function spec() {
  const sliders = {};
  for (const row of form.querySelectorAll(".slider-rule")) sliders[row.dataset.slider] = sliderRule(row);
  const deadline = form.querySelector("#deadline").value;
  return {
    scene: form.dataset.scene, variant: form.dataset.variant, lang: form.dataset.lang,
    title: form.querySelector("#title").value.trim(), sliders, toggles: toggles(), questions: questions(),
    attempts: number(form.querySelector("#attempts").value),
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

form.addEventListener("submit", async (event) => {
  event.preventDefault();
  errorLine.textContent = "";
  const button = form.querySelector("#create-assignment");
  button.disabled = true;
  try {
    const response = await fetch("/api/v1/assignments", {
      method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(spec()) });
    const payload = await response.json().catch(() => null);
    if (response.ok) showLinks(payload);
    else errorLine.textContent = reason(payload, response.status);
  } catch (error) {
    errorLine.textContent = `${t.assignment_failed}: ${error}`;
  } finally {
    button.disabled = false;
  }
});
