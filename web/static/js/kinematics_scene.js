/**
 * Kinematics scene page: wires the scene model, the kinematics client, the crank-angle clock and the views.
 * One kinematics table per parameter change; animation frames only interpolate in it.
 */
import { AnimationControls } from "./animation_controls.js";
import { CrankAnimation } from "./animation.js";
import { ApiClient } from "./api.js";
import { ControlsView } from "./controls_view.js";
import { LinkageView } from "./linkage_view.js";
import { PlotsView } from "./plots_view.js";
import { SceneModel } from "./scene_model.js";
import { StatusView } from "./status_view.js";
import { readState, writeState } from "./url_state.js";
import { byId, lang, scene, t, texts } from "./page_data.js";


const model = new SceneModel(scene, readState());
const animation = new CrankAnimation();
const stage = document.querySelector(".stage");
const client = new ApiClient(scene.endpoint, lang, (busy) => stage.classList.toggle("busy", busy));
const linkage = new LinkageView(byId("linkage"), texts);
const plots = new PlotsView(byId("plots"), { scene, ...texts });
const status = new StatusView(byId("status"), texts);
new ControlsView(byId("controls"), model, { ...texts, pickerLabel: t.mechanism });
new AnimationControls(byId("animation"), animation, texts);

let overlayKeys = [];

function requestOverlays() {
  const requests = model.overlayRequests();
  const keys = requests.map(({ lambda }) => `overlay ${lambda}`);
  for (const key of overlayKeys) if (!keys.includes(key)) client.forget(key);
  overlayKeys = keys;
  requests.forEach(({ lambda, body }, i) =>
    client.submit(keys[i], body, (answer) => model.receiveOverlay(lambda, answer)));
}

model.on("variant", (variant) => plots.build(variant));
model.on("params", () => {
  const body = model.request();
  client.submit("main", body, (answer) => model.receive(body, answer));
  requestOverlays();
  writeState(model, lang);
});
model.on("overlay", () => {
  requestOverlays();
  writeState(model, lang);
});
model.on("result", (answer) => {
  if (answer.ok) animation.setCycle(answer.data.cycle);
  linkage.show(answer, animation.phi);
  plots.show(answer, model.overlays);
  status.show(answer, model.overlays);
});
model.on("overlays", () => {
  if (!model.answer) return;
  plots.show(model.answer, model.overlays);
  status.show(model.answer, model.overlays);
});
animation.on("phi", (phi) => {
  linkage.drawAt(phi);
  plots.moveCursor(phi);
});

model.start();
