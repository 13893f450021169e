"""Thin adapter over :mod:`filterpy`: the only module that imports it.

filterpy's maintenance is uncertain, so the package uses a few of its calls
through this module (``KalmanFilter`` with ``predict``/``update``/
``batch_filter``, and ``filterpy.stats.NEES``), and the tests pin them.  The
filter here is linear with data-independent covariances, so the gains are
computed once by filterpy and then applied to many trials at once.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .validation import as_int

__all__ = ["make_filter", "gain_sequence", "apply_gains", "filterpy_batch", "nees", "FilterSequence", "filter_sequence", "nis", "chi2_band", "discretise"]


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

    For a single state (``n = 1``) with finite, non-zero variances the same
    products are taken for all estimates at once (filterpy loops over them):
    the values are filterpy's, bit for bit.

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
    covariances = np.asarray(covariances, dtype=float)
    if errors.ndim == 2 and errors.shape[1] == 1 and covariances.shape == (errors.shape[0], 1, 1):
        p = covariances[:, 0, 0]
        if np.all(np.isfinite(p)) and np.all(p != 0.0):
            # One state: filterpy's loop computes ((0 − e) P⁻¹)(0 − e) per estimate, with LAPACK's inverse
            # of a 1×1 matrix, 1/P: the same products for all estimates at once, bit for bit.
            # (A zero or non-finite variance takes filterpy's loop, which raises as it does.)
            x = -errors[:, 0]
            return (x * (1.0 / p)) * x
    return np.asarray(NEES(np.zeros_like(errors), errors, covariances), dtype=float)


class FilterSequence(NamedTuple):
    """Gains and covariances of a linear Kalman filter over ``n_steps`` predict–update cycles.

    Attributes
    ----------
    gains : ndarray
        ``(n_steps, n, m)`` Kalman gains.
    prior : ndarray
        ``(n_steps, n, n)`` covariances after the prediction.
    posterior : ndarray
        ``(n_steps, n, n)`` covariances after the update.
    innovation : ndarray
        ``(n_steps, m, m)`` innovation covariances ``S = H P⁻ Hᵀ + R``.
    """

    gains: np.ndarray
    prior: np.ndarray
    posterior: np.ndarray
    innovation: np.ndarray


def filter_sequence(F, Q, H, R, P0, n_steps: int, *, reference: bool = False) -> FilterSequence:
    """Gains, prior, posterior and innovation covariances of ``n_steps`` predict–update cycles of filterpy's ``KalmanFilter``.

    The covariances of a linear filter do not depend on the measurements, so
    one run on zero measurements serves every trial (as :func:`gain_sequence`, with the prior and
    innovation covariances that NEES and NIS need).  The cycles repeat filterpy's covariance
    arithmetic call for call (the same ``numpy.dot`` products, sums and ``numpy.linalg.inv`` in the
    same order), so the result equals filterpy's to the bit, at a fraction of its per-cycle
    overhead (a filter over a few hundred epochs is rebuilt at every amplitude of a root search);
    ``reference=True`` runs filterpy's ``KalmanFilter`` itself.

    Parameters
    ----------
    F : (n, n) array
        State transition per step.
    Q : (n, n) array
        Process noise covariance per step.
    H : (m, n) array
        Measurement matrix.
    R : (m, m) array
        Measurement noise covariance.
    P0 : (n, n) array
        Prior covariance.
    n_steps : int
        Cycles.
    reference : bool, keyword-only
        Run filterpy's ``KalmanFilter.predict`` and ``update`` (default False: the same
        arithmetic without the filter object).

    Returns
    -------
    FilterSequence

    Raises
    ------
    ValueError
        For shapes that do not fit, or a negative number of cycles.

    References
    ----------
    Labbe, R., *Kalman and Bayesian Filters in Python* (filterpy), ``KalmanFilter.predict``
    and ``update``; Bucy, R. S., Joseph, P. D., *Filtering for Stochastic Processes with
    Applications to Guidance*, 1968 (the Joseph form).
    """
    n_steps = as_int(n_steps, "n_steps", minimum=0)
    F = np.atleast_2d(np.asarray(F, dtype=float))
    H = np.atleast_2d(np.asarray(H, dtype=float))
    n, m = F.shape[0], H.shape[0]
    for name, a, shape in (("F", F, (n, n)), ("Q", Q, (n, n)), ("H", H, (m, n)), ("R", R, (m, m)), ("P0", P0, (n, n))):
        if np.atleast_2d(np.asarray(a, dtype=float)).shape != shape:
            raise ValueError(f"Expected `{name}` with shape {shape}, got shape {np.shape(a)}")
    if reference:
        return _filterpy_sequence(F, Q, H, R, P0, n_steps)
    # filterpy's covariance arithmetic, call for call (KalmanFilter.predict, then update with
    # fading factor 1 and numpy.linalg.inv), without its per-step state, copies and bookkeeping:
    # the products are written where they are kept and the factor 1.0 (exact) is left out
    Q = np.atleast_2d(np.asarray(Q, dtype=float)).copy()
    R = np.atleast_2d(np.asarray(R, dtype=float)).copy()
    F, H = F.copy(), H.copy()
    P = np.atleast_2d(np.asarray(P0, dtype=float)).copy()
    eye, dot, add, inv = np.eye(n), np.dot, np.add, np.linalg.inv
    FT, HT = F.T, H.T
    gains = np.empty((n_steps, n, m))
    prior = np.empty((n_steps, n, n))
    post = np.empty((n_steps, n, n))
    innov = np.empty((n_steps, m, m))
    for k in range(n_steps):
        P = add(dot(dot(F, P), FT), Q, out=prior[k])
        PHT = dot(P, HT)
        S = add(dot(H, PHT), R, out=innov[k])
        K = dot(PHT, inv(S), out=gains[k])
        I_KH = eye - dot(K, H)
        P = add(dot(dot(I_KH, P), I_KH.T), dot(dot(K, R), K.T), out=post[k])
    return FilterSequence(gains, prior, post, innov)


def _filterpy_sequence(F, Q, H, R, P0, n_steps: int) -> FilterSequence:
    """:func:`filter_sequence` by filterpy's ``KalmanFilter`` itself, cycle by cycle (the reference)."""
    n, m = F.shape[0], H.shape[0]
    kf = make_filter(F, Q, H, R, np.zeros(n), P0)
    z = np.zeros((m, 1))
    gains = np.empty((n_steps, n, m))
    prior = np.empty((n_steps, n, n))
    post = np.empty((n_steps, n, n))
    innov = np.empty((n_steps, m, m))
    for k in range(n_steps):
        kf.predict()
        prior[k] = kf.P
        kf.update(z)
        gains[k] = kf.K
        post[k] = kf.P
        innov[k] = kf.S
    return FilterSequence(gains, prior, post, innov)


