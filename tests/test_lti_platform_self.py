"""The test LTI platform (tests/lti_platform.py) checked against a tiny tool of this module's own: its keys and
signatures, the OIDC flow the browser driver follows, the token endpoint's check of a client assertion, the
gradebook, NRPS, the deep linking return, and the bad launches it can mint (forged, expired). Cheap: no app server.
"""
from __future__ import annotations

import secrets
import time
from urllib.parse import urlencode

import httpx
import pytest
from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, JSONResponse, RedirectResponse
from joserfc import jwt
from joserfc.errors import JoseError
from joserfc.jwk import KeySet, RSAKey

from lti_platform import (ASSERTION_TYPE, DL, INSTRUCTOR, LEARNER, LINEITEM_TYPE, LTI, NRPS_SCOPE, SCORE_SCOPE,
                          SCORE_TYPE, AGS, Browser, Platform, User, auto_form, form_of, free_port, serve_in_thread)

ANNA = User("u-anna", "Anna", "Ivanova")
BORIS = User("u-boris", "Boris", "Petrov")


class FakeTool:
    """The least a tool does: login initiation → the platform's /auth, the launch checked against the platform's
    JWKS with its state and nonce, a deep linking answer signed with its own key, a client assertion."""

    def __init__(self, platform: Platform):
        self.platform, self.port = platform, free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.key = RSAKey.generate_key(2048, parameters={"kid": "tool-1"})
        self.states: dict[str, str] = {}
        self.app = FastAPI()
        app = self.app

        @app.get("/jwks")
        def jwks():
            return {"keys": [self.key.as_dict(private=False)]}

        @app.post("/login")
        async def login(request: Request):
            form = await form_of(request)
            state, nonce = secrets.token_urlsafe(8), secrets.token_urlsafe(8)
            self.states[state] = nonce
            redirect = self.url + ("/dl" if form["target_link_uri"].endswith("/dl") else "/launch")
            return RedirectResponse(f"{platform.auth_url}?" + urlencode({
                "scope": "openid", "response_type": "id_token", "response_mode": "form_post", "prompt": "none",
                "client_id": form["client_id"], "redirect_uri": redirect, "login_hint": form["login_hint"],
                "lti_message_hint": form["lti_message_hint"], "state": state, "nonce": nonce}), status_code=302)

        def verified(form: dict) -> dict:
            nonce = self.states.pop(form.get("state"), None)
            keys = KeySet.import_key_set(httpx.get(platform.jwks_url).json())
            claims = jwt.decode(form["id_token"], keys).claims
            jwt.JWTClaimsRegistry(iss={"essential": True, "value": platform.issuer},
                                  aud={"essential": True, "value": platform.client_id},
                                  nonce={"essential": True, "value": nonce}).validate(claims)
            return claims

        @app.post("/launch")
        async def launch(request: Request):
            try:
                return verified(await form_of(request))
            except (JoseError, ValueError) as error:
                return JSONResponse({"refused": repr(error)}, status_code=401)

        @app.post("/dl")
        async def deep_link(request: Request):
            claims = verified(await form_of(request))
            settings = claims[DL + "deep_linking_settings"]
            self.deep_link_data = settings["data"]
            response = self.deep_link_response(settings["data"])
            return HTMLResponse(auto_form(settings["deep_link_return_url"], {"JWT": response}, "Back"))

    def deep_link_response(self, data: str, key: RSAKey | None = None, **changes) -> str:
        now = int(time.time())
        return jwt.encode({"alg": "RS256", "kid": "tool-1"}, {
            "iss": self.platform.client_id, "aud": self.platform.issuer, "iat": now, "exp": now + 300,
            "nonce": secrets.token_urlsafe(8), LTI + "deployment_id": self.platform.deployment_id,
            LTI + "message_type": "LtiDeepLinkingResponse", LTI + "version": "1.3.0", DL + "data": data,
            DL + "content_items": [{"type": "ltiResourceLink", "title": "Lab 1", "url": self.url + "/launch",
                                    "custom": {"assignment": "a1"},
                                    "lineItem": {"scoreMaximum": 2, "label": "Lab 1", "resourceId": "a1"}}]
        } | changes, key or self.key)

    def assertion(self, audience: str, jti: str | None = None) -> str:
        now = int(time.time())
        return jwt.encode({"alg": "RS256", "kid": "tool-1"}, {
            "iss": self.platform.client_id, "sub": self.platform.client_id, "aud": audience, "iat": now,
            "exp": now + 300, "jti": jti or secrets.token_hex(8)}, self.key)

    def access_token(self, scopes: list[str], jti: str | None = None) -> httpx.Response:
        return httpx.post(self.platform.token_url, data={
            "grant_type": "client_credentials", "client_assertion_type": ASSERTION_TYPE,
            "client_assertion": self.assertion(self.platform.token_url, jti), "scope": " ".join(scopes)})


