"""LTI Dynamic Registration: an administrator of the lab makes a single-use link; an LMS (here a small fake one
on 127.0.0.1: its OpenID configuration and registration endpoint) opens it, the lab registers itself there with
the LMS's token and keeps the client id and deployment id the LMS answered. The link works once; without the lab's
admin token no link is made. The lab runs in-process (TestClient) on a data directory of its own.
"""
from __future__ import annotations

import re
import threading
import time

import pytest
import uvicorn
from fastapi.testclient import TestClient
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse
from starlette.routing import Route

from lti_platform import free_port
from server.classroom import assignment_store
from server.api.app import create_app

ADMIN = "dyn-admin-" + "y" * 20
TOOL_CONFIGURATION = "https://purl.imsglobal.org/spec/lti-tool-configuration"


@pytest.fixture(scope="module")
def lms():
    """The fake LMS: it records the registrations it receives and answers a client id and a deployment id."""
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    received: list[dict] = []

    async def configuration(request: Request):
        return JSONResponse({"issuer": base, "authorization_endpoint": f"{base}/auth",
                             "token_endpoint": f"{base}/token", "jwks_uri": f"{base}/jwks",
                             "registration_endpoint": f"{base}/register",
                             "https://purl.imsglobal.org/spec/lti-platform-configuration":
                                 {"product_family_code": "moodle"}})

    async def register(request: Request):
        if request.headers.get("authorization") != "Bearer reg-token-1":
            return JSONResponse({"error": "invalid_token"}, status_code=401)
        received.append(await request.json())
        return JSONResponse({"client_id": "dyn-client-1", TOOL_CONFIGURATION: {"deployment_id": "5"}},
                            status_code=201)

    app = Starlette(routes=[Route("/.well-known/openid-configuration", configuration),
                            Route("/register", register, methods=["POST"])])
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30                     # a guard against a hang
    while not server.started and time.monotonic() < deadline:
        time.sleep(0.05)
    yield base, received
    server.should_exit = True
    thread.join(timeout=30)


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("MDL_DATA_DIR", str(tmp_path_factory.mktemp("lti-dynamic")))
        patch.setenv("MDL_ADMIN_TOKEN", ADMIN)
        patch.setenv("MDL_DATABASE_URL", "")
        assignment_store.store.cache_clear()
        yield TestClient(create_app())
        assignment_store.store.cache_clear()


def test_an_lms_registers_the_lab_with_a_single_use_link(lms, lab):
    base, received = lms
    assert lab.post("/api/v1/lti/registration-links").status_code == 401          # no admin token
    made = lab.post("/api/v1/lti/registration-links", headers={"Authorization": f"Bearer {ADMIN}"})
    assert made.status_code == 201, made.text
    link = made.json()["url"].replace("http://testserver", "")
    opened = lab.get(link, params={"openid_configuration": f"{base}/.well-known/openid-configuration",
                                   "registration_token": "reg-token-1"})
    assert opened.status_code == 200, opened.text
    assert base in opened.headers["content-security-policy"]
    assert_inline_scripts_allowed(opened)        # the close message's script comes from this server
    script = lab.get(re.search(r'<script src="([^"]+)"', opened.text).group(1))
    assert script.status_code == 200 and "org.imsglobal.lti.close" in script.text
    sent = received[-1]
    assert sent["initiate_login_uri"] == "http://testserver/lti/login"
    assert sent["jwks_uri"] == "http://testserver/lti/jwks" and sent["redirect_uris"] == ["http://testserver/lti/launch"]
    assert "https://purl.imsglobal.org/spec/lti-ags/scope/score" in sent["scope"].split()
    listed = lab.get("/api/v1/lti/platforms", headers={"Authorization": f"Bearer {ADMIN}"}).json()["platforms"]
    assert [(p["issuer"], p["client_id"], p["deployment_ids"], p["key_set_url"]) for p in listed] == \
        [(base, "dyn-client-1", ["5"], f"{base}/jwks")]
    again = lab.get(link, params={"openid_configuration": f"{base}/.well-known/openid-configuration",
                                  "registration_token": "reg-token-1"})
    assert again.status_code == 403 and "registration_code" in again.text              # the link worked once


def test_a_registration_the_lms_refuses_registers_nothing(lms, lab):
    base, _ = lms
    before = lab.get("/api/v1/lti/platforms", headers={"Authorization": f"Bearer {ADMIN}"}).json()["platforms"]
    made = lab.post("/api/v1/lti/registration-links", headers={"Authorization": f"Bearer {ADMIN}"}).json()
    refused = lab.get(made["url"].replace("http://testserver", ""),
                      params={"openid_configuration": f"{base}/.well-known/openid-configuration",
                              "registration_token": "wrong"})
    assert refused.status_code == 422 and "registration_token" in refused.text
    listed = lab.get("/api/v1/lti/platforms", headers={"Authorization": f"Bearer {ADMIN}"}).json()["platforms"]
    assert listed == before



def assert_inline_scripts_allowed(page) -> None:
    """The page's scripts are files of this server (the policy allows 'self' only): no inline script a browser
    would block, and each script it names is served."""
    assert "script-src 'self'" in page.headers["content-security-policy"]
    assert re.findall(r"<script>(.*?)</script>", page.text, flags=re.S) == []
    sources = re.findall(r'<script src="([^"]+)"', page.text)
    assert sources and all(source.startswith("/static/") for source in sources), sources
