"""The server's access log without the students' secrets or the instructor's results token.

A personal link, ``/assignments/<id>/me/<secret>``, carries the secret that lets a student in; the results
page, ``/assignments/<id>/results/<token>``, and the API under it (``/api/v1/assignments/<id>/results/<token>``,
``…/csv``, ``…/links``, ``…/roster``) carry the token that shows every student's answers and makes their links.
uvicorn's access log writes every request's path. ``SecretsCut`` (a logging filter on the "uvicorn.access"
logger, installed when the app is made) writes such paths as ``/assignments/<id>/me/(secret)`` and
``…/results/(token)/csv``, the rest of the path and the query kept; the shipped nginx site logs them the same
way (deploy/nginx/mdl.conf, map $mdl_logged_uri).
"""
from __future__ import annotations

import logging
import re

PERSONAL_LINK = re.compile(r"^(/assignments/[^/?#]+/me/)[^?#]*")
RESULTS_TOKEN = re.compile(r"^((?:/api/v1)?/assignments/[^/?#]+/results/)[^/?#]*")
LTI_TICKET = re.compile(r"^(/lti/continue/)[^?#]*")      # an LMS launch carried to a new window (single use)
LTI_REGISTRATION = re.compile(r"^(/lti/register/).*")   # a registration code, and the LMS's token in the query
ACCESS_LOGGER = "uvicorn.access"


def cut(path: str) -> str:
    """The path with a personal link's secret replaced by "(secret)", a results token by "(token)"."""
    path = LTI_REGISTRATION.sub(r"\1(code)", LTI_TICKET.sub(r"\1(ticket)", path))
    return RESULTS_TOKEN.sub(r"\1(token)", PERSONAL_LINK.sub(r"\1(secret)", path))


class SecretsCut(logging.Filter):
    """uvicorn's access record has args (client, method, path with query, HTTP version, status)."""

    def filter(self, record: logging.LogRecord) -> bool:
        if isinstance(record.args, tuple) and len(record.args) >= 3 and isinstance(record.args[2], str):
            record.args = (*record.args[:2], cut(record.args[2]), *record.args[3:])
        return True


def install() -> None:
    """Put the filter on uvicorn's access logger once (the app may be made more than once in a process)."""
    logger = logging.getLogger(ACCESS_LOGGER)
    if not any(isinstance(f, SecretsCut) for f in logger.filters):
        logger.addFilter(SecretsCut())
