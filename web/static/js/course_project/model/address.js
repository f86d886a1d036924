/**
 * The course project in the page address: m (the linkage) and d (its masses, loads, machine and flywheel data)
 * exactly as the editor keeps them, and p = base64url of the project's settings and title block, so that a
 * reload or a shared link shows the same project (the link is the document). No DOM.
 *
 * settings: positions (8, 12 or 24), start (null: the working stroke's extreme position found by the app, or
 * φ₀ in rad), output (null: found by the app), chosen (null: the position with the largest useful load, or
 * 1…N), drawn (null: the chosen one, or a list of 1…N), title {student, group, variant}.
 */
import { readJsonParameter, toBase64Url } from "../../common/model/base64url.js";
import { readMechanism } from "../../editor/model/address.js";
import { dynamicsParameter, readDynamics } from "../../editor/model/dynamics.js";

export const POSITION_CHOICES = [8, 12, 24];
export const TITLE_FIELDS = ["student", "group", "variant"];
export const TITLE_LENGTH = 80;                 // characters of a title-block field at most (the API's bound)

export function defaultSettings() {
  return { positions: 12, start: null, output: null, chosen: null, drawn: null,
    title: { student: "", group: "", variant: "" } };
}

/** Settings read from p, each field checked and put back to its default when it is not one the page can show. */
export function settingsOf(data) {
  const settings = defaultSettings();
  if (!data || typeof data !== "object") return settings;
  if (POSITION_CHOICES.includes(data.positions)) settings.positions = data.positions;
  if (Number.isFinite(data.start)) settings.start = data.start;
  if (typeof data.output === "string" && data.output) settings.output = data.output;
  const position = (k) => Number.isInteger(k) && k >= 1 && k <= settings.positions;
  if (position(data.chosen)) settings.chosen = data.chosen;
  if (Array.isArray(data.drawn)) settings.drawn = [...new Set(data.drawn.filter(position))].sort((a, b) => a - b);
  for (const field of TITLE_FIELDS) {
    const text = data.title?.[field];
    if (typeof text === "string") settings.title[field] = text.slice(0, TITLE_LENGTH);
  }
  return settings;
}

/** The project in an address's query: {linkage, dynamics, settings} (linkage and dynamics null when absent). */
export function readProject(search = location.search) {
  return { linkage: readMechanism(search), dynamics: readDynamics(search),
    settings: settingsOf(readJsonParameter(new URLSearchParams(search).get("p"))) };
}

/** The address query of a project in a language. */
export function projectQuery({ linkage, dynamics, settings }, lang) {
  const query = new URLSearchParams({ lang });
  if (linkage) query.set("m", toBase64Url(JSON.stringify(linkage)));
  if (dynamics) query.set("d", dynamicsParameter(dynamics));
  query.set("p", toBase64Url(JSON.stringify(settings)));
  return query;
}

/** The editor's address with the same mechanism and design data (to change the links' lengths there). */
export function editorAddress({ linkage, dynamics }, lang) {
  const query = new URLSearchParams({ lang });
  if (linkage) query.set("m", toBase64Url(JSON.stringify(linkage)));
  if (dynamics) query.set("d", dynamicsParameter(dynamics));
  return `/editor?${query}`;
}

/** The settings when the number of positions changes: a chosen or drawn position past the new N is dropped. */
export function withPositions(settings, positions) {
  return settingsOf({ ...settings, positions });
}

/**
 * The outputs the strokes may be defined by: every sliding pair where a load may go (the estimate's places,
 * "E/ram") and every moving link ("link 3", as the API names them).
 */
export function outputChoices(linkage, places) {
  const links = linkage?.input ? [linkage.input.link, ...(linkage.groups ?? []).flatMap((g) => g.links)] : [];
  return [...(places?.forces ?? []).map((f) => ({ kind: "slide", name: f.joint, value: f.joint })),
    ...links.map((link) => ({ kind: "link", name: String(link), value: `link ${link}` }))];
}
