/**
 * The mechanism taken apart as in Chaika–Vasylenko Fig. 3.3: the input mechanism I(0,1) (the crank on the
 * frame) and each class-II group alone, at the cursor angle, its outer pairs marked where it attaches
 * (open circles, the guide a dashed stroke) and its inner pair filled; each group under its name in the
 * structural formula (II₂(2,3)).
 */
import { element } from "../../common/view/dom.js";
import { fitScale, svgElement } from "../../common/view/svg.js";
import { linkShapes } from "../model/geometry.js";
import { groupName } from "../model/linkage.js";

const SIZE = [170, 130];

function figure(caption, label, shapes, outer, inner, guides) {
  const points = [...outer, ...inner].map((j) => j.at).concat(shapes.flatMap((s) => s.lines.flat()))
    .filter((p) => p && p.every(Number.isFinite));
  const svg = svgElement("svg", { viewBox: `0 0 ${SIZE[0]} ${SIZE[1]}`, class: "apart-svg", role: "img", "aria-label": label });
  if (points.length) {
    const { point } = fitScale(points, SIZE[0], SIZE[1], 22);
    for (const g of guides) {
      if (!g.at || !Number.isFinite(g.angle)) continue;
      const [x, y] = point(g.at);
      const [c, s] = [Math.cos(g.angle) * 30, -Math.sin(g.angle) * 30];
      svgElement("line", { x1: x - c, y1: y - s, x2: x + c, y2: y + s, class: "apart-guide" }, svg);
    }
    for (const shape of shapes) {
      for (const [a, b] of shape.lines) {
        if (!a || !b || ![...a, ...b].every(Number.isFinite)) continue;
        const [p, q] = [point(a), point(b)];
        svgElement("line", { x1: p[0], y1: p[1], x2: q[0], y2: q[1], class: "apart-link" }, svg);
      }
      for (const block of shape.blocks) {
        if (!block.at || !Number.isFinite(block.angle)) continue;
        const [x, y] = point(block.at);
        svgElement("rect", { x: x - 10, y: y - 5, width: 20, height: 10, class: "apart-block",
          transform: `rotate(${(-block.angle * 180) / Math.PI} ${x} ${y})` }, svg);
      }
    }
    for (const [joints, filled] of [[outer, false], [inner, true]]) {
      for (const j of joints) {
        if (!j.at) continue;
        const [x, y] = point(j.at);
        svgElement("circle", { cx: x, cy: y, r: 3.5, class: filled ? "apart-inner" : "apart-outer" }, svg);
        svgElement("text", { x: x + 5, y: y - 5, class: "apart-label" }, svg).textContent = j.name;
      }
    }
  }
  return element("figure", { className: "apart" }, svg, element("figcaption", { textContent: caption, translate: false }));
}

/** The figures into host, at state s (geometry.stateAt) of the table. */
export function renderGroupsApart(host, linkage, table, s, t) {
  if (!table || !linkage.input) {
    host.replaceChildren();
    return;
  }
  const shapes = linkShapes(linkage, table, s);
  const crank = linkage.input;
  const at = (name) => ({ name, at: s.joints[name] ?? null });
  const inputGuide = crank.kind === "slider" ? s.guideAt(crank.guide) : null;
  const figures = [figure(`I(0,${crank.link})`, t.editor_input_mechanism, shapes.filter((sh) => sh.link === crank.link),
    inputGuide ? [] : [at(crank.pivot)], [at(crank.joint)],
    inputGuide ? [{ at: s.joints[crank.joint] ?? inputGuide.point, angle: inputGuide.angle }] : [])];
  linkage.groups.forEach((group) => {
    const guideNames = group.guides ?? (group.guide ? [group.guide] : []);
    const guides = guideNames.map((name) => {
      const g = s.guideAt(name);
      const slider = group.kind === "RPP" ? s.joints[group.inner] : group.kind === "PRP" || group.kind === "RRP"
        ? s.joints[group.inner] : null;
      return { at: slider ?? g?.point, angle: g?.angle };
    });
    const inner = group.kind === "RPR" ? [] : [at(group.inner)];
    figures.push(figure(`${groupName(group)} ${group.kind}`,
      `${t.editor_group_apart} ${groupName(group)} ${group.kind}`, shapes.filter((sh) => group.links.includes(sh.link)),
      (group.outer ?? []).map(at), inner, guides));
  });
  host.replaceChildren(...figures);
}
