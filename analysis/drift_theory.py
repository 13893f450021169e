"""Asymptotic drift rate of an algorithm under regular precession (numeric side).

The symbolic drift coefficients ``d_w(ε, ϑ)`` of
:func:`derivations.drift.drift_coefficients` are lambdified once per
algorithm (cached) and evaluated on arrays.  The constant drift rate of the
attitude along the precession axis is

    u = Σ_w d_w(ε, ϑ) ν^w H^(w−1)          [rad/s],   w ≤ 7,

and the *asymptotic* drift u_a keeps only its leading nonvanishing term, of
weight ``ρ + 1``: ``u_a = |d_{ρ+1}| ν^{ρ+1} H^ρ`` (Budennyi, Kalinovsky,
Panov et al., eq. (3); Lebedev & Panov 1989, eq. (5.3)).  For the algorithms
whose fourth-order drift cancels under coning (ε = −1), ρ = 6 there.

References
----------
Lebedev & Panov (1989), section 5.
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Table 3.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import sympy as sp

from derivations import drift as sym
from derivations.algorithms import Algorithm

from .validation import as_array

__all__ = [
    "RAD_PER_S_TO_DEG_PER_H",
    "ZERO_TOLERANCE",
    "drift_terms",
    "asymptotic_drift",
    "asymptotic_order",
    "drift_series",
]

#: Factor from rad/s to deg/h.
RAD_PER_S_TO_DEG_PER_H = 180.0 / math.pi * 3600.0

#: A drift coefficient counts as zero at (ε, ϑ) when it is below this fraction of
#: the sum of the magnitudes of its terms (exact cancellation, e.g. ε = −1).
ZERO_TOLERANCE = 1e-11


@lru_cache(maxsize=None)
def _lambdified(algorithm: Algorithm):
    coeffs = sym.drift_coefficients(algorithm)
    e, s, c = sp.symbols("e s c")
    funcs, majorants = [], []
    for d in coeffs:
        expr = sp.expand(d).subs({sym.SIN: s, sym.COS: c, sym.EPS: e})
        poly = sp.Poly(expr, e, s, c)
        funcs.append(sp.lambdify((e, s, c), poly.as_expr(), "numpy"))
        maj = sum((abs(coef) * sp.Abs(e) ** i * sp.Abs(s) ** j * sp.Abs(c) ** k for (i, j, k), coef in poly.terms()), sp.Integer(0))
        majorants.append(sp.lambdify((e, s, c), maj, "numpy"))
    return tuple(funcs), tuple(majorants)


def _check_params(eps, nutation):
    eps = as_array(eps, "eps")
    nutation = as_array(nutation, "nutation")
    if np.any((nutation <= 0) | (nutation >= np.pi)):
        bad = nutation[(nutation <= 0) | (nutation >= np.pi)].ravel()[0]
        raise ValueError(f"Expected `nutation` in (0, π), got {bad:g}")
    return eps, nutation


def _check_positive(x, name):
    arr = as_array(x, name)
    if np.any(arr <= 0):
        raise ValueError(f"Expected `{name}` > 0, got {arr[arr <= 0].ravel()[0]:g}")
    return arr


def drift_terms(algorithm: Algorithm, eps, nutation):
    """Drift coefficients ``d_w(ε, ϑ)``, w = 0 … 7 (ν = 1, H = 1).

    Parameters
    ----------
    algorithm : Algorithm
    eps : array_like
        ε = μ/ν [-].
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).

    Returns
    -------
    values, majorants : ndarray, shape (..., 8)
        Signed coefficients and the sums of the magnitudes of their terms.
    """
    eps, nutation = _check_params(eps, nutation)
    eps, nutation = np.broadcast_arrays(eps, nutation)
    s, c = np.sin(nutation), np.cos(nutation)
    funcs, majs = _lambdified(algorithm)
    vals = np.stack([np.broadcast_to(np.asarray(f(eps, s, c), dtype=float), eps.shape) for f in funcs], axis=-1)
    mags = np.stack([np.broadcast_to(np.asarray(m(eps, s, c), dtype=float), eps.shape) for m in majs], axis=-1)
    return vals, mags


def asymptotic_order(algorithm: Algorithm, eps, nutation):
    """Order ρ of the drift at (ε, ϑ): the leading nonvanishing weight minus one.

    Returns
    -------
    ndarray of int
        ρ, or −1 where every coefficient through weight 7 vanishes.

    Examples
    --------
    >>> from derivations.algorithms import get
    >>> int(asymptotic_order(get("panov-4s-3"), -1.0, np.radians(1.0)))
    6
    >>> int(asymptotic_order(get("panov-4s-3"), 0.5, np.radians(1.0)))
    4
    """
    vals, mags = drift_terms(algorithm, eps, nutation)
    nonzero = np.abs(vals) > ZERO_TOLERANCE * np.maximum(mags, np.finfo(float).tiny)
    first = np.argmax(nonzero, axis=-1)
    return np.where(nonzero.any(axis=-1), first - 1, -1)


def asymptotic_drift(algorithm: Algorithm, *, eps, nu, nutation, step):
    """Asymptotic constant drift rate u_a of the attitude [rad/s].

    Parameters
    ----------
    algorithm : Algorithm
    eps : array_like
        ε = μ/ν [-]; ε = −1 is coning.
    nu : array_like
        Spin rate ν [rad/s] (> 0; ν = 2πf).
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).
    step : array_like
        Algorithm step H = N h [s], > 0.

    Returns
    -------
    ndarray
        ``|d_{ρ+1}(ε, ϑ)| ν^{ρ+1} H^ρ`` [rad/s]; NaN where the drift vanishes through weight 7.

    Raises
    ------
    ValueError
        For ϑ outside (0, π), ν or H not positive, or non-finite input.

    Examples
    --------
    >>> from derivations.algorithms import get
    >>> u = asymptotic_drift(get("panov-4s-1"), eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0), step=0.01)
    >>> round(float(u) * RAD_PER_S_TO_DEG_PER_H, 2)
    2.51
    """
    nu = _check_positive(nu, "nu")
    step = _check_positive(step, "step")
    vals, mags = drift_terms(algorithm, eps, nutation)
    rho = asymptotic_order(algorithm, eps, nutation)
    vals, rho, nu, step = np.broadcast_arrays(vals, rho[..., None], nu[..., None], step[..., None])
    w = rho[..., 0] + 1
    lead = np.take_along_axis(vals, np.clip(w, 0, vals.shape[-1] - 1)[..., None], axis=-1)[..., 0]
    out = np.abs(lead) * nu[..., 0] ** w * step[..., 0] ** (w - 1)
    return np.where(rho[..., 0] >= 0, out, np.nan)


def drift_series(algorithm: Algorithm, *, eps, nu, nutation, step):
    """Drift rate through weight 7, ``|Σ_w d_w ν^w H^(w−1)|`` [rad/s] (same parameters as :func:`asymptotic_drift`)."""
    nu = _check_positive(nu, "nu")
    step = _check_positive(step, "step")
    vals, _ = drift_terms(algorithm, eps, nutation)
    w = np.arange(vals.shape[-1])
    total = np.sum(vals * nu[..., None] ** w * step[..., None] ** np.maximum(w - 1, 0), axis=-1)
    return np.abs(total)
