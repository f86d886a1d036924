"""HTTP round trips against the floor of a bare endpoint, old app beside new.

Starts the old and the new app as the README says (``python3 -m server --port P``, one worker each, from their
own trees) and a bare Starlette/uvicorn app (bench/floor_app.py) that answers with the very bytes each app sent
for the kinematics page's default request (transfer functions, sine, 361 crank angles), captured once, with the
same Content-Type and Content-Encoding. One client (``http.client``, one keep-alive connection per target,
gzip accepted like a browser) then times round trips (send to last byte), the targets taking turns request by
request:

* kinematics, computed: the default request with the crank length scaled by 1 + k·1e-8 (k = 1, 2, …), so that
  the response cache (keys to 10 significant digits) misses every time and the app computes each answer;
* kinematics, cached: the same request every time (after the first: a cache hit);
* the floor: the same request to the bare app, answered with the captured bytes.

Then every scene's default request (its first variant at the sliders' defaults, one slider's value scaled by
1 + k·1e-8 against the cache) on the idle servers, old, new and the floor taking turns request by request; the
floor answers each scene's request with the very bytes the new app sent for it (captured once, before the floor
starts), so each scene has a floor of its own size measured beside it under the same load. Targets: kinematics
computed ≤ 2× the floor, every scene's default request ≤ 10× its floor at p50.

    python bench/http_floor.py [--old /tmp/mdl-old] [--new .] [--requests 500] [--scene-requests 30]
                               [--elastic-requests 10] [--scenes ID ...] [--output bench/results/http_floor.md]
"""
from __future__ import annotations

import argparse
import copy
import http.client
import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from trees import (ROOT, add_tree_arguments, check_tree, lessons, machine_line,  # noqa: E402
                   percentiles, running_server, write_result)

sys.path.insert(0, str(ROOT))
HEADERS = {"Content-Type": "application/json", "Accept-Encoding": "gzip", "Accept": "*/*"}
LANG = "ru"
NUDGE = 1e-8                    # relative change per request: a new cache key (10 digits), the same physics
FLOOR_RATIO_TARGET = 2.0
SCENE_FLOOR_TARGET = 10.0       # every scene's default answer ≤ 10× the floor (p50)
KINEMATICS = ("transfer-functions", "sine")


class Target:
    """One keep-alive connection to one endpoint; each round trip's time and X-Cache are kept."""

    def __init__(self, label: str, port: int, path: str):
        self.label, self.port, self.path = label, port, path
        self.connection = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
        self.times: list[float] = []
        self.cache: dict[str, int] = {}
        self.errors = 0

    def post(self, body: bytes, keep: bool = True) -> tuple[int, bytes, dict]:
        """One round trip; a connection the server closed while idle (uvicorn's keep-alive timeout, 5 s)
        is opened again and the request sent once more, timed from then."""
        for attempt in range(2):
            start = time.perf_counter()
            try:
                self.connection.request("POST", self.path, body=body, headers=HEADERS)
                answer = self.connection.getresponse()
                raw = answer.read()
                break
            except (OSError, http.client.HTTPException):
                self.connection.close()
                self.connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=120)
        else:
            self.errors += keep
            return 0, b"", {}
        elapsed = time.perf_counter() - start
        if keep:
            self.times.append(1000 * elapsed)
            cache = answer.getheader("x-cache", "none")
            self.cache[cache] = self.cache.get(cache, 0) + 1
            self.errors += not 200 <= answer.status < 300
        return answer.status, raw, {k.lower(): v for k, v in answer.getheaders()}


def variant_of(scene, variant_id: str | None = None):
    return next(v for v in scene.variants if variant_id in (None, v.id))


def nudged_request(scene, variant, k: int) -> dict:
    """The page's default request with one length or slider value scaled by 1 + k·NUDGE (k = 0: the default;
    the kinematics round trips take k > 0, the scenes' default requests k < 0)."""
    _, scene_request, _, defaults, _ = lessons()
    factor = 1 + k * NUDGE
    if scene.kind == "kinematics":
        body = copy.deepcopy(scene_request(scene, variant))
        name = "l1" if "l1" in body["params"] else next(iter(body["params"]))
        body["params"][name] *= factor
        return body
    values = defaults(variant)
    slider = next((s for s in variant.sliders if s.default), None)
    if slider is not None:
        values[slider.id] = slider.default * factor
    return scene_request(scene, variant, values)


