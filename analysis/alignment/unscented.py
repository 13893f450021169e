"""Alignment from a large initial heading error: filterpy's unscented Kalman filter on the whole navigation state.

The error-state filter of :mod:`~strapdown.analysis.alignment.fine` linearises the attitude error (``sin φ_D ≈
φ_D``); from a heading error of tens of degrees the linearisation is wrong and
the filter can settle far from the truth.  Here the state is the navigation
state itself,

    x = (ψ, β, γ, v_N, v_E, v_D, ε_x, ε_y, ε_z, ∇_x, ∇_y, ∇_z),

the attitude in the angles of :mod:`~strapdown.analysis.alignment.tilt_attitude` (ψ any angle; the
biases in body axes, stored in units of their prior standard deviations so
that the covariance stays well conditioned), propagated through the strapdown
equations of the epoch increments for every sigma point, and the zero velocity
of the block is measured.  filterpy's ``UnscentedKalmanFilter`` with
``MerweScaledSigmaPoints`` does the rest; the heading is averaged on the circle
and its residuals wrapped to (−π, π].

One filter per trial (filterpy runs one state at a time), at a coarse epoch
(the Earth rate reveals the heading over tens of seconds).  filterpy's loops
over the sigma points (the propagation, the unscented transform of the state
and the cross variance) are done for all points at once, summing in
filterpy's order: the results are filterpy's to the last bit
(``tests/test_unscented.py`` runs filterpy unmodified against them).

What the comparison in ``reports/alignment-design.md`` finds: from a small
heading error this filter and the error-state filter of :mod:`~strapdown.analysis.alignment.fine` have the
same covariance (the same information); from tens of degrees both converge,
but the closed-loop error-state filter, whose gains are those of its large
prior for longer, converges faster — its closed loop re-centres the error at
every epoch, so the small-angle model serves it well beyond its nominal range
— while this filter's unscented transform of the saturating ``sin δψ`` gives
smaller gains and it becomes confident before its error is small.

References
----------
Wan, E. A., van der Merwe, R., "The unscented Kalman filter for nonlinear
estimation", *Proc. IEEE AS-SPCC*, 2000; van der Merwe, R., *Sigma-Point Kalman
Filters for Probabilistic Inference in Dynamic State-Space Models*, PhD thesis,
OGI, 2004 (the scaled sigma points).
Labbe, R., *Kalman and Bayesian Filters in Python*, ch. 10 (filterpy's UKF).

Public API
----------
UnscentedTuning, UnscentedResult, unscented_alignment
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..core.validation import nonnegative, positive
from ..gyrocompass.rocking import as_generator
from .earth import earth_rate_ned, gravity_ned
from .error_model import skew
from .estimate import AlignmentEstimate, wrap_angle
from .imu import ImuRecord
from .preintegration import preintegrate
from .tilt_attitude import angles_from_matrix, attitude_matrix

__all__ = ["UnscentedTuning", "UnscentedResult", "unscented_alignment"]


@dataclass(frozen=True)
class UnscentedTuning:
    """What the unscented filter assumes.

    Parameters
    ----------
    epoch : float
        Measurement interval [s] (rounded to whole samples).
    prior_heading : float
        Standard deviation of the initial heading error [rad] (tens of degrees).
    prior_tilt : float
        Of the initial tilt errors [rad].
    prior_velocity : float
        [m/s].
    gyro_bias, accel_bias : float
        Prior standard deviations of the biases [rad/s, m/s²].
    gyro_noise, accel_noise : float
        Angle and velocity random walk [rad/√s, m/s/√s].
    measurement_noise : float
        Noise of the zero-velocity measurement [m/s].
    alpha, beta, kappa : float
        The scaled sigma points (van der Merwe): α = 1, κ = 0 spreads them over
        ±√n standard deviations, with a zero weight at the mean.
    """

    epoch: float = 1.0
    prior_heading: float = math.radians(30.0)
    prior_tilt: float = math.radians(0.5)
    prior_velocity: float = 1e-2
    gyro_bias: float = math.radians(0.01) / 3600.0
    accel_bias: float = 1e-4
    gyro_noise: float = 0.0
    accel_noise: float = 0.0
    measurement_noise: float = 1e-3
    alpha: float = 1.0
    beta: float = 2.0
    kappa: float = 0.0

    def __post_init__(self):
        for name in ("epoch", "prior_heading", "prior_tilt", "prior_velocity", "gyro_bias", "accel_bias", "measurement_noise", "alpha"):
            object.__setattr__(self, name, positive(getattr(self, name), name))
        for name in ("gyro_noise", "accel_noise"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))


@dataclass(frozen=True)
class UnscentedResult:
    """The unscented alignment of ``n`` trials.

    Attributes
    ----------
    estimate : AlignmentEstimate
        Heading and tilts at the end (reference ``"end"``).
    times : ndarray
        ``(E,)`` epoch ends [s].
    heading_error : ndarray
        ``(n, E)`` ``ψ̂ − ψ`` at each epoch end [rad] (NaN without the truth there).
    heading_sigma : ndarray
        ``(n, E)`` the filter's heading standard deviation [rad].
    initial_heading_error : ndarray
        ``(n,)`` [rad].
    """

    estimate: AlignmentEstimate
    times: np.ndarray
    heading_error: np.ndarray
    heading_sigma: np.ndarray
    initial_heading_error: np.ndarray


def _mean(sigmas, Wm):
    """Weighted mean of sigma points with the heading averaged on the circle."""
    x = Wm @ sigmas
    x[0] = math.atan2(Wm @ np.sin(sigmas[:, 0]), Wm @ np.cos(sigmas[:, 0]))
    return x


def _residual(a, b):
    y = a - b
    y[0] = (y[0] + math.pi) % (2.0 * math.pi) - math.pi
    return y


@functools.cache
def _batch_filter():
    """filterpy's ``UnscentedKalmanFilter`` with its sigma points propagated all at once.

    filterpy calls ``fx`` once per sigma point in a Python loop
    (``compute_process_sigmas``); here ``fx`` takes the ``(2n + 1, n)`` sigma
    points and returns them propagated, every other step being filterpy's own.
    Built on first use so that importing this module does not import filterpy.
    """
    from filterpy.kalman import UnscentedKalmanFilter

    class BatchUnscentedKalmanFilter(UnscentedKalmanFilter):
        def compute_process_sigmas(self, dt, fx=None, **fx_args):
            fx = self.fx if fx is None else fx
            self.sigmas_f = fx(self.points_fn.sigma_points(self.x, self.P), dt, **fx_args)

        def cross_variance(self, x, z, sigmas_f, sigmas_h):
            return _weighted_outer(self.Wc, _residuals(sigmas_f, x), sigmas_h - z)

    return BatchUnscentedKalmanFilter


def _residuals(a, b):
    """:func:`_residual` of every row of ``a``, at once."""
    y = a - b
    y[:, 0] = (y[:, 0] + math.pi) % (2.0 * math.pi) - math.pi
    return y


def _weighted_outer(W, Y, Z):
    """``Σ_k W_k y_k z_kᵀ`` summed in the order of k, as filterpy's loops sum it (the same bits)."""
    terms = W[:, None, None] * (Y[:, :, None] * Z[:, None, :])
    out = np.zeros(terms.shape[1:])
    for t in terms:  # in order: a pairwise sum would change the last bits
        out += t
    return out


