"""Compiled loops of the self-alignment Monte Carlo: sensor increments, preintegration, the filter's epochs.

The hot paths of the self-alignment Monte Carlo are a few dozen flops per
sample or epoch, which numpy spreads over dozens of small array operations:

* :func:`accumulate_ideal_increments` adds one Gauss node's share of the ideal
  gyro and accelerometer increments (the rates of :mod:`~strapdown.analysis.alignment.imu`: attitude,
  body rate, Earth rate in body axes, gravity, lever-arm terms), fused in one
  loop over trials and samples;
* :func:`add_sensor_terms` applies a sensor's scale factors, bias and white noise to those
  increments in one pass;
* :func:`sensor_increments` does both for the two Gauss nodes in a single pass that writes
  each record once (the same operations, so the same bits, as the separate passes);
* :func:`sinusoid_sum` sums a few sinusoids per trial and axis (the sine rocking's record);
* :func:`preintegrate_loop` condenses sample increments into epoch increments
  (the coning- and sculling-compensated sums of :mod:`~strapdown.analysis.alignment.preintegration`), and
  :func:`chain_loop` chains the epoch rotations into attitudes;
* :func:`first_order_loop` turns unit draws into the exact increments of a
  first-order Gauss–Markov process or a random walk (the flicker and rate
  random walk terms of :mod:`~strapdown.analysis.alignment.sensor_models`), fused in one pass, and
  :func:`first_order_add` adds them to a running total and sums them in the same pass;
* :func:`navigator_loop` steps the GNSS-aided navigator of
  :mod:`~strapdown.analysis.alignment.aided` over the epochs between two fixes, for every trial;
* :func:`fine_alignment_loop` runs the closed-loop error-state filter of
  :mod:`~strapdown.analysis.alignment.fine` over the epochs of every trial, with gains computed
  before (by filterpy), and scores it against the truth (NEES, NIS).

They are compiled with numba on first use (the machine code is cached on disk,
so the compile cost is paid once per installation).  Loading numba and the
cached code still costs about half a second per process, more than a small
run takes in numpy, so by default (:func:`use_compiled`) the callers use the
numpy forms until numba is loaded or :data:`START_UP_WORK` samples have gone
through them.  The vectorised numpy
forms stay in :mod:`~strapdown.analysis.alignment.imu`, :mod:`~strapdown.analysis.alignment.preintegration`,
:mod:`~strapdown.analysis.alignment.sensor_models`, :mod:`~strapdown.analysis.alignment.aided` and :mod:`~strapdown.analysis.alignment.fine` as
the references the tests compare these loops against (equal to round-off).
"""

from __future__ import annotations

import math
import sys

import numpy as np

from ..core.validation import as_array, as_int, as_vector

__all__ = [
    "START_UP_WORK", "use_compiled", "accumulate_ideal_increments", "add_sensor_terms", "sensor_increments", "sinusoid_sum",
    "preintegrate_loop", "chain_loop", "first_order_loop", "first_order_add", "navigator_loop", "fine_alignment_loop",
]  # fmt: skip

#: Samples (trials × samples, or the equivalent) the numpy forms take in about the time numba's start-up costs.
START_UP_WORK = 1_000_000

_numpy_work = [0]

_compiled: dict = {}


def _shaped(x, name: str, shape: tuple, *, output: bool = False) -> np.ndarray:
    """``x`` as a C-contiguous float array of ``shape`` (None: any length); an output must be one already.

    The loops index without bounds checks, so every shape is checked here;
    the entries are not (a NaN comes out as NaN, it cannot corrupt memory).
    """
    if output:
        if not (isinstance(x, np.ndarray) and x.dtype == np.float64 and x.flags.c_contiguous and x.flags.writeable):
            raise TypeError(f"Expected `{name}` to be a writable C-contiguous float64 array, got {type(x).__name__} {getattr(x, 'dtype', '')}".rstrip())
        a = x
    else:
        a = np.ascontiguousarray(as_array(x, name, finite=False))
    if a.ndim != len(shape) or any(want is not None and got != want for got, want in zip(a.shape, shape)):
        text = ", ".join("…" if want is None else str(want) for want in shape)
        raise ValueError(f"Expected `{name}` with shape ({text}), got shape {a.shape}")
    return a


def _read_only(x: np.ndarray) -> np.ndarray:
    """A read-only view of ``x`` (no copy; ``x`` itself unchanged)."""
    view = x.view()
    view.setflags(write=False)
    return view


def use_compiled(compiled: bool | None, work: int) -> bool:
    """Whether a caller runs its compiled loop: ``compiled`` if given, else whether the loop pays off.

    It pays off once numba is loaded (by these loops or any other part of
    the package), or once the numpy forms have taken :data:`START_UP_WORK`
    samples in this process; until then the numpy forms run.  Both agree to
    round-off.

    Parameters
    ----------
    compiled : bool or None
        The caller's choice; None: decide.
    work : int
        Samples of the call (trials × samples, or the equivalent).

    Returns
    -------
    bool
    """
    if compiled is not None:
        return bool(compiled)
    if "numba" in sys.modules:
        return True
    _numpy_work[0] += int(work)
    return _numpy_work[0] > START_UP_WORK


#: Functions the loops call, compiled (and swapped in for the Python ones) before the first loop.
_HELPERS = ("_node_rates", "_rodrigues3", "_quat_mul", "_quat_rotate", "_rotvec_quat")

#: Helpers inlined into their callers by numba itself: called per sample with many arguments, a call would cost as much as their body.
_INLINED = ("_node_rates",)


def _jit(fn):
    """``fn`` compiled with numba (imported on first use; cached on disk)."""
    name = fn.__name__
    if name not in _compiled:
        import numba

        g = globals()
        for helper in _HELPERS:
            if not isinstance(g[helper], numba.core.registry.CPUDispatcher):
                g[helper] = numba.njit(cache=True, nogil=True, inline="always" if helper in _INLINED else "never")(g[helper])
        _compiled[name] = numba.njit(cache=True, nogil=True)(fn)
    return _compiled[name]


def _node_rates(ang, rate, acc, scale, stable, yaw, cp, sp, W, g, r, lever, in_gyros, fixed_gyro):
    """Ideal gyro rate and specific force at one point of one node: ``(ωx, ωy, ωz, fx, fy, fz)``.

    Every argument is a number or a tuple of three (no array: a compiled caller
    passes them without reference counting); ``ang``, ``rate`` and ``acc`` are
    the unit rocking at the point (``acc`` read only with a lever arm), ``cp``
    and ``sp`` the cosine and sine of the stable heading (used without yaw rocking).
    """
    s0, s1, s2 = scale
    # the rocking is scale · (angles, rates, accels) per axis (a unit draw at an amplitude)
    beta = s1 * ang[1] + stable[1]
    gam = s2 * ang[2] + stable[2]
    if yaw:
        psi = s0 * ang[0] + stable[0]
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
    dp, db, dg = s0 * rate[0], s1 * rate[1], s2 * rate[2]
    wx = -cg * db - sg * cb * dp
    wy = dg - sb * dp
    wz = -sg * db + cg * cb * dp
    if lever:
        ddp, ddb, ddg = s0 * acc[0], s1 * acc[1], s2 * acc[2]
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
        return wx + ex, wy + ey, wz + ez, fx, fy, fz
    return fixed_gyro[0], fixed_gyro[1], fixed_gyro[2], fx, fy, fz


