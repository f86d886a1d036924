"""A small but real LTI 1.3 platform (as Moodle acts) for the tests, and a browser-like driver of its launches.

The platform (`Platform`) has its own RSA key pair and serves real HTTP on 127.0.0.1 (FastAPI under uvicorn in a
thread, started by `Platform.running()` and stopped when its block ends):
- `/jwks` — its public key set (JWTs signed and checked with joserfc, RS256);
- `/auth` — the OIDC authorization endpoint: checks client_id, the redirect_uri registered for the tool,
  response_type=id_token, scope=openid, response_mode=form_post, prompt=none, state, nonce, and that login_hint and
  lti_message_hint name a launch it minted; answers an auto-submitting HTML form POSTing id_token and state to the
  redirect_uri, as Moodle does;
- `/token` — the client_credentials grant with a JWT client assertion
  (`urn:ietf:params:oauth:client-assertion-type:jwt-bearer`) checked against the tool's JWKS URL
  (iss = sub = client_id, aud = this endpoint, exp, a jti used once); answers a bearer token with the scopes granted;
- AGS 2.0: `/ags/<context>/lineitems` (GET, POST), `/ags/<context>/lineitems/<n>` (GET, PUT),
  `…/scores` (POST, scope …/lti-ags/scope/score) into `gradebook`, `…/results` (GET);
- NRPS 2.0: `/nrps/<context>/memberships`;
- `/deep_link_return` — checks the tool's LtiDeepLinkingResponse JWT (signature by the tool's JWKS, iss = client_id,
  aud = this issuer, nonce used once, deployment id, the request's `data`) and keeps its content items: each
  ltiResourceLink becomes a resource link of the course, with a line item when the item asks for one (as Moodle
  does);
- `/course/<context>/<launch>` — a course page with a launch in an `<iframe>` (`/launch/<launch>`, the login
  initiation form auto-submitted inside the frame) for the browser tests.

`Platform.launch(user, roles, …)` mints a launch: the third-party login initiation (`Launch.login_url`, or its
`login_params` to POST) for the tool's `/lti/login`. The id_token is made when the tool comes back to `/auth`, with
every claim of LTI 1.3 core, AGS, NRPS and (for LtiDeepLinkingRequest) deep_linking_settings. A launch may be made
bad on purpose: `forged=True` (signed by another key under the platform's kid), `expired=True` (exp in the past),
`claims={...}` (any claim replaced, e.g. aud, iss, deployment id), `iss`/`client_id`/`deployment_id` (the login
initiation's); `Browser.replay(id_token, state, url)` posts a launch's id_token and state again. `token_outage`
makes the token endpoint answer 503 (the LMS down). Resource links come from deep linking or `add_link` (set up by
hand); the gradebook is read with `grade` / `wait_for_grade` (polling, with a guard against a hang only).

`Browser` follows a launch as a browser does with httpx (login → 302 to /auth → the auto-submitted form → POST to
the tool → the final page), keeping its cookies (one per user). `register(app_url, admin_token)` registers the
platform in the app through `POST /api/v1/lti/platforms`.
"""
from __future__ import annotations

import html
import itertools
import re
import secrets
import socket
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from html.parser import HTMLParser
from urllib.parse import parse_qsl, urlencode, urljoin

import httpx
import uvicorn
from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, JSONResponse, Response
from joserfc import jwt
from joserfc.errors import JoseError
from joserfc.jwk import KeySet, RSAKey

LTI = "https://purl.imsglobal.org/spec/lti/claim/"
AGS = "https://purl.imsglobal.org/spec/lti-ags/"
NRPS = "https://purl.imsglobal.org/spec/lti-nrps/"
DL = "https://purl.imsglobal.org/spec/lti-dl/claim/"
LEARNER = "http://purl.imsglobal.org/vocab/lis/v2/membership#Learner"
INSTRUCTOR = "http://purl.imsglobal.org/vocab/lis/v2/membership#Instructor"
SCORE_SCOPE = AGS + "scope/score"
LINEITEM_SCOPE = AGS + "scope/lineitem"
LINEITEM_READ_SCOPE = AGS + "scope/lineitem.readonly"
RESULT_SCOPE = AGS + "scope/result.readonly"
NRPS_SCOPE = NRPS + "scope/contextmembership.readonly"
SCOPES = [LINEITEM_SCOPE, LINEITEM_READ_SCOPE, RESULT_SCOPE, SCORE_SCOPE, NRPS_SCOPE]
ASSERTION_TYPE = "urn:ietf:params:oauth:client-assertion-type:jwt-bearer"
LINEITEM_TYPE = "application/vnd.ims.lis.v2.lineitem+json"
LINEITEMS_TYPE = "application/vnd.ims.lis.v2.lineitemcontainer+json"
SCORE_TYPE = "application/vnd.ims.lis.v1.score+json"
RESULTS_TYPE = "application/vnd.ims.lis.v2.resultcontainer+json"
MEMBERSHIPS_TYPE = "application/vnd.ims.lti-nrps.v2.membershipcontainer+json"
START_SECONDS = 30          # uvicorn in a thread starts in milliseconds: a guard against a hang


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@dataclass(frozen=True)
class User:
    """A user of the LMS: `id` is the LTI `sub`."""
    id: str
    given_name: str
    family_name: str

    @property
    def name(self) -> str:
        return f"{self.given_name} {self.family_name}"

    @property
    def email(self) -> str:
        return f"{self.id}@lms.example.edu"


