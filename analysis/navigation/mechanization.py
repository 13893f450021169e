"""The navigator over the rotating Earth, at rest, with sensor errors drawn inside a compiled loop.

The navigator's Earth (stated once here): a sphere of radius R (the
``EARTH_RADIUS`` of the error model) turning at the WGS-84 rate Ω about z;
gravity (gravitation plus the centrifugal term) radial, ``g₀ (R/ρ)²`` with
``g₀`` the normal gravity at the site's latitude, so that NED at the site is
the local vertical and the specific force at rest is ``(0, 0, −g₀)`` exactly,
as in the linear model.  The mechanization runs in the inertial frame I (the
Earth frame at t = 0): per step of N samples the attitude, velocity and
position increments of :mod:`~strapdown.analysis.navigation.integration` (the
coning algorithm, its dual extension, the N-sample position algorithm), turned
into I by the attitude at the start of the step, and gravitation ::

    G(r) = −g₀ R² r/|r|³ − Ω² (x, y, 0)

integrated by the trapezoid rule with a predicted end point.  The vertical
channel is held as the linear model holds it: after each step the position is
put back on the sphere and the radial velocity over the Earth removed.

At rest with constant body rate and specific force the algorithms are exact,
so an ideal run stays on the truth to round-off (and the gravity rule's
``O(H³ Ω² g)`` per step); the errors of a run are the sensor errors'.

Sensor errors are drawn per block of steps (every term of :class:`~strapdown.analysis.alignment.sensor_models.SensorSpec`:
white noise ``N √T_b``, each Gauss–Markov term and the rate random walk by the
exact joint discretisation of level and integral over the block T_b, as
:func:`~strapdown.analysis.alignment.sensor_models.simulate_sensor_errors`
draws them per sample) and shared evenly among the block's samples; the block
(:data:`strapdown.analysis.navigation.monte_carlo.BLOCK_SECONDS`) is far
shorter than the shortest correlation time and than the navigation errors'
time constants, and the errors at the ends of every block are exact; the output
quantisation acts on every sample (the quantised running sum).  Each trial has
its own stream (``SeedSequence.spawn``), so a result does not depend on how the
trials are grouped.

Public API
----------
.. autosummary::

   EarthFrames
   earth_frames
   NavigatorErrors
   run_navigator
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..alignment.earth import EARTH_RATE
from ..alignment.error_model import EARTH_RADIUS
from ..core import kalman
from .integration import position_weights

__all__ = ["EarthFrames", "earth_frames", "NavigatorErrors", "run_navigator", "noise_terms"]


@dataclass(frozen=True)
class EarthFrames:
    """The truth at rest: position and NED frame at t = 0, all in I = the Earth frame at t = 0.

    Attributes
    ----------
    latitude : float
        [rad].
    position : ndarray
        ``(3,)`` r(0) [m].
    ned : ndarray
        ``(3, 3)`` ``C_e^n`` (rows: north, east, down in the Earth frame).
    gravity : float
        g₀ [m/s²].
    """

    latitude: float
    position: np.ndarray
    ned: np.ndarray
    gravity: float


def earth_frames(latitude: float, gravity: float) -> EarthFrames:
    """The site at longitude 0 on the navigator's sphere.

    Parameters
    ----------
    latitude : float
        [rad].
    gravity : float
        g₀ [m/s²].

    Returns
    -------
    EarthFrames
    """
    c, s = math.cos(latitude), math.sin(latitude)
    ned = np.array([[-s, 0.0, c], [0.0, 1.0, 0.0], [-c, 0.0, -s]])
    return EarthFrames(latitude, EARTH_RADIUS * np.array([c, 0.0, s]), ned, float(gravity))


def noise_terms(spec, H: float) -> tuple:
    """Per-step discretisation of the Gauss–Markov terms and the rate random walk of a triad.

    Parameters
    ----------
    spec : SensorSpec
        The triad's noise.
    H : float
        Step [s].

    Returns
    -------
    tuple of ndarray
        ``(phi (K,), c (K,), L (K, 2, 2), stationary (K,))``: level factor, its
        integral factor, the Cholesky factor of the pair's noise, and the
        stationary variance of the level (0 for the random walk, which starts at 0).
    """
    terms = [(float(t), float(q)) for t, q in zip(*spec.gauss_markov())]
    if spec.rate_random_walk:
        terms.append((math.inf, spec.rate_random_walk**2))
    phi, c, L, var = [], [], [], []
    for tau, q in terms:
        if math.isinf(tau):
            A, Qc, v = np.array([[0.0, 0.0], [1.0, 0.0]]), np.diag([q, 0.0]), 0.0
        else:
            A, Qc, v = np.array([[-1.0 / tau, 0.0], [1.0, 0.0]]), np.diag([2.0 * q / tau, 0.0]), q
        F, Q = kalman.discretise(A, Qc, H)
        phi.append(F[0, 0])
        c.append(F[1, 0])
        L.append(np.linalg.cholesky(Q + 1e-300 * np.eye(2)))
        var.append(v)
    return np.array(phi), np.array(c), np.array(L).reshape(-1, 2, 2), np.array(var)


@dataclass(frozen=True)
class NavigatorErrors:
    """What one trial's sensors get wrong, in the form the compiled loop takes.

    Attributes
    ----------
    gyro_constant, accel_constant : ndarray
        ``(3,)`` fixed body errors (bias, turn-on draw, scale factor and misalignment at rest, algorithm residuals) [rad/s, m/s²].
    position_rate : ndarray
        ``(3,)`` body position-rate error [m/s].
    gyro_white, accel_white : float
        N [rad/√s, m/s/√s].
    gyro_terms, accel_terms : tuple
        :func:`noise_terms` of each triad.
    gyro_quantum, accel_quantum : float
        Output quanta [rad, m/s].
    """

    gyro_constant: np.ndarray
    accel_constant: np.ndarray
    position_rate: np.ndarray
    gyro_white: float
    accel_white: float
    gyro_terms: tuple
    accel_terms: tuple
    gyro_quantum: float
    accel_quantum: float


def _kernel():
    from ._navigator_kernel import run

    return run


def _pairs(algorithm: Algorithm):
    hist = algorithm.history
    items = list(algorithm.pairwise.items())
    pi = np.array([i - 1 + hist for (i, _), _ in items], dtype=np.int64)
    pj = np.array([j - 1 + hist for (_, j), _ in items], dtype=np.int64)
    pc = np.array([float(c) for _, c in items])
    return pi, pj, pc


def run_navigator(algorithm: Algorithm, frames: EarthFrames, attitude_bn, errors: NavigatorErrors, *, sample_interval: float, steps: int, record, rng,
                  alignment_steps: int = 0, attitude_from_sums=None, block: int = 1) -> tuple:  # fmt: skip
    """One trial: an optional alignment window, then navigation from t = 0; the computed state at ``record`` steps.

    Parameters
    ----------
    algorithm : Algorithm
        Coning algorithm (pairwise terms; cross-step allowed).
    frames : EarthFrames
        The site.
    attitude_bn : ndarray
        ``(3, 3)`` true ``C_b^n``.
    errors : NavigatorErrors
        The trial's sensor errors.
    sample_interval : float
        h [s].
    steps : int
        Navigation steps.
    record : array_like
        Step indices (0 … steps) at which the state is kept, increasing.
    rng : numpy.random.Generator
        The trial's stream.
    alignment_steps : int
        Steps of the alignment window before t = 0 (0: none).
    attitude_from_sums : callable, optional
        ``f(sum_dtheta (3,), sum_dv (3,)) -> C̃_b^n``: the alignment method on the window's sums.
    block : int
        Steps per draw of the sensor errors; ``errors`` must hold the noise
        terms of that block (:func:`noise_terms` of ``block`` steps).

    Returns
    -------
    tuple of ndarray
        ``(attitude (R, 4), velocity (R, 3), position (R, 3))`` in frame I.
    """
    if algorithm.max_degree > 2:
        raise ValueError(f"Expected an algorithm of pairwise terms only, got {algorithm.name!r}")
    run = _kernel()
    n, hist, h = algorithm.samples, algorithm.history, float(sample_interval)
    Om = EARTH_RATE
    C_bn = np.asarray(attitude_bn, float)
    w_b = C_bn.T @ frames.ned @ np.array([0.0, 0.0, Om])
    f_b = C_bn.T @ np.array([0.0, 0.0, -frames.gravity])
    p0, b0 = w_b * h, f_b * h
    pi, pj, pc = _pairs(algorithm)
    sw, dw = position_weights(n)
    gphi, gc, gL, gvar = errors.gyro_terms
    aphi, ac, aL, avar = errors.accel_terms
    gx = np.sqrt(gvar)[:, None] * rng.standard_normal((gvar.size, 3))
    ax = np.sqrt(avar)[:, None] * rng.standard_normal((avar.size, 3))
    gq = np.full(3, errors.gyro_quantum)
    aq = np.full(3, errors.accel_quantum)
    gres = gq * rng.random(3)
    ares = aq * rng.random(3)
    record = np.asarray(record, dtype=np.int64)
    out_lam, out_v, out_r = np.zeros((record.size, 4)), np.zeros((record.size, 3)), np.zeros((record.size, 3))
    args = (n, hist, h, p0, b0, pi, pj, pc, sw, dw, errors.gyro_constant, errors.accel_constant, errors.position_rate, errors.gyro_white, errors.accel_white,
            gphi, gc, gL, gx, aphi, ac, aL, ax, gq, aq, gres, ares)  # fmt: skip
    C_ni = frames.ned.T  # n → I at t = 0
    lam = _quaternion(C_ni @ C_bn)
    v = np.cross(np.array([0.0, 0.0, Om]), frames.position)
    r = frames.position.copy()
    if alignment_steps:
        sums = np.zeros(6)
        run(rng, 0, int(alignment_steps), block, *args, lam.copy(), v.copy(), r.copy(), EARTH_RADIUS, Om, frames.gravity, np.zeros(0, np.int64), out_lam, out_v, out_r, sums)
        lam = _quaternion(C_ni @ attitude_from_sums(sums[:3], sums[3:]))
    run(rng, 1, int(steps), block, *args, lam, v, r, EARTH_RADIUS, Om, frames.gravity, record, out_lam, out_v, out_r, np.zeros(6))
    return out_lam, out_v, out_r


def _quaternion(C) -> np.ndarray:
    """Unit quaternion of a rotation matrix (scalar first)."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(C).as_quat()
    return np.array([w, x, y, z])
