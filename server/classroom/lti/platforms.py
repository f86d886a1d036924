"""The LMSs registered here, and the tool configuration pylti1p3 reads them through.

A platform is identified by its issuer and the client id it gave this tool (one issuer may register the tool
more than once, e.g. two Moodle courses' administrators); a launch is accepted only from a deployment id
registered with it. The tool's own key (``tool_key``) is the same for every platform.
"""
from __future__ import annotations

import secrets
import time
from urllib.parse import urlsplit

from pylti1p3.deployment import Deployment
from pylti1p3.registration import Registration
from pylti1p3.tool_config import ToolConfAbstract

from ..store.lti_tables import PlatformRecord
from .tool_key import tool_key


class PlatformRefused(ValueError):
    """A registration that cannot be kept: the field and the reason."""

    def __init__(self, field: str, reason: str):
        super().__init__(reason)
        self.field, self.reason = field, reason


LOOPBACK = ("127.0.0.1", "localhost", "::1")


def check_url(field: str, url: str) -> str:
    """An absolute https URL (plain http only to this machine: a platform under test)."""
    parts = urlsplit(url)
    allowed = ("https", "http") if parts.hostname in LOOPBACK else ("https",)
    if parts.scheme not in allowed or not parts.netloc or len(url) > 2000:
        raise PlatformRefused(field, "must be an absolute https:// URL (http:// only for this machine)")
    return url


def new_platform(issuer: str, client_id: str, deployment_ids: list[str], auth_login_url: str, auth_token_url: str,
                 key_set_url: str, name: str) -> PlatformRecord:
    """A platform record from what its administrator's page shows; PlatformRefused naming the field."""
    if not issuer or not client_id:
        raise PlatformRefused("client_id" if issuer else "issuer", "must not be empty")
    if not deployment_ids:
        raise PlatformRefused("deployment_ids", "at least one deployment id")
    for field, url in (("auth_login_url", auth_login_url), ("auth_token_url", auth_token_url),
                       ("key_set_url", key_set_url)):
        check_url(field, url)
    return PlatformRecord(secrets.token_urlsafe(8), issuer, client_id, name or urlsplit(issuer).netloc or issuer,
                          auth_login_url, auth_token_url, key_set_url, tuple(deployment_ids), time.time())


def registration(platform: PlatformRecord, store) -> Registration:
    """pylti1p3's view of a platform, with the tool's key."""
    key = tool_key(store)
    return (Registration().set_issuer(platform.issuer).set_client_id(platform.client_id)
            .set_auth_login_url(platform.auth_login_url).set_auth_token_url(platform.auth_token_url)
            .set_key_set_url(platform.key_set_url).set_tool_private_key(key.private_pem)
            .set_tool_public_key(key.public_pem))


class DatabaseToolConf(ToolConfAbstract):
    """The registrations in the app's database (every issuer may have several client ids)."""

    def __init__(self, store):
        super().__init__()
        self.store = store
        self.issuers_relation_types = {}

    def check_iss_has_one_client(self, iss: str) -> bool:
        return False

    def check_iss_has_many_clients(self, iss: str) -> bool:
        return True

    def platform(self, iss: str, client_id: str | None) -> PlatformRecord | None:
        """The registration of this issuer and client id (the issuer's only one when no client id is sent)."""
        found = self.store.lti_platforms(iss)
        if client_id:
            found = [p for p in found if p.client_id == client_id]
        return found[0] if len(found) == 1 else None

    def find_registration_by_issuer(self, iss: str, *args, **kwargs):
        platform = self.platform(iss, None)
        return None if platform is None else registration(platform, self.store)

    def find_registration_by_params(self, iss: str, client_id: str, *args, **kwargs):
        platform = self.platform(iss, client_id)
        return None if platform is None else registration(platform, self.store)

    def find_deployment(self, iss: str, deployment_id: str):
        return self.find_deployment_by_params(iss, deployment_id, None)

    def find_deployment_by_params(self, iss: str, deployment_id: str, client_id: str | None, *args, **kwargs):
        platform = self.platform(iss, client_id)
        if platform is None or deployment_id not in platform.deployment_ids:
            return None
        return Deployment().set_deployment_id(deployment_id)
