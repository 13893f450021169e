"""Asymptotic drift rate of an algorithm under regular precession (numeric side).

The symbolic drift coefficients ``d_w(ε, ϑ)`` of
:func:`strapdown.derivations.coning.drift.drift_coefficients` are lambdified once per
algorithm (cached) and evaluated on arrays.  The constant drift rate of the
attitude along the precession axis is

    u = Σ_w d_w(ε, ϑ) ν^w H^(w−1)          [rad/s],   w ≤ 7,

and the *asymptotic* drift u_a keeps only its leading nonvanishing term, of
weight ``ρ + 1``: ``u_a = |d_{ρ+1}| ν^{ρ+1} H^ρ`` (Budennyi, Kalinovsky,
Panov et al., eq. (3); Lebedev & Panov 1989, eq. (5.3)).  For the algorithms
whose fourth-order drift cancels under coning (ε = −1), ρ = 6 there.

The accumulated attitude and apparent-velocity errors at a time t
(:func:`asymptotic_attitude_error`, :func:`asymptotic_velocity_error`) follow
the route of Lebedev & Panov (1989), eqs. (5.1)–(5.6), closed in the body
axes: the one-step error of the series (:func:`strapdown.derivations.coning.drift.mapped_error`)
drives (5.1), the integral (5.2) is taken in closed form, and the dual
(velocity) error is the dual extension of the attitude error in ν and ϑ
(transfer principle, (5.4)).  It uses neither the simulator nor
biquaternions, so it is an independent check of the parallel computation.

References
----------
Lebedev & Panov (1989), sections 3 and 5.
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Table 3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np
import sympy as sp

from ...derivations.coning import drift as sym
from ...derivations.coning.algorithms import Algorithm
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.validation import as_array, as_float, in_open_interval, positive

__all__ = [
    "RAD_PER_S_TO_DEG_PER_H",
    "ZERO_TOLERANCE",
    "drift_terms",
    "asymptotic_drift",
    "asymptotic_order",
    "drift_series",
    "AccumulatedError",
    "asymptotic_attitude_error",
    "asymptotic_velocity_error",
]

#: Factor from rad/s to deg/h.
RAD_PER_S_TO_DEG_PER_H = 180.0 / math.pi * 3600.0

#: A drift coefficient counts as zero at (ε, ϑ) when it is below this fraction of
#: the sum of the magnitudes of its terms (exact cancellation, e.g. ε = −1).
ZERO_TOLERANCE = 1e-11


@cache
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
    >>> from strapdown.derivations.coning.registry import get
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
    >>> from strapdown.derivations.coning.registry import get
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


# ---------------------------------------------------------------------------
# Accumulated attitude and apparent-velocity error at time t, (5.1)–(5.6)
# ---------------------------------------------------------------------------
@cache
def _step_error_functions(algorithm: Algorithm) -> tuple:
    """((w, (f_x, f_y, f_z)), …): weight-w parts of the one-step error on (4.1), functions of (ε, ϑ)."""
    return tuple((w, tuple(sp.lambdify((sym.EPS, sym.THETA), c, "numpy") for c in comps)) for w, comps in sym.step_error_values(algorithm))


def _rotate(axis, v, angle):
    """Rotation of ``v`` by ``angle`` about the unit ``axis`` (Rodrigues); real or dual."""
    c, s = np.cos(angle), np.sin(angle)
    return v * c + quat.cross(axis, v) * s + axis * (quat.dot(axis, v)[..., None] * (1.0 - c))


def _body_error(algorithm, t, eps, nu, nutation, step):
    """Accumulated error δφ(t) in the body axes; ``nu`` and ``nutation`` may be :class:`Dual`."""
    zero = 0.0 * nutation
    step_error = 0.0
    for w, funcs in _step_error_functions(algorithm):
        step_error = step_error + np.stack([f(eps, nutation) + zero for f in funcs], axis=-1) * (nu * step) ** w
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


def asymptotic_attitude_error(algorithm: Algorithm, t, *, eps, nu, nutation, step):
    """Accumulated attitude error δφ(t) of ``algorithm`` under regular precession, body axes [rad].

    The one-step error ``X(t_m)`` of the algorithm (algorithm minus exact,
    resolved in the body axes at the middle of the step, through weight 7 of
    the series) turns with the motion: ``X(t) = R_z(−νt) X(0)``.  Driving the
    error equation (5.1), ``α̇ + ω × α = X/H``, it accumulates in frame I
    (Λ(0) = 1) as the closed form of (5.2),

    ``α(t) = [(X·n) n t + (sin μt X_⊥ + (1 − cos μt) n × X_⊥)/μ] / H``,

    with the precession axis ``n = (0, sin ϑ, cos ϑ)`` and ``μ = εν``; the
    secular part along ``n`` is the constant drift of (5.3).  The result is
    ``α`` resolved in the body axes at t, ``δφ = Λ̄(t) ∘ α ∘ Λ(t)``, which does
    not depend on Λ(0) (computed = exact ∘ exp δφ).

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
    return _body_error(algorithm, t, eps, nu, nutation, step)


@dataclass(frozen=True)
class AccumulatedError:
    """Accumulated error of a biquaternion (attitude + apparent velocity) run, in the body axes.

    Attributes
    ----------
    attitude : ndarray, shape (..., 3)
        δφ(t) [rad]: computed = exact ∘ exp δφ.
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
        """``ΔW_E = δφ° + W_E × δφ`` [m/s] (3.5), given the exact W_E(t) [m/s], shape (..., 3)."""
        w_body = as_array(w_body, "w_body", last=3)
        return self.velocity + quat.cross(w_body, self.attitude)


def asymptotic_velocity_error(algorithm: Algorithm, t, *, eps, nu, nutation, nu_dual, nutation_dual, step) -> AccumulatedError:
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
    algorithm, t, eps, nu, nutation, step
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
    err = _body_error(algorithm, t, eps, Dual(nu, nu_dual), Dual(nutation, nutation_dual), step)
    return AccumulatedError(attitude=err.re, velocity=err.du)
