/**
 * Dynamics scene page: wires the scene model, the client of the scene's endpoint (/reduction or
 * /motion) and the views. One request per change of the values; while a slider is dragged the client
 * keeps one in flight and sends only the latest values next.
 */
import { ApiClient } from "./api.js";
import { ControlsView } from "./controls_view.js";
import { DynamicsModel } from "./dynamics_model.js";
import { DynamicsView } from "./dynamics_view.js";
import { readState, writeState } from "./url_state.js";

const readJson = (id) => JSON.parse(document.getElementById(id).textContent);
const byId = (id) => document.getElementById(id);

const scene = readJson("scene-data");
const t = readJson("interface-texts");
const lang = document.documentElement.lang;
const texts = { t, lang };

const model = new DynamicsModel(scene, readState());
const results = document.querySelector(".results");
const client = new ApiClient(scene.endpoint, lang, (busy) => results.classList.toggle("busy", busy));
const view = new DynamicsView(byId("panels"), byId("notices"), { scene, ...texts });
new ControlsView(byId("controls"), model, { ...texts, pickerLabel: t.variant });

model.on("variant", (variant) => view.build(variant));
model.on("params", () => {
  client.submit("main", model.request(), (answer) => model.receive(answer));
  writeState(model, lang);
});
model.on("result", (answer) => view.show(answer));

model.start();
