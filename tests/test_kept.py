"""server/core/dynamics/kept.py: what a process keeps across requests — at most ``size`` values, the least
recently used dropped first, a value made once per key while it is kept."""
from __future__ import annotations

from server.core.dynamics.kept import Kept


def test_the_least_recently_used_goes_first():
    kept = Kept(2)
    kept.put("a", 1)
    kept.put("b", 2)
    assert kept.get("a") == 1            # a is now the most recently used
    kept.put("c", 3)                     # b goes
    assert kept.get("b") is None and kept.get("a") == 1 and kept.get("c") == 3
    assert kept.get("b", "none") == "none"


def test_a_value_is_made_once_while_it_is_kept():
    kept, made = Kept(1), []
    make = lambda key: lambda: made.append(key) or key * 2      # noqa: E731
    assert kept.kept(3, make(3)) == 6 and kept.kept(3, make(3)) == 6 and made == [3]
    assert kept.kept(4, make(4)) == 8 and kept.kept(3, make(3)) == 6 and made == [3, 4, 3]    # 3 was dropped
