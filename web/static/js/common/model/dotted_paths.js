/**
 * Values inside nested objects named by dotted paths, as the scenes name them: a slider's "load.f" or
 * "params.l2" in a request body, a panel's "resisting.means.textbook" or "startup.omega" in an answer.
 * A number in a path indexes a list: "masses.forces.0.working" (server/lessons/requests.py, the twin).
 */

/** The value at path, or undefined where the path does not exist (null stays null). */
export function pathValue(object, path) {
  let value = object;
  for (const key of path.split(".")) {
    if (value === null || typeof value !== "object" || !(key in value)) return undefined;
    value = value[key];
  }
  return value;
}

/** Put value at path, making the objects on the way. */
export function setPath(object, path, value) {
  const keys = path.split(".");
  const last = keys.pop();
  let parent = object;
  for (const key of keys) parent = Array.isArray(parent) ? parent[Number(key)] : (parent[key] ??= {});
  parent[Array.isArray(parent) ? Number(last) : last] = value;
}
