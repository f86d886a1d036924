/**
 * The mechanism in the page address (?m=<base64url of its JSON>), so that a link or a reload shows the same
 * mechanism (the link is the document), and the language switch keeps it.
 */
import { readJsonParameter, toBase64Url } from "../../common/model/base64url.js";

/** The address query for a linkage and the page language. */
export function mechanismQuery(linkage, lang) {
  const query = new URLSearchParams({ lang });
  query.set("m", toBase64Url(JSON.stringify(linkage)));
  return query;
}

/** The linkage in an address's query, or null (none, or not readable). */
export function readMechanism(search = location.search) {
  return readJsonParameter(new URLSearchParams(search).get("m"));
}