def _ideal_loop(angles, rates, accels, scale, stable, W, g, r, fixed_gyro, in_gyros, lever, weight, dtheta, dv):
    n, N = angles.shape[0], angles.shape[1]
    sc, st, We, gn = (scale[0], scale[1], scale[2]), (stable[0], stable[1], stable[2]), (W[0], W[1], W[2]), (g[0], g[1], g[2])
    ra, fg = (r[0], r[1], r[2]), (fixed_gyro[0], fixed_gyro[1], fixed_gyro[2])
    yaw = sc[0] != 0.0  # without yaw rocking ψ is the stable heading: its cosine and sine once
    cp, sp = math.cos(st[0]), math.sin(st[0])
    acc = (0.0, 0.0, 0.0)
    for i in range(n):
        for k in range(N):
            ang, rate = (angles[i, k, 0], angles[i, k, 1], angles[i, k, 2]), (rates[i, k, 0], rates[i, k, 1], rates[i, k, 2])
            if lever:
                acc = (accels[i, k, 0], accels[i, k, 1], accels[i, k, 2])
            gx, gy, gz, fx, fy, fz = _node_rates(ang, rate, acc, sc, st, yaw, cp, sp, We, gn, ra, lever, in_gyros, fg)
            dtheta[i, k, 0] += weight * gx
            dtheta[i, k, 1] += weight * gy
            dtheta[i, k, 2] += weight * gz
            dv[i, k, 0] += weight * fx
            dv[i, k, 1] += weight * fy
            dv[i, k, 2] += weight * fz


def accumulate_ideal_increments(angles, rates, accels, stable, earth_rate, gravity, lever_arm, fixed_gyro, in_gyros: bool, weight: float, dtheta, dv, *, scale=None) -> None:
    """Add ``weight`` times the ideal gyro rate and specific force at one quadrature node, in place.

    Parameters
    ----------
    angles, rates : ndarray
        ``(n, N, 3)`` rocking angles (ψ, β, γ) [rad] and their rates [rad/s] at the node
        (times ``scale``).
    accels : ndarray or None
        ``(n, N, 3)`` angular accelerations [rad/s²] (needed only with a lever arm; times ``scale``).
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
    scale : array_like, optional, keyword-only
        ``(3,)`` factors of the rocking per axis [1] (default ones): the rocking
        is ``scale · angles`` and so on, axis by axis, as
        :meth:`strapdown.analysis.alignment.base_motion.MotionRealisation.unit_evaluation`
        returns it, so that a shared unit evaluation is not multiplied out first.

    Raises
    ------
    TypeError
        If ``dtheta`` or ``dv`` is not a writable C-contiguous float64 array.
    ValueError
        For a wrong shape, or a vector that is not three finite numbers.

    Notes
    -----
    The rates are those of :func:`strapdown.analysis.alignment.imu.ideal_increments`
    with ``compiled=False`` (the numpy form, the reference of the tests).
    """
    angles = _shaped(angles, "angles", (None, None, 3))
    n, N = angles.shape[:2]
    rates = _shaped(rates, "rates", (n, N, 3))
    named = {"scale": np.ones(3) if scale is None else scale, "stable": stable, "earth_rate": earth_rate, "gravity": gravity, "lever_arm": lever_arm, "fixed_gyro": fixed_gyro}
    vectors = [np.ascontiguousarray(_shaped(as_vector(v, name), name, (3,))) for name, v in named.items()]
    lever = bool(np.any(vectors[4]))
    accels = _shaped(accels, "accels", (n, N, 3)) if lever else np.zeros((1, 1, 3))
    dtheta, dv = _shaped(dtheta, "dtheta", (n, N, 3), output=True), _shaped(dv, "dv", (n, N, 3), output=True)
    # read-only views, whether or not the arrays are (the kept unit evaluations are): one compiled signature
    _jit(_ideal_loop)(*(_read_only(x) for x in (angles, rates, accels)), *vectors, bool(in_gyros), lever, float(weight), dtheta, dv)


def _sensor_terms_loop(x, scale, with_scale, bias, noise, with_noise):
    n, N = x.shape[0], x.shape[1]
    for i in range(n):
        for k in range(N):
            for a in range(3):
                y = x[i, k, a]
                if with_scale:
                    y = y * scale[a]
                y = y + bias[i, a]
                if with_noise:
                    y = y + noise[i, k, a]
                x[i, k, a] = y


def add_sensor_terms(increments, bias, *, scale=None, noise=None) -> None:
    """Apply a sensor's scale factors, bias and white noise to its increments, in place and in one pass.

    ``increments ← increments · scale + bias + noise``, element by element in
    that order: the operations of :func:`strapdown.analysis.alignment.imu.simulate_imu`'s
    numpy form (a product, then two sums), so the two agree to the last bit.

    Parameters
    ----------
    increments : ndarray
        ``(n, N, 3)`` writable C-contiguous float64 increments [rad or m/s], changed in place.
    bias : array_like
        ``(n, 3)`` bias of each trial times the sample interval [rad or m/s].
    scale : array_like, optional, keyword-only
        ``(3,)`` factors ``1 + s`` per axis [1] (default: none applied).
    noise : array_like, optional, keyword-only
        ``(n, N, 3)`` white-noise increments [rad or m/s] (default: none).

    Raises
    ------
    TypeError
        If ``increments`` is not a writable C-contiguous float64 array.
    ValueError
        For a shape that does not fit ``increments``.
    """
    x = _shaped(increments, "increments", (None, None, 3), output=True)
    n, N = x.shape[:2]
    b = _shaped(bias, "bias", (n, 3))
    s = np.ones(3) if scale is None else _shaped(scale, "scale", (3,))
    z = np.zeros((1, 1, 3)) if noise is None else _read_only(_shaped(noise, "noise", (n, N, 3)))
    _jit(_sensor_terms_loop)(x, s, scale is not None, b, _read_only(z), noise is not None)


def _sinusoids_loop(cr, ci, cos, sin, out):
    n, A, M = cr.shape[0], cr.shape[1], cr.shape[2]
    T = cos.shape[1]
    for i in range(n):
        for k in range(T):
            for a in range(A):
                y = 0.0
                for m in range(M):
                    y = y + (cr[i, a, m] * cos[m, k] - ci[i, a, m] * sin[m, k])
                out[i, k, a] = y


def sinusoid_sum(coefficients, cos, sin) -> np.ndarray:
    """``Σ_m (Re c_m cos_m(t) − Im c_m sin_m(t))`` per trial and axis, in one compiled pass.

    The operations of the numpy sum of
    :meth:`strapdown.analysis.alignment.base_motion.MotionRealisation._sinusoids`
    (from zeros, one sinusoid after the other: a product, a product, their
    difference, the sum), so the two agree to the last bit; the cosines and
    sines are the caller's.

    Parameters
    ----------
    coefficients : ndarray
        ``(n, A, M)`` complex coefficients.
    cos, sin : ndarray
        ``(M, T)`` ``cos ω_m t`` and ``sin ω_m t`` at the T times.

    Returns
    -------
    ndarray
        ``(n, T, A)``.

    Raises
    ------
    ValueError
        For shapes that do not fit.
    """
    c = np.asarray(coefficients)
    if c.ndim != 3:
        raise ValueError(f"Expected `coefficients` with shape (n, A, M), got shape {c.shape}")
    n, A, M = c.shape
    cos = _shaped(cos, "cos", (M, None))
    sin = _shaped(sin, "sin", cos.shape)
    out = np.empty((n, cos.shape[1], A))
    _jit(_sinusoids_loop)(np.ascontiguousarray(c.real, dtype=float), np.ascontiguousarray(c.imag, dtype=float), cos, sin, out)
    return out


