/**
 * A scene variant that computes the reader's own mechanism (its "address" in content/scenes; the twin of
 * server/lessons/scene_files.py `addressed`): the editor writes the linkage as m=<base64url of its JSON> and its
 * masses, loads and motor as d=<base64url of {masses, inertias, motor, flywheel}> into the page address; each key
 * of the variant's request named in address.request is the value at that dotted path of {m, d}, the variant's own
 * request (address.own) merged over them, and a slider with "relative" {min, max, step, default} (any of them) takes
 * those as multiples of the request's value at its param. No DOM.
 */
import { readJsonParameter } from "./base64url.js";
import { pathValue } from "./dotted_paths.js";

/** The address's documents {m, d}, or null where either is missing or unreadable. */
export function addressDocuments(search = location.search) {
  const query = new URLSearchParams(search);
  const m = readJsonParameter(query.get("m"));
  const d = readJsonParameter(query.get("d"));
  return m && d ? { m, d } : null;
}

function merged(base, own) {
  const out = { ...base };
  for (const [key, value] of Object.entries(own)) {
    const both = isObject(base[key]) && isObject(value);
    out[key] = both ? merged(base[key], value) : structuredClone(value);
  }
  return out;
}

const isObject = (value) => value !== null && typeof value === "object" && !Array.isArray(value);
const sixDigits = (value) => Number(value.toPrecision(6));

/** The variant with its request and relative sliders from the documents; null where a path is missing. */
export function addressed(variant, documents) {
  const taken = {};
  for (const [key, path] of Object.entries(variant.address.request ?? {})) {
    let value = documents;
    for (const step of String(path).split(".")) {
      if (!isObject(value) || !(step in value)) return null;
      value = value[step];
    }
    taken[key] = structuredClone(value);
  }
  const request = merged(taken, variant.address.own ?? {});
  const sliders = variant.sliders.map((slider) => {
    if (!slider.relative) return slider;
    const value = Number(pathValue(request, slider.param));
    if (!Number.isFinite(value)) return slider;
    const scaled = Object.fromEntries(Object.entries(slider.relative).map(([k, f]) => [k, sixDigits(f * value)]));
    return { ...slider, ...scaled };
  });
  return { ...variant, request, sliders };
}

/**
 * Every variant of the scene that takes its mechanism from the address, resolved in place with the address's
 * documents; one the address cannot serve is marked `addressMissing` (the page says how to get a mechanism).
 */
export function resolveAddressVariants(scene, documents = addressDocuments()) {
  scene.variants = scene.variants.map((variant) => {
    if (!variant.address) return variant;
    const resolved = documents && addressed(variant, documents);
    return resolved ?? { ...variant, addressMissing: true };
  });
}
