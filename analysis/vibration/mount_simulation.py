"""Time-domain simulation of the IMU mount under random base vibration: an independent check of the mount's spectra.

Nothing here uses the transfer matrix, the assembled mass, stiffness or
damping matrices of :mod:`strapdown.analysis.vibration.mount`, or its modes
(except, by default, to choose the warm-up time): the block is a rigid body
integrated by DOP853 (``scipy.integrate.solve_ivp``) in its nonlinear form,

* position x and velocity v of the centre of mass (inertial frame, the
  base's frame at rest), attitude ``Λ`` (block to inertial, ``2Λ̇ = Λ ∘ ω``),
  body rate ω with Euler's equations ``J ω̇ + ω × Jω = τ``;
* each isolator's force from the relative motion of its two attachment
  points: the block's ``x + R(r_i − c)`` moving with ``v + (Rω) × R(r_i − c)``,
  the base's ``u + R_b r_i`` moving with ``u̇ + ω_b × R_b r_i`` (``R_b = exp[β×]``,
  ``ω_b = J_l(β) β̇``), the force ``F_i = −K_i d_i − C_i ḋ_i`` in the axes of
  the base at rest applied at the block's point;
* the outputs at the IMU point p: the body rate ω and the vibration of the
  specific force ``Rᵀ(a_p − g) + g`` (a_p the acceleration of p, g the
  gravity vector, whose static reading −g is taken off), and their
  integrals over each sample (the gyro's and accelerometers' increments).

The right-hand side is a loop over realisations and isolators in plain
arithmetic (:func:`_rigid_body`), compiled with numba on first use and cached
on disk; DOP853 integrates all the realisations together.

The base motion of a realisation is a random-phase multisine with complex
Gaussian amplitudes: on the lines ``f_k = k/T`` (T the simulated time), each
channel c of the excitation gets ``Z = √(G_c(f_k) Δf) (n₁ + i n₂)`` with
independent standard normal n₁, n₂, so that ``E[½ conj(Z_a) Z_b] = G_ab Δf``
(a stationary Gaussian process with the profile's density on the lines).  The
displacement ``−A/ω²``, the rotation angle ``Ω/(iω)`` and their rates are
synthesised by FFT on a grid of at least :data:`OVERSAMPLING` points per
period of the highest line and interpolated by quintic splines (relative
error far below 10⁻⁶ at that sampling, and smooth, as DOP853 needs).  The
block starts at rest; :data:`WARMUP_TIME_CONSTANTS` time constants of the
slowest-decaying mode pass before the first sample (the start's transient is
then below e⁻¹⁰ of its size).

:func:`welch_cross_spectra` estimates the six channels' cross-spectra from
each realisation by Welch's method (``scipy.signal.csd``, Hann window, half
overlap, no detrending) and gives intervals from the spread over independent
realisations (Student t).  Welch's estimate is the density smoothed by its
window's spectral kernel; :func:`expected_welch` gives that smoothed value of a
density known in closed form on the multisine's lines, so that a comparison
holds at a resonance too.  :func:`simulated_drift` runs an algorithm on the
gyro increments of every realisation and measures the slope of the attitude
error ``rotvec(Λ_true ∘ Λ̄_computed)``.

Randomness: realisation i draws from the i-th child of the seed
(``SeedSequence.spawn``), so a realisation does not depend on how many others
are run with it.

Public API
----------
.. autosummary::

   MountRecord
   simulate_mount
   WelchEstimate
   welch_cross_spectra
   expected_welch
   SimulatedDrift
   simulated_drift
   OVERSAMPLING
   WARMUP_TIME_CONSTANTS

References
----------
Hairer, Nørsett & Wanner (1993), DOP853; Welch (1967); Bendat & Piersol
(2010), *Random Data*, 4th ed., sections 8.5 (bias of windowed estimates)
and 11.5; Pintelon & Schoukens (2012), *System Identification*, 2nd ed.,
section 2.5 (random-phase multisines).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import signal
from scipy.integrate import solve_ivp
from scipy.interpolate import make_interp_spline
from scipy.stats import t as student_t

from ...derivations.coning.algorithms import Algorithm
from ..coning.evaluation import increment
from ..coning.simulator import drift_rate, prefix_product, step_windows
from ..core import budget
from ..core import quaternion as quat
from ..core.validation import as_int, in_open_interval, positive
from .mount import Mount
from .profile import BaseExcitation

__all__ = ["MountRecord", "simulate_mount", "WelchEstimate", "welch_cross_spectra", "expected_welch", "SimulatedDrift", "simulated_drift", "OVERSAMPLING", "WARMUP_TIME_CONSTANTS"]

#: Grid points of the base-motion synthesis per period of its highest line [count].
OVERSAMPLING = 16
#: Time constants ``1/(ζ ω_n)`` of the slowest-decaying mode left to the start's transient by default [count].
WARMUP_TIME_CONSTANTS = 10.0
#: States per realisation: x (3), v (3), Λ (4), ω (3), ∫ω dt (3), ∫f dt (3).
_STATES = 19
#: Right-hand-side evaluations of DOP853 per simulated second and hertz of the highest line (measured: about
#: 60 at rtol 1e-8, 80 at 1e-9, 110 at 1e-11), rounded up.
_EVALUATIONS_PER_HZ = 150.0
#: Run time of one evaluation [s]: fixed (the integrator's step and the spline) and per realisation, measured on a
#: shared machine and rounded up.
_SECONDS_PER_EVALUATION = (2e-4, 2e-5)


# --------------------------------------------------------------------------- base motion
def _base_motion(excitation: BaseExcitation, period: float, streams) -> tuple:
    """Spline of ``(u, β, u̇, β̇)`` of every realisation (columns: channel × realisation) and the highest line [Hz]."""
    lo, hi = excitation.band
    df = 1.0 / period
    k = np.arange(max(1, math.ceil(lo / df - 1e-9)), math.floor(hi / df + 1e-9) + 1)
    f = k * df
    n = 2 ** math.ceil(math.log2(OVERSAMPLING * hi * period))
    w = 2.0 * math.pi * f
    columns = []
    for g in streams:
        z = np.zeros((6, f.size), dtype=complex)
        for c, p in enumerate(excitation.profiles):
            noise = g.standard_normal((2, f.size))
            if p is not None:
                z[c] = np.sqrt(p.at(f) * df) * (noise[0] + 1j * noise[1])
        # displacement u = −A/ω², rotation β = Ω/(iω), and their rates u̇ = A/(iω), β̇ = Ω
        motion = np.concatenate([-z[3:] / w**2, z[:3] / (1j * w), z[3:] / (1j * w), z[:3]])
        spec = np.zeros((12, n // 2 + 1), dtype=complex)
        spec[:, k] = 0.5 * n * motion
        columns.append(np.fft.irfft(spec, n=n, axis=1))
    grid = np.stack(columns, axis=-1)  # (channel, time, realisation)
    values = np.moveaxis(grid, 1, 0).reshape(n, -1)  # (time, channel × realisation)
    pad = 8
    values = np.concatenate([values[-pad:], values, values[:pad]])
    times = np.arange(-pad, n + pad) * (period / n)
    return make_interp_spline(times, values, k=5), float(f[-1])


def _rigid_body(y, base, mass, inertia, inverse, arm, r, k, d, p, g, dy, f):
    """Derivatives ``dy`` (19, M) and specific force ``f`` (3, M) of states ``y`` (19, M) with base motion ``base`` (12, M).

    Per realisation: the isolators' forces from the relative displacement and
    velocity of their two attachment points, Newton's law for the centre of
    mass, Euler's equations for the rotation (module docstring).  ``arm``
    (N, 3) are the block's attachment points from the centre of mass, ``r``
    (N, 3) the base's from O, ``p`` the IMU point from the centre of mass.
    """
    for m in range(y.shape[1]):
        x0, x1, x2 = y[0, m], y[1, m], y[2, m]
        v0, v1, v2 = y[3, m], y[4, m], y[5, m]
        qn = math.sqrt(y[6, m] ** 2 + y[7, m] ** 2 + y[8, m] ** 2 + y[9, m] ** 2)
        qw, qx, qy, qz = y[6, m] / qn, y[7, m] / qn, y[8, m] / qn, y[9, m] / qn
        w0, w1, w2 = y[10, m], y[11, m], y[12, m]
        # R (block to inertial) of the attitude quaternion
        r00, r01, r02 = 1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)
        r10, r11, r12 = 2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)
        r20, r21, r22 = 2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)
        wi0, wi1, wi2 = r00 * w0 + r01 * w1 + r02 * w2, r10 * w0 + r11 * w1 + r12 * w2, r20 * w0 + r21 * w1 + r22 * w2
        # the base: R_b = exp[β×] (Rodrigues), ω_b = J_l(β) β̇
        u0, u1, u2, b0, b1, b2 = base[0, m], base[1, m], base[2, m], base[3, m], base[4, m], base[5, m]
        ud0, ud1, ud2, bd0, bd1, bd2 = base[6, m], base[7, m], base[8, m], base[9, m], base[10, m], base[11, m]
        bb = b0 * b0 + b1 * b1 + b2 * b2
        if bb < 1e-8:
            a1, a2, a3 = 1.0 - bb / 6.0 + bb * bb / 120.0, 0.5 - bb / 24.0 + bb * bb / 720.0, 1.0 / 6.0 - bb / 120.0 + bb * bb / 5040.0
        else:
            b = math.sqrt(bb)
            a1, a2, a3 = math.sin(b) / b, (1.0 - math.cos(b)) / bb, (b - math.sin(b)) / (bb * b)
        c0, c1, c2 = b1 * bd2 - b2 * bd1, b2 * bd0 - b0 * bd2, b0 * bd1 - b1 * bd0
        e0, e1, e2 = b1 * c2 - b2 * c1, b2 * c0 - b0 * c2, b0 * c1 - b1 * c0
        wb0, wb1, wb2 = bd0 + a2 * c0 + a3 * e0, bd1 + a2 * c1 + a3 * e1, bd2 + a2 * c2 + a3 * e2
        fs0 = fs1 = fs2 = 0.0
        t0 = t1 = t2 = 0.0
        for i in range(arm.shape[0]):
            # the block's attachment point from the centre of mass, inertial axes, and its velocity
            l0, l1, l2 = arm[i, 0], arm[i, 1], arm[i, 2]
            a0_, a1_, a2_ = r00 * l0 + r01 * l1 + r02 * l2, r10 * l0 + r11 * l1 + r12 * l2, r20 * l0 + r21 * l1 + r22 * l2
            pv0, pv1, pv2 = v0 + wi1 * a2_ - wi2 * a1_, v1 + wi2 * a0_ - wi0 * a2_, v2 + wi0 * a1_ - wi1 * a0_
            # the base's attachment point R_b r_i and its velocity
            s0, s1, s2 = r[i, 0], r[i, 1], r[i, 2]
            h0, h1, h2 = b1 * s2 - b2 * s1, b2 * s0 - b0 * s2, b0 * s1 - b1 * s0
            k0, k1, k2 = b1 * h2 - b2 * h1, b2 * h0 - b0 * h2, b0 * h1 - b1 * h0
            g0_, g1_, g2_ = s0 + a1 * h0 + a2 * k0, s1 + a1 * h1 + a2 * k1, s2 + a1 * h2 + a2 * k2
            bv0, bv1, bv2 = ud0 + wb1 * g2_ - wb2 * g1_, ud1 + wb2 * g0_ - wb0 * g2_, ud2 + wb0 * g1_ - wb1 * g0_
            # deflection: both points are at r_i at rest (x = c, u = 0)
            dl0, dl1, dl2 = x0 + a0_ - u0 - g0_, x1 + a1_ - u1 - g1_, x2 + a2_ - u2 - g2_
            F0 = -k[i, 0] * dl0 - d[i, 0] * (pv0 - bv0)
            F1 = -k[i, 1] * dl1 - d[i, 1] * (pv1 - bv1)
            F2 = -k[i, 2] * dl2 - d[i, 2] * (pv2 - bv2)
            fs0 += F0
            fs1 += F1
            fs2 += F2
            # moment about the centre of mass, block axes: arm × Rᵀ F
            B0, B1, B2 = r00 * F0 + r10 * F1 + r20 * F2, r01 * F0 + r11 * F1 + r21 * F2, r02 * F0 + r12 * F1 + r22 * F2
            t0 += l1 * B2 - l2 * B1
            t1 += l2 * B0 - l0 * B2
            t2 += l0 * B1 - l1 * B0
        vd0, vd1, vd2 = fs0 / mass, fs1 / mass, fs2 / mass
        j0 = inertia[0, 0] * w0 + inertia[0, 1] * w1 + inertia[0, 2] * w2
        j1 = inertia[1, 0] * w0 + inertia[1, 1] * w1 + inertia[1, 2] * w2
        j2 = inertia[2, 0] * w0 + inertia[2, 1] * w1 + inertia[2, 2] * w2
        n0, n1, n2 = t0 - (w1 * j2 - w2 * j1), t1 - (w2 * j0 - w0 * j2), t2 - (w0 * j1 - w1 * j0)
        wd0 = inverse[0, 0] * n0 + inverse[0, 1] * n1 + inverse[0, 2] * n2
        wd1 = inverse[1, 0] * n0 + inverse[1, 1] * n1 + inverse[1, 2] * n2
        wd2 = inverse[2, 0] * n0 + inverse[2, 1] * n1 + inverse[2, 2] * n2
        # the IMU point: a_p = v̇ + R(ω̇ × p + ω × (ω × p)); f = Rᵀ(a_p − g) + g
        m0, m1, m2 = w1 * p[2] - w2 * p[1], w2 * p[0] - w0 * p[2], w0 * p[1] - w1 * p[0]
        e0 = wd1 * p[2] - wd2 * p[1] + w1 * m2 - w2 * m1
        e1 = wd2 * p[0] - wd0 * p[2] + w2 * m0 - w0 * m2
        e2 = wd0 * p[1] - wd1 * p[0] + w0 * m1 - w1 * m0
        ap0 = vd0 + r00 * e0 + r01 * e1 + r02 * e2 - g[0]
        ap1 = vd1 + r10 * e0 + r11 * e1 + r12 * e2 - g[1]
        ap2 = vd2 + r20 * e0 + r21 * e1 + r22 * e2 - g[2]
        f[0, m] = r00 * ap0 + r10 * ap1 + r20 * ap2 + g[0]
        f[1, m] = r01 * ap0 + r11 * ap1 + r21 * ap2 + g[1]
        f[2, m] = r02 * ap0 + r12 * ap1 + r22 * ap2 + g[2]
        dy[0, m], dy[1, m], dy[2, m] = v0, v1, v2
        dy[3, m], dy[4, m], dy[5, m] = vd0, vd1, vd2
        dy[6, m] = -0.5 * (qx * w0 + qy * w1 + qz * w2)
        dy[7, m] = 0.5 * (qw * w0 + qy * w2 - qz * w1)
        dy[8, m] = 0.5 * (qw * w1 + qz * w0 - qx * w2)
        dy[9, m] = 0.5 * (qw * w2 + qx * w1 - qy * w0)
        dy[10, m], dy[11, m], dy[12, m] = wd0, wd1, wd2
        dy[13, m], dy[14, m], dy[15, m] = w0, w1, w2
        dy[16, m], dy[17, m], dy[18, m] = f[0, m], f[1, m], f[2, m]


_compiled: dict = {}


def _kernel():
    """:func:`_rigid_body` compiled with numba (on first use; cached on disk)."""
    if "rigid_body" not in _compiled:
        import numba

        _compiled["rigid_body"] = numba.njit(cache=True, nogil=True)(_rigid_body)
    return _compiled["rigid_body"]


class _RigidBody:
    """The block's equations of motion for R realisations, states laid out (19, M) with M = times × realisations."""

    def __init__(self, mount: Mount, spline, realisations: int):
        self.mass = float(mount.mass)
        self.inertia = np.ascontiguousarray(mount.inertia, dtype=float)
        self.inverse = np.linalg.inv(self.inertia)
        r = np.array([iso.position for iso in mount.isolators], dtype=float)
        self.r = r
        self.arm = r - np.asarray(mount.cg)
        self.k = np.array([iso.stiffness for iso in mount.isolators], dtype=float)
        self.d = np.array([iso.damping for iso in mount.isolators], dtype=float)
        self.p = np.asarray(mount.imu, dtype=float) - np.asarray(mount.cg)
        self.g = np.asarray(mount.gravity, dtype=float).copy()
        self.spline, self.R = spline, realisations
        self.kernel = _kernel()
        self.calls = 0

    def base(self, t) -> np.ndarray:
        """``(u, β, u̇, β̇)`` (12, M) at the times t (a scalar: M = R; an array (T,): M = T R, time-major)."""
        s = np.asarray(self.spline(t)).reshape(-1, 12, self.R)
        return np.ascontiguousarray(np.moveaxis(s, 1, 0).reshape(12, -1))

    def derivatives(self, t, y) -> tuple:
        """``(ẏ, f)``: state derivatives (19, M) and the specific force's vibration (3, M) for states y (19, M)."""
        self.calls += 1
        y = np.ascontiguousarray(y)
        dy = np.empty_like(y)
        f = np.empty((3, y.shape[1]))
        self.kernel(y, self.base(t), self.mass, self.inertia, self.inverse, self.arm, self.r, self.k, self.d, self.p, self.g, dy, f)
        return dy, f


