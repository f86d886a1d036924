/** Text ⇄ base64url (RFC 4648 §5, no padding): how a document rides in a page address. */
export function toBase64Url(text) {
  const bytes = new TextEncoder().encode(text);
  let binary = "";
  for (const byte of bytes) binary += String.fromCharCode(byte);
  return btoa(binary).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

export function fromBase64Url(text) {
  const binary = atob(text.replace(/-/g, "+").replace(/_/g, "/"));
  return new TextDecoder().decode(Uint8Array.from(binary, (c) => c.charCodeAt(0)));
}

/** The JSON document of base64url text, or null (none, or not readable). */
export function readJsonParameter(text) {
  if (!text) return null;
  try {
    return JSON.parse(fromBase64Url(text));
  } catch {
    return null;
  }
}
