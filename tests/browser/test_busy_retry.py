"""A server busy with this browser's computations answers 429: the page says "busy, retrying", waits
Retry-After and asks again, and the student ends up with the plot, never an error."""
from __future__ import annotations

import json
import re

import pytest

from conftest import SCENE, interface_texts

pytestmark = pytest.mark.browser

REFUSALS = 3
# Chromium reports every HTTP error answer on the console; the 429s routed here are the expected ones.
BUSY_ANSWER = re.compile(r"Failed to load resource: the server responded with a status of 429")
BUSY_BODY = json.dumps({"detail": [{"loc": ["client"], "msg": "busy", "type": "too_many_requests",
                                    "ctx": {"code": "busy", "limit": 8, "scope": "client", "retry_after": 1}}]})


@pytest.mark.parametrize("lang", ["uk"])
def test_the_first_answers_busy_the_page_retries_and_draws(browser_page, lang):
    page = browser_page
    refused, sent = [], []

    def busy_at_first(route):
        sent.append(route.request.post_data)
        if len(refused) < REFUSALS:
            refused.append(route.request.post_data)
            route.fulfill(status=429, headers={"Retry-After": "1"}, content_type="application/json", body=BUSY_BODY)
        else:
            route.continue_()

    page.route("**/api/v1/kinematics*", busy_at_first)
    page.goto(f"/scenes/{SCENE['id']}?lang={lang}")
    note = page.locator("#busy-retrying")
    note.wait_for(state="visible")
    assert note.inner_text() == interface_texts(lang)["busy_retrying"]
    page.wait_for_function("() => document.querySelector('#panel-u31 .graph')?.data?.length > 0")
    note.wait_for(state="hidden")
    assert len(refused) == REFUSALS and len(sent) > REFUSALS
    assert set(refused) <= set(sent[REFUSALS:])                 # each refused request was asked again
    shown = page.inner_text("body")
    assert "429" not in shown and interface_texts(lang)["err_server"] not in shown
    assert [p for p in page.problems if not BUSY_ANSWER.search(p)] == []
