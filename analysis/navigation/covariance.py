"""Mean and covariance of a linear model over a mission, by exact discretisation.

For each interval Δ between the times asked for, the pair
``(F, Q_d) = (e^{AΔ}, ∫₀^Δ e^{As} Q e^{Aᵀs} ds)`` (Van Loan's method,
:func:`strapdown.analysis.core.kalman.discretise`), cached by interval, then
``m ← F m``, ``P ← F P Fᵀ + Q_d``: exact at those times for the model.

Public API
----------
.. autosummary::

   discretise
   propagate
"""

from __future__ import annotations

import math

import numpy as np

from ..core import kalman

__all__ = ["discretise", "propagate"]


def discretise(A, Q, dt: float, *, radius: float | None = None) -> tuple:
    """``(F, Q_d)`` of ``x' = A x + w`` over ``dt``, exactly, in sub-intervals short enough for Van Loan's method.

    Van Loan's matrix exponential holds ``e^{±A s}`` side by side, so a fast
    stable mode (a short Gauss–Markov correlation time τ) over a long interval
    loses every digit to ``e^{dt/τ}``; the interval is cut into m equal parts
    with ``ρ(A) dt/m ≤ 2`` (ρ the spectral radius) and the parts composed,
    ``F ← F_δ F``, ``Q ← F_δ Q F_δᵀ + Q_δ``.

    Parameters
    ----------
    A, Q : array_like
        ``(n, n)`` dynamics [1/s] and noise spectral density.
    dt : float
        Interval [s], ≥ 0.
    radius : float, optional, keyword-only
        ρ(A), when known [1/s].

    Returns
    -------
    tuple of ndarray

    References
    ----------
    Van Loan (1978) (:func:`strapdown.analysis.core.kalman.discretise`).
    """
    A = np.asarray(A, float)
    rho = float(np.max(np.abs(np.linalg.eigvals(A)))) if radius is None and A.size else (radius or 0.0)
    m = max(1, int(math.ceil(rho * dt / 2.0)))
    F1, Q1 = kalman.discretise(A, Q, dt / m)
    F, Qd = F1, Q1
    for _ in range(m - 1):
        F = F1 @ F
        Qd = F1 @ Qd @ F1.T + Q1
    return F, 0.5 * (Qd + Qd.T)


def propagate(A, Q, mean0, cov0, times, *, cache=None) -> tuple:
    """Mean and covariance of ``x' = A x + w`` (spectral density Q) at ``times`` from t = 0, exactly.

    Parameters
    ----------
    A, Q : array_like
        ``(n, n)`` [1/s] and the noise density.
    mean0, cov0 : array_like
        At t = 0.
    times : array_like
        ``(T,)`` increasing times ≥ 0 [s].
    cache : dict, optional
        Reused discretisations by interval (for several runs of one model).

    Returns
    -------
    tuple of ndarray
        ``(T, n)``, ``(T, n, n)``.

    References
    ----------
    Van Loan (1978) (:func:`discretise`).
    """
    A = np.asarray(A, float)
    t = np.asarray(times, float)
    cache = {} if cache is None else cache
    rho = float(np.max(np.abs(np.linalg.eigvals(A)))) if A.size else 0.0
    m, P = np.asarray(mean0, float).copy(), np.asarray(cov0, float).copy()
    means, covs = np.empty((t.size, A.shape[0])), np.empty((t.size,) + A.shape)
    last = 0.0
    for i, ti in enumerate(t):
        dt = ti - last
        if dt > 0:
            key = round(dt, 9)
            if key not in cache:
                cache[key] = discretise(A, Q, dt, radius=rho)
            F, Qd = cache[key]
            m = F @ m
            P = F @ P @ F.T + Qd
        means[i], covs[i] = m, P
        last = ti
    return means, 0.5 * (covs + np.swapaxes(covs, 1, 2))
