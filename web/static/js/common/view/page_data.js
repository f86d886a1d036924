/**
 * What the server embeds in a scene page: the scene (content/scenes), the interface texts and the
 * language. Both scene pages read it here.
 */
const readJson = (id) => JSON.parse(document.getElementById(id).textContent);

export const byId = (id) => document.getElementById(id);
export const scene = readJson("scene-data");
export const t = readJson("interface-texts");
export const lang = document.documentElement.lang;
export const texts = { t, lang };
