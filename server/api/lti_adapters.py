"""pylti1p3 on FastAPI: its Request, CookieService, Redirect, OIDCLogin and MessageLaunch over a Starlette
request whose parameters (query and urlencoded form) were read beforehand, so that pylti1p3's synchronous
calls run in a worker thread. The launch state lives in the database (classroom/lti/launch_state)."""
from __future__ import annotations

from fastapi import Request as HttpRequest
from fastapi.responses import RedirectResponse, Response
from pylti1p3.cookie import CookieService
from pylti1p3.message_launch import MessageLaunch
from pylti1p3.oidc_login import OIDCLogin
from pylti1p3.redirect import Redirect
from pylti1p3.request import Request

from ..classroom.lti.grades import TimeoutSession
from ..classroom.lti.launch_state import KEY_SET_SECONDS, DatabaseLaunchStorage, DatabaseSessionService
from ..classroom.lti.platforms import DatabaseToolConf


class LtiRequest(Request):
    """The parameters of one request (query first, then the form) and whether it came over https."""

    def __init__(self, http: HttpRequest, params: dict[str, str]):
        self.http, self.params = http, params

    @property
    def session(self):
        return {}

    def is_secure(self) -> bool:
        return self.http.url.scheme == "https"

    def get_param(self, key: str):
        return self.params.get(key)


class LtiCookies(CookieService):
    """Cookies read from the request; those pylti1p3 sets are kept and put on the response (``apply``):
    SameSite=None; Secure over https (the launch comes back cross-site), else Lax."""

    def __init__(self, request: LtiRequest):
        self.request = request
        self.to_set: list[tuple[str, str, int | None]] = []

    def _name(self, name: str) -> str:
        return f"{self._cookie_prefix}-{name}"

    def get_cookie(self, name: str):
        return self.request.http.cookies.get(self._name(name))

    def set_cookie(self, name: str, value, exp: int | None = 3600):
        self.to_set.append((self._name(name), str(value), exp))

    def apply(self, response: Response) -> Response:
        secure = self.request.is_secure()
        for name, value, exp in self.to_set:
            response.set_cookie(name, value, max_age=exp, path="/lti/", httponly=True, secure=secure,
                                samesite="none" if secure else "lax")
        return response


class LtiRedirect(Redirect):
    def __init__(self, location: str, cookies: LtiCookies):
        self.location, self.cookies = location, cookies

    def do_redirect(self) -> Response:
        return self.cookies.apply(RedirectResponse(self.location, status_code=302))

    do_js_redirect = do_redirect

    def set_redirect_url(self, location: str):
        self.location = location

    def get_redirect_url(self) -> str:
        return self.location


class LtiLogin(OIDCLogin):
    def get_redirect(self, url: str) -> LtiRedirect:
        return LtiRedirect(url, self._cookie_service)


class LtiLaunch(MessageLaunch):
    def _get_request_param(self, key: str):
        return self._request.get_param(key)


def login(http: HttpRequest, params: dict[str, str], store) -> LtiLogin:
    request = LtiRequest(http, params)
    return LtiLogin(request, DatabaseToolConf(store), DatabaseSessionService(request, store), LtiCookies(request))


def launch(http: HttpRequest, params: dict[str, str], store) -> LtiLaunch:
    request = LtiRequest(http, params)
    found = LtiLaunch(request, DatabaseToolConf(store), session_service=DatabaseSessionService(request, store),
                      cookie_service=LtiCookies(request), requests_session=TimeoutSession())
    found.set_public_key_caching(DatabaseLaunchStorage(store), cache_lifetime=KEY_SET_SECONDS)
    return found


def cached_launch(http: HttpRequest, launch_id: str, store) -> LtiLaunch:
    """A launch validated earlier (deep linking: the picker's choice), from the database; LtiException if gone."""
    request = LtiRequest(http, {})
    return LtiLaunch.from_cache(launch_id, request, DatabaseToolConf(store),
                                session_service=DatabaseSessionService(request, store),
                                cookie_service=LtiCookies(request), requests_session=TimeoutSession())