@dataclass(frozen=True, eq=False)
class MountRecord:
    """Realisations of the mount's motion, sampled after the warm-up.

    Attributes
    ----------
    sample_interval : float
        h [s].
    time : ndarray (n + 1,)
        Sample times from the end of the warm-up [s].
    attitude : ndarray (R, n + 1, 4)
        Λ (block to inertial) at the samples.
    rate : ndarray (R, n + 1, 3)
        Body rate ω at the samples [rad/s].
    specific_force : ndarray (R, n + 1, 3)
        Vibration of the specific force at the IMU point [m/s²].
    gyro_increments : ndarray (R, n, 3)
        ``∫ω dt`` over each sample interval [rad].
    velocity_increments : ndarray (R, n, 3)
        ``∫f dt`` over each sample interval, block axes [m/s].
    warmup : float
        Time simulated before the first sample [s].
    highest_line : float
        Highest frequency of the base motion [Hz].
    evaluations : int
        Right-hand-side evaluations of DOP853 [count].
    """

    sample_interval: float
    time: np.ndarray
    attitude: np.ndarray
    rate: np.ndarray
    specific_force: np.ndarray
    gyro_increments: np.ndarray
    velocity_increments: np.ndarray
    warmup: float
    highest_line: float
    evaluations: int

    @property
    def realisations(self) -> int:
        """R [count]."""
        return self.rate.shape[0]

    @property
    def channels(self) -> np.ndarray:
        """``(ω, f)`` samples, shape (R, n + 1, 6), in the order of the environment's channels."""
        return np.concatenate([self.rate, self.specific_force], axis=-1)