@dataclass
class Tool:
    """The tool as registered in the platform (from the app's answer to the registration)."""
    client_id: str
    deployment_id: str
    login_url: str
    launch_url: str
    jwks_url: str
    deep_linking_url: str

    @property
    def redirect_uris(self) -> set[str]:
        return {self.launch_url, self.deep_linking_url}


@dataclass
class Launch:
    """A launch minted by the platform, waiting for the tool's authentication request."""
    hint: str
    user: User
    roles: list[str]
    message_type: str
    context: str
    resource_link_id: str | None
    custom: dict
    target_link_uri: str
    forged: bool = False
    expired: bool = False
    claims: dict = field(default_factory=dict)
    login_params: dict = field(default_factory=dict)
    login_url: str = ""
    id_token: str | None = None        # made at /auth
    state: str | None = None
    redirect_uri: str | None = None


class PlatformError(Exception):
    def __init__(self, status: int, reason: str):
        super().__init__(reason)
        self.status, self.reason = status, reason


class Platform:
    """The LMS. `host` names it in its issuer and URLs (127.0.0.1 or localhost: both listen on 127.0.0.1)."""

    def __init__(self, host: str = "127.0.0.1", client_id: str | None = None, deployment_id: str = "1",
                 name: str = "Test Moodle"):
        self.port = free_port()
        self.issuer = f"http://{host}:{self.port}"
        self.name = name
        self.client_id = client_id or f"tool-{secrets.token_hex(4)}"
        self.deployment_id = deployment_id
        self.key = RSAKey.generate_key(2048, parameters={"kid": f"platform-{secrets.token_hex(4)}", "use": "sig",
                                                          "alg": "RS256"})
        self.stray_key = RSAKey.generate_key(2048, parameters={"kid": self.key.kid})   # a forger's key, same kid
        self.tool: Tool | None = None
        self.launches: dict[str, Launch] = {}
        self.links: dict[str, dict] = {}           # resource link id → {"context", "custom", "title", "lineitem"}
        self.lineitems: dict[str, dict] = {}       # line item URL → the line item
        self.gradebook: dict[tuple[str, str], dict] = {}   # (line item URL, user id) → the latest score
        self.scores: list[dict] = []               # every score posted, in order, with its line item URL
        self.rosters: dict[str, dict[str, tuple[User, list[str]]]] = {}   # context → user id → (user, roles)
        self.deep_links: list[dict] = []           # every accepted LtiDeepLinkingResponse's claims
        self.refusals: list[str] = []              # every request refused, with its reason
        self.tokens: dict[str, dict] = {}          # access token → {"scopes", "expires"}
        self.token_requests: list[dict] = []
        self.token_outage = False                  # True: the token endpoint answers 503 (the LMS is down)
        self._jtis: set[str] = set()
        self._dl_nonces: set[str] = set()
        self._counter = itertools.count(1)
        self._lock = threading.Lock()
        self.app = self._make_app()

    # --- URLs ------------------------------------------------------------------------------------------------

    @property
    def auth_url(self) -> str:
        return f"{self.issuer}/auth"

    @property
    def token_url(self) -> str:
        return f"{self.issuer}/token"

    @property
    def jwks_url(self) -> str:
        return f"{self.issuer}/jwks"

    @property
    def deep_link_return_url(self) -> str:
        return f"{self.issuer}/deep_link_return"

    def lineitems_url(self, context: str) -> str:
        return f"{self.issuer}/ags/{context}/lineitems"

    def memberships_url(self, context: str) -> str:
        return f"{self.issuer}/nrps/{context}/memberships"

    def course_page_url(self, launch: Launch) -> str:
        return f"{self.issuer}/course/{launch.context}/{launch.hint}"

    def registration(self) -> dict:
        """The body of `POST /api/v1/lti/platforms`."""
        return {"issuer": self.issuer, "client_id": self.client_id, "deployment_ids": [self.deployment_id],
                "auth_login_url": self.auth_url, "auth_token_url": self.token_url, "key_set_url": self.jwks_url,
                "name": self.name}

    def register(self, app_url: str, admin_token: str) -> httpx.Response:
        """Register the platform in the app; on 201 the tool's URLs are kept for the launches."""
        response = httpx.post(f"{app_url}/api/v1/lti/platforms", json=self.registration(),
                              headers={"Authorization": f"Bearer {admin_token}"}, timeout=60)
        if response.status_code == 201:
            urls = response.json()["tool"]
            self.tool = Tool(self.client_id, self.deployment_id, urls["login_url"], urls["launch_url"],
                             urls["jwks_url"], urls["deep_linking_url"])
        return response

    # --- the roster, launches ----------------------------------------------------------------------------------

    def add_link(self, context: str, custom: dict, title: str, line_item: dict | None = None) -> str:
        """A resource link set up by hand in the course (custom parameters typed in), with its line item."""
        link_id = f"link-{next(self._counter)}"
        lineitem = self.add_lineitem(context, line_item | {"resourceLinkId": link_id})["id"] if line_item else None
        self.links[link_id] = {"context": context, "custom": dict(custom), "title": title, "lineitem": lineitem}
        return link_id

    def enrol(self, context: str, user: User, roles: list[str]) -> None:
        self.rosters.setdefault(context, {})[user.id] = (user, list(roles))

    def launch(self, user: User, roles: list[str], custom: dict | None = None,
               message_type: str = "LtiResourceLinkRequest", resource_link_id: str | None = None,
               context: str = "course-1", forged: bool = False, expired: bool = False, claims: dict | None = None,
               iss: str | None = None, client_id: str | None = None, deployment_id: str | None = None) -> Launch:
        """Mint a launch of the tool for `user` (enrolled in `context` with `roles`). A resource link made by deep
        linking gives its custom parameters and line item unless `custom` is given. `iss`, `client_id`,
        `deployment_id` change only the login initiation's parameters (`claims` changes the id_token's)."""
        assert self.tool is not None, "register the platform in the app first"
        self.enrol(context, user, roles)
        link = self.links.get(resource_link_id or "", {})
        if custom is None:
            custom = link.get("custom", {})
        if message_type == "LtiResourceLinkRequest" and resource_link_id is None:
            resource_link_id = f"link-{next(self._counter)}"
        target = self.tool.deep_linking_url if message_type == "LtiDeepLinkingRequest" else self.tool.launch_url
        hint = secrets.token_urlsafe(12)
        launch = Launch(hint, user, list(roles), message_type, context, resource_link_id, dict(custom), target,
                        forged, expired, dict(claims or {}))
        launch.login_params = {"iss": iss or self.issuer, "login_hint": user.id, "target_link_uri": target,
                               "lti_message_hint": hint, "client_id": client_id or self.client_id,
                               "lti_deployment_id": deployment_id or self.deployment_id}
        launch.login_url = f"{self.tool.login_url}?{urlencode(launch.login_params)}"
        self.launches[hint] = launch
        return launch

    def id_token_claims(self, launch: Launch, nonce: str) -> dict:
        now = int(time.time())
        issued = now - 3600 if launch.expired else now
        claims = {
            "iss": self.issuer, "aud": self.client_id, "azp": self.client_id, "sub": launch.user.id,
            "iat": issued, "nbf": issued, "exp": issued + 600, "nonce": nonce,
            "name": launch.user.name, "given_name": launch.user.given_name, "family_name": launch.user.family_name,
            "email": launch.user.email, "locale": "en",
            LTI + "message_type": launch.message_type, LTI + "version": "1.3.0",
            LTI + "deployment_id": self.deployment_id, LTI + "target_link_uri": launch.target_link_uri,
            LTI + "roles": launch.roles,
            LTI + "context": {"id": launch.context, "label": launch.context.upper(), "title": f"Course {launch.context}",
                              "type": ["http://purl.imsglobal.org/vocab/lis/v2/course#CourseOffering"]},
            LTI + "tool_platform": {"guid": self.issuer, "name": self.name, "product_family_code": "moodle",
                                    "version": "4.3"},
            LTI + "launch_presentation": {"document_target": "iframe", "locale": "en",
                                          "return_url": f"{self.issuer}/course/{launch.context}"},
            LTI + "custom": launch.custom,
            AGS + "claim/endpoint": {"scope": [LINEITEM_SCOPE, LINEITEM_READ_SCOPE, RESULT_SCOPE, SCORE_SCOPE],
                                     "lineitems": self.lineitems_url(launch.context)},
            NRPS + "claim/namesroleservice": {"context_memberships_url": self.memberships_url(launch.context),
                                              "service_versions": ["2.0"]},
        }
        if launch.message_type == "LtiDeepLinkingRequest":
            claims[DL + "deep_linking_settings"] = {
                "deep_link_return_url": self.deep_link_return_url, "accept_types": ["ltiResourceLink"],
                "accept_presentation_document_targets": ["iframe", "window"], "accept_multiple": False,
                "auto_create": True, "title": "Add an activity", "data": f"dl-{launch.hint}"}
        else:
            link = self.links.get(launch.resource_link_id, {})
            claims[LTI + "resource_link"] = {"id": launch.resource_link_id, "title": link.get("title", "Activity")}
            if link.get("lineitem"):
                claims[AGS + "claim/endpoint"]["lineitem"] = link["lineitem"]
        claims.update(launch.claims)
        return {k: v for k, v in claims.items() if v is not None}

    def sign(self, claims: dict, forged: bool = False) -> str:
        key = self.stray_key if forged else self.key
        return jwt.encode({"alg": "RS256", "kid": self.key.kid, "typ": "JWT"}, claims, key)

    # --- the gradebook ---------------------------------------------------------------------------------------

    def grade(self, user: User, lineitem=None) -> dict | None:
        """The latest score of `user` in `lineitem` (the only line item when there is one; a callable: the line
        item it names now, or none yet), with the line item's URL as `lineitem`."""
        if callable(lineitem):
            lineitem = lineitem()
            if lineitem is None:
                return None
        if lineitem is None:
            assert len(self.lineitems) == 1, f"name the line item: {list(self.lineitems)}"
            lineitem = next(iter(self.lineitems))
        score = self.gradebook.get((lineitem, user.id))
        return None if score is None else score | {"lineitem": lineitem}

    def wait_for_grade(self, user: User, condition=lambda score: score is not None, lineitem=None,
                       within: float = 120.0) -> dict:
        """Poll the gradebook until `condition(score)`; `within` seconds is a guard against a hang only."""
        deadline = time.monotonic() + within
        while True:
            score = self.grade(user, lineitem) if self.lineitems else None
            if score is not None and condition(score):
                return score
            if time.monotonic() > deadline:
                raise AssertionError(f"no such score of {user.id} arrived within {within} s (a guard); latest "
                                     f"{score}; posted {self.scores}; refused {self.refusals}; token requests "
                                     f"{self.token_requests}")
            time.sleep(0.1)

    # --- the server --------------------------------------------------------------------------------------------

    @contextmanager
    def running(self):
        """Serve the platform on 127.0.0.1:port in a thread; stopped when the block ends."""
        with serve_in_thread(self.app, self.port):
            yield self

    def _refuse(self, status: int, reason: str) -> JSONResponse:
        self.refusals.append(reason)
        return JSONResponse({"error": reason}, status_code=status)

    def _bearer(self, request: Request, scope: str) -> None:
        header = request.headers.get("authorization", "")
        token = self.tokens.get(header[7:]) if header.lower().startswith("bearer ") else None
        if token is None or token["expires"] < time.time():
            raise PlatformError(401, "no valid bearer token")
        if scope not in token["scopes"] and not (scope == LINEITEM_READ_SCOPE and LINEITEM_SCOPE in token["scopes"]):
            raise PlatformError(403, f"the token lacks the scope {scope}")

    def tool_keys(self) -> KeySet:
        response = httpx.get(self.tool.jwks_url, timeout=30)
        response.raise_for_status()
        return KeySet.import_key_set(response.json())

    def verify_tool_jwt(self, token: str, audience: str) -> dict:
        """The claims of a JWT the tool signed (its JWKS), issued by the client_id for `audience`, unexpired."""
        try:
            decoded = jwt.decode(token, self.tool_keys(), algorithms=["RS256"])
        except (JoseError, ValueError) as error:
            raise PlatformError(401, f"the tool's JWT does not verify against its JWKS: {error!r}")
        claims = decoded.claims
        audiences = claims.get("aud") if isinstance(claims.get("aud"), list) else [claims.get("aud")]
        if claims.get("iss") != self.client_id:
            raise PlatformError(401, f"iss {claims.get('iss')!r} is not the client_id")
        if audience not in audiences:
            raise PlatformError(401, f"aud {claims.get('aud')!r} does not name {audience}")
        if not isinstance(claims.get("exp"), (int, float)) or claims["exp"] < time.time():
            raise PlatformError(401, "exp missing or in the past")
        return claims

    def _make_app(self) -> FastAPI:
        app = FastAPI()

        @app.exception_handler(PlatformError)
        def refused(request: Request, error: PlatformError):
            return self._refuse(error.status, error.reason)

        @app.get("/jwks")
        def jwks():
            return {"keys": [self.key.as_dict(private=False)]}

        @app.api_route("/auth", methods=["GET", "POST"])
        async def auth(request: Request):
            params = dict(request.query_params) if request.method == "GET" else await form_of(request)
            return self._authorize(params)

        @app.post("/token")
        async def token(request: Request):
            return self._token(await form_of(request))

        @app.get("/ags/{context}/lineitems")
        def lineitems(context: str, request: Request, resource_link_id: str | None = None,
                      resource_id: str | None = None, tag: str | None = None):
            self._bearer(request, LINEITEM_READ_SCOPE)
            items = [item for url, item in self.lineitems.items() if url.startswith(self.lineitems_url(context) + "/")
                     and (resource_link_id is None or item.get("resourceLinkId") == resource_link_id)
                     and (resource_id is None or item.get("resourceId") == resource_id)
                     and (tag is None or item.get("tag") == tag)]
            return JSONResponse(items, media_type=LINEITEMS_TYPE)

        @app.post("/ags/{context}/lineitems")
        async def new_lineitem(context: str, request: Request):
            self._bearer(request, LINEITEM_SCOPE)
            if not request.headers.get("content-type", "").startswith(LINEITEM_TYPE):
                raise PlatformError(415, f"a line item is {LINEITEM_TYPE}")
            body = await request.json()
            if not isinstance(body.get("scoreMaximum"), (int, float)) or body["scoreMaximum"] <= 0 \
                    or not body.get("label"):
                raise PlatformError(400, "a line item needs a label and a positive scoreMaximum")
            item = self.add_lineitem(context, body)
            return JSONResponse(item, status_code=201, media_type=LINEITEM_TYPE)

        @app.get("/ags/{context}/lineitems/{number}")
        def lineitem(context: str, number: str, request: Request):
            self._bearer(request, LINEITEM_READ_SCOPE)
            return JSONResponse(self._lineitem(context, number), media_type=LINEITEM_TYPE)

        @app.put("/ags/{context}/lineitems/{number}")
        async def put_lineitem(context: str, number: str, request: Request):
            self._bearer(request, LINEITEM_SCOPE)
            item = self._lineitem(context, number)
            item.update({k: v for k, v in (await request.json()).items() if k != "id"})
            return JSONResponse(item, media_type=LINEITEM_TYPE)

        @app.post("/ags/{context}/lineitems/{number}/scores")
        async def score(context: str, number: str, request: Request):
            self._bearer(request, SCORE_SCOPE)
            if not request.headers.get("content-type", "").startswith(SCORE_TYPE):
                raise PlatformError(415, f"a score is {SCORE_TYPE}")
            item = self._lineitem(context, number)
            self._score(item, await request.json())
            return Response(status_code=204)

        @app.get("/ags/{context}/lineitems/{number}/results")
        def results(context: str, number: str, request: Request):
            self._bearer(request, RESULT_SCOPE)
            item = self._lineitem(context, number)
            rows = [{"id": f"{item['id']}/results/{user}", "scoreOf": item["id"], "userId": user,
                     "resultScore": s.get("scoreGiven"), "resultMaximum": s.get("scoreMaximum")}
                    for (url, user), s in self.gradebook.items() if url == item["id"]]
            return JSONResponse(rows, media_type=RESULTS_TYPE)

        @app.get("/nrps/{context}/memberships")
        def memberships(context: str, request: Request):
            self._bearer(request, NRPS_SCOPE)
            members = [{"status": "Active", "user_id": user.id, "name": user.name, "given_name": user.given_name,
                        "family_name": user.family_name, "email": user.email, "roles": roles}
                       for user, roles in self.rosters.get(context, {}).values()]
            return JSONResponse({"id": self.memberships_url(context),
                                 "context": {"id": context, "label": context.upper(), "title": f"Course {context}"},
                                 "members": members}, media_type=MEMBERSHIPS_TYPE)

        @app.post("/deep_link_return")
        async def deep_link_return(request: Request):
            form = await form_of(request)
            items = self._deep_link(str(form.get("JWT", "")))
            titles = "".join(f"<li>{html.escape(str(item.get('title', '')))}</li>" for item in items)
            return HTMLResponse(f"<!doctype html><title>Added</title><h1>Content added</h1><ul>{titles}</ul>")

        @app.get("/launch/{hint}")
        def login_initiation_form(hint: str):
            launch = self.launches[hint]
            return HTMLResponse(auto_form(self.tool.login_url, launch.login_params, "Launching the tool"))

        @app.get("/course/{context}/{hint}")
        def course_page(context: str, hint: str):
            return HTMLResponse(
                f"<!doctype html><html><head><title>Course {html.escape(context)}</title></head><body>"
                f"<h1>Course {html.escape(context)}</h1>"
                f'<iframe id="tool" name="tool" title="The tool" src="/launch/{html.escape(hint)}" '
                f'style="width: 1200px; height: 760px; border: 1px solid #888" '
                f'allow="clipboard-write"></iframe></body></html>')

        @app.get("/favicon.ico")
        def favicon():
            return Response(status_code=204)

        return app

    # --- the endpoints' work -------------------------------------------------------------------------------------

    def _authorize(self, params: dict) -> Response:
        """OIDC authentication request → the auto-submitted form with the id_token (or a refusal)."""
        expected = {"scope": "openid", "response_type": "id_token", "response_mode": "form_post",
                    "prompt": "none", "client_id": self.client_id}
        for name, value in expected.items():
            if params.get(name) != value:
                return self._refuse(400, f"{name} is {params.get(name)!r}, not {value!r}")
        for name in ("state", "nonce", "login_hint", "redirect_uri"):
            if not params.get(name):
                return self._refuse(400, f"{name} is missing")
        if params["redirect_uri"] not in self.tool.redirect_uris:
            return self._refuse(400, f"redirect_uri {params['redirect_uri']} is not registered")
        launch = self.launches.get(params.get("lti_message_hint", ""))
        if launch is None or launch.user.id != params["login_hint"]:
            return self._refuse(400, "lti_message_hint / login_hint name no launch of this user")
        launch.state, launch.redirect_uri = params["state"], params["redirect_uri"]
        launch.id_token = self.sign(self.id_token_claims(launch, params["nonce"]), forged=launch.forged)
        return HTMLResponse(auto_form(params["redirect_uri"], {"id_token": launch.id_token, "state": launch.state},
                                      "Returning to the tool"))

    def _token(self, form: dict) -> Response:
        self.token_requests.append({k: v for k, v in form.items() if k != "client_assertion"})
        if self.token_outage:
            return self._refuse(503, "the token endpoint is down (an outage the test made)")
        if form.get("grant_type") != "client_credentials":
            return self._refuse(400, "grant_type is not client_credentials")
        if form.get("client_assertion_type") != ASSERTION_TYPE:
            return self._refuse(400, "client_assertion_type is not jwt-bearer")
        try:
            claims = self.verify_tool_jwt(str(form.get("client_assertion", "")), self.token_url)
        except PlatformError as error:
            return self._refuse(401, error.reason)
        if claims.get("sub") != self.client_id:
            return self._refuse(401, "sub is not the client_id")
        jti = claims.get("jti")
        with self._lock:
            if not jti or jti in self._jtis:
                return self._refuse(401, "jti missing or used before")
            self._jtis.add(jti)
        asked = str(form.get("scope", "")).split()
        granted = [scope for scope in asked if scope in SCOPES]
        if not granted:
            return self._refuse(400, f"no scope granted of {asked}")
        token = secrets.token_urlsafe(24)
        self.tokens[token] = {"scopes": set(granted), "expires": time.time() + 3600}
        return JSONResponse({"access_token": token, "token_type": "Bearer", "expires_in": 3600,
                             "scope": " ".join(granted)})

    def add_lineitem(self, context: str, body: dict) -> dict:
        with self._lock:
            url = f"{self.lineitems_url(context)}/{next(self._counter)}"
            item = {k: v for k, v in body.items() if k != "id"} | {"id": url}
            self.lineitems[url] = item
        return item

    def _lineitem(self, context: str, number: str) -> dict:
        item = self.lineitems.get(f"{self.lineitems_url(context)}/{number}")
        if item is None:
            raise PlatformError(404, "no such line item")
        return item

    def _score(self, item: dict, score: dict) -> None:
        """Keep a score (LTI AGS 2.0 §3.4): userId, timestamp, activityProgress, gradingProgress required;
        scoreGiven ≤ … with scoreMaximum; an older timestamp than the one kept does not replace it."""
        for name in ("userId", "timestamp", "activityProgress", "gradingProgress"):
            if name not in score:
                raise PlatformError(400, f"a score needs {name}")
        if "scoreGiven" in score and not isinstance(score.get("scoreMaximum"), (int, float)):
            raise PlatformError(400, "scoreGiven without scoreMaximum")
        with self._lock:
            self.scores.append(score | {"lineitem": item["id"]})
            kept = self.gradebook.get((item["id"], score["userId"]))
            if kept is not None and kept["timestamp"] > score["timestamp"]:
                raise PlatformError(409, "a newer score is kept")
            self.gradebook[(item["id"], score["userId"])] = score

    def _deep_link(self, token: str) -> list[dict]:
        claims = self.verify_tool_jwt(token, self.issuer)
        if claims.get(LTI + "message_type") != "LtiDeepLinkingResponse":
            raise PlatformError(400, "message_type is not LtiDeepLinkingResponse")
        if claims.get(LTI + "version") != "1.3.0":
            raise PlatformError(400, "version is not 1.3.0")
        if claims.get(LTI + "deployment_id") != self.deployment_id:
            raise PlatformError(400, f"deployment_id {claims.get(LTI + 'deployment_id')!r} is not ours")
        nonce = claims.get("nonce")
        with self._lock:
            if not nonce or nonce in self._dl_nonces:
                raise PlatformError(400, "nonce missing or used before")
            self._dl_nonces.add(nonce)
        data = claims.get(DL + "data")
        hint = data[3:] if isinstance(data, str) and data.startswith("dl-") else None
        request = self.launches.get(hint or "")
        if request is None or request.message_type != "LtiDeepLinkingRequest":
            raise PlatformError(400, f"data {data!r} names no deep linking request")
        items = claims.get(DL + "content_items") or []
        for item in items:
            if item.get("type") != "ltiResourceLink":
                raise PlatformError(400, f"content item type {item.get('type')!r} not accepted")
            link_id = f"link-{next(self._counter)}"
            lineitem = None
            if item.get("lineItem"):
                lineitem = self.add_lineitem(request.context, item["lineItem"] | {"resourceLinkId": link_id})["id"]
            self.links[link_id] = {"context": request.context, "custom": item.get("custom", {}),
                                   "title": item.get("title", ""), "url": item.get("url"), "lineitem": lineitem,
                                   "item": item}
            item["resource_link_id"] = link_id
        self.deep_links.append(claims)
        return items


