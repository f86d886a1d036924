"""What a process keeps across requests, by what it depends on: the last ``size`` values, the least recently used
dropped first, shared by the worker's threads (a machine's kinks, its tables between the kinks, its friction
solves: a slider's family and a dragged slider find them)."""
from __future__ import annotations

import threading
from collections import OrderedDict
from typing import Callable, Hashable, TypeVar

T = TypeVar("T")


class Kept:
    """A thread-safe least-recently-used store of at most ``size`` values."""

    def __init__(self, size: int):
        self.size = size
        self._values: OrderedDict = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: Hashable, default=None):
        """The value kept for key (now the most recently used), or ``default``."""
        with self._lock:
            if key not in self._values:
                return default
            self._values.move_to_end(key)
            return self._values[key]

    def put(self, key: Hashable, value) -> None:
        """Keep value for key, dropping the least recently used past ``size``."""
        with self._lock:
            self._values[key] = value
            self._values.move_to_end(key)
            while len(self._values) > self.size:
                self._values.popitem(last=False)

    def kept(self, key: Hashable, make: Callable[[], T]) -> T:
        """The value kept for key, or make() kept (made outside the lock: two threads may both make it)."""
        found = self.get(key)
        if found is None:
            found = make()
            self.put(key, found)
        return found
