/**
 * Dynamics scene page: wires the scene model, the client of the scene's endpoint (/reduction, /motion,
 * /forces, …) and the views. One request per change of the values; while a slider is dragged the client
 * keeps one in flight and sends only the latest values next. A variant with a drawing gets the
 * crank-angle clock and its controls above the parameters; animation frames only interpolate in the answer.
 * A drawing's crank turns by hand too (crank_drag.js): the clock is put at the pointer's angle, so the plots'
 * cursors and every per-angle readout follow as they follow the animation, and nothing is asked.
 * While a slider is dragged and its family has arrived, plots and drawings follow answers interpolated from
 * the family (a preview, marked and with the numbers of the last exact answer dimmed) and nothing is asked;
 * the exact answer is asked for when the slider comes to rest.
 *
 * A variant that computes the reader's own mechanism takes it from the address (address_mechanism.js); without
 * one it asks for nothing and says how to get one (a link to the editor).
 *
 * Performance marks (bench/browser.py): plots-drawn after a preview's redraw, exact-requested when an
 * exact answer is asked for, exact-drawn once it is plotted.
 */
import { AnimationControls } from "../common/view/animation_controls.js";
import { CrankAnimation } from "../common/model/animation.js";
import { ApiClient } from "../common/model/api.js";
import { ControlsView } from "../common/view/controls_view.js";
import { CrankDrag } from "../common/view/crank_drag.js";
import { element } from "../common/view/dom.js";
import { DynamicsModel } from "./model/dynamics_model.js";
import { DynamicsView } from "./view/dynamics_view.js";
import { FamilyPreview, previewMark } from "../common/view/family_preview.js";
import { GhostCurves } from "../common/model/ghost_curves.js";
import { describePlots } from "../common/view/plot_alternatives.js";
import { PresetsView } from "./view/presets_view.js";
import { sceneTools } from "../common/view/scene_tools.js";
import { StaleFeedback } from "../common/view/stale_feedback.js";
import { readState, writeState } from "../common/model/url_state.js";
import { resolveAddressVariants } from "../common/model/address_mechanism.js";
import { byId, lang, scene, t, texts } from "../common/view/page_data.js";

const TURN = 2 * Math.PI;
/** A cycle of crank angle is a whole number of turns: 2π, or 4π for a four-stroke engine. */
const wholeTurns = (phi) => Math.max(1, Math.round(phi / TURN)) * TURN;


resolveAddressVariants(scene);      // a reader's own mechanism from the address (m, d), before the model reads them
const model = new DynamicsModel(scene, readState());
const results = document.querySelector(".results");
const stale = new StaleFeedback([results], t.recomputing);
const client = new ApiClient(scene.endpoint, lang, (busy) => {
  results.classList.toggle("busy", busy);
  stale.busy(busy);
});
const ghosts = new GhostCurves(t.pinned);
const animation = new CrankAnimation();
const view = new DynamicsView(byId("panels"), byId("notices"), { scene, ...texts }, model, ghosts,
  (drawing) => new CrankDrag(drawing, animation, texts));
sceneTools(model, ghosts, () => view.graphs(), texts);
new ControlsView(byId("controls"), model, { ...texts, pickerLabel: t.variant });
new PresetsView(byId("controls"), model, texts);
const animationBar = element("section", { id: "animation", className: "animation", "aria-label": t.animation });
new AnimationControls(animationBar, animation, texts);

model.on("variant", (variant) => {
  view.build(variant);
  byId("controls").classList.toggle("no-mechanism", Boolean(variant.addressMissing));   // its sliders move nothing
  if (view.animated) {
    byId("controls").before(animationBar);
  } else {
    animation.pause();
    animationBar.remove();
  }
});
const previews = new FamilyPreview(scene.endpoint, lang, model);
const markPreview = previewMark(results, texts);

/** The exact answer; drag: asked while the slider is dragged with no family to draw from (api.js). */
function requestExact(drag = false) {
  if (model.variant.addressMissing) {          // an own-mechanism variant with no mechanism in the address
    client.forget("main");
    view.showMissingMechanism();
    return;
  }
  performance.mark("exact-requested");
  const body = model.request();
  if (body.outputs.length) client.submit("main", body, (answer) => model.receive(answer), { drag });
  else model.receive({ ok: true, data: { warnings: [] } });   // an assignment hid every computed panel
}

model.on("preset", () => writeState(model, lang));
model.on("params", () => {
  writeState(model, lang);
  if (!model.variant.addressMissing && previews.preview()) client.forget("main");     // drawn from the family: an answer on its way is old
  else requestExact(model.grabbed !== null);
});
model.on("rest", () => {
  if (previews.showing) requestExact();
  else if (!model.variant.addressMissing) {    // a drag's last question still waiting: sent at rest
    const body = model.request();
    if (body.outputs.length) client.submit("main", body, (answer) => model.receive(answer));
  }
});
previews.on("preview", (answer) => {
  markPreview(true);
  view.preview(answer.data).then(() => performance.mark("plots-drawn"));
});
previews.on("family", () => view.useFamily(previews.held()));
model.on("result", (answer) => {
  previews.end();
  markPreview(false);
  if (view.animated && answer.ok && Array.isArray(answer.data.phi)) animation.setCycle(wholeTurns(answer.data.phi.at(-1)));
  view.family = previews.held();        // its axes hold the family's members: the next preview fits them
  view.show(answer);
  view.drawn().then(() => performance.mark("exact-drawn"));
});
animation.on("phi", (phi) => view.drawAt(phi));

describePlots(document.querySelector("main"), texts);     // text alternatives of the plots
model.start();
