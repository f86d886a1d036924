"""The tool's RSA key pair: made once, at first use, and kept in the database so that every server signs with
the same key and publishes the same JWKS (``GET /lti/jwks``). The private key never leaves the server."""
from __future__ import annotations

import time
from dataclasses import dataclass
from functools import lru_cache

from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.asymmetric import rsa
from jwcrypto.jwk import JWK

KEY_BITS = 2048
ALGORITHM = "RS256"


@dataclass(frozen=True)
class ToolKey:
    """The key pair, with its public forms computed once (loading an RSA private key is costly: tens of ms)."""
    kid: str
    private_pem: str
    public_pem: str
    public_jwk: dict

    def __repr__(self) -> str:              # never the key in a log or a traceback
        return f"ToolKey(kid={self.kid!r})"

    @classmethod
    def from_pem(cls, private_pem: str) -> "ToolKey":
        jwk = JWK.from_pem(private_pem.encode())
        kid = jwk.thumbprint()           # RFC 7638: the kid pylti1p3 puts in the headers it signs
        return cls(kid, private_pem, jwk.export_to_pem(private_key=False).decode(),
                   jwk.export_public(as_dict=True) | {"kid": kid, "alg": ALGORITHM, "use": "sig"})


def new_key() -> ToolKey:
    private = rsa.generate_private_key(public_exponent=65537, key_size=KEY_BITS)
    pem = private.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                serialization.NoEncryption()).decode()
    return ToolKey.from_pem(pem)


@lru_cache(maxsize=4)
def _tool_key(store_id: int, store) -> ToolKey:
    stored = store.lti_stored_tool_key()
    if stored is None:                       # the first server to need it makes it; the others read it back
        made = new_key()
        stored = store.lti_tool_key(made.kid, made.private_pem, time.time())
    return ToolKey.from_pem(stored[1])


def tool_key(store) -> ToolKey:
    """The tool's key pair from this store (made and stored at first use)."""
    return _tool_key(id(store), store)


def jwks(store) -> dict:
    """The tool's public key set."""
    return {"keys": [tool_key(store).public_jwk]}
