/**
 * The student's mechanism's masses, loads and motor (the "dynamics" of a preset: masses {links, gravity, forces,
 * moments, point_forces}, inertias {J1, J_rotor, gear_ratio}, motor, flywheel), kept in the address beside the linkage as
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
 * moves; the estimate's row for a new link; loads on pairs and links that still exist (places: the estimate's
 * load_places, every sliding pair and moving link; a force at a point goes with its link), the estimate's where
 * every kept load is gone, none where the student kept none; g, the machine's inertias and motor as they were.
 */
export function keptOn(kept, estimate, places) {
  const links = new Map(kept.masses.links.map((row) => [row.link, row]));
  const rows = estimate.masses.links.map((row) => links.get(row.link) ?? row);
  const pairs = new Set(places.forces.map((f) => f.joint));
  const movingLinks = new Set(places.moments.map((m) => m.link));
  const { forces: keptForces = [], moments: keptMoments = [], point_forces: keptPoints } = kept.masses;
  const had = keptForces.length + keptMoments.length + (keptPoints ?? []).length;
  const forces = keptForces.filter((f) => pairs.has(f.joint));
  const moments = keptMoments.filter((m) => movingLinks.has(m.link));
  const points = (keptPoints ?? []).filter((f) => movingLinks.has(f.link));
  const loads = forces.length || moments.length || points.length || !had ? { forces, moments }
    : { forces: estimate.masses.forces, moments: estimate.masses.moments ?? [] };
  return { ...kept, masses: { ...kept.masses, links: rows, ...loads, ...(keptPoints ? { point_forces: points } : {}) } };
}

/**
 * A place's key in the "add a load" choice: "force:E/ram" (a sliding pair), "moment:3" (a link) or "point:5" (a
 * force at a point of link 5).
 */
export const placeKey = (kind, where) => `${kind}:${where}`;

/**
 * The places a load may still be added to: [{key, kind: "force"|"moment", joint | link}] of places (the estimate's
 * load_places) that carry none of dynamics' loads yet.
 */
export function freePlaces(dynamics, places) {
  if (!places) return [];
  const taken = new Set([...(dynamics.masses.forces ?? []).map((f) => placeKey("force", f.joint)),
    ...(dynamics.masses.moments ?? []).map((m) => placeKey("moment", m.link))]);
  return [...places.forces.map((f) => ({ key: placeKey("force", f.joint), kind: "force", joint: f.joint })),
    ...places.moments.map((m) => ({ key: placeKey("moment", m.link), kind: "moment", link: m.link }))]
    .filter((place) => !taken.has(place.key));
}

/**
 * The links a force at a point may be put on, any number on each: [{key, kind: "point", link}], every moving link
 * of places (the estimate's load_places).
 */
export function pointPlaces(places) {
  return places ? places.moments.map((m) => ({ key: placeKey("point", m.link), kind: "point", link: m.link })) : [];
}

/**
 * A new force at a point of link (the API's masses.point_forces: point [along, across] in the link's frame, m;
 * magnitude P, N; direction {kind "fixed" | "link", angle α in rad}; acts "working" | "always"): at the link's
 * origin, 1000 N along −x, on the working stroke only, for the student to move and turn.
 */
export function newPointForce(link) {
  return { link, point: [0, 0], magnitude: 1000, direction: { kind: "fixed", angle: Math.PI }, acts: "working" };
}

/**
 * The load offered at the place key added to dynamics: a slider's force or a link's moment as the places offer
 * it (its first P or M, k and the slow stroke's sense), a new force at a point of the link ("point:5").
 */
export function addLoad(dynamics, places, key) {
  const [kind, where] = [key.slice(0, key.indexOf(":")), key.slice(key.indexOf(":") + 1)];
  if (kind === "point") {
    dynamics.masses.point_forces = [...(dynamics.masses.point_forces ?? []), newPointForce(Number(where))];
    return;
  }
  const offered = kind === "force" ? places.forces.find((f) => f.joint === where)
    : places.moments.find((m) => String(m.link) === where);
  if (!offered) return;
  const list = kind === "force" ? "forces" : "moments";
  dynamics.masses[list] = [...(dynamics.masses[list] ?? []), structuredClone(offered)];
}

/** The load at index of masses[list] ("forces", "moments" or "point_forces") taken away. */
export function removeLoad(dynamics, list, index) {
  dynamics.masses[list] = (dynamics.masses[list] ?? []).filter((_, k) => k !== index);
}

export const GRAVITY = 9.81;                   // g, m/s², along −y: the table's "gravity" on

/** The address of a dynamics scene opened on its variant ``variant`` with this linkage and its dynamics. */
export function sceneAddress({ scene, variant }, linkageParameter, dynamics, lang) {
  const query = new URLSearchParams({ lang, variant });
  query.set("m", linkageParameter);
  query.set("d", dynamicsParameter(dynamics));
  return `/scenes/${scene}?${query}`;
}
