/**
 * "Copy link": the address of the scene's whole state (url_state.js stateQuery: variant, values,
 * toggles, overlay, the indicator diagram's edits, the preset), written at once — the address bar itself is
 * updated a little later while a slider moves. Put on the clipboard where the browser lets the page do so;
 * shown, selected, in a field beside the button either way, so it can be copied by hand.
 */
import { stateQuery } from "../model/url_state.js";

/** The address that opens the scene as the model has it now (never an assignment's student). */
export function stateAddress(model, lang) {
  return `${location.origin}${location.pathname}?${stateQuery(model, lang)}`;
}

/** Copy the state's address; field: the <input readonly> showing it, status: where to say what happened. */
export async function copyLink(model, lang, { field, status, t }) {
  const address = stateAddress(model, lang);
  field.value = address;
  field.hidden = false;
  field.select();
  try {
    await navigator.clipboard.writeText(address);
    status.textContent = t.link_copied;
  } catch {
    status.textContent = t.link_copy_by_hand;
  }
}
