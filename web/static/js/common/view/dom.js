/** Building HTML elements in the views. */
import { richText } from "./notation.js";

/**
 * <tag> with attributes (properties when the name is a property, e.g. textContent) and children; the
 * attribute `rich` is an interface text put in as rich text (its subscripts as <sub>, notation.js).
 */
export function element(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes)) {
    if (name === "rich") node.append(richText(value));
    else if (name in node && !name.includes("-")) node[name] = value;
    else node.setAttribute(name, value);
  }
  node.append(...children);
  return node;
}