async def form_of(request: Request) -> dict:
    """An urlencoded form's fields (without python-multipart, which the app does not need)."""
    return dict(parse_qsl((await request.body()).decode(), keep_blank_values=True))


@contextmanager
def serve_in_thread(app, port: int):
    """Serve an ASGI app with uvicorn on 127.0.0.1:`port` in a thread of this process; stopped after the block."""
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning", lifespan="off",
                                           access_log=False))
    thread = threading.Thread(target=server.run, name=f"uvicorn-{port}", daemon=True)
    thread.start()
    deadline = time.monotonic() + START_SECONDS
    while not server.started:
        if not thread.is_alive() or time.monotonic() > deadline:
            raise RuntimeError(f"the server on port {port} did not start")
        time.sleep(0.02)
    try:
        yield app
    finally:
        server.should_exit = True
        thread.join(timeout=START_SECONDS)


def auto_form(action: str, fields: dict, title: str) -> str:
    """A page POSTing `fields` to `action` at once, as an LMS's launch and authentication pages do."""
    inputs = "".join(f'<input type="hidden" name="{html.escape(k)}" value="{html.escape(str(v))}">'
                     for k, v in fields.items())
    return (f"<!doctype html><html><head><title>{html.escape(title)}</title></head><body>"
            f'<form id="auto" method="post" action="{html.escape(action)}">{inputs}'
            f'<noscript><button type="submit">Continue</button></noscript></form>'
            f"<script>document.getElementById('auto').submit();</script></body></html>")


