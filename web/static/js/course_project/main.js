/**
 * The course-project page: the student's mechanism (from the address, a file or a preset), its design data and
 * the project's settings; every change writes the address (m, d, p: the link is the document) and asks
 * POST /api/v1/course-project again (one request in flight, the newest waiting, an answer to an older one
 * dropped); the answer is shown as the report (view/report.js). A refusal names the field; a mechanism that
 * cannot turn fully shows the server's sentence and no report. A mechanism without design data gets the
 * server's first estimate (POST /api/v1/dynamics-estimate), which also gives the places a load may go.
 */
import { setPath } from "../common/model/dotted_paths.js";
import { LatestRequest, refusalText } from "../editor/model/service.js";
import { dynamicsOf } from "../editor/model/dynamics.js";
import { defaultSettings, editorAddress, outputChoices, projectQuery, readProject } from "./model/address.js";
import { completed } from "./model/design.js";
import { projectRequest } from "./model/request.js";
import { refusalSentence, refusedPath, refusesMechanism } from "./model/refusal.js";
import { renderDesign } from "./view/design.js";
import { renderSettings, renderTitleInputs } from "./view/settings.js";
import { renderReport } from "./view/report.js";
import { element } from "../common/view/dom.js";
import { richText } from "../common/view/notation.js";

const lang = document.documentElement.lang;
const t = JSON.parse(document.getElementById("interface-texts").textContent);
const presets = JSON.parse(document.getElementById("project-presets").textContent);
const $ = (id) => document.getElementById(id);

/** linkage, dynamics (completed), settings: the project; places: where loads may go; answer, refusal: the last. */
const state = { ...readProject(), places: null, answer: null, refusal: null };
const projects = new LatestRequest(lang, "course-project");
const estimates = new LatestRequest(lang, "dynamics-estimate");
const status = $("project-status");

function writeAddress() {
  const query = projectQuery(state, lang);
  history.replaceState(null, "", `?${query}`);
  for (const link of document.querySelectorAll("a[data-lang]")) {
    query.set("lang", link.dataset.lang);
    link.href = `?${query}`;
  }
  const editor = editorAddress(state, lang);
  $("project-editor-link").href = editor;
  const inDesign = $("project-dimensions-editor");
  if (inDesign) inDesign.href = editor;
}

function setStatus(kind, text) {
  status.dataset.state = kind;
  status.textContent = text;
}

/** The project changed: write the address and ask the server. */
function compute() {
  writeAddress();
  if (!state.linkage || !state.dynamics) return;
  const asked = projectRequest(state);
  setStatus("waiting", t.loading);
  projects.submit(asked, (answer) => {
    if (answer.ok) {
      state.answer = answer.data;
      state.refusal = null;
    } else {
      state.refusal = answer.error;
    }
    show(asked);
  });
}

/** Mark the input a refusal names (data-path), and no other. */
function markRefused(path) {
  for (const input of document.querySelectorAll("[data-refused]")) {
    input.removeAttribute("data-refused");
    input.removeAttribute("aria-invalid");
  }
  if (!path) return;
  const input = [...document.querySelectorAll("[data-path]")].find((node) => node.dataset.path === path
    || path.startsWith(`${node.dataset.path}.`));
  if (input) {
    input.dataset.refused = "";
    input.setAttribute("aria-invalid", "true");
  }
}

function show(asked) {
  const report = $("project-report");
  const refusal = state.refusal;
  $("project-refusal").replaceChildren();
  markRefused(refusal ? refusedPath(refusal) : null);
  report.classList.toggle("stale", Boolean(refusal));
  if (refusal) {
    const sentence = refusalSentence(refusal, refusalText(refusal, t), asked, t);
    $("project-refusal").append(element("div", { className: "refusal", role: "alert", id: "project-refusal-sentence" },
      element("strong", { textContent: refusesMechanism(refusal) ? t.project_cannot_turn : t.project_refused }),
      element("p", { rich: sentence })));
    if (refusesMechanism(refusal) || !state.answer) {
      report.hidden = true;
      state.answer = null;
    }
    setStatus("refused", "");
  } else {
    report.hidden = false;
    renderReport(report, state.answer, { t, lang, settings: state.settings, request: asked });
    setStatus("ready", "");
    showSettings();
  }
  status.dataset.answers = String(Number(status.dataset.answers ?? 0) + 1);     // answers taken (tests wait on it)
}