def encoded(body: dict) -> bytes:
    return json.dumps(body, separators=(",", ":")).encode()


def capture(port: int, path: str, body: bytes, directory: Path, name: str) -> int:
    """The app's answer bytes (as sent: gzip) and their headers, stored for the floor app; returns the size."""
    status, raw, headers = Target(name, port, path).post(body, keep=False)
    if status != 200:
        raise RuntimeError(f"{name}: HTTP {status} for the kinematics default request")
    (directory / f"{name}.body").write_bytes(raw)
    kept = {k: headers[k] for k in ("content-type", "content-encoding") if k in headers}
    (directory / f"{name}.json").write_text(json.dumps(kept))
    return len(raw)


def kinematics_round_trips(ports: dict, floor_port: int, requests: int) -> tuple[list[Target], dict]:
    scenes = lessons()[0]()
    scene = scenes[KINEMATICS[0]]
    variant = variant_of(scene, KINEMATICS[1])
    path = f"/api/v1/kinematics?lang={LANG}"
    default = encoded(nudged_request(scene, variant, 0))
    targets = []
    for tree, port in ports.items():
        targets += [Target(f"{tree} app, computed", port, path), Target(f"{tree} app, cached", port, path),
                    Target(f"{tree} floor", floor_port, f"/{tree}")]
    for _ in range(5):                                            # connections, first calls
        for target in targets:
            target.post(default, keep=False)
    for k in range(1, requests + 1):
        nudged = encoded(nudged_request(scene, variant, k))
        for target in targets[k % len(targets):] + targets[:k % len(targets)]:
            target.post(nudged if target.label.endswith("computed") else default)
    return targets, {"request": json.loads(default)}


