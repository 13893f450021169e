"""Drift rate and accumulated error of an algorithm from the symbolic one-step series (numeric side).

Sign convention: errors are exact minus algorithm (package docstring, "Errors"),
the same as the parallel computation of :mod:`strapdown.analysis.coning.simulator`:
a signed drift here and the simulator's drift are the rate of one error
rotation ``Λ_true ∘ Λ̄_computed``.

The symbolic drift coefficients ``d_w(ε, ϑ)`` of
:func:`strapdown.derivations.coning.drift.drift_coefficients` are compiled once
per algorithm and weight (:func:`strapdown.analysis.core.cache.compiled`, keyed by
the algorithm's exact terms) and evaluated on arrays.  The constant drift rate of
the attitude error along the precession axis is

    u = Σ_w d_w(ε, ϑ) ν^w H^(w−1)          [rad/s],   w ≤ max_weight (default 7),

and the *asymptotic* drift u_a keeps only its leading nonvanishing term, of
weight ``ρ + 1``: ``u_a = |d_{ρ+1}| ν^{ρ+1} H^ρ`` (Budennyi, Kalinovsky,
Panov et al., eq. (3); Lebedev & Panov 1989, eq. (5.3)).  For the algorithms
whose H⁴ drift cancels under coning (ε = −1) the drift order there is 6.

The ``d_w`` project the error of one step on the precession axis n.  The
steps compose: the error rotation after K steps is ``R^K ∘ T^K`` with
``R = exp(μH n)`` and ``T = R⁻¹ ∘ exp(s)``, s the one-step error
(:mod:`strapdown.analysis.coning.exact_drift`), so the transverse part ``s_⊥``
of the step error adds ``−|s_⊥|² / (4 tan(μH/2))`` per step to the drift, at
second order in s (:func:`composition_drift`).  It enters at weight 2ρ + 1 and
above, and where the axial drift cancels to a high order (the coning-optimised
algorithms) it is not negligible: −6.6·10⁻⁴ of the drift of ignagni-1996-5 at
α = 1°, ωh = 0.13, and 1.5·10⁻³ of that of two-sample at ε = 0.5, ϑ = 5°,
νh = 0.25.  :func:`drift_series` and :func:`drift_series_terms` include it.
:func:`converged_drift_series` raises the weight until the estimated
truncation error of the series meets a tolerance.

Under classical coning (ε = −1, half-cone angle α, rate ω) the drift is also
known in closed form in ``ωh`` for any algorithm
(:func:`strapdown.derivations.coning.drift.coning_drift`):
:func:`coning_drift_function` compiles ``D(x)`` and :func:`coning_drift_rate`
gives ``u = α² ω D(ωh)``.

The accumulated attitude and apparent-velocity errors at a time t
(:func:`asymptotic_attitude_error`, :func:`asymptotic_velocity_error`) follow
the route of Lebedev & Panov (1989), eqs. (5.1)–(5.6), closed in the body
axes: the one-step error of the series (:func:`strapdown.derivations.coning.drift.one_step_error`)
drives (5.1), the integral (5.2) is taken in closed form, and the dual
(velocity) error is the dual extension of the attitude error in ν and ϑ
(transfer principle, (5.4)).  It uses neither the simulator nor
biquaternions, so it is an independent check of the parallel computation.

Cross-step algorithms (sample indices ≤ 0) are handled throughout: the series
expand every sample about the middle of the current step.

References
----------
Lebedev & Panov (1989), sections 3 and 5.
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Table 3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import sympy as sp

from ...derivations.coning import drift as sym
from ...derivations.coning.algorithms import Algorithm
from ...derivations.coning.series import DEFAULT_MAX_WEIGHT, check_max_weight
from ..core import budget
from ..core import quaternion as quat
from ..core.cache import compiled, derived
from ..core.dual import Dual
from ..core.units import RAD_PER_S_TO_DEG_PER_H
from ..core.validation import as_array, as_float, as_quaternion, in_open_interval, positive

__all__ = [
    "RAD_PER_S_TO_DEG_PER_H",
    "ZERO_TOLERANCE",
    "algorithm_key",
    "drift_terms",
    "asymptotic_drift",
    "asymptotic_drift_vector",
    "asymptotic_order",
    "composition_drift",
    "drift_series",
    "DriftSeries",
    "drift_series_terms",
    "converged_drift_series",
    "SERIES_RTOL",
    "SERIES_MAX_WEIGHT",
    "coning_drift",
    "optimal_coning_algorithm",
    "coning_drift_function",
    "coning_drift_rate",
    "AccumulatedError",
    "asymptotic_attitude_error",
    "asymptotic_velocity_error",
]

#: A drift coefficient counts as zero at (ε, ϑ) when it is below this fraction of
#: the sum of the magnitudes of its terms (exact cancellation, e.g. ε = −1).
ZERO_TOLERANCE = 1e-11


def algorithm_key(algorithm: Algorithm) -> str:
    """The exact content of an algorithm as a string: samples and terms (not its name).

    Two algorithms with the same key have the same series and drift, so the key
    names their compiled functions in :func:`strapdown.analysis.core.cache.compiled`;
    algorithms read from TOML files get theirs too.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.

    Returns
    -------
    str

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> algorithm_key(get("two-sample"))
    'N=2;2/3|(1, 2)|()'
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    terms = sorted(f"{t.coefficient}|{t.cross}|{t.dots}" for t in algorithm.terms)
    return ";".join([f"N={algorithm.samples}"] + terms)


_E, _S, _C = sp.symbols("e s c")


