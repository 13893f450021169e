"""Strapdown integration in a non-rotating frame: attitude (coning), velocity (sculling), position (scrolling).

One step of N samples turns the gyro increments ``p_j`` and velocity
increments ``b_j`` (with the samples of earlier steps a cross-step algorithm
reads) into three step quantities, all resolved in the body axes at the start
of the step:

* the rotation vector ``φ`` of the coning algorithm
  (:func:`strapdown.analysis.coning.evaluation.increment`);
* the velocity increment ``ΔV = J(φ) φ°``, where ``Φ = φ + s φ°`` is the same
  algorithm on the dual increments ``q_j = p_j + s b_j`` (Lebedev & Panov 1989,
  eq. (2.5)) and ``J(φ) = Σ [φ×]^k/(k+1)!`` the left Jacobian of SO(3):
  ``2 vect(M ∘ Λ̄)`` of the biquaternion ``exp(Φ/2)``, eq. (1.3), in closed form;
* the position increment ``ΔR = 2 Γ₂(φ) S + h Σ d_ij p_i × b_j`` of the N-sample
  position algorithm (:mod:`strapdown.derivations.navigation.position_algorithm`),
  with ``Γ₂(φ) = Σ [φ×]^k/(k+2)!``.

Then, with ``Λ_k`` the attitude (body → frame I) after step k, ::

    Λ_k = Λ_{k−1} ∘ exp(φ_k/2),
    W_k = W_{k−1} + Λ_{k−1} ΔV_k Λ̄_{k−1},
    R_k = R_{k−1} + W_{k−1} H + Λ_{k−1} ΔR_k Λ̄_{k−1},

W the apparent velocity and R the apparent position in I (no gravity: the
navigator over the Earth, :mod:`~strapdown.analysis.navigation.mechanization`,
adds it at the step rate).  The run is vectorised: the attitudes are a prefix
product (:func:`strapdown.analysis.coning.simulator.prefix_product`), W and R
cumulative sums.

References
----------
Savage (1998), "Strapdown inertial navigation integration algorithm design",
parts 1 and 2 (two-speed structure: coning, sculling, scrolling).
Lebedev & Panov (1989), eqs. (1.3), (1.12), (2.5).

Public API
----------
.. autosummary::

   StepIncrements
   step_increments
   jacobian_terms
   IntegrationResult
   integrate
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ...derivations.navigation.position_algorithm import position_algorithm
from ..coning.evaluation import increment
from ..coning.simulator import prefix_product
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.validation import as_array, as_quaternion, as_vector, positive

__all__ = ["StepIncrements", "step_increments", "jacobian_terms", "IntegrationResult", "integrate", "position_weights"]


def jacobian_terms(phi):
    """Coefficients of ``J(φ)`` and ``Γ₂(φ)`` on ``[φ×]`` and ``[φ×]²``, stable at small angles.

    ``J = I + a [φ×] + b [φ×]²``, ``Γ₂ = ½ I + b [φ×] + c [φ×]²`` with
    ``a = (1 − cos θ)/θ²``, ``b = (θ − sin θ)/θ³``, ``c = (θ²/2 + cos θ − 1)/θ⁴``, ``θ = |φ|``.

    Parameters
    ----------
    phi : array_like
        ``(..., 3)`` rotation vectors [rad].

    Returns
    -------
    tuple of ndarray
        ``(a, b, c)``, each of shape ``(...,)``.

    Examples
    --------
    >>> a, b, c = jacobian_terms(np.zeros(3))
    >>> float(a), float(b), float(c)
    (0.5, 0.16666666666666666, 0.041666666666666664)
    """
    phi = np.asarray(phi, dtype=float)
    t2 = np.einsum("...i,...i->...", phi, phi)
    # below θ² = 0.1 the closed forms cancel (c loses ε·24/θ⁴): five terms of each series, Σ (−θ²)^k/(2k + m)!
    small = t2 < SERIES_BELOW
    ts = np.where(small, 1.0, t2)
    t = np.sqrt(ts)
    a = np.where(small, _series(t2, 2), (1.0 - np.cos(t)) / ts)
    b = np.where(small, _series(t2, 3), (t - np.sin(t)) / (ts * t))
    c = np.where(small, _series(t2, 4), (0.5 * ts + np.cos(t) - 1.0) / (ts * ts))
    return a, b, c


#: θ² below which :func:`jacobian_terms` sums the series [rad²].
SERIES_BELOW = 0.1


def _series(t2, m: int):
    """``Σ_{k<5} (−θ²)^k/(2k + m)!``."""
    out = np.zeros_like(t2)
    for k in reversed(range(5)):
        out = 1.0 / math.factorial(2 * k + m) - t2 * out
    return out


@functools.cache
def position_weights(samples: int) -> tuple:
    """``(s, d)`` of the N-sample position algorithm as float arrays ``(N,)`` and ``(N, N)``.

    Parameters
    ----------
    samples : int
        N.

    Returns
    -------
    tuple of ndarray
    """
    alg = position_algorithm(samples)
    s = np.array([float(w) for w in alg.weights])
    d = np.array([[float(x) for x in row] for row in alg.scrolling])
    s.setflags(write=False)
    d.setflags(write=False)
    return s, d


@dataclass(frozen=True)
class StepIncrements:
    """The step quantities of a run, body axes at the start of each step.

    Attributes
    ----------
    rotation : ndarray
        ``(..., steps, 3)`` φ [rad].
    velocity : ndarray
        ``(..., steps, 3)`` ΔV [m/s].
    position : ndarray
        ``(..., steps, 3)`` ΔR [m].
    """

    rotation: np.ndarray
    velocity: np.ndarray
    position: np.ndarray


def step_increments(algorithm: Algorithm, p, b, sample_interval: float) -> StepIncrements:
    """Rotation vector, velocity and position increments of each step (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm (its dual extension is the velocity algorithm; its
        N sets the position algorithm).
    p, b : array_like
        ``(..., steps, W, 3)`` windows of gyro [rad] and velocity [m/s]
        increments, ``W = algorithm.window`` (the last N rows are the step).
    sample_interval : float
        h [s].

    Returns
    -------
    StepIncrements

    Raises
    ------
    ValueError
        For windows of another shape or a non-positive ``sample_interval``.

    Examples
    --------
    Constant rates: the position increment is exact to round-off.

    >>> import math
    >>> from strapdown.derivations.coning.registry import get
    >>> w, f, h = np.array([0.3, -0.2, 0.5]), np.array([1.0, 2.0, -9.8]), 0.01
    >>> p, b = np.broadcast_to(w * h, (1, 2, 3)), np.broadcast_to(f * h, (1, 2, 3))
    >>> inc = step_increments(get("two-sample"), p, b, h)
    >>> H, phi = 2 * h, w * 2 * h
    >>> exact = H**2 * sum(np.linalg.matrix_power(np.cross(np.eye(3), phi), k) @ f / math.factorial(k + 2) for k in range(12))
    >>> bool(np.allclose(inc.position[0], exact, rtol=1e-14, atol=0))
    True
    """
    h = positive(sample_interval, "sample_interval")
    p = as_array(p, "p")
    b = as_array(b, "b")
    n, w = algorithm.samples, algorithm.window
    if p.shape != b.shape or p.ndim < 3 or p.shape[-2:] != (w, 3):
        raise ValueError(f"Expected `p` and `b` of one shape (..., steps, {w}, 3), got {p.shape} and {b.shape}")
    Phi = increment(algorithm, Dual(p, b))
    phi, phid = np.asarray(Phi.re), np.asarray(Phi.du)
    a, bb, c = jacobian_terms(phi)
    x1 = np.cross(phi, phid)
    dV = phid + a[..., None] * x1 + bb[..., None] * np.cross(phi, x1)
    s, d = position_weights(n)
    ps, bs = p[..., w - n :, :], b[..., w - n :, :]
    S = h * np.einsum("j,...jk->...k", s, bs)
    # Σ_ij d_ij p_i × b_j = Σ_i p_i × (Σ_j d_ij b_j)
    D = h * np.cross(ps, np.einsum("ij,...jk->...ik", d, bs)).sum(axis=-2)
    y1 = np.cross(phi, S)
    dR = S + 2.0 * bb[..., None] * y1 + 2.0 * c[..., None] * np.cross(phi, y1) + D
    return StepIncrements(phi, dV, dR)


@dataclass(frozen=True)
class IntegrationResult:
    """Attitude, apparent velocity and apparent position after every step.

    Attributes
    ----------
    time : ndarray
        ``(steps + 1,)`` [s].
    attitude : ndarray
        ``(..., steps + 1, 4)`` Λ (body → I).
    velocity : ndarray
        ``(..., steps + 1, 3)`` W in I [m/s].
    position : ndarray
        ``(..., steps + 1, 3)`` R in I [m].
    """

    time: np.ndarray
    attitude: np.ndarray
    velocity: np.ndarray
    position: np.ndarray


def integrate(algorithm: Algorithm, p, b, sample_interval: float, *, attitude0=(1.0, 0.0, 0.0, 0.0), velocity0=(0.0, 0.0, 0.0), position0=(0.0, 0.0, 0.0)) -> IntegrationResult:
    """Run the attitude, velocity and position algorithms over step windows of increments (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm (and its dual extension, and the position algorithm of its N).
    p, b : array_like
        ``(..., steps, W, 3)`` windows of gyro [rad] and velocity [m/s] increments.
    sample_interval : float
        h [s].
    attitude0 : array_like, keyword-only
        Λ(0), unit quaternion (body → I).
    velocity0, position0 : array_like, keyword-only
        W(0) [m/s] and R(0) [m] in I.

    Returns
    -------
    IntegrationResult

    Raises
    ------
    ValueError
        For bad shapes or a non-unit ``attitude0``.

    References
    ----------
    Savage (1998), parts 1–2; Lebedev & Panov (1989), eqs. (1.3), (2.5).
    """
    inc = step_increments(algorithm, p, b, sample_interval)
    lam0 = as_quaternion(attitude0, "attitude0", unit=True)
    w0, r0 = as_vector(velocity0, "velocity0"), as_vector(position0, "position0")
    steps = inc.rotation.shape[-2]
    H = algorithm.samples * float(sample_interval)
    lead = inc.rotation.shape[:-2]
    q = quat.rotvec_to_quat(inc.rotation, validate=False)
    lam = quat.multiply(np.broadcast_to(lam0, lead + (1, 4)), prefix_product(q))
    lam = np.concatenate([np.broadcast_to(lam0, lead + (1, 4)), lam], axis=-2)
    before = lam[..., :-1, :]
    dv = quat.rotate(before, inc.velocity)
    dr = quat.rotate(before, inc.position)
    W = np.concatenate([np.broadcast_to(w0, lead + (1, 3)), w0 + np.cumsum(dv, axis=-2)], axis=-2)
    R = np.concatenate([np.broadcast_to(r0, lead + (1, 3)), r0 + np.cumsum(W[..., :-1, :] * H + dr, axis=-2)], axis=-2)
    return IntegrationResult(np.arange(steps + 1) * H, lam, W, R)
