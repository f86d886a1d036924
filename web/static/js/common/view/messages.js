/** Why there is nothing to draw, in the reader's language. */
import { element } from "./dom.js";

/** The translated reason of an API error (content/i18n err_<code>), or the server's own words. */
export function errorReason(error, t) {
  return (error.code && t[`err_${error.code}`]) || error.message;
}

/** A box saying that the request was refused (heading) and why. */
export function refusalMessage(heading, error, t) {
  return element("div", { className: "refusal", role: "alert" },
    element("strong", { textContent: heading }),
    element("p", { rich: errorReason(error, t) }));
}

/** A box saying the mechanism cannot be assembled, and why. */
export function geometryMessage(error, t) {
  const box = refusalMessage(t.invalid_geometry, error, t);
  box.classList.add("geometry-error");
  return box;
}