def _drift_functions(algorithm: Algorithm, max_weight: int):
    """Compiled ``(d_0 … d_K, |d_0| … |d_K|)`` as functions of (ε, sin ϑ, cos ϑ)."""

    def build():
        values, majorants = [], []
        for d in sym.drift_coefficients(algorithm, max_weight):
            expr = sp.expand(d).subs({sym.SIN: _S, sym.COS: _C, sym.EPS: _E})
            poly = sp.Poly(expr, _E, _S, _C)
            values.append(poly.as_expr())
            majorants.append(sum((abs(coef) * sp.Abs(_E) ** i * sp.Abs(_S) ** j * sp.Abs(_C) ** k for (i, j, k), coef in poly.terms()), sp.Integer(0)))
        return (_E, _S, _C), tuple(values) + tuple(majorants)

    return compiled(f"coning:drift-coefficients:v2:K={max_weight}:{algorithm_key(algorithm)}", build)


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


def drift_terms(algorithm: Algorithm, eps, nutation, *, max_weight: int = DEFAULT_MAX_WEIGHT, limits: budget.Limits | None = None):
    """Drift coefficients ``d_w(ε, ϑ)``, w = 0 … max_weight (ν = 1, H = 1; exact minus algorithm).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    eps : array_like
        ε = μ/ν [-].
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).
    max_weight : int, keyword-only
        Highest weight of the series (default 7).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the symbolic series (default
        2 GB, 300 s: ``max_weight`` up to about 17); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    values, majorants : ndarray, shape (..., max_weight + 1)
        Signed coefficients and the sums of the magnitudes of their terms.

    Raises
    ------
    ValueError, TypeError
        For ϑ outside (0, π), non-finite input, a bad ``max_weight``, or a
        series beyond ``limits`` (naming ``max_weight``).
    """
    check_max_weight(max_weight)
    budget.check(budget.series_derivation(max_weight, what=f"`max_weight` = {max_weight}"), limits)
    eps, nutation = _check_params(eps, nutation)
    if eps.ndim == 0 and nutation.ndim == 0 and eps.dtype == nutation.dtype == np.float64:
        # one motion, as the design searches ask again and again: kept per algorithm, motion and weight
        vals, mags = _motion_drift_terms(algorithm, float(eps), float(nutation), max_weight)
        return vals.copy(), mags.copy()
    return _evaluate_drift_terms(algorithm, eps, nutation, max_weight)


def _evaluate_drift_terms(algorithm: Algorithm, eps, nutation, max_weight: int):
    eps, nutation = np.broadcast_arrays(eps, nutation)
    s, c = np.sin(nutation), np.cos(nutation)
    out = _drift_functions(algorithm, max_weight)(eps, s, c)
    columns = [np.broadcast_to(np.asarray(v, dtype=float), eps.shape) for v in out]
    n = max_weight + 1
    return np.stack(columns[:n], axis=-1), np.stack(columns[n:], axis=-1)


@lru_cache(maxsize=4096)
def _motion_drift_terms(algorithm: Algorithm, eps: float, nutation: float, max_weight: int):
    """:func:`_evaluate_drift_terms` at one (ε, ϑ), the same 0-d float arrays evaluated."""
    return _evaluate_drift_terms(algorithm, np.asarray(eps, dtype=float), np.asarray(nutation, dtype=float), max_weight)


def asymptotic_order(algorithm: Algorithm, eps, nutation, *, max_weight: int = DEFAULT_MAX_WEIGHT, limits: budget.Limits | None = None):
    """Drift order ρ at (ε, ϑ): the leading nonvanishing weight minus one (package docstring, "Orders").

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    eps : array_like
        ε = μ/ν [-].
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).
    max_weight : int, keyword-only
        Highest weight of the series (default 7).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the symbolic series (default
        2 GB, 300 s: ``max_weight`` up to about 17); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray of int
        ρ, or −1 where every coefficient through ``max_weight`` vanishes.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> int(asymptotic_order(get("panov-4s-3"), -1.0, np.radians(1.0)))
    6
    >>> int(asymptotic_order(get("panov-4s-3"), 0.5, np.radians(1.0)))
    4
    """
    return _order_of_terms(*drift_terms(algorithm, eps, nutation, max_weight=max_weight, limits=limits))


def _order_of_terms(vals, mags):
    """ρ from the coefficients and majorants of :func:`drift_terms` (−1 where all vanish)."""
    nonzero = np.abs(vals) > ZERO_TOLERANCE * np.maximum(mags, np.finfo(float).tiny)
    first = np.argmax(nonzero, axis=-1)
    return np.where(nonzero.any(axis=-1), first - 1, -1)


def asymptotic_drift(algorithm: Algorithm, *, eps, nu, nutation, step, max_weight: int = DEFAULT_MAX_WEIGHT, limits: budget.Limits | None = None):
    """Asymptotic constant drift rate u_a of the attitude [rad/s].

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    eps : array_like
        ε = μ/ν [-]; ε = −1 is coning.
    nu : array_like
        Spin rate ν [rad/s] (> 0; ν = 2πf).
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).
    step : array_like
        Algorithm step H = N h [s], > 0.
    max_weight : int, keyword-only
        Highest weight of the series searched for the leading term (default 7).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the symbolic series (default
        2 GB, 300 s: ``max_weight`` up to about 17); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray
        ``|d_{ρ+1}(ε, ϑ)| ν^{ρ+1} H^ρ`` [rad/s]; NaN where the drift vanishes through ``max_weight``.

    Raises
    ------
    ValueError
        For ϑ outside (0, π), ν or H not positive, or non-finite input.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> u = asymptotic_drift(get("panov-4s-1"), eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0), step=0.01)
    >>> round(float(u) * RAD_PER_S_TO_DEG_PER_H, 2)
    2.51
    """
    return np.abs(_signed_asymptotic_drift(algorithm, eps, nu, nutation, step, max_weight, limits))


