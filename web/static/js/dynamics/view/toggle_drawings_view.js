/**
 * Panel view of a linkage drawn once for every option of one of the variant's toggles, side by side (the elastic
 * four-bar's two assemblies, the '+' and '−' signs of Drakunov–Tuleshova (4)): joints from
 * POST /api/v1/kinematics for the request's mechanism and lengths with the toggle's parameter set to each option,
 * each drawing captioned by the option's label; the option the request computes is marked. spec.toggle names the
 * toggle (its id), spec.param the parameter of the kinematics request it sets ("assembly"). The drawings turn with
 * the page's crank angle; the first one's crank turns by hand.
 */
import { ApiClient } from "../../common/model/api.js";
import { element } from "../../common/view/dom.js";
import { LinkageView } from "../../common/view/linkage_view.js";

const JOINT_POINTS = 361;     // a grid step of 1° of crank angle

export class ToggleDrawingsView {
  /** model: the scene's DynamicsModel, whose request names the mechanism and its lengths and whose values the toggle. */
  constructor(body, spec, { t, lang }, model) {
    this.spec = spec;
    this.model = model;
    this.t = t;
    this.lang = lang;
    this.phi = 0;
    this.toggle = model.variant.toggles.find((toggle) => toggle.id === spec.toggle);
    this.kinematics = new ApiClient("kinematics", lang, (busy) => body.classList.toggle("busy", busy));
    this.drawings = this.toggle.options.map((option, i) => {
      const stage = element("div", { className: "linkage" });
      const caption = element("figcaption", { rich: this.toggle.option_labels[i][lang] });
      const figure = element("figure", { className: "toggle-drawing" }, stage, caption);
      return { option, figure, linkage: new LinkageView(stage, { t, lang }), joints: null };
    });
    body.append(element("div", { className: "toggle-drawings" }, ...this.drawings.map((d) => d.figure)));
    this.turnable = this.drawings[0].linkage;
  }

  /** Drawn once the answer holds what the panel needs (its lengths were computed, not refused). */
  holds(data) {
    return this.spec.needs.every((name) => data[name] !== undefined);
  }

  /** Take the answer: ask for each option's joints (the client drops answers to older lengths) and draw. */
  show() {
    const request = this.model.request();
    const chosen = this.model.values[this.toggle.id];
    for (const drawing of this.drawings) {
      const computed = String(drawing.option) === String(chosen);     // an address gives the value as text
      drawing.figure.classList.toggle("chosen", computed);
      drawing.figure.setAttribute("aria-current", String(computed));
      const params = { ...request.params, [this.spec.param]: drawing.option };
      this.kinematics.submit(`option ${drawing.option}`, {
        mechanism: request.mechanism, params, n: JOINT_POINTS, outputs: ["joints"] }, (answer) => {
        drawing.joints = answer;
        drawing.linkage.show(answer, this.phi);
      });
    }
  }

  drawAt(phi) {
    this.phi = phi;
    for (const drawing of this.drawings) if (drawing.joints) drawing.linkage.drawAt(phi);
  }
}
