"""How a request carries a student's personal secret, and how the server hands it over.

A browser keeps the secret in the ``mdl_student`` cookie, HttpOnly, set twice and scoped to the one
assignment: on ``/assignments/{id}`` (the pages; SameSite=Lax, so that the personal link opened from an e-mail
or an LMS works) and on ``/api/v1/assignments/{id}`` (the API; SameSite=Strict: another site's page can never
make a request that carries it). ``Secure`` when the request came over https. An API client sends
``Authorization: Bearer <secret>`` instead.

Registration carries no secret yet, so it is refused when a browser says that another site sent it
(``Sec-Fetch-Site: cross-site``, or an ``Origin`` whose host is not this one). The page's name form is also
refused without the ``mdl_client`` cookie (SameSite=Strict) that the form's own page handed over: a browser
never sends it with a form another site posts, and it sends ``Origin: null`` with ours (the pages' referrer
policy is no-referrer), so the origin alone cannot tell. The API's registration takes JSON only, which another
site's page cannot send without a CORS preflight, and this server grants none.
"""
from __future__ import annotations

from urllib.parse import urlsplit

from fastapi import Depends, Request, Response
from fastapi.security import APIKeyCookie, HTTPAuthorizationCredentials, HTTPBearer

from ..runtime.admission import COOKIE as CLIENT_COOKIE

COOKIE = "mdl_student"
# An answer that carries a secret or the instructor's results (a student's secret, the results token, names and
# answers) is kept by no cache, the browser's or a proxy's.
PRIVATE = {"Cache-Control": "no-store", "Pragma": "no-cache"}
COOKIE_DAYS = 200                     # a term and then some
API_PREFIX = "/api/v1"


def cookie_paths(assignment_id: str) -> dict[str, str]:
    """The cookie's path → its SameSite attribute."""
    return {f"/assignments/{assignment_id}": "lax", f"{API_PREFIX}/assignments/{assignment_id}": "strict"}


BEARER = HTTPBearer(auto_error=False, scheme_name="student_secret",
                    description="the student's personal secret, as registration returned it")
BROWSER = APIKeyCookie(name=COOKIE, auto_error=False, scheme_name="student_cookie",
                       description="the student's personal secret, as registration or the personal link set it")


def sent_secret(bearer: HTTPAuthorizationCredentials | None = Depends(BEARER),
                cookie: str | None = Depends(BROWSER)) -> str | None:
    """The secret a request carries (a dependency; both ways are in the OpenAPI document): ``Authorization:
    Bearer …`` first, else the cookie."""
    return bearer.credentials if bearer is not None else cookie


def hand_over(response: Response, request: Request, assignment_id: str, secret: str) -> None:
    """Set the secret's cookies on the response."""
    for path, same_site in cookie_paths(assignment_id).items():
        response.set_cookie(COOKIE, secret, max_age=COOKIE_DAYS * 86400, path=path, httponly=True,
                            samesite=same_site, secure=request.url.scheme == "https")


def keep_private(response: Response) -> Response:
    """Mark an answer ``PRIVATE``: stored by no cache."""
    response.headers.update(PRIVATE)
    return response


def forget(response: Response, request: Request, assignment_id: str) -> None:
    """Remove the secret's cookies from this browser (the secret itself stays valid)."""
    for path, same_site in cookie_paths(assignment_id).items():
        response.delete_cookie(COOKIE, path=path, httponly=True, samesite=same_site,
                               secure=request.url.scheme == "https")


def from_another_site(request: Request, form: bool = False) -> bool:
    """Whether the browser says the request was made by another site's page (a script sends no such header);
    for a form, also whether it lacks the SameSite=Strict cookie of our own pages."""
    if request.headers.get("sec-fetch-site") == "cross-site":
        return True
    if form and CLIENT_COOKIE not in request.cookies:
        return True
    origin = request.headers.get("origin")
    if origin is None or origin == "null":
        return False
    return urlsplit(origin).netloc.lower() != request.headers.get("host", "").lower()