def _signed_asymptotic_drift(algorithm, eps, nu, nutation, step, max_weight, limits=None):
    """``d_{ρ+1}(ε, ϑ) ν^{ρ+1} H^ρ``, signed (exact minus algorithm, along n); NaN where it vanishes."""
    nu = _check_positive(nu, "nu")
    step = _check_positive(step, "step")
    vals, mags = drift_terms(algorithm, eps, nutation, max_weight=max_weight, limits=limits)
    rho = _order_of_terms(vals, mags)  # asymptotic_order, from the same terms
    vals, rho, nu, step = np.broadcast_arrays(vals, rho[..., None], nu[..., None], step[..., None])
    w = rho[..., 0] + 1
    lead = np.take_along_axis(vals, np.clip(w, 0, vals.shape[-1] - 1)[..., None], axis=-1)[..., 0]
    out = lead * nu[..., 0] ** w * step[..., 0] ** (w - 1)
    return np.where(rho[..., 0] >= 0, out, np.nan)


def asymptotic_drift_vector(algorithm: Algorithm, *, eps, nu, nutation, step, attitude0=(1.0, 0.0, 0.0, 0.0), max_weight: int = DEFAULT_MAX_WEIGHT, limits: budget.Limits | None = None):
    """Asymptotic constant drift of the attitude as a signed vector in frame I [rad/s].

    The secular part of the accumulated error (5.2) lies along the precession
    axis n, so the drift vector is ``d_{ρ+1}(ε, ϑ) ν^{ρ+1} H^ρ n``, exact minus
    algorithm: the rate of the error rotation ``Λ_true ∘ Λ̄_computed``, the
    same quantity as the least-squares slope
    :attr:`strapdown.analysis.coning.simulator.SimulationResult.drift` of the
    parallel computation.  Its norm is :func:`asymptotic_drift`.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    eps : array_like
        ε = μ/ν [-]; ε = −1 is coning.
    nu : array_like
        Spin rate ν [rad/s] (> 0).
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).
    step : array_like
        Algorithm step H = N h [s], > 0.
    attitude0 : array_like, shape (4,), keyword-only
        Initial attitude Λ(0) of the run (E → I), which places n in frame I
        (:meth:`strapdown.analysis.coning.precession.RegularPrecession.precession_axis`).
    max_weight : int, keyword-only
        Highest weight of the series searched for the leading term (default 7).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the symbolic series (default
        2 GB, 300 s: ``max_weight`` up to about 17); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray, shape (..., 3)
        Drift vector, components in frame I [rad/s]; NaN where the drift
        vanishes through ``max_weight``.

    Raises
    ------
    ValueError
        As :func:`asymptotic_drift`, and for an ``attitude0`` that is not a unit quaternion.

    References
    ----------
    Lebedev & Panov (1989), eqs. (5.2)–(5.3); Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> u = asymptotic_drift_vector(get("panov-4s-1"), eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0), step=0.01)
    >>> round(float(np.linalg.norm(u)) * RAD_PER_S_TO_DEG_PER_H, 2)   # asymptotic_drift [deg/h]
    2.51
    >>> bool(u @ np.array([0.0, np.sin(np.radians(1.0)), np.cos(np.radians(1.0))]) < 0)   # along −n, the cone axis
    True
    """
    lam0 = as_quaternion(attitude0, "attitude0", unit=True)
    if lam0.shape != (4,):
        raise ValueError(f"Expected `attitude0` of shape (4,), got {lam0.shape}")
    signed = _signed_asymptotic_drift(algorithm, eps, nu, nutation, step, max_weight, limits)
    nutation = np.broadcast_to(as_array(nutation, "nutation"), signed.shape)
    axis = quat.rotate(lam0, np.stack([np.zeros(signed.shape), np.sin(nutation), np.cos(nutation)], axis=-1))
    return signed[..., None] * axis


def _step_error_parts(algorithm: Algorithm, eps, nutation, max_weight):
    """One-step error on (4.1) by weight, body axes at mid-step (ν = 1, H = 1): shape ``eps.shape + (max_weight + 1, 3)``.

    ``eps`` and ``nutation`` are arrays of one shape; multiply the weight-w part by ``(νH)^w``.
    """
    weights, function = _step_error_functions(algorithm, max_weight)
    values = function(eps, nutation)
    shape = np.shape(eps)
    return np.stack([np.stack([np.broadcast_to(np.asarray(values[3 * k + i], dtype=float), shape) for i in range(3)], axis=-1) for k in weights], axis=-2)


def _composition_angle(axial, transverse, turn):
    """``η − s_n`` per step: the drift angle T adds beyond the axial step error (module docstring).

    Solves ``sin(η/2) = sin(σ/2) s_n/σ + 2 cot(φ/2) sin((η+σ)/4) sin((η−σ)/4)``
    (the angle of ``exp(−φ n) ∘ exp(s)`` about n minus −φ; σ = |s|, φ = μH) by
    fixed-point iteration, written without cancellation.
    """
    axial, transverse, turn = np.broadcast_arrays(np.asarray(axial, float), np.asarray(transverse, float), np.asarray(turn, float))
    sigma = np.hypot(axial, transverse)
    with np.errstate(divide="ignore", invalid="ignore"):
        cot = 1.0 / np.tan(0.5 * turn)
        lead = np.where(sigma > 0, np.sin(0.5 * sigma) * axial / np.where(sigma > 0, sigma, 1.0), 0.0)
        eta = axial - 0.25 * transverse**2 * cot
        for _ in range(60):
            new = 2.0 * np.arcsin(lead + 2.0 * cot * np.sin(0.25 * (eta + sigma)) * np.sin(0.25 * (eta - sigma)))
            done = np.all((new == eta) | (np.abs(new - eta) <= 1e-15 * np.abs(new)))
            eta = new
            if done:
                break
        out = eta - axial
    # the expansion holds while the step error is small against the turn of a step (σ |cot(φ/2)| ≪ 1)
    out = np.where(transverse == 0.0, 0.0, np.where(sigma * np.abs(cot) < 0.25, out, np.nan))
    return out


