"""The cost of checking an LTI 1.3 launch's id_token: pylti1p3 (what the tool uses) against a direct check of the
same token with joserfc (what writing the protocol ourselves would use).

One RS256 id_token of a learner's resource-link launch, signed by a platform key made here, verified by
  1. joserfc: signature against the platform's JWKS (in memory) and the claims (iss, aud, exp, iat, nonce,
     deployment id, message type, version) — the bare minimum a hand-written tool would do;
  2. pylti1p3's verification chain without the single-use state: JWT format, the registration from the database,
     the signature (PyJWT, the key taken from the JWKS cached in the database), the deployment, the message
     validators (LTI version, message type, roles, resource link, sub);
  3. pylti1p3's whole ``validate()`` as a launch runs it: 2 plus the state taken from the database (single use),
     the nonce bound to it, and the launch data saved for later.
SQLite in a temporary directory, one process, interleaved rounds; medians and the ratios to joserfc are printed
and written to bench/results/lti.md.

    python bench/lti_launch.py [--repeats 300]
"""
from __future__ import annotations

import argparse
import os
import platform as host
import statistics
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from joserfc import jwt  # noqa: E402
from joserfc.jwk import KeySet, RSAKey  # noqa: E402
from joserfc.jwt import JWTClaimsRegistry  # noqa: E402

from server.api.lti_adapters import LtiCookies, LtiLaunch, LtiRequest  # noqa: E402
from server.classroom.lti.launch_state import (KEY_SET_SECONDS, DatabaseLaunchStorage,  # noqa: E402
                                               DatabaseSessionService)
from server.classroom.lti.platforms import DatabaseToolConf, new_platform  # noqa: E402
from server.classroom.store import SQLiteStore  # noqa: E402

ISSUER, CLIENT, DEPLOYMENT = "https://moodle.example.edu", "client-7", "1"
LTI = "https://purl.imsglobal.org/spec/lti/claim/"
RESULTS = REPO / "bench" / "results" / "lti.md"


class FakeHttp:
    """What the adapters read of a Starlette request."""
    class url:
        scheme = "https"
    cookies: dict = {}


def id_token(key: RSAKey, nonce: str) -> str:
    now = int(time.time())
    claims = {"iss": ISSUER, "aud": CLIENT, "sub": "user-42", "nonce": nonce, "iat": now, "exp": now + 600,
              "name": "Anna Kovalenko", LTI + "message_type": "LtiResourceLinkRequest", LTI + "version": "1.3.0",
              LTI + "deployment_id": DEPLOYMENT, LTI + "target_link_uri": "https://tool.example/lti/launch",
              LTI + "resource_link": {"id": "link-1"}, LTI + "custom": {"assignment": "a1"},
              LTI + "roles": ["http://purl.imsglobal.org/vocab/lis/v2/membership#Learner"]}
    return jwt.encode({"alg": "RS256", "kid": key.kid}, claims, key)


def joserfc_check(token: str, key_set: KeySet, nonce: str) -> dict:
    decoded = jwt.decode(token, key_set, algorithms=["RS256"])
    JWTClaimsRegistry(iss={"essential": True, "value": ISSUER}, aud={"essential": True, "value": CLIENT},
                      exp={"essential": True}, iat={"essential": True}, nonce={"essential": True, "value": nonce},
                      **{LTI + "deployment_id": {"essential": True, "value": DEPLOYMENT},
                         LTI + "message_type": {"essential": True, "value": "LtiResourceLinkRequest"},
                         LTI + "version": {"essential": True, "value": "1.3.0"}}).validate(decoded.claims)
    return decoded.claims


def login_again(store, state: str, nonce: str) -> None:
    """What the login keeps: the state with its nonce, in the database."""
    session = DatabaseSessionService(LtiRequest(FakeHttp(), {}), store)
    session.save_nonce(nonce)
    session.save_state_params(state, {"target": ""})


def joserfc_with_state(store, token: str, key_set: KeySet, state: str) -> dict:
    """joserfc with the single-use state a hand-written tool needs as well (taken from the same table)."""
    kept = DatabaseSessionService(LtiRequest(FakeHttp(), {}), store)
    assert kept.check_state_is_valid(state, "")
    return joserfc_check(token, key_set, kept._state["nonce"])


def launch_of(store, token: str, state: str) -> LtiLaunch:
    request = LtiRequest(FakeHttp(), {"id_token": token, "state": state})
    found = LtiLaunch(request, DatabaseToolConf(store), session_service=DatabaseSessionService(request, store),
                      cookie_service=LtiCookies(request))
    found.set_public_key_caching(DatabaseLaunchStorage(store), cache_lifetime=KEY_SET_SECONDS)
    found.set_jwt_verify_options({"verify_aud": False, "require": ["exp", "iat"]})
    return found


