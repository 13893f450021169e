"""The positions of a recorded log, and the multi-position alignment that combines them.

A block turned on a table (or a vehicle parked, turned and parked again) stays
in a few *positions*.  At rest in one position the averaged gyros measure the
Earth's rate plus the gyro bias and the averaged accelerometers gravity plus the
accelerometer bias, all in body axes; one position cannot tell a horizontal bias
from an attitude error (the azimuth error ``ε_E/(Ω cos φ)`` of the analytic
alignment).  Between positions the gyros measure the turn, and the biases, fixed
to the sensors, turn with the body while the Earth's rate and gravity do not.  So

    w̄_k = (C_1 R_k)ᵀ ω_ie^n + ε,    f̄_k = (C_1 R_k)ᵀ (−g^n) + ∇     (k = 1 … K)

with ``R_k`` the turn of position k from the first (from the gyros, the Earth's
turn taken out), determine the attitude ``C_1`` of the first position and both
biases together once the turns are large enough: 6K equations in 9 unknowns,
solved by Gauss–Newton, weighted by the noise of each position's means
(``ARW²/T_k``, ``VRW²/T_k``), whose normal matrix is then the covariance of the
estimate.

:func:`find_positions` finds the positions the way
:func:`~strapdown.analysis.logs.alignment.recorded_problem` does (the attitude
relative to the Earth averaged over windows; a new position where the mean has
turned by more than ``threshold``) and then keeps, of each, the still stretch:
the epochs within ``threshold``/2 of the position's attitude, less ``margin``
seconds at each end so that no part of a turn enters the averages (a turn of 1°
left in a 5-minute average biases it by 12 °/h, almost the Earth's rate).

The turns ``R_k`` come from the gyros, whose angle random walk between the two
stretches' means leaves each an error of variance ``ARW² (gap + T_1/3 + T_k/3)``
per axis; these errors are estimated with the rest, with that variance as
their prior, so that the covariance of the attitude counts them.

Public API
----------
.. autosummary::

   LogPosition
   position_windows
   find_positions
   MultiPositionAlignment
   multiposition_alignment
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.spatial.transform import Rotation

from ..alignment.analytic import analytic_alignment
from ..alignment.earth import earth_rate_ned, gravity_ned
from ..alignment.preintegration import chain_rotations, preintegrate
from ..alignment.tilt_attitude import attitude_matrix
from ..core.validation import nonnegative, positive
from .imu_log import ImuLog
from .records import log_record

__all__ = ["LogPosition", "position_windows", "find_positions", "MultiPositionAlignment", "multiposition_alignment"]

_RESOLUTION = 0.1  # epoch of the attitude track [s]


@dataclass(frozen=True)
class LogPosition:
    """One still stretch of a log.

    Attributes
    ----------
    start, end : int
        Its samples ``[start, end)`` in the segment [count].
    time_start, time_end : float
        Its span, from the segment's start [s].
    turn : ndarray
        ``(3, 3)`` R_k: the body in this position relative to the first position (the Earth's turn out).
    """

    start: int
    end: int
    time_start: float
    time_end: float
    turn: np.ndarray

    @property
    def duration(self) -> float:
        """Length of the stretch [s]."""
        return self.time_end - self.time_start

    @property
    def angle(self) -> float:
        """Angle of the turn from the first position [rad]."""
        return float(Rotation.from_matrix(self.turn).magnitude())


def position_windows(R: Rotation, epoch: float, window: float, threshold: float) -> tuple:
    """The positions of an attitude track: its means over windows, and the windows where a new position starts.

    A new position starts at the first window whose mean attitude has turned by more than
    ``threshold`` from the first window of the current position (the rule of
    :func:`~strapdown.analysis.logs.alignment.recorded_problem` and :func:`find_positions`).

    Parameters
    ----------
    R : scipy.spatial.transform.Rotation
        ``E + 1`` attitudes at the epoch boundaries (the body relative to the Earth).
    epoch : float
        Their spacing [s].
    window : float
        Averaging window [s].
    threshold : float
        Turn that starts a new position [rad].

    Returns
    -------
    per : int
        Epochs per window [count].
    means : list of Rotation
        The mean attitude of each window.
    first : list of int
        The first window of each position (``first[0] == 0``).
    """
    per = max(1, int(round(window / epoch)))
    n_windows = max(1, (len(R) - 1) // per)
    means = [R[w * per : (w + 1) * per + 1].mean() for w in range(n_windows)]
    first = [0]
    for w in range(1, n_windows):
        if (means[first[-1]].inv() * means[w]).magnitude() > threshold:
            first.append(w)
    return per, means, first


def _head(log: ImuLog, n: int) -> ImuLog:
    return replace(log, time=log.time[:n], dtheta=log.dtheta[:n], dv=log.dv[:n])


def _track(log: ImuLog, latitude: float, C_start, M: int, gyro_bias=None):
    """The body relative to the Earth at the epoch boundaries, in the start body frame (a Rotation of E + 1), and the epoch [s].

    The gyros' attitude in the inertial start frame followed back by the Earth's turn
    ``exp(−[ω_ie^b0] t)``, ``ω_ie^b0 = C_startᵀ ω_ie^n``.
    """
    dth = log.dtheta if gyro_bias is None else log.dtheta - np.asarray(gyro_bias, dtype=float) * log.dt
    ep = preintegrate(dth[None], log.dv[None], log.dt, M)
    Q = chain_rotations(np.array([[1.0, 0.0, 0.0, 0.0]]), ep.rotation)[0]
    w_earth = np.asarray(C_start, dtype=float).T @ earth_rate_ned(latitude)
    t = np.arange(Q.shape[0]) * ep.epoch
    return Rotation.from_rotvec(-t[:, None] * w_earth[None, :]) * Rotation.from_quat(Q, scalar_first=True), ep.epoch


def _start_attitude(log: ImuLog, latitude: float, window: float) -> np.ndarray:
    """The analytic alignment of the first ``window`` seconds, ``C_b^n`` (3, 3)."""
    return _analytic_matrix(_head(log, max(2, min(log.n_samples, int(round(window / log.dt))))), latitude)


def _analytic_matrix(log: ImuLog, latitude: float):
    a = analytic_alignment(log_record(log, latitude))
    return attitude_matrix([float(a.heading[0]), float(a.beta[0]), float(a.gamma[0])])


def find_positions(log: ImuLog, latitude: float, *, threshold: float = math.radians(5.0), window: float = 20.0, margin: float = 2.0, C_start=None, gyro_bias=None) -> tuple:
    """The still stretches of a log, one per position, with the turn of each from the first.

    Parameters
    ----------
    log : ImuLog
        The samples.
    latitude : float
        Latitude φ [rad].
    threshold : float, keyword-only
        Turn that starts a new position [rad].
    window : float, keyword-only
        Averaging window of the attitude [s] (several rocking periods).
    margin : float, keyword-only
        Time cut from each end of a stretch that borders a turn [s].
    C_start : array_like, optional, keyword-only
        ``(3, 3)`` the attitude at the log's start, whose Earth rate is taken out of the gyros
        (default: the analytic alignment of the first ``window`` seconds).
    gyro_bias : array_like, optional, keyword-only
        ``(3,)`` a gyro bias to take out of the increments first [rad/s].

    Returns
    -------
    tuple of LogPosition
        In time order; the first has ``turn`` the identity.
    """
    threshold = positive(threshold, "threshold")
    window = positive(window, "window")
    margin = nonnegative(margin, "margin")
    M = max(1, int(round(min(_RESOLUTION, window / 10.0) / log.dt)))
    C0 = _start_attitude(log, latitude, window) if C_start is None else np.asarray(C_start, dtype=float)
    R, epoch = _track(log, latitude, C0, M, gyro_bias)
    E = len(R) - 1
    per, means, first = position_windows(R, epoch, window, threshold)
    n_windows = len(means)
    bounds = first + [n_windows]
    cut = int(round(margin / epoch))
    out, ref0 = [], None
    for i in range(len(first)):
        lo_w, hi_w = bounds[i], bounds[i + 1]
        ref = means[(lo_w + hi_w - 1) // 2]  # the middle window: away from the turns at either end
        lo = 0 if i == 0 else (lo_w - 1) * per  # the turn may start in the window before
        hi = E if i == len(first) - 1 else min(E, (hi_w + 1) * per)
        near = (ref.inv() * R[lo : hi + 1]).magnitude() < 0.5 * threshold
        runs = np.flatnonzero(np.diff(np.concatenate([[0], near.astype(np.int8), [0]])))
        starts, ends = runs[0::2], runs[1::2]
        j = int(np.argmax(ends - starts))
        a, b = lo + int(starts[j]), lo + int(ends[j]) - 1  # epoch boundaries of the run
        if i > 0:
            a += cut
        if i < len(first) - 1:
            b -= cut
        if b - a < 1:
            continue
        mean = R[a : b + 1].mean()
        ref0 = mean if ref0 is None else ref0
        out.append(LogPosition(a * M, b * M, a * epoch, b * epoch, (ref0.inv() * mean).as_matrix()))
    return tuple(out)


@dataclass(frozen=True)
class MultiPositionAlignment:
    """The multi-position alignment of a log.

    Attributes
    ----------
    attitude : ndarray
        ``(3, 3)`` ``C_b^n`` of the first position.
    end_attitude : ndarray
        ``(3, 3)`` ``C_b^n`` at the end of the log (the first position's, carried by the gyros).
    gyro_bias, accel_bias : ndarray
        ``(3,)`` the estimated biases, body axes [rad/s, m/s²].
    covariance : ndarray or None
        ``(9, 9)`` of (attitude error φ in NED [rad], ε, ∇), from the noise given (None without it).
    positions : tuple of LogPosition
        The stretches used.
    residual_rms : float
        Root-mean-square of the weighted residuals [dimensionless: 1 where the noise fits].
    """

    attitude: np.ndarray
    end_attitude: np.ndarray
    gyro_bias: np.ndarray
    accel_bias: np.ndarray
    covariance: np.ndarray | None
    positions: tuple
    residual_rms: float

    @property
    def heading_sigma(self) -> float | None:
        """Standard deviation of the azimuth [rad], None without the noise."""
        return None if self.covariance is None else float(math.sqrt(self.covariance[2, 2]))

    @property
    def tilt_sigma(self) -> tuple | None:
        """Standard deviations of the north and east tilts [rad], None without the noise."""
        return None if self.covariance is None else (float(math.sqrt(self.covariance[0, 0])), float(math.sqrt(self.covariance[1, 1])))


def _skew(v):
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def multiposition_alignment(
    log: ImuLog, latitude: float, *, gyro_noise: float = 0.0, accel_noise: float = 0.0, threshold: float = math.radians(5.0), window: float = 20.0, margin: float = 2.0
) -> MultiPositionAlignment:
    """Align a log that stays in two or more positions, estimating the gyro and accelerometer biases with the attitude.

    Parameters
    ----------
    log : ImuLog
        The samples.
    latitude : float
        Latitude φ [rad].
    gyro_noise, accel_noise : float, keyword-only
        Angle and velocity random walk [rad/√s, m/s/√s]: the weights and the covariance
        (0: weights from the sizes of the Earth's rate and gravity, and no covariance).
    threshold, window, margin : float, keyword-only
        Of :func:`find_positions` [rad, s, s].

    Returns
    -------
    MultiPositionAlignment

    Raises
    ------
    ValueError
        Fewer than two positions, or turns that cannot separate the biases from the attitude.

    References
    ----------
    Titterton & Weston (2004), sec. 10.3.3 (multi-position alignment, bias separation by
    indexing); Goshen-Meskin & Bar-Itzhack (1992) (observability of the piecewise-constant model).
    """
    gyro_noise, accel_noise = nonnegative(gyro_noise, "gyro_noise"), nonnegative(accel_noise, "accel_noise")
    W = earth_rate_ned(latitude)
    gam = -gravity_ned(latitude)  # the specific force at rest, NED
    positions = find_positions(log, latitude, threshold=threshold, window=window, margin=margin)
    if len(positions) < 2:
        raise ValueError(f"Expected a log in at least two positions (turns of more than {math.degrees(threshold):g}° between still stretches), got {len(positions)}")
    C_start = None
    bg = np.zeros(3)
    for _ in range(2):  # positions and turns again with the start attitude and gyro bias of the first solution
        if C_start is not None:
            positions = find_positions(log, latitude, threshold=threshold, window=window, margin=margin, C_start=C_start, gyro_bias=bg)
        Ts = np.array([p.duration for p in positions])
        wbar = np.array([log.dtheta[p.start : p.end].sum(axis=0) / ((p.end - p.start) * log.dt) for p in positions])
        fbar = np.array([log.dv[p.start : p.end].sum(axis=0) / ((p.end - p.start) * log.dt) for p in positions])
        Rk = np.array([p.turn for p in positions])
        first = positions[0]
        C = _analytic_matrix(replace(log, time=log.time[first.start : first.end], dtheta=log.dtheta[first.start : first.end], dv=log.dv[first.start : first.end]), latitude)
        sw = gyro_noise / np.sqrt(Ts) if gyro_noise > 0 else np.full(Ts.size, np.linalg.norm(W) * 1e-3)
        sf = accel_noise / np.sqrt(Ts) if accel_noise > 0 else np.full(Ts.size, np.linalg.norm(gam) * 1e-3)
        K = len(positions)
        # turn errors δ_k (C_k = C_1 R_k exp([δ_k×]), k ≥ 2) with the gyros' random walk between the two stretches' means as prior:
        # var = ARW² (gap + T_1/3 + T_k/3) per axis
        tau = np.array([positions[k].time_start - first.time_end + (Ts[0] + Ts[k]) / 3.0 for k in range(1, K)])
        n_turn = 3 * (K - 1) if gyro_noise > 0 else 0
        st = gyro_noise * np.sqrt(tau)
        x = np.zeros(6 + n_turn)  # ε, ∇, then the turn errors
        for _ in range(20):  # Gauss–Newton on (δ, ε, ∇[, δ_k]), C ← exp([δ×]) C
            J, r = [], []
            for k in range(K):
                Tk = Rk[k] if k == 0 or not n_turn else Rk[k] @ Rotation.from_rotvec(x[6 + 3 * (k - 1) : 9 + 3 * (k - 1)]).as_matrix()
                B = Tk.T @ C.T
                for v, bias, s, meas, col in ((W, x[0:3], sw[k], wbar[k], 3), (gam, x[3:6], sf[k], fbar[k], 6)):
                    Jk = np.zeros((3, 9 + n_turn))
                    Jk[:, 0:3] = B @ _skew(v)
                    Jk[:, col : col + 3] = np.eye(3)
                    if k > 0 and n_turn:
                        Jk[:, 9 + 3 * (k - 1) : 12 + 3 * (k - 1)] = _skew(B @ v)
                    J.append(Jk / s)
                    r.append((meas - B @ v - bias) / s)
            for k in range(1, K if n_turn else 1):  # the turn errors' prior
                Jk = np.zeros((3, 9 + n_turn))
                Jk[:, 9 + 3 * (k - 1) : 12 + 3 * (k - 1)] = np.eye(3) / st[k - 1]
                J.append(Jk)
                r.append(-x[6 + 3 * (k - 1) : 9 + 3 * (k - 1)] / st[k - 1])
            J, r = np.vstack(J), np.concatenate(r)
            sv = np.linalg.svd(J[:, :9] if not n_turn else J, compute_uv=False)
            if sv[-1] < 1e-9 * sv[0] or (n_turn and np.linalg.svd(J[: 6 * K, :9], compute_uv=False)[-1] < 1e-9 * sv[0]):
                raise ValueError(
                    f"Expected turns between the {len(positions)} positions that separate the biases from the attitude, got turns of "
                    f"{', '.join(f'{math.degrees(p.angle):.3g}°' for p in positions[1:])} that leave a combination unobservable"
                )
            dx = np.linalg.lstsq(J, r, rcond=None)[0]
            C = Rotation.from_rotvec(dx[0:3]).as_matrix() @ C
            x = x + dx[3:]
            if np.max(np.abs(dx[0:3])) < 1e-13:
                break
        bg = x[0:3]
        R, mean_1 = _first_mean(log, latitude, C_start if C_start is not None else _start_attitude(log, latitude, window), bg, positions[0])
        C_start = C @ mean_1.inv().as_matrix()  # C_1 = C_start mean_1: the start attitude that the next pass takes the Earth's rate with
    cov = np.linalg.inv(J.T @ J)[:9, :9] if gyro_noise > 0 and accel_noise > 0 else None
    rms = float(np.sqrt(np.mean(r * r)))
    R, mean_1 = _first_mean(log, latitude, C_start, bg, positions[0])
    return MultiPositionAlignment(C, C @ (mean_1.inv() * R[-1]).as_matrix(), x[0:3], x[3:6], cov, positions, rms)


def _first_mean(log: ImuLog, latitude: float, C_start, gyro_bias, first: LogPosition):
    """The Earth-relative track of the log and its mean over the first position's stretch."""
    M = max(1, int(round(_RESOLUTION / log.dt)))
    R, epoch = _track(log, latitude, C_start, M, gyro_bias)
    a, b = int(round(first.time_start / epoch)), int(round(first.time_end / epoch))
    return R, R[a : b + 1].mean()