def composition_drift(algorithm: Algorithm, *, eps, nu, nutation, step, max_weight: int = DEFAULT_MAX_WEIGHT):
    """Drift that the composition of the steps adds to the axial series, second order in the step error [rad/s].

    The error rotation after K steps is ``R^K ∘ T^K`` (``R = exp(μH n)``,
    ``T = R⁻¹ ∘ exp(s)``, s the one-step error, :mod:`strapdown.analysis.coning.exact_drift`).
    The angle of T about n exceeds −μH by the axial step error ``s_n`` plus
    ``≈ −|s_⊥|² / (4 tan(μH/2))``; this function returns that excess divided
    by H, with s summed through ``max_weight`` and the relation solved
    exactly.  Its leading term has weight ``2w − 1``, w the lowest weight of
    the step error across n (2ρ + 1 for a leading error across n): through a
    lower ``max_weight`` it is not in the series and 0 is returned.  Signed
    along n, exact minus algorithm; add it to ``Σ_w d_w ν^w H^(w−1)``.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    eps : array_like
        ε = μ/ν [-].
    nu : array_like
        Spin rate ν [rad/s], > 0.
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).
    step : array_like
        Algorithm step H = N h [s], > 0.
    max_weight : int, keyword-only
        Highest weight of the one-step error (default 7).

    Returns
    -------
    ndarray
        [rad/s], signed; NaN where the step error is not small against the
        turn μH of a step (``|s| |cot(μH/2)| ≥ 1/4``).

    Raises
    ------
    ValueError
        As :func:`asymptotic_drift`.

    References
    ----------
    Lebedev & Panov (1989), eqs. (5.1)–(5.3) (the error recursion whose product this is).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> kw = dict(eps=0.5, nu=2 * np.pi * 10, nutation=np.radians(5.0), step=0.008, max_weight=11)
    >>> round(float(composition_drift(get("two-sample"), **kw) / drift_series(get("two-sample"), **kw)), 5)
    -0.00155
    """
    nu = _check_positive(nu, "nu")
    step = _check_positive(step, "step")
    eps, nutation = _check_params(eps, nutation)
    max_weight = check_max_weight(max_weight)
    eps, nu, nutation, step = np.broadcast_arrays(eps, nu, nutation, step)
    parts = _step_error_parts(algorithm, eps, nutation, max_weight)
    axis = np.stack([np.zeros(nutation.shape), np.sin(nutation), np.cos(nutation)], axis=-1)[..., None, :]
    across = np.linalg.norm(parts - np.sum(parts * axis, axis=-1, keepdims=True) * axis, axis=-1)
    # the composition starts at weight 2w − 1, w the lowest weight of the step error across n: in the series through
    # max_weight only where that is reached
    size = np.abs(parts).sum(axis=(-2, -1))[..., None]
    present = across > 1e-13 * np.maximum(size, np.finfo(float).tiny)
    lowest = np.where(present.any(axis=-1), np.argmax(present, axis=-1), max_weight + 1)
    s = np.sum(parts * ((nu * step)[..., None] ** np.arange(max_weight + 1))[..., None], axis=-2)
    axial = np.sum(s * axis[..., 0, :], axis=-1)
    transverse = np.linalg.norm(s - axial[..., None] * axis[..., 0, :], axis=-1)
    angle = _composition_angle(axial, transverse, eps * nu * step)
    return np.where(2 * lowest - 1 <= max_weight, angle, 0.0) / step


def drift_series(algorithm: Algorithm, *, eps, nu, nutation, step, max_weight: int = DEFAULT_MAX_WEIGHT, limits: budget.Limits | None = None):
    """Drift rate through ``max_weight``, ``|Σ_w d_w ν^w H^(w−1) + composition|`` [rad/s].

    The axial series plus :func:`composition_drift`, the drift the composition
    of the steps adds at second order in the transverse step error.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    eps : array_like
        ε = μ/ν [-].
    nu : array_like
        Spin rate ν [rad/s], > 0.
    nutation : array_like
        Nutation angle ϑ [rad], in (0, π).
    step : array_like
        Algorithm step H = N h [s], > 0.
    max_weight : int, keyword-only
        Highest weight kept (default 7).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the symbolic series (default
        2 GB, 300 s: ``max_weight`` up to about 17); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray
        [rad/s]

    Raises
    ------
    ValueError
        As :func:`asymptotic_drift`.
    """
    nu = _check_positive(nu, "nu")
    step = _check_positive(step, "step")
    vals, _ = drift_terms(algorithm, eps, nutation, max_weight=max_weight, limits=limits)
    w = np.arange(vals.shape[-1])
    total = np.sum(vals * nu[..., None] ** w * step[..., None] ** np.maximum(w - 1, 0), axis=-1)
    return np.abs(total + composition_drift(algorithm, eps=eps, nu=nu, nutation=nutation, step=step, max_weight=max_weight))


