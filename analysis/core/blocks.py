"""Elementwise array expressions evaluated in cache-sized blocks.

An expression of numpy ufuncs over large arrays makes one temporary per
operation, each a pass over memory.  Evaluated block by block along the first
axis, the temporaries of a block stay in the cache.  Each element of an
elementwise expression depends on the same elements of its inputs only, so the
blocks give the whole-array values bit for bit.

Public API: :data:`BLOCK`, :func:`row_slices`.
"""

from __future__ import annotations

import math

__all__ = ["BLOCK", "row_slices"]

#: Elements per block: the temporaries of a block (a few dozen arrays of this many doubles) stay in the cache.
BLOCK = 4096


def row_slices(shape: tuple) -> list | None:
    """Slices of the first axis of ``shape`` into blocks of about :data:`BLOCK` elements, or None.

    Parameters
    ----------
    shape : tuple of int
        Shape of the elements of the expression (without a trailing axis of components).

    Returns
    -------
    list of slice or None
        The blocks, each of at least one row; None for a shape of at most
        :data:`BLOCK` elements (or no axes), which the whole-array form serves as well.

    Examples
    --------
    >>> row_slices((10000,))
    [slice(0, 4096, None), slice(4096, 8192, None), slice(8192, 12288, None)]
    >>> row_slices((100, 3)) is None
    True
    """
    size = math.prod(shape)
    if not shape or size <= BLOCK:
        return None
    rows = max(1, BLOCK // (size // shape[0]))
    return [slice(i, i + rows) for i in range(0, shape[0], rows)]
