"""Integrals of smooth or oscillatory vector functions over a few intervals, to a relative tolerance.

:func:`integrate` is composite Gauss–Legendre quadrature (nodes of
:func:`numpy.polynomial.legendre.leggauss`) on panels that are halved until two
successive halvings agree: the integrand is evaluated on whole arrays of nodes
at once, so an integrand with thousands of oscillations (the spectrum of a
rocking seen through the transfer function of a long average) costs a few
vectorised calls, where an adaptive scalar routine would call it node by node.

Public API
----------
MAX_VALUE_BYTES
    Largest array of integrand values one evaluation may produce.
integrate
    ``∫ f(x) dx`` over consecutive intervals, for ``f`` returning ``(..., M)`` values at ``M`` nodes.
"""

from __future__ import annotations

import numpy as np

from .validation import as_array, positive

__all__ = ["MAX_VALUE_BYTES", "integrate"]

_ORDER = 16
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(_ORDER)


def _panels(edges: np.ndarray, per_interval: np.ndarray):
    """Nodes and weights of ``per_interval[k]`` equal panels on each interval ``[edges[k], edges[k+1]]``."""
    starts, widths = [], []
    for a, b, k in zip(edges[:-1], edges[1:], per_interval):
        w = (b - a) / k
        starts.append(a + w * np.arange(k))
        widths.append(np.full(k, w))
    s, w = np.concatenate(starts), np.concatenate(widths)
    x = s[:, None] + 0.5 * w[:, None] * (_NODES[None, :] + 1.0)
    return x.ravel(), (0.5 * w[:, None] * _WEIGHTS[None, :]).ravel()


#: Largest array of integrand values one evaluation may produce [bytes] (it bounds the nodes for a wide integrand).
MAX_VALUE_BYTES = 2**25


def integrate(f, edges, *, rtol: float = 1e-10, atol: float = 0.0, panels: int = 64, max_nodes: int = 2**21) -> np.ndarray:
    """``∫ f(x) dx`` from ``edges[0]`` to ``edges[-1]``, exact at the break points ``edges``.

    The panels of each interval are halved until the estimate changes by at
    most ``atol + rtol·|I|`` (elementwise) over two successive halvings.

    Parameters
    ----------
    f : callable
        ``f(x)`` for a 1-D array ``x`` of nodes returns an array ``(..., x.size)``
        (real or complex); it must be smooth inside each interval.
    edges : array_like
        Increasing break points [units of x]: the ends and the places where ``f``
        or a derivative jumps or varies fast.
    rtol, atol : float
        Tolerances of the result [relative, units of the integral].
    panels : int
        Panels to start with, shared among the intervals by their widths.
    max_nodes : int
        Most nodes evaluated at once; fewer for an integrand of many values per
        node, so that one evaluation stays within :data:`MAX_VALUE_BYTES`.

    Returns
    -------
    ndarray
        ``(...)`` the integral.

    Raises
    ------
    ValueError
        For fewer than two edges, edges not increasing or not finite, or no
        convergence within ``max_nodes``.

    Examples
    --------
    >>> import numpy as np
    >>> x = integrate(lambda w: np.sin(w * 300.0) ** 2 / w**2, [1e-9, 50.0])
    >>> round(float(x), 3)    # ∫_0^∞ sin²(aw)/w² dw = πa/2 = 150π, less the tail beyond 50, about 1/100
    471.229
    """
    e = as_array(edges, "edges").ravel()
    if e.size < 2 or not np.all(np.isfinite(e)) or np.any(np.diff(e) <= 0):
        raise ValueError(f"Expected `edges` as at least two finite increasing break points, got {e.tolist()}")
    rtol = positive(rtol, "rtol")
    widths = np.diff(e)
    k = np.maximum(1, np.ceil(int(panels) * widths / widths.sum()).astype(int))
    previous, agreed = None, 0
    while True:
        x, w = _panels(e, k)
        values = np.asarray(f(x))
        value = values @ w
        max_nodes = min(max_nodes, max(MAX_VALUE_BYTES // max(values.nbytes // x.size, 1), 4 * _ORDER))
        if previous is not None:
            if np.all(np.abs(value - previous) <= atol + rtol * np.abs(value)):
                agreed += 1
                if agreed == 2:
                    return value
            else:
                agreed = 0
        if 2 * k.sum() * _ORDER > max_nodes:
            before = value if previous is None else previous
            worst = int(np.argmax(np.abs(value - before) - rtol * np.abs(value)))
            raise ValueError(
                f"Expected an integrand resolved by {max_nodes} nodes (rtol {rtol:g}, atol {atol:g}); its worst element still changes: "
                f"{np.ravel(value)[worst]:.10g} after {np.ravel(before)[worst]:.10g}"
            )
        previous = value
        k = 2 * k
