/**
 * The student's mechanism's masses, loads and motor (the "dynamics" of a preset: masses {links, gravity, forces,
 * moments}, inertias {J1, J_rotor, gear_ratio}, motor, flywheel), kept in the address beside the linkage as
 * d=<base64url of its JSON> (the link is the document), and the addresses that open the dynamics scenes with both
 * (the scenes with a variant that takes the mechanism from the address: the page's "editor-own-scenes").
 * A mechanism without any starts from the server's estimate (POST /api/v1/dynamics-estimate,
 * server/core/structure/estimate.py); one from a preset with dynamics starts from the preset's. No DOM.
 */
import { readJsonParameter, toBase64Url } from "../../common/model/base64url.js";

export const DYNAMICS_KEYS = ["masses", "inertias", "motor", "flywheel"];

/** Only the keys a scene takes (an estimate's answer also has warnings). */
export function dynamicsOf(data) {
  return data ? Object.fromEntries(DYNAMICS_KEYS.filter((k) => data[k] !== undefined).map((k) => [k, structuredClone(data[k])])) : null;
}

/** The dynamics in an address's query, or null. */
export function readDynamics(search = location.search) {
  const data = readJsonParameter(new URLSearchParams(search).get("d"));
  return data && data.masses ? dynamicsOf(data) : null;
}

export const dynamicsParameter = (dynamics) => toBase64Url(JSON.stringify(dynamics));

/**
 * Kept values on a changed mechanism: each link's row the student (or the preset) gave, while the link still
 * moves; the estimate's row for a new link; loads on pairs and links that still exist (the estimate's
 * otherwise); the machine's inertias and motor as they were.
 */
export function keptOn(kept, estimate) {
  const links = new Map(kept.masses.links.map((row) => [row.link, row]));
  const rows = estimate.masses.links.map((row) => links.get(row.link) ?? row);
  const movingLinks = new Set(estimate.masses.links.map((row) => row.link));
  const pairs = new Set(estimate.masses.forces.map((f) => f.joint));
  const forces = (kept.masses.forces ?? []).filter((f) => pairs.has(f.joint));
  const moments = (kept.masses.moments ?? []).filter((m) => movingLinks.has(m.link));
  const loads = forces.length || moments.length ? { forces, moments }
    : { forces: estimate.masses.forces, moments: estimate.masses.moments ?? [] };
  return { ...kept, masses: { ...kept.masses, links: rows, ...loads } };
}

/** The address of a dynamics scene opened on its variant ``variant`` with this linkage and its dynamics. */
export function sceneAddress({ scene, variant }, linkageParameter, dynamics, lang) {
  const query = new URLSearchParams({ lang, variant });
  query.set("m", linkageParameter);
  query.set("d", dynamicsParameter(dynamics));
  return `/scenes/${scene}?${query}`;
}