@dataclass(frozen=True)
class DriftSeries:
    """The terms of the drift series at one motion and step (:func:`drift_series_terms`).

    Attributes
    ----------
    terms : ndarray, shape (max_weight + 1,)
        Signed terms ``d_w(ε, ϑ) ν^w H^(w−1)``, w = 0 … max_weight [rad/s]
        (exact minus algorithm, along the precession axis); terms that cancel
        exactly at (ε, ϑ) are 0.
    leading_weight : int
        Weight of the first nonvanishing term, ρ + 1 (−1 if every term vanishes).
    composition : float
        :func:`composition_drift`, the drift the composition of the steps adds
        at second order in the transverse step error [rad/s], signed; NaN where
        that expansion does not hold.
    """

    terms: np.ndarray
    leading_weight: int
    composition: float = 0.0

    @property
    def max_weight(self) -> int:
        """Highest weight kept."""
        return self.terms.shape[-1] - 1

    @property
    def signed_total(self) -> float:
        """``Σ_w terms + composition`` [rad/s], signed along the precession axis."""
        return float(self.terms.sum() + self.composition)

    @property
    def total(self) -> float:
        """Drift rate through ``max_weight``, ``|Σ_w terms + composition|`` [rad/s] (:func:`drift_series`)."""
        return abs(self.signed_total)

    @property
    def asymptotic(self) -> float:
        """The leading term alone, ``|d_{ρ+1}| ν^{ρ+1} H^ρ`` [rad/s] (:func:`asymptotic_drift`); NaN if none."""
        return float(abs(self.terms[self.leading_weight])) if self.leading_weight >= 0 else math.nan

    @property
    def largest_weight(self) -> int:
        """Weight of the largest term in magnitude (−1 if every term vanishes)."""
        return int(np.argmax(np.abs(self.terms))) if self.leading_weight >= 0 else -1

    @property
    def truncation_error(self) -> float:
        """Estimate of the terms beyond ``max_weight`` [rad/s]: the last nonzero term kept.

        Once the terms fall, the omitted ones are smaller than the last one
        kept (they fall by about ``(νH)²`` per two weights; the estimate is
        conservative by that factor).  Infinite while the last term is not
        smaller than the one before it, or fewer than two terms are nonzero:
        then the series says nothing of its remainder.
        """
        nonzero = np.flatnonzero(self.terms)
        if nonzero.size < 2:
            return math.inf
        last, previous = abs(float(self.terms[nonzero[-1]])), abs(float(self.terms[nonzero[-2]]))
        return last if last < previous else math.inf

    def leading_term_dominates(self, rtol: float = 0.1) -> bool | None:
        """Whether the leading term is the drift to ``rtol``: ``|asymptotic − total| ≤ rtol · total``.

        Parameters
        ----------
        rtol : float
            Relative tolerance [-], > 0.

        Returns
        -------
        bool or None
            None when the series vanishes through ``max_weight``.
        """
        rtol = positive(rtol, "rtol")
        if self.leading_weight < 0 or self.total == 0.0:
            return None
        return bool(abs(self.asymptotic - self.total) <= rtol * self.total)


def drift_series_terms(algorithm: Algorithm, *, eps: float, nu: float, nutation: float, step: float, max_weight: int = DEFAULT_MAX_WEIGHT, limits: budget.Limits | None = None) -> DriftSeries:
    """The drift series term by term at one motion and step: which term leads and which is largest.

    The asymptotic drift u_a of the papers is the leading term; where a later
    term is larger (a large νH, or a leading term of higher order in the
    nutation angle than the next one) the series, not u_a, is the drift.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    eps : float
        ε = μ/ν [-].
    nu : float
        Spin rate ν [rad/s], > 0.
    nutation : float
        Nutation angle ϑ [rad], in (0, π).
    step : float
        Algorithm step H = N h [s], > 0.
    max_weight : int, keyword-only
        Highest weight kept (default 7).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the symbolic series (default
        2 GB, 300 s: ``max_weight`` up to about 17); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    DriftSeries

    Raises
    ------
    ValueError
        As :func:`asymptotic_drift`, and for array arguments (one point only).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> s = drift_series_terms(get("ignagni-1996-2"), eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0), step=0.005, max_weight=9)
    >>> s.leading_weight, s.largest_weight, s.leading_term_dominates()
    (5, 7, False)
    """
    nu = _check_positive(nu, "nu")
    step = _check_positive(step, "step")
    for name, value in (("eps", eps), ("nu", nu), ("nutation", nutation), ("step", step)):
        if np.ndim(value) != 0:
            raise ValueError(f"Expected `{name}` as one number, got an array of shape {np.shape(value)}")
    vals, mags = drift_terms(algorithm, eps, nutation, max_weight=max_weight, limits=limits)
    w = np.arange(vals.shape[-1])
    nonzero = np.abs(vals) > ZERO_TOLERANCE * np.maximum(mags, np.finfo(float).tiny)
    terms = np.where(nonzero, vals, 0.0) * float(nu) ** w * float(step) ** np.maximum(w - 1, 0)
    rho = int(asymptotic_order(algorithm, eps, nutation, max_weight=max_weight, limits=limits))
    composition = float(composition_drift(algorithm, eps=eps, nu=nu, nutation=nutation, step=step, max_weight=max_weight))
    return DriftSeries(terms, rho + 1 if rho >= 0 else -1, composition)


#: Default relative truncation error :func:`converged_drift_series` aims at [-].
SERIES_RTOL = 1e-3
#: Default highest weight :func:`converged_drift_series` reaches (the symbolic cost grows fast beyond it).
SERIES_MAX_WEIGHT = 13


