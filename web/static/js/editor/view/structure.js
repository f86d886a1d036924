/**
 * The structural analysis (Chaika–Vasylenko §3.1; Chebyshev's formula W = 3n − 2p₅ − p₄), the structural
 * formula I(0,1) → II₃(2,3) → …, the class of the mechanism and its groups, each by its name in the formula
 * (class II, Artobolevsky's kind as the subscript, its links); or why the mechanism is refused.
 */
import { element } from "../../common/view/dom.js";

export function renderStructure(host, structure, refusal, t) {
  if (refusal) {
    host.replaceChildren(element("div", { className: "refusal", role: "alert" },
      element("strong", { textContent: t.editor_refused }), element("p", { textContent: refusal })));
    return;
  }
  if (!structure) {
    host.replaceChildren(element("p", { className: "hint", textContent: t.editor_no_crank }));
    return;
  }
  const s = structure;
  const list = element("dl", { className: "structure-list" },
    element("dt", { textContent: t.editor_n }), element("dd", { textContent: String(s.n), "data-q": "n" }),
    element("dt", { rich: t.editor_p5 }), element("dd", { textContent: String(s.p5), "data-q": "p5" }),
    element("dt", { rich: t.editor_p4 }), element("dd", { textContent: String(s.p4), "data-q": "p4" }),
    element("dt", { textContent: t.editor_mobility }),
    element("dd", { id: "editor-mobility", textContent: `W = 3·${s.n} − 2·${s.p5} − ${s.p4} = ${s.W}` }),
    element("dt", { textContent: t.editor_formula }),
    element("dd", { id: "editor-formula", textContent: s.formula }),
    element("dt", { textContent: t.editor_class }),
    element("dd", { id: "editor-class", textContent: `${s.class === 2 ? "II" : "I"}` }));
  const groups = element("ul", { className: "structure-groups" }, ...s.groups.map((g) => element("li", { "data-group-name": g.name },
    `${g.name} — ${g.kind}, ${t.editor_kind} ${g.kind_number}: ${t.editor_attached_to} ${g.attached_to.join(", ")}`)));
  host.replaceChildren(list, groups);
}
