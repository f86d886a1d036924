"""A student's own mechanism carried from the editor into the dynamics scenes, in a real browser: a preset loaded
and changed (a rod's length), one mass edited in "Masses and loads", the equation of motion opened from the
editor draws the steady cycle and follows M₀; the link keeps the mechanism and the edited mass; the flywheel and
forces scenes open and draw; without a mechanism in the address the variant says how to get one. No console
problems; screenshots in ru and at phone size."""
from __future__ import annotations

import base64
import json
import math
import re
from pathlib import Path

import pytest

from conftest import ARTIFACTS, PHONE, REPO, drag_slider, interface_texts, read_scene, screenshot
from test_dynamics import figure_value, open_scene, trace, wait_for_new_trace, wait_for_panels
from test_editor import REFUSED, act, number
from test_general_dynamics_scenes import english_words

pytestmark = pytest.mark.browser

MOTION = read_scene("equation_of_motion")
FLYWHEEL = read_scene("flywheel")
FORCES = read_scene("forces_friction")
INERTIA = read_scene("reduced_inertia")
MOMENT = read_scene("resisting_moment")
SHAPING = json.loads((REPO / "content" / "mechanisms" / "shaping_machine.json").read_text(encoding="utf-8"))
ROD = '[data-group="1"] > label.field input[type="text"]'      # the RRP group's rod length
MASS = 'input[data-path="masses.links.1.mass"]'                 # the rocker's mass (link 3)


def own(scene: dict) -> dict:
    return next(v for v in scene["variants"] if v["id"] == "own")


def masses_ready(page) -> None:
    page.wait_for_function("() => document.querySelector('#editor-open-dynamics a[data-scene]') !== null",
                           timeout=30_000)


def estimated(page) -> int:
    """How many estimates the editor's masses table has taken."""
    return int(page.get_attribute("#editor-masses", "data-estimates") or 0)


def open_from_editor(page, scene: dict) -> None:
    with page.expect_navigation(url=re.compile(r"/scenes/")):       # not the editor's own address rewritten meanwhile
        page.click(f'#editor-open-dynamics a[data-scene="{scene["id"]}"]')
    wait_for_panels(page, scene, own(scene))


def test_own_mechanism_from_the_editor_into_the_dynamics_scenes(browser_page):
    page = browser_page
    page.goto("/editor?lang=ru")
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state !== undefined")
    act(page, lambda: page.select_option("#editor-preset", "shaping_machine"))
    masses_ready(page)
    assert number(page.input_value(MASS)) == 11.0                       # the preset's, not the estimate
    page.fill(MASS, "15,5")                                             # one mass edited
    page.press(MASS, "Tab")
    estimates = estimated(page)
    act(page, lambda: (page.fill(ROD, "0,2"), page.press(ROD, "Enter")))   # the student's own: a longer rod
    page.wait_for_function("n => Number(document.querySelector('#editor-masses').dataset.estimates) > n",
                           arg=estimates)
    assert number(page.input_value(MASS)) == 15.5                       # kept on the changed mechanism
    assert number(page.input_value('input[data-path="masses.links.2.mass"]')) == 3.0   # the preset's rod, kept
    page.wait_for_function("""() => { const d = new URLSearchParams(location.search).get('d');
        return d && JSON.parse(atob(d.replace(/-/g, '+').replace(/_/g, '/'))).masses.links[1].mass === 15.5; }""")
    page.locator("#editor-dynamics").screenshot(path=ARTIFACTS / "own_mechanism_masses_table_ru.png")
    screenshot(page, "own_mechanism_editor_masses_ru")
    editor = page.url

    open_from_editor(page, MOTION)                                      # the steady cycle of the student's machine
    assert page.inner_text("#notices") == ""
    sent = page.evaluate("() => new URLSearchParams(location.search).get('variant')")
    assert sent == "own"
    before = trace(page, "omega_phi")
    drag_slider(page, "#slider-M0", 0.9)                                # a stronger motor: another steady cycle
    wait_for_new_trace(page, "omega_phi", before)
    assert "NaN" not in page.inner_html("#panels")
    assert english_words(page) == []
    screenshot(page, "own_mechanism_motion_ru")

    page.goto(editor)                                                   # the link is the document
    masses_ready(page)
    assert number(page.input_value(MASS)) == 15.5
    assert number(page.input_value(ROD)) == 0.2
    open_from_editor(page, FLYWHEEL)
    assert page.inner_text("#notices") == ""
    page.go_back()
    masses_ready(page)
    open_from_editor(page, FORCES)
    assert "NaN" not in page.inner_html("#panels")
    screenshot(page, "own_mechanism_forces_ru")
    page.go_back()
    masses_ready(page)
    offered = page.eval_on_selector_all("#editor-open-dynamics a[data-scene]", "as => as.map((a) => a.dataset.scene)")
    assert sorted(offered) == sorted([*(scene["id"] for scene in (MOTION, FLYWHEEL, FORCES, INERTIA, MOMENT)),
                                      "course-project"])      # and the course project's assignments
    for scene in (INERTIA, MOMENT):                                     # the reduced model, link by link
        open_from_editor(page, scene)
        assert page.inner_text("#notices") == ""
        assert "NaN" not in page.inner_html("#panels") and english_words(page) == []
        parts = "link_parts" if scene is INERTIA else "load_parts"
        page.wait_for_function("id => document.querySelector(`#panel-${id} .graph`)?.data?.length > 1", arg=parts)
        if scene is MOMENT:                                             # the table's loads × 2.7: another M_c
            before = trace(page, "general_moment")
            drag_slider(page, "#slider-load_factor", 0.9)
            wait_for_new_trace(page, "general_moment", before)
            page.wait_for_function("() => new URLSearchParams(location.search).get('load_factor') === '2.7'")
        screenshot(page, f"own_mechanism_{scene['id'].replace('-', '_')}_ru")
        page.go_back()
        masses_ready(page)
    assert page.problems == []