def converged_drift_series(
    algorithm: Algorithm, *, eps: float, nu: float, nutation: float, step: float, rtol: float = SERIES_RTOL, max_weight: int = SERIES_MAX_WEIGHT
) -> DriftSeries:
    """The drift series through the lowest odd weight whose estimated truncation error meets ``rtol``.

    The weight is raised 7, 9, 11, … (the even-weight terms vanish; below 7,
    ``max_weight`` itself) until
    :attr:`DriftSeries.truncation_error` is at most ``rtol`` times the drift,
    or ``max_weight`` is reached; the result says which
    (:attr:`DriftSeries.max_weight`, :attr:`DriftSeries.truncation_error`).
    Where the leading terms cancel each other (the coning-optimised
    algorithms at a finite cone angle) a fixed weight can be far off: for
    ignagni-1996-5 at α = 1°, ωh = 0.13 the series through h⁹ is 5.6 % above
    the drift, through h¹³ within 3·10⁻⁶ (:func:`strapdown.analysis.coning.exact_drift.exact_drift`),
    with an estimated truncation error of 1.2·10⁻⁴.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    eps : float
        ε = μ/ν [-].
    nu : float
        Spin rate ν [rad/s], > 0.
    nutation : float
        Nutation angle ϑ [rad], in (0, π).
    step : float
        Algorithm step H = N h [s], > 0.
    rtol : float, keyword-only
        Relative truncation error aimed at [-], > 0 (default :data:`SERIES_RTOL`).
    max_weight : int, keyword-only
        Highest weight tried, 1 … :data:`~strapdown.derivations.coning.series.WEIGHT_LIMIT`
        (default :data:`SERIES_MAX_WEIGHT`).

    Returns
    -------
    DriftSeries
        Through the weight chosen.

    Raises
    ------
    ValueError
        As :func:`drift_series_terms`, and for ``rtol`` not positive or a bad ``max_weight``.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> s = converged_drift_series(get("ignagni-1996-5"), eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0), step=3 / 480)
    >>> s.max_weight, bool(s.truncation_error < 1e-3 * s.total)
    (13, True)
    """
    rtol = positive(rtol, "rtol")
    max_weight = check_max_weight(max_weight)
    weights = sorted(set(range(7, max_weight + 1, 2)) | {max_weight})
    for K in weights:
        series = drift_series_terms(algorithm, eps=eps, nu=nu, nutation=nutation, step=step, max_weight=K)
        if series.truncation_error <= rtol * series.total:
            break
    return series


# ---------------------------------------------------------------------------
# Classical coning in closed form
# ---------------------------------------------------------------------------
def coning_drift(algorithm: Algorithm) -> sym.ConingDrift:
    """The closed-form coning drift of :func:`strapdown.derivations.coning.drift.coning_drift`, derived once.

    The derivation's result (exact fractions and SymPy expressions) is kept in
    the cache of derived results (:func:`strapdown.analysis.core.cache.derived`),
    per algorithm content (:func:`algorithm_key`) and source version.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).

    Returns
    -------
    ConingDrift
        The derivation's object itself.
    """
    return derived(f"coning:coning-drift:v1:{algorithm_key(algorithm)}", lambda: sym.coning_drift(algorithm))


def optimal_coning_algorithm(samples: int, *, history: int = 0) -> Algorithm:
    """The optimal coning algorithm of :func:`strapdown.derivations.coning.drift.optimal_coning_algorithm`, derived once.

    The derivation (an exact linear system in the lag sums) is kept in the
    cache of derived results (:func:`strapdown.analysis.core.cache.derived`),
    per ``(samples, history)`` and source version.

    Parameters
    ----------
    samples : int
        N ≥ 1.
    history : int, keyword-only
        Samples of earlier steps used (≥ 0); N + history ≥ 2.

    Returns
    -------
    Algorithm
        Equal to the derivation's algorithm.

    Raises
    ------
    TypeError, ValueError
        As :func:`strapdown.derivations.coning.drift.optimal_coning_algorithm`.
    """
    return derived(f"coning:optimal-coning-algorithm:v1:{samples!r}:{history!r}", lambda: sym.optimal_coning_algorithm(samples, history=history))


def coning_drift_function(algorithm: Algorithm):
    """``D(x)``, x = ωh, of the coning drift ``u = α² ω D(ωh)`` as a compiled numpy function.

    The closed form of :func:`strapdown.derivations.coning.drift.coning_drift`
    (exact in x at order α²), evaluated by its Taylor polynomial where the
    closed form would lose accuracy to cancellation (small x) and by the closed
    form above.  Derived once per algorithm content (:func:`algorithm_key`) and
    cached on disk (:func:`strapdown.analysis.core.cache.compiled`).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).

    Returns
    -------
    callable
        ``D(x)`` for ``x > 0`` [rad] (array in, array out); positive: the
        computed attitude lags the coning rotation.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> D = coning_drift_function(get("two-sample"))
    >>> round(float(D(1e-2) / 1e-8), 5)        # (1/60) x^4 at small x
    0.01667
    """
    key = f"coning:coning-drift:v1:{algorithm_key(algorithm)}"
    return compiled(key, lambda: ((sym.X,), sym.coning_drift(algorithm).stable_expression()))


