/**
 * Kinematics scene page: wires the scene model, the kinematics client, the crank-angle clock and the views.
 * One kinematics table per parameter change; animation frames only interpolate in it. While a slider is
 * dragged and its family has arrived, the drawing and the plots follow tables interpolated from the family
 * (a preview, marked and with the numbers of the last exact table dimmed) and nothing is asked; the exact
 * table is asked for when the slider comes to rest.
 *
 * Performance marks (bench/browser.py): plots-drawn after a preview's redraw, exact-requested when an
 * exact table is asked for, exact-drawn once it is plotted.
 */
import { AnimationControls } from "../common/view/animation_controls.js";
import { CrankAnimation } from "../common/model/animation.js";
import { ApiClient } from "../common/model/api.js";
import { ControlsView } from "../common/view/controls_view.js";
import { CrankDrag } from "../common/view/crank_drag.js";
import { FamilyPreview, previewMark } from "../common/view/family_preview.js";
import { GhostCurves } from "../common/model/ghost_curves.js";
import { LinkageView } from "../common/view/linkage_view.js";
import { describePlots } from "../common/view/plot_alternatives.js";
import { PlotsView } from "./view/plots_view.js";
import { SceneModel } from "./model/scene_model.js";
import { sceneTools } from "../common/view/scene_tools.js";
import { StaleFeedback } from "../common/view/stale_feedback.js";
import { StatusView } from "./view/status_view.js";
import { readState, writeState } from "../common/model/url_state.js";
import { byId, lang, scene, t, texts } from "../common/view/page_data.js";


const model = new SceneModel(scene, readState());
const animation = new CrankAnimation();
const stage = document.querySelector(".stage");
const stale = new StaleFeedback([stage, byId("plots"), byId("status")], t.recomputing);
const client = new ApiClient(scene.endpoint, lang, (busy) => {
  stage.classList.toggle("busy", busy);
  stale.busy(busy);
});
const linkage = new LinkageView(byId("linkage"), texts);
const ghosts = new GhostCurves(t.pinned);
const plots = new PlotsView(byId("plots"), { scene, ...texts }, ghosts);
new CrankDrag(linkage, animation, texts);
sceneTools(model, ghosts, () => plots.graphs(), texts);
const status = new StatusView(byId("status"), texts);
new ControlsView(byId("controls"), model, { ...texts, pickerLabel: t.mechanism });
new AnimationControls(byId("animation"), animation, texts);

let overlayKeys = [];

function requestOverlays(drag = false) {
  const requests = model.overlayRequests();
  const keys = requests.map(({ lambda }) => `overlay ${lambda}`);
  for (const key of overlayKeys) if (!keys.includes(key)) client.forget(key);
  overlayKeys = keys;
  requests.forEach(({ lambda, body }, i) =>
    client.submit(keys[i], body, (answer) => model.receiveOverlay(lambda, answer), { drag }));
}

model.on("variant", (variant) => plots.build(variant));
const previews = new FamilyPreview(scene.endpoint, lang, model);
const markPreview = previewMark(stage, texts);
let previewed = null;      // the preview on the screen, if any

/** The exact answer and the overlays; drag: asked while the slider is dragged with no family (api.js). */
function requestExact(drag = false) {
  performance.mark("exact-requested");
  const body = model.request();
  client.submit("main", body, (answer) => model.receive(body, answer), { drag });
  requestOverlays(drag);
}

model.on("params", () => {
  writeState(model, lang);
  if (previews.preview()) client.forget("main");     // drawn from the family: an answer on its way is old
  else requestExact(model.grabbed !== null);
});
model.on("rest", () => {
  if (previews.showing) requestExact();
  else {                                             // a drag's last questions, still waiting: sent at rest
    const body = model.request();
    client.submit("main", body, (answer) => model.receive(body, answer));
    requestOverlays();
  }
});
model.on("overlay", () => {
  requestOverlays();
  writeState(model, lang);
});
previews.on("preview", (answer) => {
  previewed = answer;
  markPreview(true);
  linkage.show(answer, animation.phi);
  plots.preview(answer, model.overlays).then(() => performance.mark("plots-drawn"));
});
previews.on("family", () => plots.useFamily(previews.held()));
model.on("result", (answer) => {
  previews.end();
  previewed = null;
  markPreview(false);
  if (answer.ok) animation.setCycle(answer.data.cycle);
  linkage.show(answer, animation.phi);
  plots.family = previews.held();        // its axes hold the family's members: the next preview fits them
  plots.show(answer, model.overlays);
  status.show(answer, model.overlays);
  plots.drawn().then(() => performance.mark("exact-drawn"));
});
model.on("overlays", () => {
  if (!model.answer) return;
  if (previewed) plots.preview(previewed, model.overlays);
  else plots.show(model.answer, model.overlays);
  status.show(model.answer, model.overlays);
});
animation.on("phi", (phi) => {
  linkage.drawAt(phi);
  plots.moveCursor(phi);
});

describePlots(document.querySelector("main"), texts);     // text alternatives of the plots
model.start();