def address_dynamics(page) -> dict:
    return page.evaluate("""() => JSON.parse(atob(new URLSearchParams(location.search).get('d')
        .replace(/-/g, '+').replace(/_/g, '/')))""")


def sent_body(request) -> dict:
    return json.loads(request.post_data)


ROCKER_LOAD = {"link": 3, "working": 400.0, "k": 0.25, "sense": -1}
# the shaping machine's rocker swings through 2·asin(l₁/OC) = 2·asin(0.1/0.3) each way: the useful work per cycle of
# a moment M on it, k·M on the return, is M·2·asin(1/3)·(1 + k), whichever stroke is the working one
ROCKER_WORK = 400.0 * 2 * math.asin(1 / 3) * 1.25


def test_the_student_places_the_loads_and_the_equation_of_motion_takes_them(browser_page):
    """The preset's force on the ram removed, a moment on the rocker added and set (M, k, the working stroke, no
    gravity); a cell typed into keeps its text while an estimate arrives; the equation of motion computes with the
    table's loads (its request carries them, its useful work is M·2·asin(1/3)·(1 + k) and what /motion answers for
    the same body); the link keeps them; the flywheel starts from the address's [δ]."""
    page = browser_page
    page.goto("/editor?lang=ru")
    page.wait_for_function("() => document.querySelector('#editor-drawing').dataset.state !== undefined")
    act(page, lambda: page.select_option("#editor-preset", "shaping_machine"))
    masses_ready(page)
    texts = interface_texts("ru")
    assert address_dynamics(page)["masses"]["forces"] == SHAPING["dynamics"]["masses"]["forces"]   # the preset's
    page.click('[data-remove="forces.0"]')
    page.wait_for_selector("#editor-masses-loads td.hint")                                # no loads now
    assert address_dynamics(page)["masses"]["forces"] == []
    offered = page.eval_on_selector_all("#editor-load-place option", "os => os.map((o) => o.value)")
    assert offered == ["force:s23", "force:E/ram", *(f"moment:{k}" for k in range(1, 6)),   # every pair and link,
                       *(f"point:{k}" for k in range(1, 6))]                          # a force at a point of each
    page.select_option("#editor-load-place", "moment:3")
    page.click("#editor-load-add")
    page.fill('input[data-path="masses.moments.0.working"]', "400")
    page.press('input[data-path="masses.moments.0.working"]', "Tab")
    page.fill('input[data-path="masses.moments.0.k"]', "0,25")
    page.press('input[data-path="masses.moments.0.k"]', "Tab")
    sense = 'select[data-path="masses.moments.0.sense"]'
    assert page.eval_on_selector_all(f"{sense} option", "os => os.map((o) => o.textContent)") == [
        texts["editor_sense_link_plus"], texts["editor_sense_link_minus"]]
    page.select_option(sense, "-1")
    page.uncheck("#editor-gravity")
    assert "moment:3" not in page.eval_on_selector_all("#editor-load-place option", "os => os.map((o) => o.value)")
    masses = address_dynamics(page)["masses"]
    assert (masses["forces"], masses["moments"], masses["gravity"]) == ([], [ROCKER_LOAD], 0)
    page.locator("#editor-dynamics").screenshot(path=ARTIFACTS / "own_mechanism_loads_ru.png")

    held = []                                          # an estimate held back while a cell is typed into
    page.route("**/api/v1/dynamics-estimate*", lambda route: held.append(route))
    estimates = estimated(page)
    act(page, lambda: (page.fill(ROD, "0,2"), page.press(ROD, "Enter")))
    page.click(MASS)
    page.keyboard.press("Control+A")
    page.keyboard.type("12,3")
    while not held:
        page.wait_for_timeout(50)
    held[0].continue_()
    page.unroute("**/api/v1/dynamics-estimate*")
    page.wait_for_function("n => Number(document.querySelector('#editor-masses').dataset.estimates) > n",
                           arg=estimates)
    assert page.input_value(MASS) == "12,3"
    assert page.evaluate("() => document.activeElement.dataset.path") == "masses.links.1.mass"
    page.keyboard.press("Tab")                                       # taken when the student leaves the cell
    masses = address_dynamics(page)["masses"]
    assert masses["links"][1]["mass"] == 12.3 and masses["moments"] == [ROCKER_LOAD]   # the loads kept, too
    screenshot(page, "own_mechanism_editor_loads_ru")
    editor = page.url

    with page.expect_request(lambda r: r.url.split("?")[0].endswith("/api/v1/motion") and r.method == "POST") as asked:
        open_from_editor(page, MOTION)
    body = sent_body(asked.value)
    assert (body["masses"]["forces"], body["masses"]["moments"], body["masses"]["gravity"]) == ([], [ROCKER_LOAD], 0)
    assert page.inner_text("#notices") == ""
    useful = number(figure_value(page, "полезная работа за цикл").split()[0])
    assert useful == pytest.approx(ROCKER_WORK, rel=1e-4)            # 5 digits shown
    direct = page.request.post("/api/v1/motion?lang=ru", data=body)
    assert useful == pytest.approx(direct.json()["works"]["useful"], rel=1e-4)
    preset = page.request.post("/api/v1/motion?lang=ru", data=body | {"masses": body["masses"] | {
        "forces": SHAPING["dynamics"]["masses"]["forces"], "moments": []}})
    assert preset.json()["works"]["useful"] > 2 * useful             # the preset's ram load did far more
    assert english_words(page) == []
    screenshot(page, "own_mechanism_motion_loads_ru")

    page.goto(editor)                                                # the link keeps the loads
    masses_ready(page)
    assert number(page.input_value('input[data-path="masses.moments.0.working"]')) == 400
    assert page.input_value(sense) == "-1" and not page.is_checked("#editor-gravity")
    with page.expect_request(lambda r: r.url.split("?")[0].endswith("/api/v1/flywheel") and r.method == "POST") as asked:
        open_from_editor(page, FLYWHEEL)
    flywheel = sent_body(asked.value)
    assert (flywheel["delta"], flywheel["omega_mean"]) == pytest.approx(      # d.flywheel's, not the scene's 0.05
        (SHAPING["dynamics"]["flywheel"]["delta"], SHAPING["dynamics"]["flywheel"]["omega_mean"]))
    assert flywheel["masses"]["moments"] == [ROCKER_LOAD]
    assert page.problems == []


