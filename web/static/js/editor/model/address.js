/**
 * The mechanism in the page address (?m=<base64url of its JSON>), so that a link or a reload shows the same
 * mechanism (the link is the document), and the language switch keeps it.
 */
function toBase64Url(text) {
  const bytes = new TextEncoder().encode(text);
  let binary = "";
  for (const byte of bytes) binary += String.fromCharCode(byte);
  return btoa(binary).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function fromBase64Url(text) {
  const binary = atob(text.replace(/-/g, "+").replace(/_/g, "/"));
  return new TextDecoder().decode(Uint8Array.from(binary, (c) => c.charCodeAt(0)));
}

/** The address query for a linkage and the page language. */
export function mechanismQuery(linkage, lang) {
  const query = new URLSearchParams({ lang });
  query.set("m", toBase64Url(JSON.stringify(linkage)));
  return query;
}

/** The linkage in an address's query, or null (none, or not readable). */
export function readMechanism(search = location.search) {
  const text = new URLSearchParams(search).get("m");
  if (!text) return null;
  try {
    return JSON.parse(fromBase64Url(text));
  } catch {
    return null;
  }
}
