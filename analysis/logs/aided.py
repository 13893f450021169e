"""GNSS-aided in-motion alignment of a recorded log: the navigator on the log's increments, corrected at its GNSS fixes.

The navigator and the error model are those of the simulated aided alignment
(:func:`~strapdown.analysis.alignment.aided.navigator_step`,
:func:`~strapdown.analysis.alignment.error_model.navigation_error_model` with
position states and transport rate, 15 states ``(φ, δv, δp, ε, ∇)``, biases in
body axes).  A recorded drive has no true trajectory to linearise along, so the
filter is an extended one: between two fixes the model is taken at the
navigator's own estimate (its latitude, velocity, attitude and the mean specific
force of the interval), discretised exactly (Van Loan), and filterpy predicts
and updates the covariance; the closed loop feeds the whole estimate back after
each update.  The measurement is the navigator's velocity and position minus the
fix's (interpolated to the epoch boundary), so the innovation, its covariance
``S`` and the NIS come from the data alone.

Start: at the first epoch boundary with a fix, the position and velocity are the
fix's (without GNSS velocities, 2 s later, with the velocity and acceleration of a
quadratic fitted to the fixes of ±2 s and the prior's velocity σ raised to the
fit's), the tilts level the specific force less the GNSS acceleration, and the
heading is the course over ground ``atan2(v_E, v_N)`` (a vehicle whose body x
axis points along its track; the prior's azimuth σ must cover the slip) or the one
given.  The GNSS antenna is taken at the IMU (no lever arm).

Public API
----------
.. autosummary::

   AidedLogResult
   aided_log_alignment
   GNSS_NAMES
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..alignment.aided import AidedTuning, navigator_step, ned_offset
from ..alignment.error_model import navigation_error_model
from ..alignment.preintegration import preintegrate
from ..alignment.tilt_attitude import angles_from_matrix, attitude_matrix, tilts_from_specific_force
from ..alignment.trajectory import radii
from ..core import budget, kalman
from ..core import quaternion as quat
from ..core.progress import bar
from .filter_history import FilterHistory, filter_history
from .imu_log import ImuLog
from .inventory import GnssTrack

__all__ = ["AidedLogResult", "aided_log_alignment", "GNSS_NAMES"]

#: The measurements of one fix: NED velocity [m/s] and NED position [m] of the navigator minus the fix's.
GNSS_NAMES = ("v_N", "v_E", "v_D", "p_N", "p_E", "p_D")

_MIN_SPEED = 1.0  # [m/s]: below it the course over ground does not give a heading
_FIT = 2.0  # [s]: half-width of the fixes fitted for the start's velocity where the fixes have none


@dataclass(frozen=True)
class AidedLogResult:
    """The aided alignment of a log.

    Attributes
    ----------
    heading, beta, gamma : float
        The attitude at the end of the log's last whole epoch [rad] (navigated from the last update).
    time : float
        That instant, from the segment's start [s].
    heading_sigma : float
        The filter's azimuth standard deviation there [rad] (predicted from the last update).
    tilt_sigma : tuple of float
        Its standard deviations of the north and east tilts [rad].
    gyro_bias, accel_bias : ndarray
        ``(3,)`` the bias estimates, body axes [rad/s, m/s²].
    history : FilterHistory
        σ, bias estimates, innovations and NIS at every update.
    initial_heading : float
        The heading the navigator started from [rad].
    start : float
        Time the navigator started, from the segment's start [s].
    """

    heading: float
    beta: float
    gamma: float
    time: float
    heading_sigma: float
    tilt_sigma: tuple
    gyro_bias: np.ndarray
    accel_bias: np.ndarray
    history: FilterHistory
    initial_heading: float
    start: float


def _expm(X: np.ndarray) -> np.ndarray:
    """``exp(X)`` by scaling, an order-16 Taylor polynomial and squaring, in numpy matrix products.

    The same as :func:`scipy.linalg.expm` to round-off for these models (‖X‖ ≲ 10³); scipy's
    Padé step goes through LAPACK calls that take milliseconds on a loaded machine with a threaded
    BLAS, where these products of 30 × 30 matrices take microseconds, and the filter discretises once per fix.
    """
    s = max(0, int(math.ceil(math.log2(max(np.abs(X).sum(axis=0).max(), 1e-300)))) + 1)
    Y = X / 2.0**s
    out = np.eye(X.shape[0])
    term = np.eye(X.shape[0])
    for k in range(1, 17):
        term = term @ Y / k
        out = out + term
    for _ in range(s):
        out = out @ out
    return out


def _discretise(A, Qc, dt: float):
    """``(Φ, Q_d)`` of ``x' = A x + w``, ``E w wᵀ = Qc δ``, by Van Loan's block exponential (:func:`~strapdown.analysis.core.kalman.discretise` with :func:`_expm`)."""
    n = A.shape[0]
    Mx = np.zeros((2 * n, 2 * n))
    Mx[:n, :n] = -A
    Mx[:n, n:] = Qc
    Mx[n:, n:] = A.T
    X = _expm(Mx * dt)
    Phi = X[n:, n:].T
    Qd = Phi @ X[:n, n:]
    return Phi, 0.5 * (Qd + Qd.T)


def _interp(t_query, t, x):
    x = np.asarray(x, dtype=float)
    if x.ndim == 1:
        return np.interp(t_query, t, x)
    return np.stack([np.interp(t_query, t, x[:, i]) for i in range(x.shape[1])], axis=-1)


def aided_log_alignment(
    log: ImuLog, gnss: GnssTrack, *, tuning: AidedTuning | None = None, heading: float | None = None, limits: budget.Limits | None = None, progress: bool = False
) -> AidedLogResult:
    """Align a moving log with its GNSS fixes by the extended aided filter.

    Parameters
    ----------
    log : ImuLog
        The samples (times from the log's start, as the fixes').
    gnss : GnssTrack
        The fixes (velocity where the log has it; positions always).
    tuning : AidedTuning, optional, keyword-only
        The filter: epoch, interval between updates, GNSS noise, prior, sensor noise and biases.
    heading : float, optional, keyword-only
        Initial heading [rad] (default: the course over ground at the start).
    limits : Limits, optional, keyword-only
        Largest estimated memory and run time (default 2 GB, 300 s), naming ``log``.
    progress : bool, keyword-only
        Progress on stderr.

    Returns
    -------
    AidedLogResult

    Raises
    ------
    ValueError
        Fixes that do not overlap the log, fewer than two updates, a vehicle too slow at the start to
        take the course as heading (give ``heading``), or work beyond ``limits``.

    References
    ----------
    Groves (2013), sec. 14.2 (the INS/GNSS error model), 3.4 (the extended Kalman filter);
    Bar-Shalom, Li & Kirubarajan (2001), sec. 5.4 (NIS).
    """
    tuning = AidedTuning() if tuning is None else tuning
    if not isinstance(gnss, GnssTrack):
        raise TypeError(f"Expected `gnss` to be a GnssTrack, got {type(gnss).__name__}")
    dt = log.dt
    M = max(1, int(round(tuning.epoch / dt)))
    D = M * dt
    K = max(1, int(round(tuning.gnss_interval / D)))
    t0 = float(log.time[0]) - dt  # the start of the first sample interval
    E = log.n_samples // M
    tb = t0 + D * np.arange(E + 1)  # epoch boundaries
    tg = np.asarray(gnss.time, dtype=float)
    has_vel = gnss.velocity is not None
    # without velocities, the start's velocity and acceleration are fitted to the fixes of ±2 s around it
    j0 = int(np.searchsorted(tb, tg[0] + (0.0 if has_vel else _FIT)))
    j_end = int(np.searchsorted(tb, tg[-1], side="right")) - 1
    U = (min(E, j_end) - j0) // K if j_end > j0 else 0
    if U < 2:
        raise ValueError(f"Expected GNSS fixes over at least two updates of the log ({t0:.4g}..{tb[-1]:.4g} s), got fixes over {tg[0]:.4g}..{tg[-1]:.4g} s")
    what = f"`log` of {log.n_samples:.3g} samples ({E - j0:.3g} navigator epochs, {U} GNSS updates)"
    budget.check(budget.Estimate(budget.AIDED_EPOCH_SECONDS * (E - j0) + budget.AIDED_FIX.estimate(U, what=what).seconds, 200.0 * log.n_samples + 4e4 * U, what), limits)
    ep = preintegrate(log.dtheta[None, j0 * M : E * M], log.dv[None, j0 * M : E * M], dt, M)
    vel = np.asarray(gnss.velocity, dtype=float) if has_vel else None
    rows = np.arange(6) if has_vel else np.arange(3, 6)

    # the start: position and velocity of the fix, tilts from gravity, heading from the course
    ts = tb[j0]
    lat, lon, h = (np.array([float(_interp(ts, tg, x))]) for x in (gnss.latitude, gnss.longitude, gnss.altitude))
    prior_velocity = tuning.prior_velocity
    if has_vel:
        v = _interp(np.array([ts]), tg, vel)
        a_n = _interp(np.array([ts + 1.0]), tg, vel)[0] - v[0]  # the GNSS acceleration over the first second [m/s²]
    else:
        near = np.abs(tg - ts) <= _FIT
        if np.count_nonzero(near) < 5:
            raise ValueError(f"Expected at least five GNSS fixes within {_FIT:g} s of the start ({ts:.4g} s) to fit its velocity, got {np.count_nonzero(near)}")
        ned = ned_offset(gnss.latitude[near], gnss.longitude[near], gnss.altitude[near], lat[0], lon[0], h[0])
        coef = np.polyfit(tg[near] - ts, ned, 2)  # (3 powers, 3 axes): acceleration/2, velocity, offset
        v, a_n = coef[1][None], 2.0 * coef[0]
        # the slope's standard deviation under the position noise: the velocity the prior must cover
        X = np.vander(tg[near] - ts, 3)
        prior_velocity = max(prior_velocity, float(tuning.position_noise * math.sqrt(np.linalg.inv(X.T @ X)[1, 1])))
    if heading is None:
        speed = float(np.hypot(v[0, 0], v[0, 1]))
        if speed < _MIN_SPEED:
            raise ValueError(f"Expected the vehicle moving at the start of the aided alignment (course over ground as heading, speed above {_MIN_SPEED:g} m/s), got {speed:.3g} m/s: give `heading`")
        psi0 = math.atan2(v[0, 1], v[0, 0])
    else:
        psi0 = float(heading)
    n1 = max(1, int(round(1.0 / dt)))
    f_body = log.dv[j0 * M : j0 * M + n1].sum(axis=0) / (n1 * dt)
    c, s = math.cos(psi0), math.sin(psi0)
    a_b = np.array([c * a_n[0] + s * a_n[1], -s * a_n[0] + c * a_n[1], a_n[2]])
    tilt = tilts_from_specific_force((f_body - a_b)[None, None, :])[0, 0]
    C0 = attitude_matrix([psi0, float(tilt[0]), float(tilt[1])])
    q = Rotation.from_matrix(C0).as_quat(scalar_first=True)[None]
    bg, ba = np.zeros((1, 3)), np.zeros((1, 3))
    P = np.diag(
        np.square([tuning.prior_tilt, tuning.prior_tilt, tuning.prior_heading] + [prior_velocity] * 3 + [tuning.prior_position] * 3 + [tuning.gyro_bias] * 3 + [tuning.accel_bias] * 3)
    )
    R = np.diag([tuning.velocity_noise**2] * 3 + [tuning.position_noise**2] * 3)[np.ix_(rows, rows)]
    times, sig, gbs, abs_, ys, nis = [], [], [], [], [], []
    f_sum = np.zeros(3)
    with bar(desc="aided alignment", total=E - j0, enabled=progress, unit="epoch") as pbar:
        for j in range(E - j0):  # one navigator step per epoch, to the log's last whole epoch
            f_sum += quat.rotate(q, ep.velocity[:, j])[0]
            q, v, lat, lon, h = navigator_step(q, v, lat, lon, h, bg, ba, ep.rotation[:, j], ep.velocity[:, j], ep.moment[:, j], D)
            if (j + 1) % K or j + 1 > U * K:
                continue
            pbar.update(K)
            t_now = tb[j0 + j + 1]
            Cn = Rotation.from_quat(q[0], scalar_first=True).as_matrix()
            f_n = f_sum / (K * D)
            f_sum[:] = 0.0
            model = navigation_error_model(
                float(lat[0]), velocity=v[0], specific_force=f_n, attitude=Cn, height=float(h[0]), biases="body", position=True, transport=True,
                gyro_noise=tuning.gyro_noise, accel_noise=tuning.accel_noise, gyro_bias_walk=tuning.gyro_bias_walk, accel_bias_walk=tuning.accel_bias_walk,
            )  # fmt: skip
            F, Q = _discretise(model.A, model.Qc, K * D)
            H = model.H[rows]
            g_lat, g_lon, g_alt = (float(_interp(t_now, tg, x)) for x in (gnss.latitude, gnss.longitude, gnss.altitude))
            z = ned_offset(lat, lon, h, g_lat, g_lon, g_alt)[0]
            if has_vel:
                z = np.concatenate([v[0] - _interp(np.array([t_now]), tg, vel)[0], z])
            kf = kalman.make_filter(F, Q, H, R, np.zeros(15), P)
            kf.predict()
            kf.update(z.reshape(-1, 1))
            x = kf.x[:, 0]
            P = 0.5 * (kf.P + kf.P.T)
            y = np.asarray(kf.y, dtype=float).ravel()
            nis.append(float(kalman.nis(y, kf.S)))
            # the closed loop: the whole estimate fed back, the error state reset to zero
            q = quat.normalize(quat.multiply(quat.rotvec_to_quat(x[None, 0:3], validate=False), q))
            RN, RE = radii(lat)
            v = v - x[None, 3:6]
            lat = lat - x[6] / (RN + h)
            lon = lon - x[7] / ((RE + h) * np.cos(lat))
            h = h + x[8]
            bg, ba = bg + x[None, 9:12], ba + x[None, 12:15]
            times.append(t_now - t0)
            sig.append(np.sqrt(np.diag(P)[0:3]))
            gbs.append(bg[0].copy())
            abs_.append(ba[0].copy())
            ys.append(y)
    rest = E - j0 - U * K  # epochs after the last fix: the covariance predicted to the end
    if rest:
        Cn = Rotation.from_quat(q[0], scalar_first=True).as_matrix()
        model = navigation_error_model(
            float(lat[0]), velocity=v[0], specific_force=f_sum / (rest * D), attitude=Cn, height=float(h[0]), biases="body", position=True, transport=True,
            gyro_noise=tuning.gyro_noise, accel_noise=tuning.accel_noise, gyro_bias_walk=tuning.gyro_bias_walk, accel_bias_walk=tuning.accel_bias_walk,
        )  # fmt: skip
        F, Q = _discretise(model.A, model.Qc, rest * D)
        P = F @ P @ F.T + Q
    names = tuple(GNSS_NAMES[i] for i in rows)
    hist = filter_history(np.array(times), np.array(sig), np.array(gbs), np.array(abs_), np.array(ys), np.array(nis), bias_frame="body", innovation_names=names)
    a = angles_from_matrix(Rotation.from_quat(q[0], scalar_first=True).as_matrix())
    sd = np.sqrt(np.diag(P)[0:3])
    return AidedLogResult(
        float(a.heading), float(a.beta), float(a.gamma), float(tb[E] - t0), float(sd[2]), (float(sd[0]), float(sd[1])), bg[0].copy(), ba[0].copy(), hist, psi0, ts - t0,
    )  # fmt: skip

