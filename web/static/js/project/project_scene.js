/**
 * A course-project scene's page (kind "project"): each variant (a crank preset) with its design data at the
 * sliders' defaults and a link that opens it on the course-project page (/project) with that data in the
 * address, as server/lessons/project_links.py writes a student's link. The variant of one's own mechanism is
 * shown when the address holds one (the editor's m and d: the editor's scene links open it so), and the button
 * that makes an assignment then takes it along. A student's assignment page lists their own values
 * (assignment_panel.js) and the server writes their links, so this page draws nothing there.
 */
import { element } from "../common/view/dom.js";
import { formatQuantity } from "../common/view/notation.js";
import { byId, lang, scene, t } from "../common/view/page_data.js";
import { toBase64Url } from "../common/model/base64url.js";
import { pathValue, setPath } from "../common/model/dotted_paths.js";
import { resolveAddressVariants } from "../common/model/address_mechanism.js";

/** The course-project request of a variant at its sliders' defaults (the twin of requests.project_body). */
export function projectBody(variant) {
  const body = structuredClone(variant.request);
  for (const slider of variant.sliders) {
    const scale = slider.scale ? Number(pathValue(body, slider.scale)) : 1;
    for (const path of [slider.param, ...(slider.also ?? [])]) setPath(body, path, slider.default * slider.to_si * scale);
  }
  return body;
}

/** The /project address of the body (m, d, p as course_project/model/address.js reads them). */
export function projectAddress(body) {
  const dynamics = { masses: body.masses, inertias: body.inertias ?? {},
    flywheel: { omega_mean: body.omega_mean, delta: body.delta } };
  const settings = { positions: body.positions ?? 12, start: null, output: null, chosen: body.chosen ?? null,
    drawn: null, title: { student: "", group: "", variant: "" } };
  const query = new URLSearchParams({ lang, m: toBase64Url(JSON.stringify(body.linkage)),
    d: toBase64Url(JSON.stringify(dynamics)), p: toBase64Url(JSON.stringify(settings)) });
  return `/project?${query}`;
}

function variantCard(variant) {
  const rows = variant.sliders.map((slider) => element("li", {
    textContent: `${slider.label[lang]} = ${formatQuantity(slider.default, lang, 6)}` }));
  return element("section", { className: "project-variant", id: `project-variant-${variant.id}` },
    element("h2", { textContent: variant.label[lang] }),
    element("p", { textContent: variant.text[lang] }),
    element("p", { className: "hint", textContent: t.project_scene_data }),
    element("ul", {}, ...rows),
    element("p", {}, element("a", { className: "button secondary", href: projectAddress(projectBody(variant)),
      textContent: t.project_scene_open })));
}

const holder = byId("project-variants");
if (holder && !byId("assignment-data")) {
  resolveAddressVariants(scene);
  const shown = scene.variants.filter((variant) => !variant.addressMissing);
  holder.replaceChildren(...shown.map(variantCard));
  const own = shown.find((variant) => variant.address);
  const assign = byId("make-assignment");
  if (own && assign) {
    const search = new URLSearchParams(location.search);
    const query = new URLSearchParams({ lang, variant: own.id, m: search.get("m"), d: search.get("d") });
    assign.href = `/scenes/${scene.id}/assign?${query}`;
  }
}
