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


_KERNEL = {}


def _kernel():
    if "run" in _KERNEL:
        return _KERNEL["run"]
    import numba

    @numba.njit(cache=True)
    def cross(a, b, out):
        out[0] = a[1] * b[2] - a[2] * b[1]
        out[1] = a[2] * b[0] - a[0] * b[2]
        out[2] = a[0] * b[1] - a[1] * b[0]

    @numba.njit(cache=True)
    def draw_step(g, N, H, white, phi, c, L, x, out):
        """Error of one step per axis (sum over its samples) of white noise and the first-order terms; updates x."""
        sq = math.sqrt(H)
        for k in range(3):
            e = white * sq * g.standard_normal() if white > 0.0 else 0.0
            for m in range(phi.shape[0]):
                z1 = g.standard_normal()
                z2 = g.standard_normal()
                e1 = L[m, 0, 0] * z1
                e2 = L[m, 1, 0] * z1 + L[m, 1, 1] * z2
                e += c[m] * x[m, k] + e2
                x[m, k] = phi[m] * x[m, k] + e1
            out[k] = e

    @numba.njit(cache=True)
    def run(g, mode, steps, block, N, hist, h, p0, b0, pi, pj, pc, sw, dw,
            gconst, aconst, prate, gwhite, awhite, gphi, gc, gL, gx, aphi, ac, aL, ax,
            gq, aq, gres, ares, lam, v, r, R, Om, g0, record, out_lam, out_v, out_r, sums):  # fmt: skip
        H = N * h
        W = N + hist
        P = np.zeros((W, 3))
        B = np.zeros((W, 3))
        # history rows start with the ideal increments (steady state before t = 0)
        for i in range(W):
            for k in range(3):
                P[i, k] = p0[k]
                B[i, k] = b0[k]
        eg = np.zeros(3)
        ea = np.zeros(3)
        tmp = np.zeros(3)
        tmp2 = np.zeros(3)
        phi = np.zeros(3)
        phid = np.zeros(3)
        S = np.zeros(3)
        D = np.zeros(3)
        rec = 0
        nrec = record.shape[0]
        while rec < nrec and record[rec] == 0:
            for k in range(4):
                out_lam[rec, k] = lam[k]
            for k in range(3):
                out_v[rec, k] = v[k]
                out_r[rec, k] = r[k]
            rec += 1
        egb = np.zeros(3)
        eab = np.zeros(3)
        for step in range(steps):
            if step % block == 0:  # the errors of a block of steps, shared evenly among its steps
                draw_step(g, N, H * block, gwhite, gphi, gc, gL, gx, egb)
                draw_step(g, N, H * block, awhite, aphi, ac, aL, ax, eab)
                for k in range(3):
                    eg[k] = egb[k] / block
                    ea[k] = eab[k] / block
            # shift the history
            for i in range(hist):
                for k in range(3):
                    P[i, k] = P[i + N, k]
                    B[i, k] = B[i + N, k]
            for j in range(N):
                for k in range(3):
                    pv = p0[k] + (gconst[k] * H + eg[k]) / N
                    bv = b0[k] + (aconst[k] * H + ea[k]) / N
                    if gq[k] > 0.0:
                        before = gq[k] * math.floor(gres[k] / gq[k])
                        gres[k] += pv
                        pv = gq[k] * math.floor(gres[k] / gq[k]) - before
                    if aq[k] > 0.0:
                        before = aq[k] * math.floor(ares[k] / aq[k])
                        ares[k] += bv
                        bv = aq[k] * math.floor(ares[k] / aq[k]) - before
                    P[hist + j, k] = pv
                    B[hist + j, k] = bv
            if mode == 0:  # alignment: sums of the increments only
                for j in range(N):
                    for k in range(3):
                        sums[k] += P[hist + j, k]
                        sums[3 + k] += B[hist + j, k]
                continue
            # coning, sculling (dual extension), scrolling
            for k in range(3):
                phi[k] = 0.0
                phid[k] = 0.0
                S[k] = 0.0
                D[k] = 0.0
            for j in range(N):
                for k in range(3):
                    phi[k] += P[hist + j, k]
                    phid[k] += B[hist + j, k]
                    S[k] += h * sw[j] * B[hist + j, k]
            for m in range(pi.shape[0]):
                cross(P[pi[m]], P[pj[m]], tmp)
                for k in range(3):
                    phi[k] += pc[m] * tmp[k]
                cross(P[pi[m]], B[pj[m]], tmp)
                cross(B[pi[m]], P[pj[m]], tmp2)
                for k in range(3):
                    phid[k] += pc[m] * (tmp[k] + tmp2[k])
            for i in range(N):
                for k in range(3):
                    tmp2[k] = 0.0
                for j in range(N):
                    for k in range(3):
                        tmp2[k] += dw[i, j] * B[hist + j, k]
                cross(P[hist + i], tmp2, tmp)
                for k in range(3):
                    D[k] += h * tmp[k]
            t2 = phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]
            if t2 < 0.1:  # the series, five terms (integration.jacobian_terms)
                ja = 1.0 / 2.0 - t2 * (1.0 / 24.0 - t2 * (1.0 / 720.0 - t2 * (1.0 / 40320.0 - t2 / 3628800.0)))
                jb = 1.0 / 6.0 - t2 * (1.0 / 120.0 - t2 * (1.0 / 5040.0 - t2 * (1.0 / 362880.0 - t2 / 39916800.0)))
                jc = 1.0 / 24.0 - t2 * (1.0 / 720.0 - t2 * (1.0 / 40320.0 - t2 * (1.0 / 3628800.0 - t2 / 479001600.0)))
            else:
                th = math.sqrt(t2)
                ja = (1.0 - math.cos(th)) / t2
                jb = (th - math.sin(th)) / (t2 * th)
                jc = (0.5 * t2 + math.cos(th) - 1.0) / (t2 * t2)
            dV = np.zeros(3)
            dR = np.zeros(3)
            cross(phi, phid, tmp)
            cross(phi, tmp, tmp2)
            for k in range(3):
                dV[k] = phid[k] + ja * tmp[k] + jb * tmp2[k]
            cross(phi, S, tmp)
            cross(phi, tmp, tmp2)
            for k in range(3):
                dR[k] = S[k] + 2.0 * jb * tmp[k] + 2.0 * jc * tmp2[k] + D[k] + prate[k] * H
            # to frame I with the attitude at the start of the step
            q0, q1, q2, q3 = lam[0], lam[1], lam[2], lam[3]
            c00 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
            c01 = 2.0 * (q1 * q2 - q0 * q3)
            c02 = 2.0 * (q1 * q3 + q0 * q2)
            c10 = 2.0 * (q1 * q2 + q0 * q3)
            c11 = q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3
            c12 = 2.0 * (q2 * q3 - q0 * q1)
            c20 = 2.0 * (q1 * q3 - q0 * q2)
            c21 = 2.0 * (q2 * q3 + q0 * q1)
            c22 = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
            dVi0 = c00 * dV[0] + c01 * dV[1] + c02 * dV[2]
            dVi1 = c10 * dV[0] + c11 * dV[1] + c12 * dV[2]
            dVi2 = c20 * dV[0] + c21 * dV[1] + c22 * dV[2]
            dRi0 = c00 * dR[0] + c01 * dR[1] + c02 * dR[2]
            dRi1 = c10 * dR[0] + c11 * dR[1] + c12 * dR[2]
            dRi2 = c20 * dR[0] + c21 * dR[1] + c22 * dR[2]
            # gravitation, trapezoid with a predicted end point
            rho = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
            k0 = -g0 * R * R / (rho * rho * rho)
            G00, G01, G02 = k0 * r[0] - Om * Om * r[0], k0 * r[1] - Om * Om * r[1], k0 * r[2]
            x0 = r[0] + v[0] * H + dRi0 + 0.5 * G00 * H * H
            x1 = r[1] + v[1] * H + dRi1 + 0.5 * G01 * H * H
            x2 = r[2] + v[2] * H + dRi2 + 0.5 * G02 * H * H
            rho = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
            k1 = -g0 * R * R / (rho * rho * rho)
            G10, G11, G12 = k1 * x0 - Om * Om * x0, k1 * x1 - Om * Om * x1, k1 * x2
            r[0] += v[0] * H + dRi0 + H * H * (G00 / 3.0 + G10 / 6.0)
            r[1] += v[1] * H + dRi1 + H * H * (G01 / 3.0 + G11 / 6.0)
            r[2] += v[2] * H + dRi2 + H * H * (G02 / 3.0 + G12 / 6.0)
            v[0] += dVi0 + 0.5 * H * (G00 + G10)
            v[1] += dVi1 + 0.5 * H * (G01 + G11)
            v[2] += dVi2 + 0.5 * H * (G02 + G12)
            # attitude: Λ ← Λ ∘ exp(φ/2)
            th = math.sqrt(t2)
            if th < 1e-8:
                s0, sv = 1.0 - t2 / 8.0, 0.5 - t2 / 48.0
            else:
                s0, sv = math.cos(0.5 * th), math.sin(0.5 * th) / th
            u0, u1, u2, u3 = s0, sv * phi[0], sv * phi[1], sv * phi[2]
            n0 = q0 * u0 - q1 * u1 - q2 * u2 - q3 * u3
            n1 = q0 * u1 + q1 * u0 + q2 * u3 - q3 * u2
            n2 = q0 * u2 - q1 * u3 + q2 * u0 + q3 * u1
            n3 = q0 * u3 + q1 * u2 - q2 * u1 + q3 * u0
            nn = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2 + n3 * n3)
            lam[0], lam[1], lam[2], lam[3] = n0 / nn, n1 / nn, n2 / nn, n3 / nn
            # vertical channel held: back on the sphere, no radial velocity over the Earth
            rho = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
            for k in range(3):
                r[k] *= R / rho
            w0, w1 = v[0] + Om * r[1], v[1] - Om * r[0]  # v − Ω × r
            w2 = v[2]
            radial = (w0 * r[0] + w1 * r[1] + w2 * r[2]) / R
            w0 -= radial * r[0] / R
            w1 -= radial * r[1] / R
            w2 -= radial * r[2] / R
            v[0], v[1], v[2] = w0 - Om * r[1], w1 + Om * r[0], w2
            while rec < nrec and record[rec] == step + 1:
                for k in range(4):
                    out_lam[rec, k] = lam[k]
                for k in range(3):
                    out_v[rec, k] = v[k]
                    out_r[rec, k] = r[k]
                rec += 1

    _KERNEL["run"] = run
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