def nis(innovations, covariances):
    """Normalised innovation squared ``yᵀ S⁻¹ y`` (filterpy has no NIS function).

    Parameters
    ----------
    innovations : (..., m) array
        Innovations y.
    covariances : (..., m, m) array
        Innovation covariances S (broadcast against y).

    Returns
    -------
    ndarray
        ``(...)``.
    """
    y = np.asarray(innovations, dtype=float)
    S = np.asarray(covariances, dtype=float)
    return np.einsum("...i,...i->...", y, np.linalg.solve(S, y[..., None])[..., 0])


def chi2_band(dof: int, n_trials: int, level: float = 0.95) -> tuple:
    """Two-sided band of the trial average of a χ²(dof) statistic: ``χ²_{(1∓level)/2}(dof·n)/n``.

    Parameters
    ----------
    dof : int
        Degrees of freedom of one statistic (state or measurement dimension).
    n_trials : int
        Trials averaged.
    level : float
        Coverage of the band.

    Returns
    -------
    (low, high) : tuple of float
    """
    from scipy.stats import chi2

    a = (1.0 - level) / 2.0
    return tuple(float(x) for x in chi2.ppf([a, 1.0 - a], dof * n_trials) / n_trials)


def discretise(A, G_Qc_Gt, dt: float):
    """Exact discretisation of ``x' = A x + w``, ``E w wᵀ = G Qc Gᵀ δ``: ``(Φ, Q_d)`` by Van Loan's method.

    Parameters
    ----------
    A : (n, n) array
        Continuous dynamics.
    G_Qc_Gt : (n, n) array
        Continuous process-noise spectral density.
    dt : float
        Step [s].

    Returns
    -------
    Phi, Qd : ndarray

    References
    ----------
    Van Loan, C. F., "Computing integrals involving the matrix exponential",
    *IEEE Trans. Autom. Control* 23(3), 1978.
    """
    from scipy.linalg import expm

    A = np.atleast_2d(np.asarray(A, dtype=float))
    n = A.shape[0]
    M = np.zeros((2 * n, 2 * n))
    M[:n, :n] = -A
    M[:n, n:] = np.asarray(G_Qc_Gt, dtype=float)
    M[n:, n:] = A.T
    E = expm(M * dt)
    Phi = E[n:, n:].T
    Qd = Phi @ E[:n, n:]
    return Phi, 0.5 * (Qd + Qd.T)
