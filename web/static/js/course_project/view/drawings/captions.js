/**
 * What the course project's drawings write: a drawing's heading and its scale factors ("μ_l = 0,0025 м/мм"),
 * the names of points, forces and vectors in the textbook's notation (markup of notation.js), and the texts a
 * drawing lists beside it. No DOM.
 */
import { formatQuantity } from "../../../common/view/notation.js";
import { FONT } from "../../model/drawing_layout.js";

/** A scale factor's unit: "м" per millimetre as "м/мм", "м/с" as "(м/с)/мм" (as the page writes them). */
export function perMillimetre(unit, t) {
  const mm = t.editor_mm;
  if (!unit) return `1/${mm}`;
  return unit.includes("/") ? `(${unit})/${mm}` : `${unit}/${mm}`;
}

/** "μ_l = 0,0025 м/мм": a scale factor as written on a drawing. */
export function scaleText(symbol, mu, unit, t, lang) {
  return `${symbol} = ${formatQuantity(mu, lang, 3)} ${perMillimetre(unit, t)}`;
}

/** A point's name with its digits lowered: "S3" → "S_3", "A3" → "A_3", "S3 (centre)" → "S_3". */
export function pointSymbol(name) {
  const [, letters, digits] = String(name).match(/^([^\d\s(/]+)(\d*)/) ?? [null, String(name), ""];
  return digits ? `${letters}_${digits}` : letters;
}

/** A point's image on a plan: the point's symbol in lower case ("S3" → "s_3"). */
export function imageSymbol(name) {
  return pointSymbol(name).toLowerCase();
}

/**
 * A drawing's heading and the lines under it (scale factors), stacked from top (mm, y down) at left x: each
 * text a fixed part of the figure; returns the y below the last line.
 */
export function heading(figure, [x, top], title, lines = []) {
  figure.text(title, [x, top + FONT.caption], { size: FONT.caption, attrs: { class: "cp-heading" } });
  let y = top + FONT.caption + 1.5;
  for (const line of lines) {
    y += FONT.label + 1.5;
    figure.text(line, [x, y], { size: FONT.label, attrs: { class: "cp-scale" } });
  }
  return y + 3;
}

const SHIFT_ROOM = 0.45;       // of the font size: the extra room between lines that a sub- or superscript needs

/** Lines of text (a list beside a drawing) from top at left x, font size size; returns the y below them. */
export function textLines(figure, [x, top], lines, size = FONT.label) {
  let y = top;
  let lowered = false;            // the line above has a subscript, which reaches below its baseline
  for (const line of lines) {
    const raised = /\^/.test(line);    // a superscript reaches above the line's capitals
    y += size + 1.6 + (raised || lowered ? SHIFT_ROOM * size : 0);
    figure.text(line, [x, y], { size, attrs: { class: "cp-list" } });
    lowered = /_/.test(line);
  }
  return y + 2;
}

const SAME_PLACE = 0.4;        // mm: images of a plan closer than this share a label

/**
 * The letters of a plan's images ([{name, p}], p on paper): images at one place, the pole's too, share one
 * label ("p, o, c"), set beside them on the side given by anchor ("start": right, "end": left).
 */
export function imageLabels(figure, poleName, pole, images, anchor = "start") {
  const groups = [{ p: pole, names: [poleName] }];
  for (const image of images) {
    const group = groups.find((g) => Math.hypot(g.p[0] - image.p[0], g.p[1] - image.p[1]) < SAME_PLACE);
    const name = imageSymbol(image.name);
    if (group) {
      if (!group.names.includes(name)) group.names.push(name);
    } else groups.push({ p: image.p, names: [name] });
  }
  const side = anchor === "end" ? -1 : 1;
  for (const group of groups) {
    figure.label(group.names.join(", "), [group.p[0] + side * 1.6, group.p[1] - 1.6],
      { anchor, target: group.p, attrs: { "data-role": "vertex" } });
  }
}
