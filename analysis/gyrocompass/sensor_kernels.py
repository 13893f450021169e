"""Compiled loops of the whole-system simulation: ideal sensor increments and epoch preintegration.

Two hot paths of the self-alignment Monte Carlo are a few dozen flops per
sample, which numpy spreads over dozens of array passes:

* :func:`accumulate_ideal_increments` adds one Gauss node's share of the ideal
  gyro and accelerometer increments (the rates of :mod:`.imu`: attitude,
  body rate, Earth rate in body axes, gravity, lever-arm terms), fused in one
  loop over trials and samples;
* :func:`preintegrate_loop` condenses sample increments into epoch increments
  (the coning- and sculling-compensated sums of :mod:`.preintegration`).

Both are compiled with numba on first use (the machine code is cached on disk,
so the compile cost is paid once per installation).  The vectorised numpy
forms stay in :mod:`.imu` and :mod:`.preintegration` as the references the tests
compare these loops against (equal to round-off).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["accumulate_ideal_increments", "preintegrate_loop"]

_compiled: dict = {}


def _jit(fn):
    """``fn`` compiled with numba (imported on first use; cached on disk)."""
    name = fn.__name__
    if name not in _compiled:
        import numba

        _compiled[name] = numba.njit(cache=True, nogil=True)(fn)
    return _compiled[name]


def _ideal_loop(angles, rates, accels, stable, W, g, r, fixed_gyro, in_gyros, lever, weight, dtheta, dv):
    n, N = angles.shape[0], angles.shape[1]
    for i in range(n):
        for k in range(N):
            psi = angles[i, k, 0] + stable[0]
            beta = angles[i, k, 1] + stable[1]
            gam = angles[i, k, 2] + stable[2]
            cp, sp = math.cos(psi), math.sin(psi)
            cb, sb = math.cos(beta), math.sin(beta)
            cg, sg = math.cos(gam), math.sin(gam)
            # C_b^n = R_z(ψ) R_x(−β) R_y(γ) (tilt_attitude.attitude_matrix); columns are the body axes in NED
            r1x, r1y, r1z = cg, 0.0, sg
            r2x, r2y, r2z = -sb * sg, cb, sb * cg
            c00, c01, c02 = cp * r1x - sp * r2x, cp * r1y - sp * r2y, cp * r1z - sp * r2z
            c10, c11, c12 = sp * r1x + cp * r2x, sp * r1y + cp * r2y, sp * r1z + cp * r2z
            c20, c21, c22 = -cb * sg, -sb, cb * cg
            # C_n^b W and −C_n^b g
            ex = c00 * W[0] + c10 * W[1] + c20 * W[2]
            ey = c01 * W[0] + c11 * W[1] + c21 * W[2]
            ez = c02 * W[0] + c12 * W[1] + c22 * W[2]
            fx = -(c00 * g[0] + c10 * g[1] + c20 * g[2])
            fy = -(c01 * g[0] + c11 * g[1] + c21 * g[2])
            fz = -(c02 * g[0] + c12 * g[1] + c22 * g[2])
            # body rate ω_nb^b of the angle rates (tilt_attitude.body_rate)
            dp, db, dg = rates[i, k, 0], rates[i, k, 1], rates[i, k, 2]
            wx = -cg * db - sg * cb * dp
            wy = dg - sb * dp
            wz = -sg * db + cg * cb * dp
            if lever:
                ddp, ddb, ddg = accels[i, k, 0], accels[i, k, 1], accels[i, k, 2]
                ax = -cg * ddb + sg * dg * db - (cg * dg * cb - sg * sb * db) * dp - sg * cb * ddp
                ay = ddg - cb * db * dp - sb * ddp
                az = -cg * dg * db - sg * ddb + (-sg * dg * cb - cg * sb * db) * dp + cg * cb * ddp
                # ω × r, then ω̇ × r + ω × (ω × r) + 2 ω_e × (ω × r)
                qx = wy * r[2] - wz * r[1]
                qy = wz * r[0] - wx * r[2]
                qz = wx * r[1] - wy * r[0]
                fx += (ay * r[2] - az * r[1]) + (wy * qz - wz * qy) + 2.0 * (ey * qz - ez * qy)
                fy += (az * r[0] - ax * r[2]) + (wz * qx - wx * qz) + 2.0 * (ez * qx - ex * qz)
                fz += (ax * r[1] - ay * r[0]) + (wx * qy - wy * qx) + 2.0 * (ex * qy - ey * qx)
            if in_gyros:
                dtheta[i, k, 0] += weight * (wx + ex)
                dtheta[i, k, 1] += weight * (wy + ey)
                dtheta[i, k, 2] += weight * (wz + ez)
            else:
                dtheta[i, k, 0] += weight * fixed_gyro[0]
                dtheta[i, k, 1] += weight * fixed_gyro[1]
                dtheta[i, k, 2] += weight * fixed_gyro[2]
            dv[i, k, 0] += weight * fx
            dv[i, k, 1] += weight * fy
            dv[i, k, 2] += weight * fz


def accumulate_ideal_increments(angles, rates, accels, stable, earth_rate, gravity, lever_arm, fixed_gyro, in_gyros: bool, weight: float, dtheta, dv) -> None:
    """Add ``weight`` times the ideal gyro rate and specific force at one quadrature node, in place.

    Parameters
    ----------
    angles, rates : ndarray
        ``(n, N, 3)`` rocking angles (ψ, β, γ) [rad] and their rates [rad/s] at the node.
    accels : ndarray or None
        ``(n, N, 3)`` angular accelerations [rad/s²] (needed only with a lever arm).
    stable : ndarray
        ``(3,)`` stable attitude (ψ0, β0, γ0) added to ``angles`` [rad].
    earth_rate, gravity : ndarray
        ``(3,)`` ω_ie^n [rad/s] and g^n [m/s²] in NED.
    lever_arm : ndarray
        ``(3,)`` r in body axes [m].
    fixed_gyro : ndarray
        ``(3,)`` gyro rate when the gyros do not see the rocking [rad/s].
    in_gyros : bool
        The gyros see the rocking (``Scenario.rocking_in_gyros``).
    weight : float
        Quadrature weight [s].
    dtheta, dv : ndarray
        ``(n, N, 3)`` C-contiguous float arrays, incremented in place [rad, m/s].

    Notes
    -----
    The rates are those of :func:`strapdown.analysis.gyrocompass.imu._ideal_rates`
    (its numpy form is the reference of the tests).
    """
    lever = bool(np.any(lever_arm))
    angles, rates = np.ascontiguousarray(angles, dtype=float), np.ascontiguousarray(rates, dtype=float)
    accels = np.ascontiguousarray(accels, dtype=float) if lever else np.zeros((1, 1, 3))
    vec = lambda x: np.ascontiguousarray(x, dtype=float).reshape(3)  # noqa: E731
    _jit(_ideal_loop)(
        angles, rates, accels, vec(stable), vec(earth_rate), vec(gravity), vec(lever_arm), vec(fixed_gyro), bool(in_gyros), lever, float(weight), dtheta, dv
    )


def _preintegrate_loop(th, v, dt, M, E, R, V, S):
    n = th.shape[0]
    for i in range(n):
        pa0 = pa1 = pa2 = 0.0  # the previous sample (the last of the previous epoch at an epoch start)
        pb0 = pb1 = pb2 = 0.0
        for j in range(E):
            q0, q1, q2, q3 = 1.0, 0.0, 0.0, 0.0
            V0 = V1 = V2 = 0.0
            S0 = S1 = S2 = 0.0
            for k in range(M):
                s = j * M + k
                a0, a1, a2 = th[i, s, 0], th[i, s, 1], th[i, s, 2]
                b0, b1, b2 = v[i, s, 0], v[i, s, 1], v[i, s, 2]
                # sculling: b + ½ a×b + a×(a×b)/6 + (pa×b + pb×a)/12
                c0, c1, c2 = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0
                d0, d1, d2 = a1 * c2 - a2 * c1, a2 * c0 - a0 * c2, a0 * c1 - a1 * c0
                e0 = (pa1 * b2 - pa2 * b1) + (pb1 * a2 - pb2 * a1)
                e1 = (pa2 * b0 - pa0 * b2) + (pb2 * a0 - pb0 * a2)
                e2 = (pa0 * b1 - pa1 * b0) + (pb0 * a1 - pb1 * a0)
                u0 = b0 + 0.5 * c0 + d0 / 6.0 + e0 / 12.0
                u1 = b1 + 0.5 * c1 + d1 / 6.0 + e1 / 12.0
                u2 = b2 + 0.5 * c2 + d2 / 6.0 + e2 / 12.0
                # rotate by the epoch's running attitude: vect(q ∘ {0, u} ∘ q̄)
                t0 = -q1 * u0 - q2 * u1 - q3 * u2
                t1 = q0 * u0 + q2 * u2 - q3 * u1
                t2 = q0 * u1 - q1 * u2 + q3 * u0
                t3 = q0 * u2 + q1 * u1 - q2 * u0
                x0 = -t0 * q1 + t1 * q0 - t2 * q3 + t3 * q2
                x1 = -t0 * q2 + t1 * q3 + t2 * q0 - t3 * q1
                x2 = -t0 * q3 - t1 * q2 + t2 * q1 + t3 * q0
                V0 += x0
                V1 += x1
                V2 += x2
                tk = (k + 0.5) * dt
                S0 += tk * x0
                S1 += tk * x1
                S2 += tk * x2
                # coning: the rotation vector a + pa×a/12, then q ← q ∘ Δq
                p0 = a0 + (pa1 * a2 - pa2 * a1) / 12.0
                p1 = a1 + (pa2 * a0 - pa0 * a2) / 12.0
                p2 = a2 + (pa0 * a1 - pa1 * a0) / 12.0
                th2 = p0 * p0 + p1 * p1 + p2 * p2
                if th2 < 1e-4:  # the series branch of quaternion.rotvec_to_quat
                    x = th2 * 0.25
                    cw = 1.0 - x / 2.0 + x * x / 24.0 - x * x * x / 720.0
                    sw = 0.5 * (1.0 - x / 6.0 + x * x / 120.0 - x * x * x / 5040.0)
                else:
                    tt = math.sqrt(th2)
                    cw = math.cos(0.5 * tt)
                    sw = math.sin(0.5 * tt) / tt
                w0, w1, w2, w3 = cw, sw * p0, sw * p1, sw * p2
                q0, q1, q2, q3 = (
                    q0 * w0 - q1 * w1 - q2 * w2 - q3 * w3,
                    q0 * w1 + q1 * w0 + q2 * w3 - q3 * w2,
                    q0 * w2 - q1 * w3 + q2 * w0 + q3 * w1,
                    q0 * w3 + q1 * w2 - q2 * w1 + q3 * w0,
                )
                pa0, pa1, pa2 = a0, a1, a2
                pb0, pb1, pb2 = b0, b1, b2
            R[i, j, 0], R[i, j, 1], R[i, j, 2], R[i, j, 3] = q0, q1, q2, q3
            V[i, j, 0], V[i, j, 1], V[i, j, 2] = V0, V1, V2
            S[i, j, 0], S[i, j, 1], S[i, j, 2] = S0, S1, S2


def preintegrate_loop(dtheta, dv, dt: float, samples_per_epoch: int, n_epochs: int):
    """Epoch rotations, velocity increments and their first moments, in one compiled loop.

    Parameters
    ----------
    dtheta, dv : ndarray
        ``(n, N, 3)`` sample increments [rad, m/s], ``N ≥ samples_per_epoch · n_epochs``.
    dt : float
        Sample interval [s].
    samples_per_epoch : int
        M.
    n_epochs : int
        E.

    Returns
    -------
    tuple of ndarray
        ``(n, E, 4)`` rotations, ``(n, E, 3)`` velocity increments [m/s] and
        moments [m] (the fields of
        :class:`strapdown.analysis.gyrocompass.preintegration.EpochIncrements`).
    """
    th, v = np.ascontiguousarray(dtheta, dtype=float), np.ascontiguousarray(dv, dtype=float)
    n = th.shape[0]
    R, V, S = np.empty((n, n_epochs, 4)), np.empty((n, n_epochs, 3)), np.empty((n, n_epochs, 3))
    _jit(_preintegrate_loop)(th, v, float(dt), int(samples_per_epoch), int(n_epochs), R, V, S)
    return R, V, S
