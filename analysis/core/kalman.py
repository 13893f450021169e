"""Thin adapter over :mod:`filterpy`: the only module that imports it.

filterpy's maintenance is uncertain, so the package uses a few of its calls
through this module (``KalmanFilter`` with ``predict``/``update``/
``batch_filter``, and ``filterpy.stats.NEES``), and the tests pin them.  The
filter here is linear with data-independent covariances, so the gains are
computed once by filterpy and then applied to many trials at once.
"""

from __future__ import annotations

import numpy as np

__all__ = ["make_filter", "gain_sequence", "apply_gains", "filterpy_batch", "nees"]


def make_filter(F, Q, H, R, x0, P0):
    """A :class:`filterpy.kalman.KalmanFilter` with the given model and prior.

    Parameters
    ----------
    F : array_like, shape (n, n)
        State transition per step.
    Q : array_like, shape (n, n)
        Process noise covariance per step.
    H : array_like, shape (m, n)
        Measurement matrix.
    R : array_like, shape (m, m)
        Measurement noise covariance.
    x0 : array_like, shape (n,)
        Prior mean.
    P0 : array_like, shape (n, n)
        Prior covariance.

    Returns
    -------
    filterpy.kalman.KalmanFilter
        A filter holding copies of the arrays.
    """
    from filterpy.kalman import KalmanFilter

    F = np.atleast_2d(np.asarray(F, dtype=float))
    H = np.atleast_2d(np.asarray(H, dtype=float))
    kf = KalmanFilter(dim_x=F.shape[0], dim_z=H.shape[0])
    kf.F = F.copy()
    kf.Q = np.atleast_2d(np.asarray(Q, dtype=float)).copy()
    kf.H = H.copy()
    kf.R = np.atleast_2d(np.asarray(R, dtype=float)).copy()
    kf.x = np.asarray(x0, dtype=float).reshape(-1, 1).copy()
    kf.P = np.atleast_2d(np.asarray(P0, dtype=float)).copy()
    return kf


def gain_sequence(F, Q, H, R, P0, n_steps: int):
    """Kalman gains and posterior covariances of ``n_steps`` predict–update cycles.

    The covariances of a linear filter do not depend on the measurements, so
    filterpy is run once on zero measurements.

    Parameters
    ----------
    F, Q, H, R : array_like
        Model, as in :func:`make_filter`.
    P0 : array_like, shape (n, n)
        Prior covariance.
    n_steps : int
        Number of predict–update cycles [count].

    Returns
    -------
    gains : ndarray, shape (n_steps, n, m)
        Kalman gain of each cycle.
    covariances : ndarray, shape (n_steps, n, n)
        Posterior covariance of each cycle.
    """
    F = np.atleast_2d(np.asarray(F, dtype=float))
    kf = make_filter(F, Q, H, R, np.zeros(F.shape[0]), P0)
    z = np.zeros((kf.dim_z, 1))
    gains = np.empty((n_steps, kf.dim_x, kf.dim_z))
    covs = np.empty((n_steps, kf.dim_x, kf.dim_x))
    for k in range(n_steps):
        kf.predict()
        kf.update(z)
        gains[k] = kf.K
        covs[k] = kf.P
    return gains, covs


def apply_gains(F, H, gains, x0, zs):
    """Filter many trials at once with precomputed gains.

    Parameters
    ----------
    F : array_like, shape (n, n)
        State transition.
    H : array_like, shape (m, n)
        Measurement matrix.
    gains : array_like, shape (n_steps, n, m)
        From :func:`gain_sequence`.
    x0 : array_like, shape (n,)
        Prior mean.
    zs : array_like, shape (n_trials, n_steps, m)
        Measurements.

    Returns
    -------
    ndarray, shape (n_trials, n_steps, n)
        Posterior means (one step per measurement).
    """
    F = np.atleast_2d(np.asarray(F, dtype=float))
    H = np.atleast_2d(np.asarray(H, dtype=float))
    zs = np.asarray(zs, dtype=float)
    n_trials, n_steps = zs.shape[:2]
    x = np.broadcast_to(np.asarray(x0, dtype=float), (n_trials, F.shape[0])).copy()
    out = np.empty((n_trials, n_steps, F.shape[0]))
    FT, HT = F.T, H.T
    for k in range(n_steps):  # vectorised over trials; one step per iteration
        x = x @ FT
        x += (zs[:, k, :] - x @ HT) @ gains[k].T
        out[:, k] = x
    return out


def filterpy_batch(F, Q, H, R, x0, P0, zs):
    """Reference: ``KalmanFilter.batch_filter`` on one trial.

    Parameters
    ----------
    F, Q, H, R : array_like
        Model, as in :func:`make_filter`.
    x0 : array_like, shape (n,)
        Prior mean.
    P0 : array_like, shape (n, n)
        Prior covariance.
    zs : array_like, shape (n_steps, m)
        Measurements of the trial.

    Returns
    -------
    means : ndarray, shape (n_steps, n)
        Posterior means.
    covariances : ndarray, shape (n_steps, n, n)
        Posterior covariances.
    """
    kf = make_filter(F, Q, H, R, x0, P0)
    means, covs, _, _ = kf.batch_filter(np.asarray(zs, dtype=float).reshape(len(zs), -1, 1))
    return means[..., 0], covs


def nees(errors, covariances):
    """Normalised estimation error squared ``eᵀ P⁻¹ e`` by ``filterpy.stats.NEES``.

    Parameters
    ----------
    errors : array_like, shape (k, n)
        Estimate minus truth.
    covariances : array_like, shape (k, n, n)
        Covariances the estimates claim.

    Returns
    -------
    ndarray, shape (k,)
    """
    from filterpy.stats import NEES

    errors = np.asarray(errors, dtype=float)
    return np.asarray(NEES(np.zeros_like(errors), errors, np.asarray(covariances, dtype=float)), dtype=float)