# --- the browser ---------------------------------------------------------------------------------------------

class Forms(HTMLParser):
    """The forms of a page: [{"action", "method", "id", "fields": {name: value}, "buttons": [(name, value, text)]}]."""

    def __init__(self):
        super().__init__()
        self.forms: list[dict] = []
        self._button: list | None = None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "form":
            self.forms.append({"action": attrs.get("action") or "", "method": (attrs.get("method") or "get").lower(),
                               "id": attrs.get("id"), "fields": {}, "buttons": []})
        elif not self.forms:
            return
        elif tag == "input" and attrs.get("name"):
            kind = (attrs.get("type") or "text").lower()
            if kind == "submit":
                self.forms[-1]["buttons"].append((attrs["name"], attrs.get("value", ""), attrs.get("value", "")))
            elif kind not in ("checkbox", "radio") or "checked" in attrs:
                self.forms[-1]["fields"][attrs["name"]] = attrs.get("value") or ""
        elif tag == "button":
            self._button = [attrs.get("name"), attrs.get("value", ""), ""]
        elif tag in ("textarea", "select") and attrs.get("name"):
            self.forms[-1]["fields"][attrs["name"]] = ""

    def handle_data(self, data):
        if self._button is not None:
            self._button[2] += data

    def handle_endtag(self, tag):
        if tag == "button" and self._button is not None and self.forms:
            self.forms[-1]["buttons"].append(tuple(self._button))
            self._button = None


