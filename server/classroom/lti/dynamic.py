"""LTI Dynamic Registration 1.0: the LMS's administrator pastes one URL of this tool, and the tool registers
itself with the LMS and the LMS here, with no values copied by hand.

The URL carries a single-use code an administrator of this tool made (``POST /api/v1/lti/registration-links``
with MDL_ADMIN_TOKEN): without it anybody could register a platform of their own. The LMS opens
``/lti/register?code=…&openid_configuration=…&registration_token=…``; the tool reads the LMS's OpenID
configuration (its issuer must be on the configuration URL's host), posts its own client registration to the
LMS's registration endpoint with the registration token, and keeps the client id and deployment id the LMS answers.
"""
from __future__ import annotations

from urllib.parse import urlsplit

import requests

from ..store.lti_tables import PlatformRecord
from .platforms import PlatformRefused, check_url, new_platform

TOOL_CONFIGURATION = "https://purl.imsglobal.org/spec/lti-tool-configuration"
PLATFORM_CONFIGURATION = "https://purl.imsglobal.org/spec/lti-platform-configuration"
SCOPES = ("https://purl.imsglobal.org/spec/lti-ags/scope/lineitem",
          "https://purl.imsglobal.org/spec/lti-ags/scope/lineitem.readonly",
          "https://purl.imsglobal.org/spec/lti-ags/scope/result.readonly",
          "https://purl.imsglobal.org/spec/lti-ags/scope/score",
          "https://purl.imsglobal.org/spec/lti-nrps/scope/contextmembership.readonly")


def client_registration(base: str, name: str) -> dict:
    """What the tool asks the LMS to register (OpenID Connect Dynamic Client Registration with the LTI extension)."""
    return {
        "application_type": "web", "response_types": ["id_token"], "grant_types": ["implicit", "client_credentials"],
        "initiate_login_uri": f"{base}/lti/login", "redirect_uris": [f"{base}/lti/launch"], "client_name": name,
        "jwks_uri": f"{base}/lti/jwks", "token_endpoint_auth_method": "private_key_jwt", "scope": " ".join(SCOPES),
        TOOL_CONFIGURATION: {
            "domain": urlsplit(base).netloc, "target_link_uri": f"{base}/lti/launch",
            "claims": ["iss", "sub", "name", "given_name", "family_name"],
            "messages": [{"type": "LtiResourceLinkRequest"},
                         {"type": "LtiDeepLinkingRequest", "target_link_uri": f"{base}/lti/launch",
                          "placements": ["ContentArea"]}]},
    }


def register(configuration_url: str, registration_token: str, base: str, name: str,
             session: requests.Session) -> PlatformRecord:
    """Register with the LMS whose OpenID configuration is at this URL; the platform to keep here.
    PlatformRefused (the field and the reason) when the LMS's answers are not usable."""
    check_url("openid_configuration", configuration_url)
    answer = session.get(configuration_url)
    if answer.status_code != 200:
        raise PlatformRefused("openid_configuration", f"the LMS answered {answer.status_code} for its configuration")
    configuration = answer.json()
    issuer = str(configuration.get("issuer") or "")
    if urlsplit(issuer).netloc != urlsplit(configuration_url).netloc:
        raise PlatformRefused("openid_configuration", "the issuer is not on the configuration URL's host")
    endpoint = check_url("registration_endpoint", str(configuration.get("registration_endpoint") or ""))
    made = session.post(endpoint, json=client_registration(base, name),
                        headers={"Authorization": f"Bearer {registration_token}"} if registration_token else {})
    if made.status_code not in (200, 201):
        raise PlatformRefused("registration_token", f"the LMS refused the registration ({made.status_code})")
    client = made.json()
    deployment = str((client.get(TOOL_CONFIGURATION) or {}).get("deployment_id") or "")
    product = (configuration.get(PLATFORM_CONFIGURATION) or {}).get("product_family_code") or ""
    return new_platform(issuer, str(client.get("client_id") or ""), [deployment] if deployment else [],
                        str(configuration.get("authorization_endpoint") or ""),
                        str(configuration.get("token_endpoint") or ""), str(configuration.get("jwks_uri") or ""),
                        f"{product} {urlsplit(issuer).netloc}".strip())