function showSettings() {
  const found = state.answer ? { phi0: state.answer.positions?.phi0, chosen: state.answer.kinetostatics?.number,
    output: state.answer.positions?.output && { kind: state.answer.positions.output.kind,
      name: state.answer.positions.output.name.replace(/^link /, "") } } : null;
  const onSettings = (change) => {
    change(state.settings);
    showSettings();
    compute();
  };
  renderSettings($("project-settings"), state.settings, found, outputChoices(state.linkage, state.places), { t, lang, onSettings });
}

function showDesign() {
  if (!state.linkage || !state.dynamics) {
    $("project-design").replaceChildren(element("p", { className: "hint", textContent: t.project_no_mechanism }));
    return;
  }
  renderDesign($("project-design"), state.linkage, state.dynamics, {
    t, lang, places: state.places, editorHref: editorAddress(state, lang),
    onEdit: (path, value) => {
      setPath(state.dynamics, path, value);
      compute();
    },
    onChange: () => {
      showDesign();
      compute();
    },
  });
}

/** The estimate: the places a load may go, and the design data where the mechanism came without any. */
function askEstimate() {
  estimates.submit({ linkage: state.linkage }, (answer) => {
    const estimated = answer.ok && !state.dynamics;
    if (answer.ok) {
      state.places = answer.data.load_places;
      if (estimated) state.dynamics = completed(dynamicsOf(answer.data));
    } else if (!state.dynamics) {
      state.refusal = answer.error;
      show(null);
    }
    showDesign();
    showSettings();
    if (estimated) compute();
  });
}

/** Open a mechanism with its design data (null: the server's estimate), the settings kept but the positions'. */
function open(linkage, dynamics, message = "") {
  state.linkage = linkage;
  state.dynamics = dynamics?.masses ? completed(dynamicsOf(dynamics)) : null;
  state.answer = null;
  state.settings = { ...defaultSettings(), title: state.settings.title };
  $("project-file-status").replaceChildren(richText(message));          // a preset's source writes J_S, J₁
  showSettings();
  showDesign();
  compute();
  askEstimate();
}

/* ---- tools ---- */

const presetSelect = $("project-preset");
presetSelect.append(...presets.map((p) => new Option(p.title, p.name)));
presetSelect.addEventListener("change", () => {
  const preset = presets.find((p) => p.name === presetSelect.value);
  if (preset) open(preset.linkage, preset.dynamics, preset.source);
});
$("project-import").addEventListener("change", async (event) => {
  const file = event.target.files?.[0];
  if (!file) return;
  try {
    const data = JSON.parse(await file.text());
    open(data.linkage ?? data, data.linkage ? data.dynamics : null, `${t.editor_imported}: ${file.name}`);
  } catch {
    $("project-file-status").textContent = t.editor_import_failed;
  }
  event.target.value = "";
});
$("project-copy-link").addEventListener("click", async () => {
  try {
    await navigator.clipboard.writeText(location.href);
    $("project-file-status").textContent = t.editor_link_copied;
  } catch {
    $("project-file-status").textContent = location.href;
  }
});
$("project-print").addEventListener("click", () => window.print());

renderTitleInputs($("project-title-inputs"), state.settings, { t, onSettings: (change) => {
  change(state.settings);
  compute();
} });
showSettings();
if (state.linkage) {
  if (state.dynamics) state.dynamics = completed(state.dynamics);
  showDesign();
  compute();
  askEstimate();
} else {
  writeAddress();
}
