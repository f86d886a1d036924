"""pylti1p3's launch state in the app's database, so that any server behind the load balancer can take the
launch whose login another one answered, and a launch works without cookies (third-party cookies blocked in
an LMS frame).

- ``DatabaseLaunchStorage`` is pylti1p3's LaunchDataStorage on the store's ``lti_launch_state`` table (JSON
  values with an expiry): launch data for deep linking, the platforms' cached key sets.
- ``DatabaseSessionService`` keeps each OIDC login's state *with its nonce* (one row, STATE_SECONDS) instead of
  pylti1p3's state cookie plus a free-standing nonce: the state a launch brings must be one this tool issued and
  not yet used, and the id_token's nonce must be the one issued with it; the row is taken (deleted) by the one
  launch that uses it, so a replayed id_token (same state, same nonce) is refused on every server.
"""
from __future__ import annotations

import time
import typing as t

from pylti1p3.launch_data_storage.base import LaunchDataStorage
from pylti1p3.session import SessionService

STATE_SECONDS = 600           # from the login redirect to the launch: the platform's login page included
LAUNCH_SECONDS = 3600         # a deep-linking picker stays usable this long
KEY_SET_SECONDS = 3600        # a platform's public key set is fetched again after this


class DatabaseLaunchStorage(LaunchDataStorage):
    """Key → JSON value with an expiry, in the store; no session cookie (the keys are unguessable ids)."""

    def __init__(self, store):
        super().__init__()
        self.store = store

    def get_session_cookie_name(self):
        return None

    def can_set_keys_expiration(self) -> bool:
        return True

    def get_value(self, key: str):
        return self.store.lti_get(self._prepare_key(key), time.time())

    def set_value(self, key: str, value, exp: int | None = None) -> None:
        self.store.lti_put(self._prepare_key(key), value, time.time() + (exp or LAUNCH_SECONDS))

    def check_value(self, key: str) -> bool:
        return self.get_value(key) is not None

    def take_value(self, key: str):
        """The value, removed: exactly one caller gets it."""
        return self.store.lti_take(self._prepare_key(key), time.time())


class DatabaseSessionService(SessionService):
    """pylti1p3's SessionService with the state and nonce bound together, single use, in the database."""

    def __init__(self, request, store):
        super().__init__(request)
        self.data_storage: DatabaseLaunchStorage = DatabaseLaunchStorage(store)
        self.data_storage.set_request(request)
        self._launch_data_lifetime = LAUNCH_SECONDS
        self._issued_nonce: str | None = None
        self._state: dict | None = None

    def set_data_storage(self, data_storage) -> None:     # the database storage stays
        pass

    # the login: the nonce is made first, then the state is saved with it
    def save_nonce(self, nonce: str) -> None:
        self._issued_nonce = nonce

    def save_state_params(self, state: str, params: t.Dict[str, object]) -> None:
        self.data_storage.set_value(self._get_key("state", state),
                                    {"nonce": self._issued_nonce, "params": params}, exp=STATE_SECONDS)

    def get_state_params(self, state: str):
        return (self._state or {}).get("params")

    # the launch: the state is taken (once), then the id_token's nonce must be the one issued with it
    def check_state_is_valid(self, state: str, id_token_hash: str) -> bool:
        self._state = self.data_storage.take_value(self._get_key("state", state))
        return self._state is not None

    def check_nonce(self, nonce: str) -> bool:
        return self._state is not None and self._state.get("nonce") == nonce

    def set_state_valid(self, state: str, id_token_hash: str) -> None:
        pass                                                # the state is used up: nothing to mark
