"""Normal draws repeated from the same generator state, served from memory.

A search over a parameter with common random numbers — the admissible rocking
amplitude of :mod:`strapdown.analysis.gyrocompass.alignment_design`, whose
every amplitude reruns the same trials from the same seeds — draws the same
white noise again and again.  :func:`standard_normal` returns
``rng.standard_normal(shape)`` and leaves ``rng`` in the state that call would
leave it in, but a draw already made from the same state and shape (recently:
the oldest are dropped past a memory bound) is copied from memory instead of
generated.  The numbers are the generator's own, bit for bit, so a result does
not depend on whether a draw was served from memory.
"""

from __future__ import annotations

import threading
from collections import OrderedDict

import numpy as np

__all__ = ["standard_normal", "MAX_BYTES"]

#: Memory bound of the kept draws [bytes].
MAX_BYTES = 32 * 2**20

_draws: OrderedDict = OrderedDict()
_held = [0]
_lock = threading.Lock()


def standard_normal(rng: np.random.Generator, shape) -> np.ndarray:
    """``rng.standard_normal(shape)``, from memory when the same state drew the same shape before.

    Parameters
    ----------
    rng : numpy.random.Generator
        The stream; it is advanced exactly as by ``rng.standard_normal(shape)``.
    shape : tuple of int
        Shape of the draw.

    Returns
    -------
    ndarray
        Standard normal numbers (a read-only array when served from memory; new arrays result from arithmetic on it).

    Examples
    --------
    >>> a, b = np.random.default_rng(5), np.random.default_rng(5)
    >>> bool(np.array_equal(standard_normal(a, (3,)), b.standard_normal(3)))
    True
    >>> bool(np.array_equal(a.random(2), b.random(2)))  # the states agree after the draw
    True
    """
    shape = tuple(int(s) for s in np.atleast_1d(shape))
    bits = rng.bit_generator
    key = (type(bits).__name__, repr(bits.state), shape)
    with _lock:
        hit = _draws.get(key)
        if hit is not None:
            _draws.move_to_end(key)
    if hit is not None:
        values, after = hit
        bits.state = after
        return values
    values = rng.standard_normal(shape)
    values.setflags(write=False)
    with _lock:
        if key not in _draws:
            _draws[key] = (values, bits.state)
            _held[0] += values.nbytes
            while _held[0] > MAX_BYTES and len(_draws) > 1:
                _, (old, _) = _draws.popitem(last=False)
                _held[0] -= old.nbytes
    return values