def simulate_mount(mount: Mount, excitation: BaseExcitation, *, duration: float, sample_interval: float, realisations: int = 1, warmup: float | None = None,
                   rng=None, rtol: float = 1e-9, limits: budget.Limits | None = None) -> MountRecord:  # fmt: skip
    """Simulate ``realisations`` independent realisations of the mount under random base motion (module docstring).

    Parameters
    ----------
    mount : Mount
        The mount.
    excitation : BaseExcitation
        The base's profiles.
    duration : float
        Time sampled after the warm-up [s], > 0.
    sample_interval : float
        Sample interval h of the records [s], > 0, at most ``duration``.
    realisations : int, keyword-only
        Independent realisations R [count], ≥ 1 (integrated together).
    warmup : float, keyword-only, optional
        Time left to the transient of the start from rest [s], ≥ 0 (default:
        :data:`WARMUP_TIME_CONSTANTS` time constants ``1/(ζ ω_n)`` of the
        slowest-decaying mode).
    rng : numpy.random.Generator, SeedSequence, int or None, keyword-only
        Seed; realisation i draws from the i-th spawned child.
    rtol : float, keyword-only
        Relative tolerance of DOP853, in (1e-13, 1e-3).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a run
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`
        (naming ``duration``, ``realisations`` or ``sample_interval``).

    Returns
    -------
    MountRecord

    Raises
    ------
    TypeError
        A mount or excitation of the wrong type.
    ValueError
        Bad durations, counts or tolerances, a failed integration, or a run
        beyond ``limits``.
    """
    if not isinstance(mount, Mount):
        raise TypeError(f"Expected `mount` to be a Mount, got {type(mount).__name__}")
    if not isinstance(excitation, BaseExcitation):
        raise TypeError(f"Expected `excitation` to be a BaseExcitation, got {type(excitation).__name__}")
    duration = positive(duration, "duration")
    h = positive(sample_interval, "sample_interval")
    if h > duration:
        raise ValueError(f"Expected `sample_interval` at most `duration` = {duration:g} s, got {h:g}")
    count = as_int(realisations, "realisations", minimum=1)
    rtol = in_open_interval(rtol, "rtol", 1e-13, 1e-3)
    if warmup is None:
        slowest = min(md.damping_ratio * md.frequency * 2 * math.pi for md in mount.modes())
        warmup = WARMUP_TIME_CONSTANTS / slowest
    warmup = 0.0 if warmup == 0 else positive(warmup, "warmup")
    start = math.ceil(warmup / h) * h
    period = start + duration
    hi = excitation.band[1]
    evaluations = _EVALUATIONS_PER_HZ * hi * period
    grid = 2.0 ** math.ceil(math.log2(OVERSAMPLING * hi * period)) + 16
    fixed, per = _SECONDS_PER_EVALUATION
    # the run of one realisation (named by the duration), of all of them, then their records (named by the interval)
    one = budget.Estimate(evaluations * (fixed + per), 8.0 * 12 * grid * 3, f"`duration` = {duration:g} s after a warm-up of {start:.3g} s (base motion up to {hi:g} Hz)")
    budget.check(one, limits)
    budget.check(budget.Estimate(evaluations * (fixed + per * count), one.memory * count, f"`realisations` = {count} realisations of {period:.3g} s"), limits)
    samples = duration / h
    budget.check(budget.Estimate(0.0, 8.0 * count * (samples + 1) * (_STATES + 12) * 2, f"`sample_interval` = {h:g} s ({samples:.3g} samples of {count} realisations)"), limits)
    n = int(round(samples))
    seed = rng if isinstance(rng, np.random.SeedSequence) else np.random.SeedSequence(rng if not isinstance(rng, np.random.Generator) else rng.integers(2**63))
    streams = [np.random.default_rng(s) for s in seed.spawn(count)]
    period = start + n * h
    spline, top = _base_motion(excitation, period, streams)
    body = _RigidBody(mount, spline, count)
    y0 = np.zeros((count, _STATES))
    y0[:, 0:3] = mount.cg
    y0[:, 6] = 1.0
    scale = np.array([1e-3] * 3 + [1e-1] * 3 + [1.0] * 4 + [1.0] * 3 + [1e-2] * 3 + [1.0] * 3)
    atol = np.repeat(scale * rtol, count)
    times = start + np.arange(n + 1) * h
    sol = solve_ivp(lambda t, y: body.derivatives(t, y.reshape(_STATES, count))[0].ravel(), (0.0, times[-1]), y0.T.ravel(), method="DOP853",
                    rtol=rtol, atol=atol, t_eval=times)  # fmt: skip
    if not sol.success:
        raise ValueError(f"DOP853 failed on the mount: {sol.message}")
    states = sol.y.reshape(_STATES, count, -1)  # (19, R, n + 1)
    f = body.derivatives(times, np.swapaxes(states, 1, 2).reshape(_STATES, -1))[1].reshape(3, -1, count)  # (3, n + 1, R)
    y = np.moveaxis(states, 0, -1)  # (R, n + 1, 19)
    f = np.moveaxis(f, 0, -1).swapaxes(0, 1)
    q = y[..., 6:10] / np.linalg.norm(y[..., 6:10], axis=-1, keepdims=True)
    return MountRecord(h, times - start, q, y[..., 10:13], f, np.diff(y[..., 13:16], axis=1), np.diff(y[..., 16:19], axis=1), start, top, body.calls)