#: Samples of a trial per block of :func:`sensor_increments` (its working arrays stay in the first-level cache).
_BLOCK = 64


def _increments_loop(first, second, scale, stable, W, g, r, fixed_gyro, in_gyros, lever, weight, scales, with_scale, bias, with_bias, gyro_noise, accel_noise, with_noise, dtheta, dv):
    # _node_rates's operations, block by block of samples: the sines and cosines first (library calls), then the
    # arithmetic in a loop without calls or branches that the compiler vectorises over the samples (each lane
    # the same IEEE operations, so the same bits), then the sensor terms
    angles1, rates1, accels1 = first
    angles2, rates2, accels2 = second
    n, N = angles1.shape[0], angles1.shape[1]
    s0, s1, s2 = scale[0], scale[1], scale[2]
    W0, W1, W2, g0, g1, g2, r0, r1, r2 = W[0], W[1], W[2], g[0], g[1], g[2], r[0], r[1], r[2]
    fg0, fg1, fg2 = fixed_gyro[0], fixed_gyro[1], fixed_gyro[2]
    (gyro_scaled, accel_scaled), (gyro_noisy, accel_noisy) = with_scale, with_noise
    yaw = s0 != 0.0  # without yaw rocking ψ is the stable heading: its cosine and sine once
    cp0, sp0 = math.cos(stable[0]), math.sin(stable[0])
    trig = np.empty((2, 6, _BLOCK))  # per node: cos β, sin β, cos γ, sin γ, cos ψ, sin ψ
    rate = np.empty((2, 3, _BLOCK))
    acc = np.zeros((2, 3, _BLOCK))  # zeros without a lever arm (its terms are then left out)
    out = np.empty((6, _BLOCK))
    for i in range(n):
        for k0 in range(0, N, _BLOCK):
            m = min(_BLOCK, N - k0)
            for q in range(m):
                k = k0 + q
                for node in range(2):
                    a_k = angles1[i, k] if node == 0 else angles2[i, k]
                    beta = s1 * a_k[1] + stable[1]
                    gam = s2 * a_k[2] + stable[2]
                    trig[node, 0, q], trig[node, 1, q] = math.cos(beta), math.sin(beta)
                    trig[node, 2, q], trig[node, 3, q] = math.cos(gam), math.sin(gam)
                    if yaw:
                        psi = s0 * a_k[0] + stable[0]
                        trig[node, 4, q], trig[node, 5, q] = math.cos(psi), math.sin(psi)
                    else:
                        trig[node, 4, q], trig[node, 5, q] = cp0, sp0
                for a in range(3):
                    rate[0, a, q] = rates1[i, k, a]
                    rate[1, a, q] = rates2[i, k, a]
                if lever:
                    for a in range(3):
                        acc[0, a, q] = accels1[i, k, a]
                        acc[1, a, q] = accels2[i, k, a]
            for node in range(2):
                for q in range(m):
                    cb, sb, cg, sg, cp, sp = trig[node, 0, q], trig[node, 1, q], trig[node, 2, q], trig[node, 3, q], trig[node, 4, q], trig[node, 5, q]
                    # C_b^n = R_z(ψ) R_x(−β) R_y(γ) (tilt_attitude.attitude_matrix); columns are the body axes in NED
                    r1x, r1y, r1z = cg, 0.0, sg
                    r2x, r2y, r2z = -sb * sg, cb, sb * cg
                    c00, c01, c02 = cp * r1x - sp * r2x, cp * r1y - sp * r2y, cp * r1z - sp * r2z
                    c10, c11, c12 = sp * r1x + cp * r2x, sp * r1y + cp * r2y, sp * r1z + cp * r2z
                    c20, c21, c22 = -cb * sg, -sb, cb * cg
                    # C_n^b W and −C_n^b g
                    ex = c00 * W0 + c10 * W1 + c20 * W2
                    ey = c01 * W0 + c11 * W1 + c21 * W2
                    ez = c02 * W0 + c12 * W1 + c22 * W2
                    fx = -(c00 * g0 + c10 * g1 + c20 * g2)
                    fy = -(c01 * g0 + c11 * g1 + c21 * g2)
                    fz = -(c02 * g0 + c12 * g1 + c22 * g2)
                    # body rate ω_nb^b of the angle rates (tilt_attitude.body_rate)
                    dp, db, dg = s0 * rate[node, 0, q], s1 * rate[node, 1, q], s2 * rate[node, 2, q]
                    wx = -cg * db - sg * cb * dp
                    wy = dg - sb * dp
                    wz = -sg * db + cg * cb * dp
                    # the lever-arm terms, computed always and kept with a lever arm (a select, not a branch)
                    ddp, ddb, ddg = s0 * acc[node, 0, q], s1 * acc[node, 1, q], s2 * acc[node, 2, q]
                    ax = -cg * ddb + sg * dg * db - (cg * dg * cb - sg * sb * db) * dp - sg * cb * ddp
                    ay = ddg - cb * db * dp - sb * ddp
                    az = -cg * dg * db - sg * ddb + (-sg * dg * cb - cg * sb * db) * dp + cg * cb * ddp
                    qx = wy * r2 - wz * r1
                    qy = wz * r0 - wx * r2
                    qz = wx * r1 - wy * r0
                    lx = fx + ((ay * r2 - az * r1) + (wy * qz - wz * qy) + 2.0 * (ey * qz - ez * qy))
                    ly = fy + ((az * r0 - ax * r2) + (wz * qx - wx * qz) + 2.0 * (ez * qx - ex * qz))
                    lz = fz + ((ax * r1 - ay * r0) + (wx * qy - wy * qx) + 2.0 * (ex * qy - ey * qx))
                    fx, fy, fz = (lx, ly, lz) if lever else (fx, fy, fz)
                    gx, gy, gz = (wx + ex, wy + ey, wz + ez) if in_gyros else (fg0, fg1, fg2)
                    # the sums of accumulate_ideal_increments from zeros
                    if node == 0:
                        out[0, q], out[1, q], out[2, q] = 0.0 + weight * gx, 0.0 + weight * gy, 0.0 + weight * gz
                        out[3, q], out[4, q], out[5, q] = 0.0 + weight * fx, 0.0 + weight * fy, 0.0 + weight * fz
                    else:
                        out[0, q], out[1, q], out[2, q] = out[0, q] + weight * gx, out[1, q] + weight * gy, out[2, q] + weight * gz
                        out[3, q], out[4, q], out[5, q] = out[3, q] + weight * fx, out[4, q] + weight * fy, out[5, q] + weight * fz
            for q in range(m):
                k = k0 + q
                # add_sensor_terms' product and sums
                for c in range(3):
                    y = out[c, q]
                    if gyro_scaled:
                        y = y * scales[0, c]
                    if with_bias:
                        y = y + bias[0, i, c]
                    if gyro_noisy:
                        y = y + gyro_noise[i, k, c]
                    dtheta[i, k, c] = y
                for c in range(3):
                    y = out[3 + c, q]
                    if accel_scaled:
                        y = y * scales[1, c]
                    if with_bias:
                        y = y + bias[1, i, c]
                    if accel_noisy:
                        y = y + accel_noise[i, k, c]
                    dv[i, k, c] = y


