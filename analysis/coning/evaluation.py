"""Numerical evaluation of a rotation-vector algorithm given as data.

One function, :func:`increment`, evaluates an
:class:`strapdown.derivations.coning.algorithms.Algorithm` on real increments ``p`` (coning:
rotation-vector increment Δφ) or on dual increments ``q = p + s b``
(sculling: ``ΔΦ = Δφ + s Δφ°``, Lebedev & Panov 1989, eq. (2.5)).

The evaluation works on the three coordinate arrays of each ``p_j``
separately (each a contiguous or strided ``(...)`` array), and folds the
pairwise terms by their left factor, ``Σ_ij c_ij p_i × p_j =
Σ_i p_i × (Σ_j c_ij p_j)``, so that an algorithm with many pairs costs few
cross products.  The same code serves real and :class:`~strapdown.analysis.core.dual.Dual`
input, and so do arrays of Python objects such as :mod:`mpmath` numbers, which are evaluated with
the exact fractions of the algorithm (for extended-precision references).
"""

from __future__ import annotations

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core.dual import Dual

__all__ = ["increment"]


class _IndexedRows:
    """``rows`` addressed by ``index − 1`` for sample indices ``1 − history … N``."""

    def __init__(self, rows, history):
        self._rows = rows
        self._offset = history

    def __getitem__(self, position):
        return self._rows[position + self._offset]


def _cross(a, b):
    a0, a1, a2 = a
    b0, b1, b2 = b
    return (a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0)


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _expr(expr, comps):
    if isinstance(expr, int):
        return comps[expr - 1]
    a, b = expr
    return _cross(_expr(a, comps), _expr(b, comps))


def increment(algorithm: Algorithm, p):
    """Rotation-vector increment ``Δφ`` of ``algorithm`` over one step ``H = N h``.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    p : array_like or Dual, shape (..., W, 3)
        Increments ``p_j`` [rad] (real) or ``q_j = p_j + s b_j`` (dual, ``b_j`` in m/s),
        ``j = 1 − history … N`` oldest first: ``W = algorithm.window`` rows, the
        last ``N`` of them the current step.  An array of dtype ``object``
        (e.g. :mod:`mpmath` numbers) is evaluated with the exact coefficients.

    Returns
    -------
    ndarray or Dual, shape (..., 3)
        ``Δφ`` [rad], or ``ΔΦ = Δφ + s Δφ°`` for dual input.

    Raises
    ------
    ValueError
        If the second-to-last axis of ``p`` is not ``algorithm.window``.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> p = np.array([[1e-3, 0, 0], [0, 1e-3, 0]])
    >>> increment(get("two-sample"), p)
    array([1.00000000e-03, 1.00000000e-03, 6.66666667e-07])
    """
    exact = not isinstance(p, Dual) and np.asarray(p).dtype == object
    if not isinstance(p, Dual):
        p = np.asarray(p, dtype=object if exact else float)
    scalar = (lambda c: c) if exact else float  # object arrays keep the exact fractions
    if p.ndim < 2 or p.shape[-1] != 3 or p.shape[-2] != algorithm.window:
        raise ValueError(f"Expected `p` with shape (..., {algorithm.window}, 3) for algorithm {algorithm.name!r}, got shape {p.shape}")
    # comps[j - 1] is p_j for j = 1 - history ... N (negative list positions reach back).
    rows = [tuple(p[..., r, c] for c in range(3)) for r in range(algorithm.window)]
    comps = _IndexedRows(rows, algorithm.history)
    total = [sum((comps[j][c] for j in range(1, algorithm.samples)), comps[0][c]) for c in range(3)]
    # Pairwise terms folded by their left factor: p_i × (Σ_j c_ij p_j).
    by_left: dict = {}
    for (i, j), c in algorithm.pairwise.items():
        by_left.setdefault(i, []).append((j, scalar(c)))
    for i, row in by_left.items():
        right = [sum(c * comps[j - 1][k] for j, c in row) for k in range(3)]
        term = _cross(comps[i - 1], right)
        total = [total[k] + term[k] for k in range(3)]
    for term in algorithm.terms:
        plain_pair = not term.dots and isinstance(term.cross[0], int) and isinstance(term.cross[1], int)
        if plain_pair:
            continue
        value = _expr(term.cross, comps)
        factor = scalar(term.coefficient)
        for i, j in term.dots:
            factor = factor * _dot(comps[i - 1], comps[j - 1])
        total = [total[k] + factor * value[k] for k in range(3)]
    return np.stack(total, axis=-1)