# --------------------------------------------------------------------------- spectra
@dataclass(frozen=True, eq=False)
class WelchEstimate:
    """Welch estimates of the six channels' cross-spectra, one per realisation.

    Attributes
    ----------
    frequency : ndarray (F,)
        Welch frequencies [Hz].
    estimates : ndarray of complex (R, F, 6, 6)
        One-sided cross-spectral density of each realisation, in the
        package's convention (``G_ab ∝ conj(X_a) X_b``).
    segment : int
        Samples per segment [count].
    window : ndarray (segment,)
        The window (Hann).
    sample_interval : float
        [s].
    """

    frequency: np.ndarray
    estimates: np.ndarray
    segment: int
    window: np.ndarray
    sample_interval: float

    @property
    def mean(self) -> np.ndarray:
        """Mean over the realisations (F, 6, 6)."""
        return self.estimates.mean(axis=0)

    @property
    def standard_error(self) -> np.ndarray:
        """Standard error of the mean of the real and of the imaginary parts, complex (F, 6, 6)."""
        r = self.estimates.shape[0]
        return (np.std(self.estimates.real, axis=0, ddof=1) + 1j * np.std(self.estimates.imag, axis=0, ddof=1)) / math.sqrt(r)

    def half_width(self, level: float = 0.95) -> np.ndarray:
        """Half-width of the two-sided Student-t interval of the mean at ``level``, real and imaginary parts, complex (F, 6, 6).

        Parameters
        ----------
        level : float
            Confidence level of each interval, in (0, 1).

        Returns
        -------
        ndarray of complex
        """
        level = in_open_interval(level, "level", 0.0, 1.0)
        r = self.estimates.shape[0]
        if r < 2:
            raise ValueError(f"Expected at least two realisations for an interval, got {r}")
        return student_t.ppf(0.5 + 0.5 * level, r - 1) * self.standard_error

    def covers(self, expected, level: float = 0.95) -> np.ndarray:
        """Whether each real and imaginary part of ``expected`` (F, 6, 6) lies in its interval: bool (F, 6, 6, 2).

        Parameters
        ----------
        expected : array_like of complex, shape (F, 6, 6)
            The values to check.
        level : float
            Confidence level of each interval.

        Returns
        -------
        ndarray of bool
        """
        e = np.asarray(expected, dtype=complex)
        hw, m = self.half_width(level), self.mean
        return np.stack([np.abs(e.real - m.real) <= hw.real, np.abs(e.imag - m.imag) <= hw.imag], axis=-1)