def session_cpu_s(session: int) -> float:
    """CPU seconds (user + system) of every live process in the session (a server started in a session of its
    own: its workers and process pools included), from /proc; NaN where /proc is not there."""
    if not os.path.isdir("/proc"):
        return float("nan")
    total, tick = 0.0, os.sysconf("SC_CLK_TCK")
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            fields = Path(f"/proc/{entry}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[3]) == session:                # field 6 of stat: the session id
            total += (int(fields[11]) + int(fields[12])) / tick
    return total


def chosen_scenes(only: list[str] | None) -> list:
    return [scene for scene in lessons()[0]().values() if not only or scene.id in only]


def capture_scenes(port: int, directory: Path, only: list[str] | None) -> dict:
    """Each scene's default answer from the new app, stored for the floor as ``scene-<id>``; {id: bytes sent}
    (None where the app refused it)."""
    sizes = {}
    for scene in chosen_scenes(only):
        body = encoded(nudged_request(scene, variant_of(scene), 0))
        try:
            sizes[scene.id] = capture(port, f"/api/v1/{scene.endpoint}?lang={LANG}", body, directory,
                                      f"scene-{scene.id}")
        except RuntimeError:
            sizes[scene.id] = None
    return sizes


def scene_round_trips(ports: dict, floor_port: int, light: int, elastic: int, sizes: dict,
                      sessions: dict) -> dict:
    """{scene: (scene, variant, {tree: Target, "floor": Target})} for every scene's default request, nudged
    against the cache; the floor answers the same request with the new app's bytes for it. Each target's
    ``cpu_ms``: the CPU its server's session spent per timed request (``sessions``: {label: session id}),
    which the machine's load does not inflate as it does the wall-clock times."""
    found = {}
    for scene in chosen_scenes(list(sizes)):
        variant = variant_of(scene)
        path = f"/api/v1/{scene.endpoint}?lang={LANG}"
        targets = {tree: Target(tree, port, path) for tree, port in ports.items()}
        if sizes[scene.id] is not None:
            targets["floor"] = Target("floor", floor_port, f"/scene-{scene.id}")
        for target in targets.values():                          # warm-up, untimed
            target.post(encoded(nudged_request(scene, variant, 0)), keep=False)
        count = elastic if scene.endpoint == "elastic" else light
        before = {label: session_cpu_s(sessions[label]) for label in targets}
        for k in range(1, count + 1):
            body = encoded(nudged_request(scene, variant, -k))
            order = list(targets.values())
            shift = k % len(order)
            for target in order[shift:] + order[:shift]:
                target.post(body)
        for label, target in targets.items():
            target.cpu_ms = 1000 * (session_cpu_s(sessions[label]) - before[label]) / count
        found[scene.id] = (scene, variant, targets)
        print(f"{scene.id}: done", file=sys.stderr, flush=True)
    return found


def cpu_cells(targets: dict, floor: float) -> str:
    """'old / new | old× / new×': the CPU each server spent per request and its ratio to the floor's
    (``floor``: the floor's CPU per request over the kinematics round trips, hundreds of them)."""
    cpu = {label: getattr(target, "cpu_ms", float("nan")) for label, target in targets.items()}
    ratio = lambda label: "–" if not floor > 0 else f"{cpu[label] / floor:.0f}×"
    return f"{fmt(cpu['old'])} / {fmt(cpu['new'])} | {ratio('old')} / {ratio('new')}"


def counts(cache: dict) -> str:
    return ", ".join(f"{name} {count}" for name, count in sorted(cache.items())) or "–"


def fmt(ms: float) -> str:
    return "–" if ms != ms else (f"{ms:.0f}" if ms >= 100 else f"{ms:.1f}")


def markdown(args, targets: list[Target], sizes: dict, scenes: dict, startup: dict) -> str:
    by_label = {t.label: t for t in targets}
    lines = ["# HTTP round trips against the floor, old beside new", "",
             f"{machine_line()}. `python bench/http_floor.py --requests {args.requests} --scene-requests "
             f"{args.scene_requests} --elastic-requests {args.elastic_requests}"
             f"{' --scenes ' + ' '.join(args.scenes) if args.scenes else ''}`.", "",
             f"* old tree: `{args.old}` (a worktree of the baseline), new tree: `{args.new}`; each "
             f"`python3 -m server --port <free port>` (1 worker) from its tree (ready after {startup['old']:.1f} s "
             f"and {startup['new']:.1f} s); the floor: `bench/floor_app.py` (bare Starlette under uvicorn) "
             "answering with the bytes the app sent for the same request.",
             f"* Client: `http.client`, one keep-alive connection per target, `Accept-Encoding: gzip`; time from "
             f"sending to the last byte; the targets take turns request by request; {args.requests} requests each.",
             "", "## Kinematics (transfer functions, sine, 361 crank angles)", "",
             "| tree | bytes on the wire | computed p50 | computed p95 | cached p50 | cached p95 | floor p50 "
             "| floor p95 | computed / floor (p50) | computed / floor (p95) | ≤ 2× floor (p50 and p95) "
             "| X-Cache computed / cached "
             "| errors |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|"]
    for tree in ("old", "new"):
        computed, cached, floor = (by_label[f"{tree} {s}"] for s in ("app, computed", "app, cached", "floor"))
        c50, c95 = percentiles(computed.times)
        h50, h95 = percentiles(cached.times)
        f50, f95 = percentiles(floor.times)
        lines.append(f"| {tree} | {sizes[tree]} | {fmt(c50)} | {fmt(c95)} | {fmt(h50)} | {fmt(h95)} | {fmt(f50)} | "
                     f"{fmt(f95)} | {c50 / f50:.2f}× | {c95 / f95:.2f}× | "
                     f"{'yes' if max(c50 / f50, c95 / f95) <= FLOOR_RATIO_TARGET else '**no**'} | "
                     f"{counts(computed.cache)} / {counts(cached.cache)} | "
                     f"{computed.errors + cached.errors + floor.errors} |")
    old_c, new_c = (percentiles(by_label[f"{t} app, computed"].times) for t in ("old", "new"))
    lines += ["", f"Computed kinematics round trip, old/new: p50 {old_c[0] / new_c[0]:.1f}×, "
                  f"p95 {old_c[1] / new_c[1]:.1f}×.", "",
              "## Every scene's default request against its floor", "",
              f"The scene's first variant at its defaults (one value nudged by 1 + k·{NUDGE:g} so that each request "
              f"is computed, not cached); {args.scene_requests} requests per target "
              f"({args.elastic_requests} for the elastic scenes), old, new and the floor taking turns. The floor: "
              "the bare app answering the same request with the bytes the new app sent for it. Times in ms; "
              f"× floor = p50 / the floor's p50 beside it. Target: new ≤ {SCENE_FLOOR_TARGET:g}× floor. CPU per "
              "request: the CPU time of each server's processes over the scene's timed requests (from /proc, "
              "1/100 s ticks), divided by their count; a loaded machine stretches wall-clock times far more than "
              "the CPU a request takes. CPU × floor: against the floor's CPU per request over the kinematics "
              f"round trips, {args.floor_cpu_ms:.2f} ms. "
              f"Load average at the end: {os.getloadavg()[0]:.1f}.", "",
              "| scene | variant | endpoint | bytes (gzip) | floor p50 | old p50 | old p95 | old × floor | new p50 "
              f"| new p95 | new × floor | old/new (p50) | new ≤ {SCENE_FLOOR_TARGET:g}× floor | CPU ms per request: "
              "old / new | CPU × floor: old / new | X-Cache new | errors old / new |",
              "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|---|"]
    for scene, variant, targets in scenes.values():
        o50, o95 = percentiles(targets["old"].times)
        n50, n95 = percentiles(targets["new"].times)
        floor = targets.get("floor")
        f50 = percentiles(floor.times)[0] if floor is not None else float("nan")
        size = sizes.get(f"scene-{scene.id}")
        within = "–" if f50 != f50 else ("yes" if n50 / f50 <= SCENE_FLOOR_TARGET else "**no**")
        lines.append(f"| {scene.id} | {variant.id} | {scene.endpoint} | {size if size is not None else '–'} | "
                     f"{fmt(f50)} | {fmt(o50)} | {fmt(o95)} | {o50 / f50:.1f}× | {fmt(n50)} | {fmt(n95)} | "
                     f"{n50 / f50:.1f}× | {o50 / n50:.1f}× | {within} | {cpu_cells(targets, args.floor_cpu_ms)} | "
                     f"{counts(targets['new'].cache)} | {targets['old'].errors} / {targets['new'].errors} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_tree_arguments(parser)
    parser.add_argument("--requests", type=int, default=500, help="kinematics round trips per target")
    parser.add_argument("--scene-requests", type=int, default=30, help="default requests per light scene and server")
    parser.add_argument("--elastic-requests", type=int, default=10, help="the same for the elastic scenes")
    parser.add_argument("--scenes", nargs="*", help="only these scene ids (default: every scene)")
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "http_floor.md")
    args = parser.parse_args(argv)
    args.old, args.new = check_tree(args.old), check_tree(args.new)
    with running_server(tree=args.old) as (old_port, old_process), \
            running_server(tree=args.new) as (new_port, new_process), \
            tempfile.TemporaryDirectory(prefix="mdl-floor-") as directory:
        ports = {"old": old_port, "new": new_port}
        scene = lessons()[0]()[KINEMATICS[0]]
        default = encoded(nudged_request(scene, variant_of(scene, KINEMATICS[1]), 0))
        sizes = {tree: capture(port, f"/api/v1/kinematics?lang={LANG}", default, Path(directory), tree)
                 for tree, port in ports.items()}
        sizes |= {f"scene-{name}": size for name, size in capture_scenes(new_port, Path(directory),
                                                                         args.scenes).items()}
        floor_command = [sys.executable, str(Path(__file__).resolve().parent / "floor_app.py"), "{port}", directory]
        with running_server(tree=ROOT, command=floor_command, ready_path="/ready") as (floor_port, floor_process):
            floor_cpu = session_cpu_s(floor_process.pid)
            targets, _ = kinematics_round_trips(ports, floor_port, args.requests)
            args.floor_cpu_ms = 1000 * (session_cpu_s(floor_process.pid) - floor_cpu) / (2 * args.requests + 10)
            sessions = {"old": old_process.pid, "new": new_process.pid, "floor": floor_process.pid}
            scenes = scene_round_trips(ports, floor_port, args.scene_requests, args.elastic_requests,
                                       {name[len("scene-"):]: size for name, size in sizes.items()
                                        if name.startswith("scene-")}, sessions)
        startup = {"old": old_process.startup_s, "new": new_process.startup_s}
    text = markdown(args, targets, sizes, scenes, startup)
    print(text)
    write_result(text, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