def test_own_variant_without_a_mechanism_says_how_to_get_one(browser_page):
    page = browser_page
    page.goto(f"/scenes/{MOTION['id']}?lang=uk&variant=own")
    page.wait_for_selector(".own-mechanism-missing")
    texts = interface_texts("uk")
    assert texts["own_mechanism_open_editor"] in page.inner_text("#notices")
    assert page.get_attribute(".own-mechanism-missing a", "href") == "/editor?lang=uk"
    assert page.locator("#controls label.slider").first.is_hidden()         # sliders that would move nothing
    screenshot(page, "own_mechanism_missing_uk")
    assert page.problems == []


def encoded(document: dict) -> str:
    return base64.urlsafe_b64encode(json.dumps(document).encode()).decode().rstrip("=")


def test_a_mechanism_the_machine_refuses_is_said_in_words(browser_page):
    """A rod too short for the crank's whole turn: the motion endpoint's 422 is shown as every dynamics page shows
    one (the reason in the reader's language), and nothing else goes wrong."""
    from server.core.structure.estimate import estimated_dynamics
    short = json.loads(json.dumps(SHAPING["linkage"]))
    short["groups"][1]["length"] = 0.01
    page = browser_page
    page.goto(f"/scenes/{MOTION['id']}?lang=ru&variant=own&m={encoded(short)}"
              f"&d={encoded(estimated_dynamics(SHAPING['linkage']))}")
    page.wait_for_selector("#notices .refusal")
    texts = interface_texts("ru")
    assert texts["computation_refused"] in page.inner_text("#notices")
    assert texts["err_no_full_turn"].split("{")[0].strip() in page.inner_text("#notices")
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def test_own_mechanism_on_a_phone(phone, tmp_path):
    linkage = base64.urlsafe_b64encode(json.dumps(SHAPING["linkage"]).encode()).decode().rstrip("=")
    phone.goto(f"/editor?lang=ru&m={linkage}")                          # a shared mechanism without masses
    masses_ready(phone)
    assert number(phone.input_value(MASS)) == pytest.approx(5.5)        # the estimate: 10 kg/m × 0.55 m
    phone.locator("#editor-dynamics").scroll_into_view_if_needed()
    width = phone.evaluate("() => document.documentElement.scrollWidth")
    assert width <= PHONE["width"], f"the editor is {width} px wide on a 390 px screen"
    sideways = phone.evaluate("() => [...document.querySelectorAll('#editor-dynamics .table-scroll')]"
                              ".filter((box) => box.scrollWidth > box.clientWidth).map((box) => box.innerText.slice(0, 40))")
    assert sideways == [], f"tables that scroll sideways at 390 px: {sideways}"       # rows as cards there
    assert phone.locator("#editor-masses-links tbody tr").first.locator(".cell-label").all_inner_texts() == [
        "m, кг", "S вдоль, м", "S поперёк, м", "JS, кг·м²"]                          # each input under its header
    screenshot(phone, "own_mechanism_editor_phone_ru")
    phone.locator("#editor-dynamics").screenshot(path=ARTIFACTS / "own_mechanism_loads_phone_ru.png")
    with phone.expect_download() as download:                          # a file keeps the masses as the link does
        phone.click("#editor-export")
    saved = json.loads(Path(download.value.path()).read_text(encoding="utf-8"))
    assert saved["dynamics"]["masses"]["links"][1]["mass"] == pytest.approx(5.5)
    saved["dynamics"]["masses"]["links"][1]["mass"] = 7.25
    path = tmp_path / "own.json"
    path.write_text(json.dumps(saved), encoding="utf-8")
    phone.set_input_files("#editor-import", str(path))
    phone.wait_for_function(f"() => document.querySelector('{MASS}')?.value === '7,25'")
    open_from_editor(phone, MOTION)
    width = phone.evaluate("() => document.documentElement.scrollWidth")
    assert width <= PHONE["width"], f"the scene is {width} px wide on a 390 px screen"
    screenshot(phone, "own_mechanism_motion_phone_ru")
    assert phone.problems == []


