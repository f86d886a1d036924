"""Turn numpy results into JSON that never holds NaN or infinity."""
from __future__ import annotations

import numpy as np


def finite_or_none(value):
    """Arrays to nested lists with every non-finite number replaced by None; dicts and lists recursively."""
    if isinstance(value, dict):
        return {k: finite_or_none(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite_or_none(v) for v in value]
    if isinstance(value, np.ndarray):
        out = value.astype(object)
        out[~np.isfinite(value)] = None
        return out.tolist()
    if isinstance(value, (float, np.floating)):
        return float(value) if np.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    return value


def count_undefined(value) -> int:
    """Number of non-finite numbers inside an output."""
    if isinstance(value, dict):
        return sum(count_undefined(v) for v in value.values())
    if isinstance(value, (list, tuple)):
        return sum(count_undefined(v) for v in value)
    if isinstance(value, np.ndarray) and value.dtype.kind == "f":
        return int(np.count_nonzero(~np.isfinite(value)))
    if isinstance(value, float):
        return int(not np.isfinite(value))
    return 0
