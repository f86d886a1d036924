"""A scene loads only the JS modules it uses: a panel view's module is fetched when a variant has such a panel."""
from __future__ import annotations

import pytest

pytestmark = pytest.mark.browser

VIEW_MODULES = {"efficiency_chain_view.js", "flywheel_drawing_view.js", "free_body_view.js", "gear_train_view.js",
                "group_free_body_view.js", "indicator_diagram_view.js", "wittenbauer_view.js", "work_precision_view.js"}


def scripts_requested(page, scene: str, shown: str) -> set[str]:
    """The file names of the scripts the page asked for until the selector `shown` is visible."""
    requested = []
    page.on("request", lambda request: request.resource_type == "script" and requested.append(request.url))
    page.goto(f"/scenes/{scene}?lang=en")
    page.locator(shown).first.wait_for(state="visible")
    assert page.problems == []
    return {url.rsplit("/", 1)[-1] for url in requested}


def test_the_equation_of_motion_fetches_no_drawing_views(browser_page):
    scripts = scripts_requested(browser_page, "equation-of-motion", "#panels .graph .main-svg")
    assert scripts & VIEW_MODULES == {"work_precision_view.js"}           # its variant has a study panel
    assert "dynamics_view.js" in scripts


def test_forces_and_friction_fetches_the_free_body_view_and_draws_it(browser_page):
    scripts = scripts_requested(browser_page, "forces-friction", "#panel-free_body svg")
    assert {"free_body_view.js", "efficiency_chain_view.js"} <= scripts
    assert scripts.isdisjoint({"gear_train_view.js", "group_free_body_view.js", "wittenbauer_view.js",
                               "work_precision_view.js"})      # the six-bar's group bodies: its variant only