def coning_drift_rate(algorithm: Algorithm, *, cone_angle, nu, sample_interval):
    """Constant coning drift rate ``u = α² ω D(ωh)`` [rad/s], to leading order in the half-cone angle.

    Classical coning is the regular precession (4.1) with ε = −1, ϑ = α; the
    drift is along the cone axis (the direction of the mean inertial angular
    velocity), exact minus algorithm: ``u > 0`` when the computed attitude lags
    the coning rotation.  The relative error of the α² approximation is O(α²).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    cone_angle : array_like
        Half-cone angle α [rad], in (0, π/2).
    nu : array_like
        Coning rate ω = ν [rad/s], > 0.
    sample_interval : array_like
        Sample interval h [s], > 0 (the step is H = N h).

    Returns
    -------
    ndarray
        u [rad/s], signed.

    Raises
    ------
    ValueError
        For α outside (0, π/2), ν or h not positive, or non-finite input.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> u = coning_drift_rate(get("panov-4s-1"), cone_angle=np.radians(1.0), nu=2 * np.pi * 10, sample_interval=0.0025)
    >>> round(float(u) * RAD_PER_S_TO_DEG_PER_H, 2)    # all orders in ωh (the leading term alone: 2.51)
    2.47
    """
    alpha = as_array(cone_angle, "cone_angle")
    if np.any((alpha <= 0) | (alpha >= np.pi / 2)):
        bad = alpha[(alpha <= 0) | (alpha >= np.pi / 2)].ravel()[0]
        raise ValueError(f"Expected `cone_angle` in (0, π/2), got {bad:g}")
    nu = _check_positive(nu, "nu")
    h = _check_positive(sample_interval, "sample_interval")
    x = nu * h
    return alpha**2 * nu * np.asarray(coning_drift_function(algorithm)(x), dtype=float)


# ---------------------------------------------------------------------------
# Accumulated attitude and apparent-velocity error at time t, (5.1)–(5.6)
# ---------------------------------------------------------------------------
def _step_error_functions(algorithm: Algorithm, max_weight: int = DEFAULT_MAX_WEIGHT):
    """Weights 0 … max_weight and a compiled function of (ε, ϑ) returning the one-step error parts on (4.1).

    Every weight has its three components (zero where the part vanishes), so
    nothing is derived when the compiled code is cached.
    """

    def build():
        parts = dict(sym.step_error_values(algorithm, max_weight))
        zero = (sp.Integer(0),) * 3
        return (sym.EPS, sym.THETA), tuple(c for w in range(max_weight + 1) for c in parts.get(w, zero))

    return tuple(range(max_weight + 1)), compiled(f"coning:step-error:v3:K={max_weight}:{algorithm_key(algorithm)}", build)


def _rotate(axis, v, angle):
    """Rotation of ``v`` by ``angle`` about the unit ``axis`` (Rodrigues); real or dual."""
    c, s = np.cos(angle), np.sin(angle)
    return v * c + quat.cross(axis, v) * s + axis * (quat.dot(axis, v)[..., None] * (1.0 - c))


def _body_error(algorithm, t, eps, nu, nutation, step, max_weight=DEFAULT_MAX_WEIGHT):
    """Accumulated error δφ(t) in the body axes; ``nu`` and ``nutation`` may be :class:`Dual`."""
    zero = 0.0 * nutation
    step_error = 0.0
    weights, function = _step_error_functions(algorithm, max_weight)
    parts = function(eps, nutation)
    for k, w in enumerate(weights):
        comps = [parts[3 * k + i] + zero for i in range(3)]
        step_error = step_error + np.stack(comps, axis=-1) * (nu * step) ** w
    axis = np.stack([zero, np.sin(nutation), np.cos(nutation)], axis=-1)  # precession axis n(0) in E
    along = quat.dot(step_error, axis)
    across = step_error - axis * along
    mu = eps * nu
    psi = (mu * t)[..., None]
    t = t[..., None]
    # (5.2): α(t) = (1/H) ∫ Rot(n, μτ) X dτ  (frame I with Λ(0) = 1)
    alpha = (axis * (along * t) + (across * np.sin(psi) + quat.cross(axis, across) * (1.0 - np.cos(psi))) / mu) / step
    e_z = np.stack([zero, zero, zero + 1.0], axis=-1)
    # back to the body axes: Λ(t) = exp(μt n/2) ∘ exp(νt e_z/2)
    return _rotate(e_z, _rotate(axis, alpha, -psi), -(nu * t))


def _check_error_params(t, eps, nu, nutation, step):
    t = as_array(t, "t")
    if np.any(t < 0):
        raise ValueError(f"Expected `t` >= 0, got {t[t < 0].ravel()[0]:g}")
    eps = as_float(eps, "eps")
    if eps == 0.0:
        raise ValueError("Expected `eps` nonzero (a precessing motion), got 0")
    nu = positive(nu, "nu")
    nutation = in_open_interval(nutation, "nutation", 0.0, math.pi, text="(0, π)")
    step = positive(step, "step")
    return t, eps, nu, nutation, step