def sensor_increments(first, second, stable, earth_rate, gravity, lever_arm, fixed_gyro, in_gyros: bool, weight: float, *, scale=None, gyro=None, accel=None):
    """The increments of both Gauss nodes in one pass, a sensor's terms applied: new arrays, written once.

    Equal to the last bit to :func:`accumulate_ideal_increments` of ``first``
    and then ``second`` into zeros, followed by :func:`add_sensor_terms` of
    ``gyro`` and ``accel`` (the same operations in the same order), without
    reading back or zeroing the records in between.

    Parameters
    ----------
    first, second : tuple
        ``(angles, rates, accels)`` at the two nodes, as :func:`accumulate_ideal_increments`
        takes them (``accels`` may be None without a lever arm).
    stable, earth_rate, gravity, lever_arm, fixed_gyro, in_gyros, weight
        As :func:`accumulate_ideal_increments` (one weight for both nodes).
    scale : array_like, optional, keyword-only
        ``(3,)`` factors of the rocking per axis [1] (default ones).
    gyro, accel : tuple, optional, keyword-only
        ``(bias, scale, noise)`` of the gyros and the accelerometers, as
        :func:`add_sensor_terms` takes them (``scale`` and ``noise`` may be
        None); both or neither (default: the ideal increments).

    Returns
    -------
    tuple of ndarray
        ``dtheta, dv``, each ``(n, N, 3)`` [rad, m/s].

    Raises
    ------
    ValueError
        For ``first`` or ``second`` not three arrays, a wrong shape, a vector that is not three finite numbers, or only one of ``gyro`` and ``accel``.
    """
    if (gyro is None) != (accel is None):
        raise ValueError("Expected `gyro` and `accel` both given (a sensor's terms) or both None")
    for name, node in (("first", first), ("second", second)):
        if not (isinstance(node, tuple | list) and len(node) == 3):
            raise ValueError(f"Expected `{name}` as (angles, rates, accels), got {type(node).__name__} of length {len(node) if hasattr(node, '__len__') else 'none'}")
    n, N = _shaped(first[0], "angles", (None, None, 3)).shape[:2]
    named = {"scale": np.ones(3) if scale is None else scale, "stable": stable, "earth_rate": earth_rate, "gravity": gravity, "lever_arm": lever_arm, "fixed_gyro": fixed_gyro}
    vectors = [np.ascontiguousarray(_shaped(as_vector(v, name), name, (3,))) for name, v in named.items()]
    lever = bool(np.any(vectors[4]))
    nodes = [
        (_shaped(angles, "angles", (n, N, 3)), _shaped(rates, "rates", (n, N, 3)), _shaped(accels, "accels", (n, N, 3)) if lever else np.zeros((1, 1, 3))) for angles, rates, accels in (first, second)
    ]
    scales, with_scale = np.ones((2, 3)), [False, False]
    bias = np.zeros((2, n, 3))
    noise, with_noise = [np.zeros((1, 1, 3)), np.zeros((1, 1, 3))], [False, False]
    for s, terms in enumerate((gyro, accel)):
        if terms is None:
            continue
        b, sc, z = terms
        bias[s] = _shaped(b, "bias", (n, 3))
        if sc is not None:
            scales[s], with_scale[s] = _shaped(sc, "scale", (3,)), True
        if z is not None:
            noise[s], with_noise[s] = _shaped(z, "noise", (n, N, 3)), True
    out = np.empty((2, n, N, 3))  # both records in one block: one allocation
    # read-only views, whether or not the arrays are (the kept unit evaluations are): one compiled signature
    _jit(_increments_loop)(
        *(tuple(_read_only(x) for x in node) for node in nodes), *vectors, bool(in_gyros), lever, float(weight), scales, tuple(with_scale), bias, gyro is not None,
        _read_only(noise[0]), _read_only(noise[1]), tuple(with_noise), out[0], out[1],
    )  # fmt: skip
    return out[0], out[1]


#: Trials :func:`preintegrate_loop` steps side by side (each in its own lane of the vector registers).
_LANES = 8


