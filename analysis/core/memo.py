"""A bounded memo of arrays: the most recently used values kept, the oldest dropped past a memory bound.

The common random numbers of a parameter search make the same deterministic
work recur (the same draw evaluated again, the same noise drawn again, the
same records filtered by another filter); the modules that serve it from
memory (:mod:`.repeated_draws`, :mod:`strapdown.analysis.alignment.base_motion`,
:mod:`strapdown.analysis.alignment.fine`) keep it here.  A value
is an array, or a tuple of arrays and other items; its arrays are made
read-only and count against the bound.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable

import numpy as np

from .validation import as_int

__all__ = ["BoundedMemo"]


class BoundedMemo:
    """Values by key, least recently used out once their arrays exceed ``max_bytes``; thread-safe.

    Parameters
    ----------
    max_bytes : int
        Memory bound of the kept arrays [bytes] (the newest value is kept even if it alone exceeds it).

    Raises
    ------
    TypeError, ValueError
        If ``max_bytes`` is not an integer >= 0.

    Examples
    --------
    >>> import numpy as np
    >>> memo = BoundedMemo(16)
    >>> a = memo.get("a", lambda: np.zeros(2))   # built: 16 bytes
    >>> memo.get("a", lambda: np.ones(2)) is a  # served
    True
    >>> _ = memo.get("b", lambda: np.zeros(2))   # "a" is dropped
    >>> float(memo.get("a", lambda: np.ones(2))[0])
    1.0
    """

    def __init__(self, max_bytes: int):
        self.max_bytes = as_int(max_bytes, "max_bytes", minimum=0)
        self._items: OrderedDict = OrderedDict()
        self._bytes = 0
        self._lock = threading.Lock()

    @staticmethod
    def _arrays(value):
        items = value if isinstance(value, tuple) else (value,)
        return [x for x in items if isinstance(x, np.ndarray)]

    def get(self, key: Hashable, build: Callable[[], object]):
        """The value of ``key``: from memory, or ``build()`` (its array made read-only) and kept.

        Parameters
        ----------
        key : hashable
            What identifies the value.
        build : callable
            Makes the value when it is not kept.

        Returns
        -------
        object
            The kept or built value.
        """
        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
                return self._items[key]
        value = build()
        for a in self._arrays(value):
            a.setflags(write=False)
        with self._lock:
            if key not in self._items:
                self._items[key] = value
                self._bytes += sum(a.nbytes for a in self._arrays(value))
                while self._bytes > self.max_bytes and len(self._items) > 1:
                    _, old = self._items.popitem(last=False)
                    self._bytes -= sum(a.nbytes for a in self._arrays(old))
        return value