def asymptotic_attitude_error(algorithm: Algorithm, t, *, eps, nu, nutation, step, max_weight: int = DEFAULT_MAX_WEIGHT):
    """Accumulated attitude error δφ(t) of ``algorithm`` under regular precession, body axes [rad].

    The one-step error ``X(t_m)`` of the algorithm (exact minus algorithm,
    resolved in the body axes at the middle of the step, through ``max_weight``
    of the series) turns with the motion: ``X(t) = R_z(−νt) X(0)``.  Driving the
    error equation (5.1), ``α̇ + ω × α = X/H``, it accumulates in frame I
    (Λ(0) = 1) as the closed form of (5.2),

    ``α(t) = [(X·n) n t + (sin μt X_⊥ + (1 − cos μt) n × X_⊥)/μ] / H``,

    with the precession axis ``n = (0, sin ϑ, cos ϑ)`` and ``μ = εν``; the
    secular part along ``n`` is the constant drift of (5.3).  The result is
    ``α`` resolved in the body axes at t, ``δφ = Λ̄(t) ∘ α ∘ Λ(t)``, which does
    not depend on Λ(0) (exact = computed ∘ exp δφ).

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm over ``step``.
    t : array_like
        Time(s) since the start [s], ≥ 0, at step boundaries.
    eps : float, keyword-only
        ε = μ/ν [-], nonzero; ε = −1 is coning.
    nu : float, keyword-only
        Spin rate ν [rad/s], > 0.
    nutation : float, keyword-only
        Nutation angle ϑ [rad], in (0, π).
    step : float, keyword-only
        Algorithm step H = N h [s], > 0.
    max_weight : int, keyword-only
        Highest weight of the one-step error series (default 7).

    Returns
    -------
    ndarray, shape (..., 3)
        δφ(t) [rad], the shape of ``t`` plus a last axis.

    Raises
    ------
    ValueError, TypeError
        For ε = 0, ν or H not positive, ϑ outside (0, π), t negative, or non-finite input.

    References
    ----------
    Lebedev & Panov (1989), eqs. (5.1)–(5.3).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> e = asymptotic_attitude_error(get("lebedev-panov-4"), 100.0, eps=-1.0, nu=2 * np.pi, nutation=np.radians(10.0), step=0.04)
    >>> round(float(np.linalg.norm(e)) / 100.0 * RAD_PER_S_TO_DEG_PER_H, 3)   # ≈ the drift rate [deg/h]
    0.159
    """
    t, eps, nu, nutation, step = _check_error_params(t, eps, nu, nutation, step)
    return _body_error(algorithm, t, eps, nu, nutation, step, check_max_weight(max_weight))


@dataclass(frozen=True)
class AccumulatedError:
    """Accumulated error of a biquaternion (attitude + apparent velocity) run, in the body axes.

    Attributes
    ----------
    attitude : ndarray, shape (..., 3)
        δφ(t) [rad]: exact = computed ∘ exp δφ (exact minus algorithm).
    velocity : ndarray, shape (..., 3)
        δφ°(t) [m/s]: the dual part of the same error (Lebedev & Panov 1989, (3.4)).
    """

    attitude: np.ndarray
    velocity: np.ndarray

    @property
    def dw_inertial(self) -> np.ndarray:
        """``|ΔW_I| = |Λ ∘ δφ° ∘ Λ̄| = |δφ°|`` [m/s] (3.5); independent of Λ(0) and W_I(0)."""
        return np.linalg.norm(self.velocity, axis=-1)

    def dw_body(self, w_body) -> np.ndarray:
        """``ΔW_E = δφ° + W_E × δφ`` [m/s] (3.5), exact minus computed, given the exact W_E(t).

        Parameters
        ----------
        w_body : array_like, shape (..., 3)
            Exact apparent velocity W_E(t) in the body axes [m/s].

        Returns
        -------
        ndarray, shape (..., 3)
            ΔW_E [m/s].
        """
        w_body = as_array(w_body, "w_body", last=3)
        return self.velocity + quat.cross(w_body, self.attitude)


def asymptotic_velocity_error(algorithm: Algorithm, t, *, eps, nu, nutation, nu_dual, nutation_dual, step, max_weight: int = DEFAULT_MAX_WEIGHT) -> AccumulatedError:
    """Accumulated attitude and apparent-velocity error of the dual extension of ``algorithm``.

    The velocity algorithm (2.5) is the dual extension of the attitude
    algorithm, and the dual regular precession (4.2)–(4.3) is the real one at
    ``ν + s ν°``, ``ϑ + s ϑ°``; the error recursion in the body axes involves
    neither Λ(0) nor W_I(0).  So the dual error ``δφ + s δφ°`` is
    :func:`asymptotic_attitude_error` evaluated on dual ν and ϑ (transfer
    principle; the body-axes form of (5.4)), and by (3.5)
    ``|ΔW_I| = |δφ°|``, ``ΔW_E = δφ° + W_E × δφ``.

    Parameters
    ----------
    algorithm, t, eps, nu, nutation, step, max_weight
        As in :func:`asymptotic_attitude_error`.
    nu_dual : float, keyword-only
        ν° [m/s²].
    nutation_dual : float, keyword-only
        ϑ° [m/s].

    Returns
    -------
    AccumulatedError
        δφ(t) [rad] and δφ°(t) [m/s] in the body axes.

    Raises
    ------
    ValueError, TypeError
        As :func:`asymptotic_attitude_error`, and for non-finite ν°, ϑ°.

    References
    ----------
    Lebedev & Panov (1989), eqs. (3.4)–(3.5), (4.2)–(4.3), (5.1)–(5.6).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> err = asymptotic_velocity_error(get("lebedev-panov-4"), 100.0, eps=-1.0, nu=2 * np.pi, nutation=np.radians(10.0),
    ...                                 nu_dual=0.5, nutation_dual=10.0, step=0.04)
    >>> round(float(err.dw_inertial), 5)   # m/s
    0.00866
    """
    t, eps, nu, nutation, step = _check_error_params(t, eps, nu, nutation, step)
    nu_dual = as_float(nu_dual, "nu_dual")
    nutation_dual = as_float(nutation_dual, "nutation_dual")
    err = _body_error(algorithm, t, eps, Dual(nu, nu_dual), Dual(nutation, nutation_dual), step, check_max_weight(max_weight))
    return AccumulatedError(attitude=err.re, velocity=err.du)