def _preintegrate_loop(th, v, dt, M, E, R, V, S):
    # _LANES trials side by side: every step of a sample is a loop over the lanes without calls or branches,
    # which the compiler vectorises (each lane the same IEEE operations in the same order as one trial alone);
    # the rotation's exact branch, rare, is taken lane by lane after the series.  The lanes' state is one
    # array, a row per quantity, so that the compiler sees that the rows do not overlap.
    n = th.shape[0]
    L = _LANES
    # rows: the sample a, b (0-5), the previous sample pa, pb (6-11; the last of the previous epoch at an epoch start),
    # q (12-15), Δq (16-19), V (20-22), S (23-25), the rotation vector (26-28) and its square (29)
    z = np.zeros((30, L))
    for i0 in range(0, n, L):
        nl = min(L, n - i0)  # lanes beyond nl step zeros, which are not written
        for r in range(12):
            for l in range(L):
                z[r, l] = 0.0
        for j in range(E):
            for l in range(L):
                z[12, l], z[13, l], z[14, l], z[15, l] = 1.0, 0.0, 0.0, 0.0
                z[20, l] = z[21, l] = z[22, l] = 0.0
                z[23, l] = z[24, l] = z[25, l] = 0.0
            for k in range(M):
                s = j * M + k
                for l in range(nl):
                    for c in range(3):
                        z[c, l], z[3 + c, l] = th[i0 + l, s, c], v[i0 + l, s, c]
                tk = (k + 0.5) * dt
                for l in range(L):
                    a0, a1, a2, b0, b1, b2 = z[0, l], z[1, l], z[2, l], z[3, l], z[4, l], z[5, l]
                    pa0, pa1, pa2, pb0, pb1, pb2 = z[6, l], z[7, l], z[8, l], z[9, l], z[10, l], z[11, l]
                    q0, q1, q2, q3 = z[12, l], z[13, l], z[14, l], z[15, l]
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
                    z[20, l] += x0
                    z[21, l] += x1
                    z[22, l] += x2
                    z[23, l] += tk * x0
                    z[24, l] += tk * x1
                    z[25, l] += tk * x2
                    # coning: the rotation vector a + pa×a/12 and its quaternion by the series branch of
                    # quaternion.rotvec_to_quat (replaced below where the rotation is too large for it)
                    p0 = a0 + (pa1 * a2 - pa2 * a1) / 12.0
                    p1 = a1 + (pa2 * a0 - pa0 * a2) / 12.0
                    p2 = a2 + (pa0 * a1 - pa1 * a0) / 12.0
                    th2 = p0 * p0 + p1 * p1 + p2 * p2
                    x = th2 * 0.25
                    cw = 1.0 - x / 2.0 + x * x / 24.0 - x * x * x / 720.0
                    sw = 0.5 * (1.0 - x / 6.0 + x * x / 120.0 - x * x * x / 5040.0)
                    z[16, l], z[17, l], z[18, l], z[19, l] = cw, sw * p0, sw * p1, sw * p2
                    z[26, l], z[27, l], z[28, l], z[29, l] = p0, p1, p2, th2
                    z[6, l], z[7, l], z[8, l], z[9, l], z[10, l], z[11, l] = a0, a1, a2, b0, b1, b2
                for l in range(L):
                    th2 = z[29, l]
                    if not th2 < 1e-4:  # the exact branch
                        tt = math.sqrt(th2)
                        cw = math.cos(0.5 * tt)
                        sw = math.sin(0.5 * tt) / tt
                        z[16, l], z[17, l], z[18, l], z[19, l] = cw, sw * z[26, l], sw * z[27, l], sw * z[28, l]
                # q ← q ∘ Δq
                for l in range(L):
                    q0, q1, q2, q3 = z[12, l], z[13, l], z[14, l], z[15, l]
                    w0, w1, w2, w3 = z[16, l], z[17, l], z[18, l], z[19, l]
                    z[12, l] = q0 * w0 - q1 * w1 - q2 * w2 - q3 * w3
                    z[13, l] = q0 * w1 + q1 * w0 + q2 * w3 - q3 * w2
                    z[14, l] = q0 * w2 - q1 * w3 + q2 * w0 + q3 * w1
                    z[15, l] = q0 * w3 + q1 * w2 - q2 * w1 + q3 * w0
            for l in range(nl):
                R[i0 + l, j, 0], R[i0 + l, j, 1], R[i0 + l, j, 2], R[i0 + l, j, 3] = z[12, l], z[13, l], z[14, l], z[15, l]
                V[i0 + l, j, 0], V[i0 + l, j, 1], V[i0 + l, j, 2] = z[20, l], z[21, l], z[22, l]
                S[i0 + l, j, 0], S[i0 + l, j, 1], S[i0 + l, j, 2] = z[23, l], z[24, l], z[25, l]


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
        :class:`strapdown.analysis.alignment.preintegration.EpochIncrements`).

    Raises
    ------
    ValueError
        For a wrong shape, or a record shorter than the epochs.
    """
    M, E = as_int(samples_per_epoch, "samples_per_epoch", minimum=1), as_int(n_epochs, "n_epochs", minimum=0)
    th = _shaped(dtheta, "dtheta", (None, None, 3))
    n, N = th.shape[:2]
    v = _shaped(dv, "dv", (n, N, 3))
    if N < M * E:
        raise ValueError(f"Expected `dtheta` of at least samples_per_epoch × n_epochs = {M * E} samples, got {N}")
    n_epochs = E
    R, V, S = np.empty((n, n_epochs, 4)), np.empty((n, n_epochs, 3)), np.empty((n, n_epochs, 3))
    _jit(_preintegrate_loop)(th, v, float(dt), M, E, R, V, S)
    return R, V, S


def _chain_loop(start, rot, out):
    n, E = rot.shape[0], rot.shape[1]
    for i in range(n):
        q0, q1, q2, q3 = start[i, 0], start[i, 1], start[i, 2], start[i, 3]
        out[i, 0, 0], out[i, 0, 1], out[i, 0, 2], out[i, 0, 3] = q0, q1, q2, q3
        for j in range(E):
            w0, w1, w2, w3 = rot[i, j, 0], rot[i, j, 1], rot[i, j, 2], rot[i, j, 3]
            q0, q1, q2, q3 = (
                q0 * w0 - q1 * w1 - q2 * w2 - q3 * w3,
                q0 * w1 + q1 * w0 + q2 * w3 - q3 * w2,
                q0 * w2 - q1 * w3 + q2 * w0 + q3 * w1,
                q0 * w3 + q1 * w2 - q2 * w1 + q3 * w0,
            )
            out[i, j + 1, 0], out[i, j + 1, 1], out[i, j + 1, 2], out[i, j + 1, 3] = q0, q1, q2, q3


def chain_loop(start, rotations):
    """Attitudes at the epoch boundaries, ``Q_0 = start``, ``Q_{j+1} = Q_j ∘ ΔR_j``, in one compiled loop.

    Parameters
    ----------
    start : ndarray
        ``(n, 4)`` initial quaternions.
    rotations : ndarray
        ``(n, E, 4)`` epoch rotations.

    Returns
    -------
    ndarray
        ``(n, E + 1, 4)``.

    Raises
    ------
    ValueError
        For a wrong shape.
    """
    rot = _shaped(rotations, "rotations", (None, None, 4))
    n, E = rot.shape[:2]
    q0 = as_array(start, "start", last=4)
    if q0.ndim > 2 or (q0.ndim == 2 and q0.shape[0] not in (1, n)):
        raise ValueError(f"Expected `start` with shape (4,) or ({n}, 4), got shape {q0.shape}")
    out = np.empty((n, E + 1, 4))
    _jit(_chain_loop)(np.ascontiguousarray(np.broadcast_to(q0, (n, 4))), rot, out)
    return out


def _first_order_loop(e, x0, phi, c, l00, l10, l11, add, out, sums):
    n, N, k = out.shape
    for i in range(n):
        for a in range(k):
            x = x0[i, 0, a]
            d = c * x + (l10 * e[0, i, 0, a] + l11 * e[1, i, 0, a])
            s = d
            out[i, 0, a] = out[i, 0, a] + d if add else d
            for t in range(1, N):
                x = l00 * e[0, i, t - 1, a] + phi * x
                d = c * x + (l10 * e[0, i, t, a] + l11 * e[1, i, t, a])
                s += d
                out[i, t, a] = out[i, t, a] + d if add else d
            sums[i, a] = s


def first_order_loop(draws, start, transition: float, coupling: float, noise_factor) -> np.ndarray:
    """Increments of a first-order process from unit draws, in one compiled pass (the loop of ``sensor_models._first_order``).

    With the level ``x`` and its integral over each interval driven by the
    correlated pair ``(L e₀, L e₁)`` (``L`` the Cholesky factor of the
    discretised noise): ``x_0 = start``, ``x_{j+1} = φ x_j + L₀₀ e₀ⱼ``, and the
    increment ``c x_j + (L₁₀ e₀ⱼ + L₁₁ e₁ⱼ)``, the same operations in the same
    order as the numpy form (``scipy.signal.lfilter``), so the two agree to
    the last bit.

    Parameters
    ----------
    draws : ndarray
        ``(2, n, N, k)`` unit normal draws ``(e₀, e₁)``.
    start : ndarray
        ``(n, 1, k)`` levels at the first interval's start.
    transition : float
        φ, the level's transition over one interval.
    coupling : float
        ``c``, the increment's share of the level at the interval start [s].
    noise_factor : array_like
        ``(2, 2)`` lower Cholesky factor ``L`` of the discretised noise.

    Returns
    -------
    ndarray
        ``(n, N, k)`` increments.

    Raises
    ------
    ValueError
        For shapes that do not fit ``draws``.
    """
    e = _shaped(draws, "draws", (2, None, None, None))
    n, N, k = e.shape[1:]
    x0 = _shaped(start, "start", (n, 1, k))
    L = _shaped(noise_factor, "noise_factor", (2, 2))
    out = np.empty((n, N, k))
    _jit(_first_order_loop)(e, x0, float(transition), float(coupling), float(L[0, 0]), float(L[1, 0]), float(L[1, 1]), False, out, np.empty((n, k)))
    return out


def first_order_add(draws, start, transition: float, coupling: float, noise_factor, total) -> np.ndarray:
    """Add the increments of :func:`first_order_loop` to ``total`` in place and return their sums over the samples.

    One pass instead of three (the increments, ``total += increments`` and
    ``increments.sum(axis=1)``) and no ``(n, N, k)`` temporary: each element of
    ``total`` gets the same sum as in ``total + increments``, and the sums are
    taken in sample order, as numpy's ``sum(axis=1)`` takes them for ``k > 1``
    (for ``k = 1`` numpy sums pairwise, so the bits may differ there).

    Parameters
    ----------
    draws, start, transition, coupling, noise_factor
        As for :func:`first_order_loop`.
    total : ndarray
        ``(n, N, k)`` writable C-contiguous float64 array, added to in place.

    Returns
    -------
    ndarray
        ``(n, k)`` sum of each trial's and axis's increments.

    Raises
    ------
    ValueError
        For shapes that do not fit ``draws``.
    TypeError
        For a ``total`` that cannot be written in place.
    """
    e = _shaped(draws, "draws", (2, None, None, None))
    n, N, k = e.shape[1:]
    x0 = _shaped(start, "start", (n, 1, k))
    L = _shaped(noise_factor, "noise_factor", (2, 2))
    out = _shaped(total, "total", (n, N, k), output=True)
    sums = np.empty((n, k))
    _jit(_first_order_loop)(e, x0, float(transition), float(coupling), float(L[0, 0]), float(L[1, 0]), float(L[1, 1]), True, out, sums)
    return sums


def _quat_mul(a0, a1, a2, a3, b0, b1, b2, b3):
    """Hamilton product, written as ``quaternion.multiply_parts`` writes it."""
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def _quat_rotate(q0, q1, q2, q3, v0, v1, v2):
    """``Λ ∘ v ∘ Λ̄``, written as ``quaternion.rotate`` writes it."""
    w0, w1, w2, w3 = _quat_mul(q0, q1, q2, q3, v0 * 0.0, v0, v1, v2)
    c1, c2, c3 = -q1, -q2, -q3
    return w0 * c1 + w1 * q0 + w2 * c3 - w3 * c2, w0 * c2 - w1 * c3 + w2 * q0 + w3 * c1, w0 * c3 + w1 * c2 - w2 * c1 + w3 * q0


def _rotvec_quat(p0, p1, p2, small_angle):
    """Quaternion of a rotation vector, written as ``quaternion.rotvec_to_quat`` writes it (series below ``small_angle``)."""
    theta2 = p0 * p0 + p1 * p1 + p2 * p2
    x2 = theta2 * 0.25
    if theta2 < small_angle * small_angle:
        c = 1.0 - x2 / 2.0 + x2 * x2 / 24.0 - x2 * x2 * x2 / 720.0
        s = 0.5 * (1.0 - x2 / 6.0 + x2 * x2 / 120.0 - x2 * x2 * x2 / 5040.0)
    else:
        theta = math.sqrt(theta2)
        half = theta * 0.5
        c = math.cos(half)
        s = math.sin(half) / theta
    return c, s * p0, s * p1, s * p2


def _navigator_loop(q, v, lat, lon, h, bg, ba, rot, vel, mom, D, const, qo, vo, lato, lono, ho):
    n, E = rot.shape[0], rot.shape[1]
    earth_rate, a, e2, gamma_e, k_g, e2_g, small = const[0], const[1], const[2], const[3], const[4], const[5], const[6]
    for i in range(n):
        q0, q1, q2, q3 = q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        v0, v1, v2 = v[i, 0], v[i, 1], v[i, 2]
        la, lo, hi = lat[i], lon[i], h[i]
        for j in range(E):
            sl = math.sin(la)
            s2 = sl * sl
            w = math.sqrt(1.0 - e2 * s2)
            RN, RE = a * (1.0 - e2) / math.pow(w, 3.0), a / w
            cl = math.cos(la)
            wie0, wie1, wie2 = earth_rate * cl, earth_rate * 0.0, earth_rate * -sl
            wen0, wen1, wen2 = v1 / (RE + hi), -v0 / (RN + hi), -v1 * math.tan(la) / (RE + hi)
            win0, win1, win2 = wie0 + wen0, wie1 + wen1, wie2 + wen2
            r0, r1, r2 = _quat_rotate(q0, q1, q2, q3, vel[i, j, 0] - ba[i, 0] * D, vel[i, j, 1] - ba[i, 1] * D, vel[i, j, 2] - ba[i, 2] * D)
            m0, m1, m2 = _quat_rotate(q0, q1, q2, q3, mom[i, j, 0], mom[i, j, 1], mom[i, j, 2])
            dv0 = r0 - (win1 * m2 - win2 * m1)
            dv1 = r1 - (win2 * m0 - win0 * m2)
            dv2 = r2 - (win0 * m1 - win1 * m0)
            gd = gamma_e * (1.0 + k_g * s2) / math.sqrt(1.0 - e2_g * s2) * (1.0 - 2.0 * hi / a)
            c0, c1, c2 = 2.0 * wie0 + wen0, 2.0 * wie1 + wen1, 2.0 * wie2 + wen2
            n0 = v0 + dv0 - (c1 * v2 - c2 * v1) * D
            n1 = v1 + dv1 - (c2 * v0 - c0 * v2) * D
            n2 = v2 + dv2 - (c0 * v1 - c1 * v0) * D
            n2 += gd * D
            va0, va1, va2 = 0.5 * (v0 + n0), 0.5 * (v1 + n1), 0.5 * (v2 + n2)
            la_new = la + va0 * D / (RN + hi)
            lo = lo + va1 * D / ((RE + hi) * cl)
            hi = hi - va2 * D
            t0, t1, t2, t3 = _rotvec_quat(-win0 * D, -win1 * D, -win2 * D, small)
            t0, t1, t2, t3 = _quat_mul(t0, t1, t2, t3, q0, q1, q2, q3)
            b0, b1, b2, b3 = _rotvec_quat(-bg[i, 0] * D, -bg[i, 1] * D, -bg[i, 2] * D, small)
            b0, b1, b2, b3 = _quat_mul(rot[i, j, 0], rot[i, j, 1], rot[i, j, 2], rot[i, j, 3], b0, b1, b2, b3)
            q0, q1, q2, q3 = _quat_mul(t0, t1, t2, t3, b0, b1, b2, b3)
            v0, v1, v2, la = n0, n1, n2, la_new
        qo[i, 0], qo[i, 1], qo[i, 2], qo[i, 3] = q0, q1, q2, q3
        vo[i, 0], vo[i, 1], vo[i, 2] = v0, v1, v2
        lato[i], lono[i], ho[i] = la, lo, hi


def navigator_loop(q, v, lat, lon, h, gyro_bias, accel_bias, rotation, velocity, moment, epoch: float, constants):
    """The GNSS-aided navigator over ``E`` epochs for every trial (``E`` steps of ``aided.navigator_step``), in one compiled loop.

    The same operations in the same order as the numpy step (the
    quaternion product, rotation and rotation-vector quaternion as
    :mod:`strapdown.analysis.core.quaternion` writes them, the radii and normal
    gravity as :mod:`~strapdown.analysis.alignment.trajectory` and
    :mod:`~strapdown.analysis.alignment.earth` write them), so the two agree to
    the last bit where the platform's ``sin``, ``cos``, ``tan`` and ``pow`` are
    numpy's (``tests/test_aided.py`` compares them).

    Parameters
    ----------
    q : ndarray
        ``(n, 4)`` attitude quaternions of ``C_b^n``.
    v : ndarray
        ``(n, 3)`` NED velocity [m/s].
    lat, lon, h : ndarray
        ``(n,)`` latitude, longitude [rad] and height [m].
    gyro_bias, accel_bias : ndarray
        ``(n, 3)`` bias estimates, body axes [rad/s, m/s²] (held over the epochs).
    rotation : ndarray
        ``(n, E, 4)`` the epoch rotations.
    velocity, moment : ndarray
        ``(n, E, 3)`` the epochs' velocity increments [m/s] and first moments [m].
    epoch : float
        The epoch D [s].
    constants : array_like
        ``(7,)``: Earth rate [rad/s], WGS-84 semi-major axis [m] and first
        eccentricity squared (of the radii of curvature), the constants of normal
        gravity (:data:`~strapdown.analysis.alignment.earth.SOMIGLIANA`), and the series
        angle of the rotation-vector quaternion [rad].

    Returns
    -------
    tuple
        ``(q, v, lat, lon, h)`` after the ``E`` epochs.

    Raises
    ------
    ValueError
        For shapes that do not fit ``rotation`` (n trials, E epochs).
    """
    rot = _shaped(rotation, "rotation", (None, None, 4))
    n, E = rot.shape[:2]
    args = [_shaped(x, name, shape) for x, name, shape in (
        (q, "q", (n, 4)), (v, "v", (n, 3)), (lat, "lat", (n,)), (lon, "lon", (n,)), (h, "h", (n,)), (gyro_bias, "gyro_bias", (n, 3)),
        (accel_bias, "accel_bias", (n, 3)), (velocity, "velocity", (n, E, 3)), (moment, "moment", (n, E, 3)),
    )]  # fmt: skip
    const = _shaped(constants, "constants", (7,))
    out = (np.empty((n, 4)), np.empty((n, 3)), np.empty(n), np.empty(n), np.empty(n))
    _jit(_navigator_loop)(*args[:7], rot, args[7], args[8], float(epoch), const, *out)
    return out


def _rodrigues3(p0, p1, p2, out):
    """``exp([φ×])`` into ``out`` (3, 3); the series below 1e-6 rad as in ``fine_alignment._rodrigues``."""
    th2 = p0 * p0 + p1 * p1 + p2 * p2
    if th2 < 1e-12:
        a = 1.0 - th2 / 6.0
        b = 0.5 - th2 / 24.0
    else:
        th = math.sqrt(th2)
        a = math.sin(th) / th
        b = (1.0 - math.cos(th)) / th2
    # I + a K + b K², K = [φ×]
    out[0, 0] = 1.0 - b * (p1 * p1 + p2 * p2)
    out[1, 1] = 1.0 - b * (p0 * p0 + p2 * p2)
    out[2, 2] = 1.0 - b * (p0 * p0 + p1 * p1)
    out[0, 1] = -a * p2 + b * p0 * p1
    out[1, 0] = a * p2 + b * p0 * p1
    out[0, 2] = a * p1 + b * p0 * p2
    out[2, 0] = -a * p1 + b * p0 * p2
    out[1, 2] = -a * p0 + b * p1 * p2
    out[2, 1] = a * p0 + b * p1 * p2


def _fine_loop(C0, v0, dR, vel, moment, noise, w_end, C_true, v_true, eps_true, acc_true, rock_true, E_earth, Wx, gn, D, r, lever, shaping, Fdd, H, K, score, Pinv, Sinv, C_out, nees, nis, heading):
    n, E = dR.shape[0], dR.shape[1]
    dim = H.shape[1]
    nd = Fdd.shape[0]
    C = np.empty((3, 3))
    T = np.empty((3, 3))
    U = np.empty((3, 3))
    Rr = np.empty((3, 3))
    eps = np.empty(3)
    acc = np.empty(3)
    v = np.empty(3)
    xd = np.zeros(nd)
    xn = np.empty(nd)
    pred = np.empty(dim)
    x = np.empty(dim)
    y = np.empty(3)
    err = np.empty(dim)
    u = np.empty(3)
    w = np.empty(3)
    dv = np.empty(3)
    for i in range(n):
        for a in range(3):
            v[a] = v0[i, a]
            eps[a] = 0.0
            acc[a] = 0.0
            for b in range(3):
                C[a, b] = C0[i, a, b]
        for m in range(nd):
            xd[m] = 0.0
        for j in range(E):
            # ε̂ and the accelerometer bias in body axes, C̃ᵀ ε̂
            eb0 = C[0, 0] * eps[0] + C[1, 0] * eps[1] + C[2, 0] * eps[2]
            eb1 = C[0, 1] * eps[0] + C[1, 1] * eps[1] + C[2, 1] * eps[2]
            eb2 = C[0, 2] * eps[0] + C[1, 2] * eps[1] + C[2, 2] * eps[2]
            ab0 = C[0, 0] * acc[0] + C[1, 0] * acc[1] + C[2, 0] * acc[2]
            ab1 = C[0, 1] * acc[0] + C[1, 1] * acc[1] + C[2, 1] * acc[2]
            ab2 = C[0, 2] * acc[0] + C[1, 2] * acc[1] + C[2, 2] * acc[2]
            # dV = C (ΔV − b_a D) − [ω_ie×] C S, then v ← v + dV + g D − 2 D [ω_ie×] v
            u[0], u[1], u[2] = vel[i, j, 0] - ab0 * D, vel[i, j, 1] - ab1 * D, vel[i, j, 2] - ab2 * D
            for a in range(3):
                w[a] = C[a, 0] * moment[i, j, 0] + C[a, 1] * moment[i, j, 1] + C[a, 2] * moment[i, j, 2]
            for a in range(3):
                dv[a] = C[a, 0] * u[0] + C[a, 1] * u[1] + C[a, 2] * u[2] - (Wx[a, 0] * w[0] + Wx[a, 1] * w[1] + Wx[a, 2] * w[2])
            for a in range(3):
                y[a] = Wx[a, 0] * v[0] + Wx[a, 1] * v[1] + Wx[a, 2] * v[2]
            for a in range(3):
                v[a] = v[a] + dv[a] + gn[a] * D - 2.0 * D * y[a]
            # C ← E_earth C ΔR exp(−[ε_b D ×])
            for a in range(3):
                for b in range(3):
                    T[a, b] = C[a, 0] * dR[i, j, 0, b] + C[a, 1] * dR[i, j, 1, b] + C[a, 2] * dR[i, j, 2, b]
            _rodrigues3(-eb0 * D, -eb1 * D, -eb2 * D, Rr)
            for a in range(3):
                for b in range(3):
                    U[a, b] = T[a, 0] * Rr[0, b] + T[a, 1] * Rr[1, b] + T[a, 2] * Rr[2, b]
            for a in range(3):
                for b in range(3):
                    C[a, b] = E_earth[a, 0] * U[0, b] + E_earth[a, 1] * U[1, b] + E_earth[a, 2] * U[2, b]
            # measurement: zero velocity (less the known lever-arm velocity)
            z0, z1, z2 = v[0] + noise[i, j, 0], v[1] + noise[i, j, 1], v[2] + noise[i, j, 2]
            if lever:
                q0, q1, q2 = w_end[i, j, 0] - eb0, w_end[i, j, 1] - eb1, w_end[i, j, 2] - eb2
                c0, c1, c2 = q1 * r[2] - q2 * r[1], q2 * r[0] - q0 * r[2], q0 * r[1] - q1 * r[0]
                z0 -= C[0, 0] * c0 + C[0, 1] * c1 + C[0, 2] * c2
                z1 -= C[1, 0] * c0 + C[1, 1] * c1 + C[1, 2] * c2
                z2 -= C[2, 0] * c0 + C[2, 1] * c1 + C[2, 2] * c2
            for m in range(dim):
                pred[m] = 0.0
            if shaping:
                for m in range(nd):
                    acc_m = 0.0
                    for l in range(nd):
                        acc_m += Fdd[m, l] * xd[l]
                    xn[m] = acc_m
                for m in range(nd):
                    xd[m] = xn[m]
                    pred[12 + m] = xn[m]
            y[0], y[1], y[2] = z0, z1, z2
            for a in range(3):
                hp = 0.0
                for m in range(dim):
                    hp += H[a, m] * pred[m]
                y[a] -= hp
            for m in range(dim):
                x[m] = pred[m] + K[j, m, 0] * y[0] + K[j, m, 1] * y[1] + K[j, m, 2] * y[2]
            # closed-loop correction
            _rodrigues3(x[0], x[1], x[2], Rr)
            for a in range(3):
                for b in range(3):
                    T[a, b] = Rr[a, 0] * C[0, b] + Rr[a, 1] * C[1, b] + Rr[a, 2] * C[2, b]
            for a in range(3):
                for b in range(3):
                    C[a, b] = T[a, b]
            for a in range(3):
                v[a] -= x[3 + a]
                eps[a] += x[6 + a]
                acc[a] += x[9 + a]
            if shaping:
                for m in range(nd):
                    xd[m] = x[12 + m]
            # consistency against the truth: Er = C̃ Cᵀ = exp(−[φ×])
            for a in range(3):
                for b in range(3):
                    U[a, b] = C[a, 0] * C_true[i, j + 1, b, 0] + C[a, 1] * C_true[i, j + 1, b, 1] + C[a, 2] * C_true[i, j + 1, b, 2]
            s0, s1, s2 = 0.5 * (U[2, 1] - U[1, 2]), 0.5 * (U[0, 2] - U[2, 0]), 0.5 * (U[1, 0] - U[0, 1])
            sn = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
            sc = math.asin(min(sn, 1.0)) / sn if sn > 1e-15 else 1.0
            err[0], err[1], err[2] = -s0 * sc, -s1 * sc, -s2 * sc
            heading[i, j] = -err[2]
            if not score:
                continue
            for a in range(3):
                err[3 + a] = v[a] - v_true[i, j + 1, a]
                err[6 + a] = eps_true[i, j + 1, a] - eps[a]
                err[9 + a] = acc_true[i, j + 1, a] - acc[a]
            if shaping:
                for m in range(nd):
                    err[12 + m] = rock_true[i, j + 1, m] - xd[m]
            total = 0.0
            for a in range(dim):
                row = 0.0
                for b in range(dim):
                    row += err[b] * Pinv[j, b, a]
                total += row * err[a]
            nees[i, j] = total
            total = 0.0
            for a in range(3):
                total += (y[0] * Sinv[j, 0, a] + y[1] * Sinv[j, 1, a] + y[2] * Sinv[j, 2, a]) * y[a]
            nis[i, j] = total
        for a in range(3):
            for b in range(3):
                C_out[i, a, b] = C[a, b]


def fine_alignment_loop(
    C0, v0, dR, velocity, moment, noise, end_rate, C_true, v_true, eps_true, acc_true, rock_true,
    earth_turn, earth_rate_skew, gravity, epoch, lever_arm, lever_arm_known, F_rocking, H, gains, posterior_inv, innovation_inv,
):  # fmt: skip
    """The epoch loop of the fine-alignment filter for every trial (the loop of :func:`~strapdown.analysis.alignment.fine.fine_alignment`).

    Parameters
    ----------
    C0 : ndarray
        ``(n, 3, 3)`` initial attitude estimates C̃_b^n.
    v0 : ndarray
        ``(n, 3)`` initial velocity estimates [m/s].
    dR : ndarray
        ``(n, E, 3, 3)`` epoch rotations of the body.
    velocity, moment : ndarray
        ``(n, E, 3)`` epoch velocity increments [m/s] and their moments [m].
    noise : ndarray
        ``(n, E, 3)`` noise of the zero-velocity reference [m/s].
    end_rate : ndarray
        ``(n, E, 3)`` gyro rate at each epoch end [rad/s].
    C_true : ndarray
        ``(n, E + 1, 3, 3)`` true attitudes at the epoch boundaries.
    v_true, eps_true, acc_true : ndarray
        ``(n, E + 1, 3)`` true velocity [m/s] and biases in NED [rad/s, m/s²].
    rock_true : ndarray
        ``(n, E + 1, d)`` true rocking states (``d`` = 0 without shaping states).
    earth_turn, earth_rate_skew : ndarray
        ``(3, 3)`` ``exp(−[ω_ie D×])`` and ``[ω_ie×]``.
    gravity : ndarray
        ``(3,)`` g^n [m/s²].
    epoch : float
        Epoch D [s].
    lever_arm : ndarray
        ``(3,)`` r [m].
    lever_arm_known : bool
        The measurement removes the lever-arm velocity.
    F_rocking : ndarray
        ``(d, d)`` transition of the rocking states (``(0, 0)`` without them).
    H : ndarray
        ``(3, dim)`` measurement matrix.
    gains : ndarray
        ``(E, dim, 3)`` Kalman gains.
    posterior_inv, innovation_inv : ndarray or None
        ``(E, dim, dim)`` and ``(E, 3, 3)`` inverse posterior and innovation
        covariances; None (both): the filter is not scored, NEES and NIS are NaN.

    Returns
    -------
    tuple of ndarray
        The attitude estimates at the end ``(n, 3, 3)``; NEES, NIS and the
        heading error [rad] at each epoch, ``(n, E)`` each.

    Raises
    ------
    ValueError
        For a shape that does not fit ``dR`` (n trials, E epochs) and ``F_rocking`` (d rocking states).
    """
    dR = _shaped(dR, "dR", (None, None, 3, 3))
    n, E = dR.shape[:2]
    F_rocking = _shaped(F_rocking, "F_rocking", (None, None))
    d = F_rocking.shape[0]
    dim = 12 + d  # attitude, velocity, gyro and accelerometer biases, then the rocking states
    if (posterior_inv is None) != (innovation_inv is None):
        raise ValueError("Expected `posterior_inv` and `innovation_inv` both given (a scored filter) or both None")
    score = posterior_inv is not None
    if not score:  # placeholders the loop does not read
        posterior_inv, innovation_inv = np.zeros((0, 0, 0)), np.zeros((0, 0, 0))
    shapes = {
        "C0": (n, 3, 3), "v0": (n, 3), "velocity": (n, E, 3), "moment": (n, E, 3), "noise": (n, E, 3), "end_rate": (n, E, 3),
        "C_true": (n, E + 1, 3, 3), "v_true": (n, E + 1, 3), "eps_true": (n, E + 1, 3), "acc_true": (n, E + 1, 3), "rock_true": (n, E + 1, d),
        "earth_turn": (3, 3), "earth_rate_skew": (3, 3), "gravity": (3,), "lever_arm": (3,), "H": (3, dim), "gains": (E, dim, 3),
        "posterior_inv": (E, dim, dim) if score else (0, 0, 0), "innovation_inv": (E, 3, 3) if score else (0, 0, 0),
    }  # fmt: skip
    given = dict(
        C0=C0, v0=v0, velocity=velocity, moment=moment, noise=noise, end_rate=end_rate, C_true=C_true, v_true=v_true, eps_true=eps_true, acc_true=acc_true,
        rock_true=rock_true, earth_turn=earth_turn, earth_rate_skew=earth_rate_skew, gravity=gravity, lever_arm=lever_arm, H=H, gains=gains,
        posterior_inv=posterior_inv, innovation_inv=innovation_inv,
    )  # fmt: skip
    a = {name: _shaped(given[name], name, shape) for name, shape in shapes.items()}
    if F_rocking.shape != (d, d):
        raise ValueError(f"Expected `F_rocking` square, got shape {F_rocking.shape}")
    C_out, heading = np.empty((n, 3, 3)), np.empty((n, E))
    nees, nis = (np.empty((n, E)), np.empty((n, E))) if score else (np.full((n, E), np.nan), np.full((n, E), np.nan))
    _jit(_fine_loop)(
        a["C0"], a["v0"], dR, a["velocity"], a["moment"], a["noise"], a["end_rate"], a["C_true"], a["v_true"], a["eps_true"], a["acc_true"], a["rock_true"],
        a["earth_turn"], a["earth_rate_skew"], a["gravity"], float(epoch), a["lever_arm"], bool(lever_arm_known), d > 0, F_rocking,
        a["H"], a["gains"], score, a["posterior_inv"], a["innovation_inv"], C_out, nees, nis, heading,
    )  # fmt: skip
    return C_out, nees, nis, heading
