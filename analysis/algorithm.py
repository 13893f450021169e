"""Numerical evaluation of a rotation-vector algorithm given as data.

One function, :func:`increment`, evaluates an
:class:`derivations.algorithms.Algorithm` on real increments ``p`` (coning:
rotation-vector increment Δφ) or on dual increments ``q = p + s b``
(sculling: ``ΔΦ = Δφ + s Δφ°``, Lebedev & Panov 1989, eq. (2.5)).
"""

from __future__ import annotations

import numpy as np

from derivations.algorithms import Algorithm

from .dual import Dual
from .quaternion import cross, dot

__all__ = ["increment"]


def _expr(expr, p):
    if isinstance(expr, int):
        return p[..., expr - 1, :]
    a, b = expr
    return cross(_expr(a, p), _expr(b, p))


def increment(algorithm: Algorithm, p):
    """Rotation-vector increment ``Δφ`` of ``algorithm`` over one step ``H = N h``.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    p : array_like or Dual, shape (..., N, 3)
        Increments ``p_j`` [rad] (real) or ``q_j = p_j + s b_j`` (dual, ``b_j`` in m/s).

    Returns
    -------
    ndarray or Dual, shape (..., 3)
        ``Δφ`` [rad], or ``ΔΦ = Δφ + s Δφ°`` for dual input.

    Raises
    ------
    ValueError
        If the second-to-last axis of ``p`` is not ``algorithm.samples``.

    Examples
    --------
    >>> from derivations.algorithms import get
    >>> p = np.array([[1e-3, 0, 0], [0, 1e-3, 0]])
    >>> increment(get("two-sample"), p)
    array([1.00000000e-03, 1.00000000e-03, 6.66666667e-07])
    """
    if not isinstance(p, Dual):
        p = np.asarray(p, dtype=float)
    if p.ndim < 2 or p.shape[-1] != 3 or p.shape[-2] != algorithm.samples:
        raise ValueError(f"Expected `p` with shape (..., {algorithm.samples}, 3) for algorithm {algorithm.name!r}, got shape {p.shape}")
    total = np.sum(p, axis=-2)
    # Pairwise terms are folded so that each p_i × p_j is formed once.
    for (i, j), c in algorithm.pairwise.items():
        total = total + float(c) * cross(p[..., i - 1, :], p[..., j - 1, :])
    for term in algorithm.terms:
        plain_pair = not term.dots and isinstance(term.cross[0], int) and isinstance(term.cross[1], int)
        if plain_pair:
            continue
        value = _expr(term.cross, p)
        for i, j in term.dots:
            d = dot(p[..., i - 1, :], p[..., j - 1, :])
            value = value * d[..., None]
        total = total + float(term.coefficient) * value
    return total