@pytest.fixture(scope="module")
def pair():
    platform = Platform()
    tool = FakeTool(platform)
    from lti_platform import Tool
    platform.tool = Tool(platform.client_id, platform.deployment_id, tool.url + "/login", tool.url + "/launch",
                         tool.url + "/jwks", tool.url + "/dl")
    with platform.running(), serve_in_thread(tool.app, tool.port):
        yield platform, tool


def test_a_launch_carries_every_claim_and_verifies_against_the_platforms_jwks(pair):
    platform, tool = pair
    browser = Browser(platform)
    claims = browser.launch(platform.launch(ANNA, [LEARNER], custom={"scene": "flywheel"})).json()
    assert claims["sub"] == ANNA.id and claims["name"] == "Anna Ivanova" and claims["email"] == ANNA.email
    assert claims[LTI + "message_type"] == "LtiResourceLinkRequest" and claims[LTI + "version"] == "1.3.0"
    assert claims[LTI + "deployment_id"] == platform.deployment_id and claims[LTI + "roles"] == [LEARNER]
    assert claims[LTI + "custom"] == {"scene": "flywheel"} and claims[LTI + "resource_link"]["id"]
    assert claims[LTI + "target_link_uri"] == tool.url + "/launch" and claims[LTI + "context"]["id"] == "course-1"
    assert SCORE_SCOPE in claims[AGS + "claim/endpoint"]["scope"]
    assert claims["https://purl.imsglobal.org/spec/lti-nrps/claim/namesroleservice"]["service_versions"] == ["2.0"]
    assert [r.status_code for r in browser.history[:3]] == [302, 200, 200]   # login → auth's form → the launch


def test_forged_and_expired_launches_fail_the_tools_check(pair):
    platform, _ = pair
    forged = Browser(platform).launch(platform.launch(ANNA, [LEARNER], forged=True))
    assert forged.status_code == 401 and "signature" in forged.text.lower()
    expired = Browser(platform).launch(platform.launch(ANNA, [LEARNER], expired=True))
    assert expired.status_code == 401 and "exp" in expired.text


def test_auth_refuses_an_unregistered_redirect_uri_and_a_wrong_client(pair):
    platform, tool = pair
    launch = platform.launch(ANNA, [LEARNER])
    good = {"scope": "openid", "response_type": "id_token", "response_mode": "form_post", "prompt": "none",
            "client_id": platform.client_id, "redirect_uri": tool.url + "/launch", "login_hint": ANNA.id,
            "lti_message_hint": launch.hint, "state": "s", "nonce": "n"}
    assert httpx.get(platform.auth_url, params=good).status_code == 200
    for change in ({"redirect_uri": "http://evil.example/launch"}, {"client_id": "other"},
                   {"response_type": "code"}, {"nonce": ""}, {"login_hint": BORIS.id}):
        refused = httpx.get(platform.auth_url, params=good | change)
        assert refused.status_code == 400, change
    assert "redirect_uri http://evil.example/launch is not registered" in platform.refusals