def pylti_chain(store, token: str) -> dict:
    found = launch_of(store, token, "unused")
    found._validated = True                                   # the chain's steps by hand, without the state
    found.validate_jwt_format().validate_registration().validate_jwt_signature().validate_deployment() \
        .validate_message()
    return found._jwt["body"]


def pylti_full(store, token: str, state: str) -> dict:
    return launch_of(store, token, state).get_launch_data()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=300)
    repeats = parser.parse_args().repeats
    key = RSAKey.generate_key(2048, parameters={"kid": "platform-1", "alg": "RS256", "use": "sig"})
    key_set = KeySet([key])
    public_jwks = {"keys": [key.as_dict(private=False)]}
    with tempfile.TemporaryDirectory() as directory:
        store = SQLiteStore(Path(directory) / "bench.sqlite3")
        platform = new_platform(ISSUER, CLIENT, [DEPLOYMENT], f"{ISSUER}/auth", f"{ISSUER}/token", f"{ISSUER}/jwks",
                                "Moodle")
        store.lti_add_platform(platform)
        DatabaseLaunchStorage(store).set_value(                 # the JWKS as pylti1p3's cache keeps it
            "key-set-url-" + __import__("hashlib").md5(f"{ISSUER}/jwks".encode()).hexdigest(), public_jwks,
            KEY_SET_SECONDS)
        times = {"joserfc": [], "joserfc + state taken": [], "pylti1p3 chain": [], "pylti1p3 validate()": []}
        for round_ in range(repeats + 10):                     # 10 warm-up rounds, not counted
            nonce, state = f"nonce-{round_}", f"state-{round_}"
            login_again(store, state, nonce)
            token = id_token(key, nonce)
            login_again(store, f"{state}-j", nonce)
            for name, check in (("joserfc", lambda: joserfc_check(token, key_set, nonce)),
                                ("joserfc + state taken", lambda: joserfc_with_state(store, token, key_set,
                                                                                     f"{state}-j")),
                                ("pylti1p3 chain", lambda: pylti_chain(store, token)),
                                ("pylti1p3 validate()", lambda: pylti_full(store, token, state))):
                started = time.perf_counter()
                claims = check()
                elapsed = time.perf_counter() - started
                assert claims["sub"] == "user-42"
                if round_ >= 10:
                    times[name].append(elapsed)
    medians = {name: statistics.median(values) * 1e3 for name, values in times.items()}
    base = medians["joserfc"]
    rows = [f"| {name} | {ms:.3f} | {ms / base:.2f} |" for name, ms in medians.items()]
    table = "\n".join(["| verification of one id_token | median, ms | ÷ joserfc |", "|---|---:|---:|", *rows])
    text = (f"# LTI launch: checking the id_token, pylti1p3 against joserfc\n\n"
            f"`python bench/lti_launch.py --repeats {repeats}` on {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC, "
            f"Python {host.python_version()}, {os.cpu_count()} CPUs (a shared machine: other work ran meanwhile). "
            f"One RS256 token (2048-bit key) per round, the three checks interleaved, {repeats} rounds after 10 "
            f"of warm-up; SQLite in a temporary directory.\n\n{table}\n\n"
            "- **joserfc**: signature against the JWKS in memory and the claims a tool must check (iss, aud, exp, "
            "iat, nonce, deployment id, message type, version).\n"
            "- **joserfc + state taken**: the same, after taking the launch's state (single use, with its nonce) "
            "from the database, as any tool must.\n"
            "- **pylti1p3 chain**: JWT format, the registration read from the database, the signature (PyJWT; the "
            "key converted from the JWKS cached in the database), the deployment (database), the message "
            "validators (version, message type, roles, resource link, sub).\n"
            "- **pylti1p3 validate()**: the chain plus the launch's state taken from the database (single use), "
            "the nonce bound to it, and the launch data saved — what `POST /lti/launch` runs.\n\n"
            "pylti1p3's chain costs a few times joserfc's bare check because the registration, "
            "deployment and cached key set are read from the database and the platform's JWK is converted to PEM "
            "for PyJWT on every launch. The single-use state is a write (SQLite with synchronous=FULL: an fsync), "
            "which a hand-written tool needs as well; pylti1p3 also saves the launch for deep linking (another "
            "write). The RSA check itself is the same in both; a launch is one request "
            "per student per visit, so either is far below the page that follows it.\n")
    RESULTS.write_text(text, encoding="utf-8")
    print(text)


if __name__ == "__main__":
    main()
