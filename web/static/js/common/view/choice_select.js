/**
 * View of a toggle shown as a drop-down list (`display: "select"`): a long list of choices, e.g. the rows of
 * a source's table (content/tables, server/lessons/tables.py). The model is the scene's SceneSettings, as for
 * the radio buttons: the list shows the toggle's value and sets it; options are told apart by their index,
 * so a number keeps its type.
 */
import { element } from "./dom.js";
import { plainText } from "./notation.js";

/** A labelled <select id="toggle-<id>"> for toggle over model (values, setValue) in lang. */
export function choiceSelect(toggle, model, lang) {
  const select = element("select", { id: `toggle-${toggle.id}` }, ...toggle.options.map((option, i) =>
    element("option", { value: String(i), textContent: plainText(toggle.option_labels[i][lang]),
      selected: option === model.values[toggle.id] })));
  select.addEventListener("change", () => model.setValue(toggle.id, toggle.options[Number(select.value)]));
  return element("label", { className: "field choice" }, element("span", { rich: toggle.label[lang] }), select);
}
