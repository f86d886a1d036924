"""The LTI registration API's bodies: a platform as its administrator's page shows it, and the tool's URLs."""
from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class PlatformRegistration(BaseModel):
    """POST /api/v1/lti/platforms: the values the LMS shows once the tool is configured there (in Moodle:
    Site administration → Plugins → Activity modules → External tool → Manage tools → the tool's details)."""

    model_config = ConfigDict(extra="forbid")
    issuer: str = Field(min_length=1, max_length=500, description="Platform ID (the `iss` of its launches)")
    client_id: str = Field(min_length=1, max_length=200, description="Client ID the platform gave this tool")
    deployment_ids: list[str] = Field(min_length=1, max_length=50, description="Deployment ID(s) of the tool")
    auth_login_url: str = Field(max_length=2000, description="Authentication request URL (OIDC)")
    auth_token_url: str = Field(max_length=2000, description="Access token URL (OAuth 2 client credentials)")
    key_set_url: str = Field(max_length=2000, description="Public keyset URL of the platform (JWKS)")
    name: str = Field("", max_length=200, description="a name to show (default: the issuer's host)")


class ToolUrls(BaseModel):
    """What to paste into the LMS's tool configuration."""
    login_url: str = Field(description="Initiate login URL (OIDC third-party login)")
    launch_url: str = Field(description="Tool URL and Redirection URI: where launches are posted")
    jwks_url: str = Field(description="Public keyset URL of the tool")
    deep_linking_url: str = Field(description="Content selection URL (Deep Linking requests)")


class PlatformRegistered(BaseModel):
    id: str
    tool: ToolUrls


class PlatformInfo(BaseModel):
    id: str
    issuer: str
    client_id: str
    name: str
    deployment_ids: list[str]
    auth_login_url: str
    auth_token_url: str
    key_set_url: str
    created_at: str


class PendingScoreInfo(BaseModel):
    assignment_id: str
    tries: int
    last_error: str | None
    retry_at: str


class Platforms(BaseModel):
    platforms: list[PlatformInfo]
    pending_scores: list[PendingScoreInfo] = Field(description="scores not yet accepted by a gradebook")


class RegistrationLink(BaseModel):
    url: str = Field(description="paste into the LMS as the tool's dynamic registration URL; works once")
    expires_in: int = Field(description="seconds the link stays valid")
