"""Normal draws repeated from the same generator state, served from memory.

A search over a parameter with common random numbers — the admissible rocking
amplitude of :mod:`strapdown.analysis.alignment.design`, whose
every amplitude reruns the same trials from the same seeds — draws the same
white noise again and again.  :func:`standard_normal` returns
``rng.standard_normal(shape)`` and leaves ``rng`` in the state that call would
leave it in, but a draw already made from the same state and shape (recently:
the oldest are dropped past a memory bound) is served from memory instead of
generated.  The numbers are the generator's own, bit for bit, so a result does
not depend on whether a draw was served from memory.
"""

from __future__ import annotations

import numpy as np

from .memo import BoundedMemo
from .validation import as_float, as_int

__all__ = ["standard_normal", "MAX_BYTES"]

#: Memory bound of the kept draws [bytes].
MAX_BYTES = 32 * 2**20

_draws = BoundedMemo(MAX_BYTES)


def standard_normal(rng: np.random.Generator, shape, *, scale: float | None = None) -> np.ndarray:
    """``rng.standard_normal(shape)``, from memory when the same state drew the same shape before.

    Parameters
    ----------
    rng : numpy.random.Generator
        The stream; it is advanced exactly as by ``rng.standard_normal(shape)``.
    shape : tuple of int
        Shape of the draw.
    scale : float, optional, keyword-only
        Return ``scale * rng.standard_normal(shape)`` (the product kept as
        well, so that a repeated draw costs no pass over it) [units of the
        result].

    Returns
    -------
    ndarray
        Standard normal numbers, times ``scale`` if given (a read-only array;
        new arrays result from arithmetic on it).

    Raises
    ------
    TypeError
        If ``rng`` is not a numpy Generator.
    ValueError
        For a negative size in ``shape``.

    Examples
    --------
    >>> a, b = np.random.default_rng(5), np.random.default_rng(5)
    >>> bool(np.array_equal(standard_normal(a, (3,)), b.standard_normal(3)))
    True
    >>> bool(np.array_equal(a.random(2), b.random(2)))  # the states agree after the draw
    True
    """
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"Expected `rng` to be a numpy.random.Generator, got {type(rng).__name__}")
    shape = tuple(as_int(s, "shape", minimum=0) for s in np.atleast_1d(shape).tolist())
    factor = None if scale is None else as_float(scale, "scale")
    bits = rng.bit_generator

    def draw():
        values = rng.standard_normal(shape)
        return (values if factor is None else factor * values), bits.state

    values, after = _draws.get((type(bits).__name__, repr(bits.state), shape, None if factor is None else factor.hex()), draw)
    bits.state = after  # a served draw: the state a fresh one would leave
    return values