def welch_cross_spectra(record: MountRecord, *, segment: int) -> WelchEstimate:
    """Welch's estimate of the cross-spectra of each realisation (``scipy.signal.csd``, Hann, half overlap, no detrending).

    Parameters
    ----------
    record : MountRecord
        The simulated realisations.
    segment : int, keyword-only
        Samples per segment [count], at least 8 and at most the record's length.

    Returns
    -------
    WelchEstimate

    References
    ----------
    Welch (1967); Bendat & Piersol (2010), section 11.5.
    """
    x = record.channels
    segment = as_int(segment, "segment", minimum=8)
    if segment > x.shape[1]:
        raise ValueError(f"Expected `segment` at most the record's {x.shape[1]} samples, got {segment}")
    fs = 1.0 / record.sample_interval
    a = np.moveaxis(x, -1, 1)[:, :, None, :]  # (R, 6, 1, n)
    b = np.moveaxis(x, -1, 1)[:, None, :, :]  # (R, 1, 6, n)
    freq, p = signal.csd(a, b, fs=fs, window="hann", nperseg=segment, detrend=False, scaling="density", axis=-1)
    return WelchEstimate(freq, np.moveaxis(p, -1, 1), segment, signal.get_window("hann", segment), record.sample_interval)


def expected_welch(density, line_frequency, line_spacing: float, estimate: WelchEstimate, frequency) -> np.ndarray:
    """The expected Welch estimate at ``frequency`` of a multisine with cross-power ``density · line_spacing`` on its lines.

    For lines ``f_k`` carrying ``E[½ conj(Z_a) Z_b] = G_ab(f_k) Δf``, each
    Welch segment's expected one-sided estimate is
    ``Σ_k Δf [G(f_k) |W(f − f_k)|² + conj(G(f_k)) |W(f + f_k)|²] / (f_s Σ w²)``
    with ``W(ν) = Σ_n w_n e^{−i2πν n h}`` the window's transform: the density
    seen through the estimator's spectral kernel (Bendat & Piersol 2010,
    section 8.5).

    Parameters
    ----------
    density : array_like of complex, shape (K, 6, 6)
        ``G(f_k)`` at the lines (a closed form).
    line_frequency : array_like, shape (K,)
        The lines f_k [Hz].
    line_spacing : float
        Δf [Hz].
    estimate : WelchEstimate
        Supplies the window and the sample interval.
    frequency : array_like, shape (F,)
        Where to evaluate [Hz].

    Returns
    -------
    ndarray of complex, shape (F, 6, 6)
    """
    g = np.asarray(density, dtype=complex)
    fk = np.asarray(line_frequency, dtype=float)
    f = np.asarray(frequency, dtype=float)
    w = estimate.window
    h = estimate.sample_interval
    n = np.arange(w.size)

    def kernel(nu):  # |W(ν)|² for ν of shape (F, K)
        return np.abs(np.exp(-2j * np.pi * nu[..., None] * n * h) @ w) ** 2

    norm = (1.0 / h) * np.sum(w**2)
    minus = kernel(f[:, None] - fk[None, :]) * line_spacing / norm
    plus = kernel(f[:, None] + fk[None, :]) * line_spacing / norm
    return np.einsum("fk,kab->fab", minus, g) + np.einsum("fk,kab->fab", plus, np.conj(g))