def forms_of(page: str) -> list[dict]:
    parser = Forms()
    parser.feed(page)
    return parser.forms


class Browser:
    """One user's browser: an httpx client keeping its cookies, following redirects and auto-submitted forms."""

    def __init__(self, platform: Platform | None = None):
        self.platform = platform
        self.http = httpx.Client(timeout=120, follow_redirects=False)
        self.history: list[httpx.Response] = []
        self.last_post: tuple[str, dict] | None = None

    def close(self) -> None:
        self.http.close()

    def _follow(self, response: httpx.Response, limit: int = 10) -> httpx.Response:
        """Follow redirects (GET after 301/302/303, as browsers do) and pages that only submit a form at once."""
        for _ in range(limit):
            self.history.append(response)
            if response.is_redirect:
                response = self.http.get(urljoin(str(response.url), response.headers["location"]))
                continue
            if response.status_code == 200 and "text/html" in response.headers.get("content-type", ""):
                forms = forms_of(response.text)
                if len(forms) == 1 and forms[0]["method"] == "post" \
                        and re.search(r"\.submit\(\)", self._scripts_of(response)):
                    response = self.post_form(str(response.url), forms[0], follow=False)
                    continue
            return response
        raise AssertionError(f"more than {limit} redirects or forms: {[str(r.url) for r in self.history[-limit:]]}")

    def _scripts_of(self, page: httpx.Response) -> str:
        """The page's scripts as a browser runs them: inline, and those it loads from its own server."""
        loaded = [self.http.get(urljoin(str(page.url), src)).text
                  for src in re.findall(r'<script[^>]*\ssrc="([^"]+)"', page.text) if "://" not in src]
        return "\n".join([page.text, *loaded])

    def post_form(self, page_url: str, form: dict, extra: dict | None = None, follow: bool = True) -> httpx.Response:
        url = urljoin(page_url, form["action"] or page_url)
        data = dict(form["fields"]) | dict(extra or {})
        self.last_post = (url, data)
        response = self.http.post(url, data=data)
        return self._follow(response) if follow else response

    def get(self, url: str) -> httpx.Response:
        return self._follow(self.http.get(url))

    def launch(self, launch: Launch, method: str = "POST") -> httpx.Response:
        """The launch as the LMS page starts it: the login initiation (a POSTed form, as Moodle sends it, or a
        GET), then everything the tool and the platform answer, to the tool's page after the launch."""
        if method == "GET":
            response = self.http.get(launch.login_url)
        else:
            self.last_post = (self.platform.tool.login_url if self.platform else launch.login_url.split("?")[0],
                              launch.login_params)
            response = self.http.post(self.last_post[0], data=launch.login_params)
        return self._follow(response)

    def login_only(self, launch: Launch) -> httpx.Response:
        """The login initiation and the platform's answer, without posting the id_token: the auth page."""
        response = self.http.post(launch.login_url.split("?")[0], data=launch.login_params)
        assert response.is_redirect, (response.status_code, response.text[:500])
        return self.http.get(response.headers["location"])

    def replay(self, id_token: str, state: str, url: str) -> httpx.Response:
        """POST an id_token and state again, as an attacker replaying a captured launch does."""
        return self.http.post(url, data={"id_token": id_token, "state": state})


def page_text(response: httpx.Response) -> str:
    """The visible words of an HTML page (tags, scripts and styles removed), for reasons and names."""
    text = re.sub(r"(?is)<(script|style)\b.*?</\1>", " ", response.text)
    return html.unescape(re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", text))).strip()