def _transform(sigmas, Wm, Wc, noise_cov=None, mean_fn=None, residual_fn=None):
    """filterpy's ``unscented_transform`` with the heading residual applied to all sigma points at once.

    The state's transform (``residual_fn`` :func:`_residual`) sums the weighted
    outer products in filterpy's order; the measurement's (a plain difference)
    is filterpy's own.
    """
    from filterpy.kalman import unscented_transform

    if residual_fn is not _residual:
        return unscented_transform(sigmas, Wm, Wc, noise_cov, mean_fn, residual_fn)
    x = mean_fn(sigmas, Wm)
    P = _weighted_outer(Wc, _residuals(sigmas, x), _residuals(sigmas, x))
    if noise_cov is not None:
        P += noise_cov
    return x, P


def unscented_alignment(record: ImuRecord, tuning: UnscentedTuning | None = None, *, rng=None, initial_errors=None) -> UnscentedResult:
    """Align every trial of a record with filterpy's unscented Kalman filter, from a large heading error.

    Parameters
    ----------
    record : ImuRecord
        Sensor increments at rest or rocking at the rocking centre, with the
        truth every epoch to follow the error (else at the end only).
    tuning : UnscentedTuning, optional
        What the filter assumes (default :class:`UnscentedTuning`).
    rng : Generator | SeedSequence | int | None, keyword-only
        Stream of the initial errors (from the prior) and of the measurement noise.
    initial_errors : array_like, optional, keyword-only
        ``(n, 3)`` errors of the initial (ψ, β, γ) [rad] (default drawn from the prior).

    Returns
    -------
    UnscentedResult

    Raises
    ------
    TypeError
        If ``record`` is not an ImuRecord.

    References
    ----------
    Wan & van der Merwe (2000); filterpy's ``UnscentedKalmanFilter`` and ``MerweScaledSigmaPoints``.
    """
    from filterpy.kalman import MerweScaledSigmaPoints

    if not isinstance(record, ImuRecord):
        raise TypeError(f"Expected `record` to be an ImuRecord, got {type(record).__name__}")
    t = UnscentedTuning() if tuning is None else tuning
    g = as_generator(rng)
    sc = record.scenario
    M = max(1, int(round(t.epoch / sc.dt)))
    ep = preintegrate(record.dtheta, record.dv, sc.dt, M)
    n, E, D = record.n_trials, ep.n_epochs, ep.epoch
    dR = Rotation.from_quat(ep.rotation.reshape(-1, 4), scalar_first=True).as_matrix().reshape(n, E, 3, 3)
    W, gn = earth_rate_ned(sc.latitude), gravity_ned(sc.latitude)
    Wx = skew(W)
    E_earth = Rotation.from_rotvec(-W * D).as_matrix()
    sg, sa = t.gyro_bias, t.accel_bias

    def fx(x, dt, R, dV, S):
        """The sigma points ``x`` (``(k, 12)``) propagated over one epoch, all at once."""
        C = attitude_matrix(x[:, 0:3])
        bg, ba = x[:, 6:9] * sg, x[:, 9:12] * sa
        v = x[:, 3:6]
        v = v + (C @ (dV - ba * D)[:, :, None])[:, :, 0] - (Wx @ (C @ S)[:, :, None])[:, :, 0] + gn * D - 2.0 * D * (Wx @ v[:, :, None])[:, :, 0]
        C = E_earth @ C @ R @ Rotation.from_rotvec(-bg * D).as_matrix()
        a = angles_from_matrix(C)
        out = x.copy()
        out[:, 0], out[:, 1], out[:, 2] = a.heading, a.beta, a.gamma
        out[:, 3:6] = v
        return out

    def hx(x):
        return x[3:6]

    points = MerweScaledSigmaPoints(12, alpha=t.alpha, beta=t.beta, kappa=t.kappa, subtract=_residual)
    P0 = np.diag(np.square([t.prior_heading, t.prior_tilt, t.prior_tilt] + [t.prior_velocity] * 3 + [1.0] * 6))
    Q = np.diag(np.square([t.gyro_noise] * 3 + [t.accel_noise] * 3 + [0.0] * 6) * D + 1e-14)
    R = t.measurement_noise**2 * np.eye(3)
    truth_every = record.truth_times.size >= E + 1 and np.allclose(record.truth_times[: E + 1], D * np.arange(E + 1))
    heading_err = np.full((n, E), np.nan)
    heading_sig = np.empty((n, E))
    final = np.empty((n, 3))
    x0_err = g.standard_normal((n, 3)) * np.array([t.prior_heading, t.prior_tilt, t.prior_tilt])
    if initial_errors is not None:
        x0_err = np.asarray(initial_errors, dtype=float).reshape(n, 3)
    noise = t.measurement_noise * g.standard_normal((n, E, 3))
    for i in range(n):  # filterpy runs one state at a time
        ukf = _batch_filter()(12, 3, D, hx, fx, points, x_mean_fn=_mean, z_mean_fn=None, residual_x=_residual)
        ukf.x = np.zeros(12)
        ukf.x[0:3] = record.truth_angles[i, 0] + x0_err[i]
        ukf.P, ukf.Q, ukf.R = P0.copy(), Q.copy(), R.copy()
        for j in range(E):
            ukf.predict(UT=_transform, R=dR[i, j], dV=ep.velocity[i, j], S=ep.moment[i, j])
            ukf.update(noise[i, j], UT=_transform)  # the block's velocity is zero: the measurement is its noise
            heading_sig[i, j] = math.sqrt(max(ukf.P[0, 0], 0.0))
            if truth_every:
                heading_err[i, j] = wrap_angle(ukf.x[0] - record.truth_angles[i, j + 1, 0])
        final[i] = ukf.x[0:3]
    truth = record.truth_angles[:, E] if truth_every else record.truth_angles[:, -1]
    est = AlignmentEstimate("unscented", final[:, 0], final[:, 1], final[:, 2], truth[:, 0], truth[:, 1], truth[:, 2], "end")
    return UnscentedResult(est, D * np.arange(1, E + 1), heading_err, heading_sig, x0_err[:, 0])