ADDRESSED_JS = """async ({ scenes, documents }) => {
  const entry = document.querySelector('script[type="module"][src*="_scene.js"]').src;
  const { resolveAddressVariants } = await import(new URL("../common/model/address_mechanism.js", entry));
  const { DynamicsModel } = await import(new URL("../dynamics/model/dynamics_model.js", entry));
  return Object.fromEntries(Object.entries(scenes).map(([id, scene]) => {
    resolveAddressVariants(scene, documents);
    const model = new DynamicsModel(scene, { variant: "own", values: {} });
    return [id, { sliders: model.variant.sliders, body: model.request() }];
  }));
}"""


def test_the_page_and_the_server_resolve_the_address_alike(browser_page):
    """address_mechanism.js against server/lessons (scene_files.addressed, requests.scene_request) on a hand-built
    six-bar and its estimate: the same sliders and the same request body, exactly."""
    from server.core.structure.estimate import estimated_dynamics
    from server.lessons.requests import address_variant, scene_request
    from server.lessons.scenes import scenes
    from test_dynamics_estimate import HAND_BUILT

    documents = {"m": HAND_BUILT, "d": estimated_dynamics(HAND_BUILT)}
    chosen = {s.id: s for s in scenes().values() if s.kind == "dynamics" and any(v.address for v in s.variants)}
    # (the course project's scene sends no dynamics request: test_course_project_assignment checks its own twin)
    page = browser_page
    page.goto(f"/scenes/{MOTION['id']}?lang=en")
    page.locator(".main-svg").first.wait_for(state="visible")
    built = page.evaluate(ADDRESSED_JS, {"scenes": {i: json.loads(s.model_dump_json()) for i, s in chosen.items()},
                                         "documents": documents})
    for scene_id, scene in chosen.items():
        variant = address_variant(next(v for v in scene.variants if v.address), documents)
        assert built[scene_id]["body"] == scene_request(scene, variant), scene_id
        assert [(s["min"], s["max"], s["step"], s["default"]) for s in built[scene_id]["sliders"]] == \
            [(s.min, s.max, s.step, s.default) for s in variant.sliders], scene_id
    assert page.problems == []