def test_token_endpoint_checks_the_client_assertion_and_grants_scopes(pair):
    platform, tool = pair
    granted = tool.access_token([SCORE_SCOPE, NRPS_SCOPE, "https://example.com/other"], jti="once")
    assert granted.status_code == 200 and set(granted.json()["scope"].split()) == {SCORE_SCOPE, NRPS_SCOPE}
    assert tool.access_token([SCORE_SCOPE], jti="once").status_code == 401          # a jti used before
    wrong_audience = httpx.post(platform.token_url, data={
        "grant_type": "client_credentials", "client_assertion_type": ASSERTION_TYPE,
        "client_assertion": tool.assertion("http://elsewhere/token"), "scope": SCORE_SCOPE})
    assert wrong_audience.status_code == 401
    stranger = RSAKey.generate_key(2048, parameters={"kid": "tool-1"})
    now = int(time.time())
    forged = jwt.encode({"alg": "RS256", "kid": "tool-1"}, {"iss": platform.client_id, "sub": platform.client_id,
                        "aud": platform.token_url, "exp": now + 60, "iat": now, "jti": "x"}, stranger)
    assert httpx.post(platform.token_url, data={"grant_type": "client_credentials", "client_assertion_type":
                      ASSERTION_TYPE, "client_assertion": forged, "scope": SCORE_SCOPE}).status_code == 401


def test_deep_linking_scores_and_memberships(pair):
    platform, tool = pair
    added = Browser(platform).launch(platform.launch(BORIS, [INSTRUCTOR], message_type="LtiDeepLinkingRequest"))
    assert added.status_code == 200 and "Lab 1" in added.text, added.text
    item = platform.deep_links[-1][DL + "content_items"][0]
    link = platform.links[item["resource_link_id"]]
    assert link["custom"] == {"assignment": "a1"} and platform.lineitems[link["lineitem"]]["scoreMaximum"] == 2
    claims = Browser(platform).launch(platform.launch(ANNA, [LEARNER], resource_link_id=item["resource_link_id"])
                                      ).json()
    assert claims[AGS + "claim/endpoint"]["lineitem"] == link["lineitem"]
    assert claims[LTI + "custom"] == {"assignment": "a1"}

    token = tool.access_token([SCORE_SCOPE, NRPS_SCOPE]).json()["access_token"]
    score = {"userId": ANNA.id, "scoreGiven": 1, "scoreMaximum": 2, "activityProgress": "Submitted",
             "gradingProgress": "FullyGraded", "timestamp": "2026-01-01T10:00:00+00:00"}
    posted = httpx.post(link["lineitem"] + "/scores", json=score, headers={
        "Authorization": f"Bearer {token}", "Content-Type": SCORE_TYPE})
    assert posted.status_code == 204 and platform.grade(ANNA, link["lineitem"])["scoreGiven"] == 1
    unauthorised = httpx.post(link["lineitem"] + "/scores", json=score, headers={"Content-Type": SCORE_TYPE})
    assert unauthorised.status_code == 401
    members = httpx.get(claims["https://purl.imsglobal.org/spec/lti-nrps/claim/namesroleservice"]
                        ["context_memberships_url"], headers={"Authorization": f"Bearer {token}"})
    assert {m["user_id"]: m["roles"] for m in members.json()["members"]} == {ANNA.id: [LEARNER],
                                                                             BORIS.id: [INSTRUCTOR]}
    no_scope = httpx.post(platform.lineitems_url("course-1"), json={"label": "x", "scoreMaximum": 1}, headers={
        "Authorization": f"Bearer {token}", "Content-Type": LINEITEM_TYPE})
    assert no_scope.status_code == 403


def test_the_deep_linking_return_refuses_what_the_tool_did_not_sign_for_this_request(pair):
    platform, tool = pair
    Browser(platform).launch(platform.launch(BORIS, [INSTRUCTOR], message_type="LtiDeepLinkingRequest"))
    data, kept = tool.deep_link_data, len(platform.deep_links)
    stranger = RSAKey.generate_key(2048, parameters={"kid": "tool-1"})
    used = tool.deep_link_response(data, nonce="used-once")
    assert httpx.post(platform.deep_link_return_url, data={"JWT": used}).status_code == 200
    kept += 1
    for bad in (tool.deep_link_response(data, key=stranger), tool.deep_link_response(data, aud="http://other"),
                tool.deep_link_response(data, iss="someone"), tool.deep_link_response(data, exp=1),
                tool.deep_link_response(data, **{LTI + "deployment_id": "99"}),
                tool.deep_link_response("dl-unknown"), used):
        assert httpx.post(platform.deep_link_return_url, data={"JWT": bad}).status_code in (400, 401)
    assert len(platform.deep_links) == kept