# --------------------------------------------------------------------------- drift
@dataclass(frozen=True, eq=False)
class SimulatedDrift:
    """Coning drift of an algorithm run on the simulated gyro increments.

    Attributes
    ----------
    algorithm : Algorithm
    drifts : ndarray (R, 3)
        Slope of ``rotvec(Λ_true ∘ Λ̄_computed)`` of each realisation, inertial axes [rad/s].
    """

    algorithm: Algorithm
    drifts: np.ndarray

    @property
    def mean(self) -> np.ndarray:
        """Mean drift vector (3,) [rad/s]."""
        return self.drifts.mean(axis=0)

    @property
    def standard_error(self) -> np.ndarray:
        """Standard error of each component of the mean (3,) [rad/s]."""
        return np.std(self.drifts, axis=0, ddof=1) / math.sqrt(self.drifts.shape[0])

    def half_width(self, level: float = 0.95) -> np.ndarray:
        """Half-width of the Student-t interval of each component at ``level`` (3,) [rad/s].

        Parameters
        ----------
        level : float
            Confidence level, in (0, 1).

        Returns
        -------
        ndarray
        """
        level = in_open_interval(level, "level", 0.0, 1.0)
        return student_t.ppf(0.5 + 0.5 * level, self.drifts.shape[0] - 1) * self.standard_error


