/**
 * The instructor's side of the students on the results page: upload a roster (pasted or from a file), lock
 * registration to it or open it again, make one student's new personal link, delete a student's row, replace
 * the results link itself (the page then goes on under the new token). Every action is a request to
 * /api/v1/assignments/{id}/results/{token}/…; after a change the table is read again from the page. The links
 * CSV downloads are plain forms (no script needed).
 */
import { element } from "../../common/view/dom.js";

const t = JSON.parse(document.getElementById("interface-texts").textContent);
const root = document.getElementById("students");
let api = root.dataset.api;
const outcome = document.getElementById("roster-outcome");

async function send(method, path, body) {
  const response = await fetch(`${api}${path}`, {
    method, headers: body === undefined ? {} : { "Content-Type": "application/json" },
    body: body === undefined ? undefined : JSON.stringify(body) });
  if (!response.ok) {
    const payload = await response.json().catch(() => null);
    throw new Error(payload?.detail?.[0]?.msg ?? payload?.detail ?? `HTTP ${response.status}`);
  }
  return response.status === 204 ? null : response.json();
}

/** The results table as the server renders it now. */
async function refreshTable() {
  const html = await (await fetch(location.href, { cache: "no-store" })).text();
  const fresh = new DOMParser().parseFromString(html, "text/html").getElementById("results-wrap");
  document.getElementById("results-wrap").replaceChildren(...fresh.childNodes);
}

function listOf(label, names) {
  return names.length ? element("p", {}, element("strong", { textContent: `${label} (${names.length}): ` }),
    names.join(", ")) : "";
}

document.getElementById("roster-file").addEventListener("change", async (event) => {
  const file = event.target.files[0];
  if (file) document.getElementById("roster-names").value = await file.text();
});

document.getElementById("roster-form").addEventListener("submit", async (event) => {
  event.preventDefault();
  const names = document.getElementById("roster-names").value;
  if (!names.trim()) return;
  try {
    const result = await send("POST", "/roster", { names });
    const refused = result.refused.map((r) => `${r.line} — ${r.reason}`);
    outcome.replaceChildren(listOf(t.assignment_roster_added, result.added),
      listOf(t.assignment_roster_already, result.already),
      refused.length ? element("p", { className: "error" }, `${t.assignment_roster_refused} (${refused.length}): `,
        element("ul", {}, ...refused.map((line) => element("li", { textContent: line })))) : "");
    await refreshTable();
  } catch (error) {
    outcome.replaceChildren(element("p", { className: "error", textContent: `${t.assignment_failed}: ${error.message}` }));
  }
});

const lockButton = document.getElementById("roster-lock");
lockButton.addEventListener("click", async () => {
  const state = document.getElementById("registration-state");
  const locked = state.dataset.locked !== "true";
  try {
    await send("PUT", "/roster-lock", { locked });
    state.dataset.locked = String(locked);
    state.querySelector("span").textContent = locked ? lockButton.dataset.lockedText : lockButton.dataset.openText;
    lockButton.textContent = locked ? lockButton.dataset.unlock : lockButton.dataset.lock;
  } catch (error) {
    state.querySelector("span").textContent = `${t.assignment_failed}: ${error.message}`;
  }
});

document.getElementById("links-all-form").addEventListener("submit", (event) => {
  if (!window.confirm(event.currentTarget.dataset.confirm)) event.preventDefault();
});

/** The row buttons (the table is replaced after changes, so one listener on the container). */
document.getElementById("results-wrap").addEventListener("click", async (event) => {
  const button = event.target.closest("button.new-link, button.delete-student");
  if (!button) return;
  const row = button.closest("tr");
  if (!window.confirm(button.dataset.confirm.replace("{name}", row.dataset.name))) return;
  button.disabled = true;
  try {
    if (button.classList.contains("delete-student")) {
      await send("DELETE", `/students/${row.dataset.student}`);
      await refreshTable();
    } else {
      const link = await send("POST", `/students/${row.dataset.student}/link`);
      row.querySelector(".new-link-shown").replaceChildren(element("input", { type: "text", readOnly: true,
        className: "shown-link", value: link.personal_url, "aria-label": row.dataset.name }));
      row.querySelector(".no-link")?.remove();
      button.disabled = false;
    }
  } catch (error) {
    row.querySelector(".new-link-shown").textContent = `${t.assignment_failed}: ${error.message}`;
    button.disabled = false;
  }
});

/** A new results token: the old link stops working, so every address on the page moves to the new one. */
document.getElementById("replace-results-link").addEventListener("click", async (event) => {
  const button = event.currentTarget;
  if (!window.confirm(button.dataset.confirm)) return;
  const shown = document.getElementById("new-results-link");
  button.disabled = true;
  try {
    const lang = new URLSearchParams(location.search).get("lang");
    const fresh = await send("POST", `/token${lang ? `?lang=${encodeURIComponent(lang)}` : ""}`);
    const old = api;
    api = old.replace(/[^/]+$/, encodeURIComponent(fresh.results_token));
    root.dataset.api = api;
    for (const link of document.querySelectorAll(`[href^="${old}"]`)) link.href = link.getAttribute("href").replace(old, api);
    for (const form of document.querySelectorAll(`form[action^="${old}"]`)) {
      form.action = form.getAttribute("action").replace(old, api);
    }
    const target = new URL(fresh.results_url);                // this page's own origin, as the instructor opened it
    history.replaceState(null, "", target.pathname + target.search);
    document.getElementById("new-results-url").value = location.origin + target.pathname + target.search;
    shown.hidden = false;
  } catch (error) {
    shown.hidden = false;
    shown.textContent = `${t.assignment_failed}: ${error.message}`;
  }
  button.disabled = false;
});
