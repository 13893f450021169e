"""Estimating the stable tilts β0, γ0 under rocking: sample mean (16) against a Kalman filter.

Hrechka & Koroliov estimate β0, γ0 by the sample means of n accelerometer
tilt samples (their eq. (16)).  Under correlated (narrow-band) rocking the
sample mean converges slowly; a Kalman filter that knows the rocking model
(the shaping filter of :class:`strapdown.analysis.gyrocompass.rocking.NarrowbandRocking`, or the
undamped oscillator of a sinusoid) estimates the constant tilt together with
the rocking state.  This module compares both, through the alignment error
``σ(β̂0, γ̂0) − σ(β0, γ0)`` of the azimuth, against the averaging time, and
checks the filter's consistency by the NEES.

Filter state per axis: ``(β0, ξ, ξ')`` (``(β0,)`` for white rocking), with
measurement ``z = β0 + ξ + v``, v the accelerometer noise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

from ..core import kalman
from ..core.validation import as_array, as_int, nonnegative, positive
from .azimuth import check_latitude, relative_angle, tilt_components
from .rocking import GaussianRocking, NarrowbandRocking, SineRocking, as_generator

__all__ = ["TiltFilterModel", "tilt_filter_model", "EstimatorComparison", "compare_estimators"]


@dataclass(frozen=True)
class TiltFilterModel:
    """Linear model of one tilt channel for the Kalman filter (per sample step).

    Attributes
    ----------
    F : ndarray
        State transition per step.
    Q : ndarray
        Process noise covariance per step [rad², (rad/s)²].
    H : ndarray
        Measurement matrix.
    R : ndarray
        Measurement noise covariance [rad²].
    P0 : ndarray
        Prior covariance.
    """

    F: np.ndarray
    Q: np.ndarray
    H: np.ndarray
    R: np.ndarray
    P0: np.ndarray


def tilt_filter_model(rocking, dt, *, axis: str = "xi", prior_sigma: float, noise_sigma: float) -> TiltFilterModel:
    """Kalman model of ``z = β0 + ξ + v`` for one axis of a rocking model.

    Parameters
    ----------
    rocking : rocking model
        Supplies the rocking dynamics and variance.
    dt : float
        Sample interval [s].
    axis : str
        ``"xi"`` or ``"eta"``.
    prior_sigma : float
        Prior standard deviation of the stable tilt [rad].
    noise_sigma : float
        Accelerometer tilt noise v [rad], > 0.

    Returns
    -------
    TiltFilterModel

    Raises
    ------
    TypeError
        For an unknown rocking model.
    """
    dt = positive(dt, "dt")
    prior = positive(prior_sigma, "prior_sigma")
    r = positive(noise_sigma, "noise_sigma")
    sigma = rocking.sigma_xi if axis == "xi" else rocking.sigma_eta
    if isinstance(rocking, GaussianRocking):
        one = np.ones((1, 1))
        return TiltFilterModel(one, np.zeros((1, 1)), one, np.array([[sigma**2 + r**2]]), np.array([[prior**2]]))
    if isinstance(rocking, SineRocking):
        w = 2.0 * math.pi / (rocking.period_xi if axis == "xi" else rocking.period_eta)
        c, s = math.cos(w * dt), math.sin(w * dt)
        Fr = np.array([[c, s / w], [-w * s, c]])
        Qr = np.zeros((2, 2))
    elif isinstance(rocking, NarrowbandRocking):
        w = rocking.omega0
        Fr, Qr = rocking.discretisation(dt)
        Qr = Qr * sigma**2
    else:
        raise TypeError(f"Expected `rocking` to be a rocking model, got {type(rocking).__name__}")
    F = np.zeros((3, 3))
    F[0, 0] = 1.0
    F[1:, 1:] = Fr
    Q = np.zeros((3, 3))
    Q[1:, 1:] = Qr
    P0 = np.diag([prior**2, sigma**2, (w * sigma) ** 2])
    return TiltFilterModel(F, Q, np.array([[1.0, 1.0, 0.0]]), np.array([[r**2]]), P0)


@dataclass(frozen=True)
class EstimatorComparison:
    """Alignment errors against averaging time for the sample mean and the Kalman filter.

    Attributes
    ----------
    times : ndarray
        Averaging times [s].
    rms_mean, rms_kalman : ndarray
        rms alignment error of the sample mean (16) and of the Kalman filter [rad].
    rms_tilt_mean, rms_tilt_kalman : ndarray
        rms error of the estimated β0 [rad].
    kalman_sigma_tilt : ndarray
        The filter's own standard deviation of β0 [rad].
    nees_mean : ndarray
        NEES of the β0 estimate averaged over trials.
    nees_band : tuple
        Two-sided 95 % band of that average for a consistent filter (χ² with
        ``dim·n_trials`` degrees of freedom, divided by ``n_trials``).
    dim : int
        Degrees of freedom of one NEES.
    n_trials : int
        Trials.
    """

    times: np.ndarray
    rms_mean: np.ndarray
    rms_kalman: np.ndarray
    rms_tilt_mean: np.ndarray
    rms_tilt_kalman: np.ndarray
    kalman_sigma_tilt: np.ndarray
    nees_mean: np.ndarray
    nees_band: tuple
    dim: int
    n_trials: int


def compare_estimators(
    latitude,
    rocking,
    *,
    dt: float,
    averaging_times,
    n_trials: int,
    rng=None,
    prior_sigma: float = math.radians(2.0),
    noise_sigma: float = math.radians(0.001),
) -> EstimatorComparison:
    """Compare the sample mean (16) and the Kalman filter as estimates of β0, γ0.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    rocking : rocking model
        The simulated rocking (and the filter's model of it).
    dt : float
        Sample interval [s].
    averaging_times : array_like
        Averaging times to report [s], each ≥ dt.
    n_trials : int
        Monte Carlo trials, at least 2.
    rng : Generator | int | None
        Random stream.
    prior_sigma : float
        Spread of the true stable tilts and the filter prior [rad].
    noise_sigma : float
        Accelerometer tilt noise [rad].

    Returns
    -------
    EstimatorComparison

    References
    ----------
    Hrechka & Koroliov, eq. (16) (sample means).
    """
    latitude = check_latitude(latitude)
    dt = positive(dt, "dt")
    n_trials = as_int(n_trials, "n_trials", minimum=2)
    times = as_array(averaging_times, "averaging_times").ravel()
    steps = np.maximum(np.rint(times / dt).astype(int), 1)
    if np.any(times < dt * 0.5):
        raise ValueError(f"Expected `averaging_times` >= dt = {dt:g} s, got {times.min():g}")
    prior, r = positive(prior_sigma, "prior_sigma"), nonnegative(noise_sigma, "noise_sigma")
    g = as_generator(rng)
    n_max = int(steps.max())
    truth = g.normal(0.0, prior, size=(2, n_trials))
    xi, eta = rocking.sample(g, n_trials, n_max, dt)
    noise = g.normal(0.0, r, size=(2, n_trials, n_max))
    z = np.stack([truth[0][:, None] + xi + noise[0], truth[1][:, None] + eta + noise[1]])
    idx = steps - 1
    # sample means (16) at each averaging time
    means = np.cumsum(z, axis=-1)[:, :, idx] / steps
    # Kalman filter, gains from filterpy, applied to all trials at once
    est, sig, nees_vals, dim = [], None, None, 1  # NEES on β0: one degree of freedom per trial
    sequences = {}  # the gains do not depend on the data: one Riccati recursion per distinct axis model
    for ax, name in enumerate(("xi", "eta")):
        model = tilt_filter_model(rocking, dt, axis=name, prior_sigma=prior, noise_sigma=max(r, 1e-12))
        key = tuple(np.asarray(m, dtype=float).tobytes() for m in (model.F, model.Q, model.H, model.R, model.P0))
        if key not in sequences:
            sequences[key] = kalman.gain_sequence(model.F, model.Q, model.H, model.R, model.P0, n_max)
        gains, covs = sequences[key]
        x = kalman.apply_gains(model.F, model.H, gains, np.zeros(model.F.shape[0]), z[ax][:, :, None])
        est.append(x[:, idx, 0])
        if ax == 0:
            # NEES of the estimated stable tilt β0 (the state the alignment uses), dim 1
            sig = np.sqrt(covs[idx, 0, 0])
            err = x[:, idx, :1] - truth[0][:, None, None]
            nees_vals = np.array([kalman.nees(err[:, j, :], np.broadcast_to(covs[idx[j], :1, :1], (n_trials, 1, 1))).mean() for j in range(len(idx))])
    sphi, cphi = math.sin(latitude), math.cos(latitude)
    A_ref, B_ref = tilt_components(truth[0][:, None], truth[1][:, None], sphi, cphi)
    d_mean = relative_angle(*tilt_components(means[0], means[1], sphi, cphi), A_ref, B_ref)
    d_kf = relative_angle(*tilt_components(est[0], est[1], sphi, cphi), A_ref, B_ref)
    band = tuple(stats.chi2.ppf([0.025, 0.975], dim * n_trials) / n_trials)
    rms = lambda e: np.sqrt(np.mean(e * e, axis=0))  # noqa: E731
    return EstimatorComparison(
        times=steps * dt,
        rms_mean=rms(d_mean),
        rms_kalman=rms(d_kf),
        rms_tilt_mean=rms(means[0] - truth[0][:, None]),
        rms_tilt_kalman=rms(est[0] - truth[0][:, None]),
        kalman_sigma_tilt=sig,
        nees_mean=nees_vals,
        nees_band=band,
        dim=dim,
        n_trials=n_trials,
    )