def simulated_drift(algorithm: Algorithm, record: MountRecord) -> SimulatedDrift:
    """Run ``algorithm`` on the gyro increments of every realisation and measure its drift.

    The computed attitude starts at the true one at the first sample of the
    algorithm's first whole step, and is composed step by step
    (:func:`strapdown.analysis.coning.simulator.prefix_product`); the drift is
    the least-squares slope of the error rotation vector at the step ends
    (:func:`strapdown.analysis.coning.simulator.drift_rate`).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (cross-step indices allowed).
    record : MountRecord
        The simulated realisations.

    Returns
    -------
    SimulatedDrift

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm.
    ValueError
        A record too short for two steps.
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    inc = record.gyro_increments
    n_steps = (inc.shape[1] - algorithm.history) // algorithm.samples
    if n_steps < 2:
        raise ValueError(f"Expected a record of at least two steps of {algorithm.name}, got {inc.shape[1]} samples")
    inc = inc[:, : algorithm.history + n_steps * algorithm.samples]
    dphi = increment(algorithm, step_windows(inc, algorithm.samples, algorithm.history))  # (R, steps, 3)
    first = algorithm.history  # the sample where the first step starts
    q0 = record.attitude[:, first]
    chain = prefix_product(np.concatenate([q0[:, None], quat.rotvec_to_quat(dphi)], axis=1))
    ends = first + np.arange(n_steps + 1) * algorithm.samples
    truth = record.attitude[:, ends]
    error = quat.quat_to_rotvec(quat.multiply(truth, quat.conjugate(chain)))
    return SimulatedDrift(algorithm, drift_rate(record.time[ends], error))
