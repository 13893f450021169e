"""Initial conditions of the navigation errors: the attitude error an alignment leaves, source by source.

An alignment at rest over ``[−T, 0]`` estimates the attitude from the sensor
outputs averaged over the window, so its attitude error is linear in the
window means of the sensor errors to first order, ::

    φ(0) = L_g δω̄ + L_a δf̄,

with the gains ``L_g``, ``L_a`` of the method (:func:`analytic_gains`: the
analytic alignment of :mod:`strapdown.analysis.alignment.analytic`, the
levelled formula on the averaged outputs, differentiated numerically at the
ideal outputs).  For each source the window means and the source's states at
t = 0 are jointly Gaussian: the source model (:mod:`~strapdown.analysis.navigation.error_model`)
is run over the window with the integrals ``z_g = ∫ δω``, ``z_a = ∫ δf``
appended (exact discretisation, Van Loan), from the source's state at turn-on
(at −T).  Then, with ``K = P_φx P_xx⁺`` the regression of φ(0) on the
source's states, ::

    φ(0) = K x_s(0) + r,      r independent of x_s(0) and of the source's future noise:

the part ``K x_s(0)`` (and the mean, for fixed errors) travels with the source
— it is why a horizontal accelerometer bias and the tilt it causes cancel, and
an east gyro bias and the heading error it causes — while ``r``, the noise
averaged over the window, is the source's contribution to the *alignment*
line of the budget.  The sum over sources is exact by superposition.

``alignment="none"`` starts with zero attitude error, and a
:class:`GivenAlignment` with an attitude error independent of the sensors.

Public API
----------
.. autosummary::

   ALIGNMENTS
   AlignmentGains
   GivenAlignment
   analytic_gains
   InitialCondition
   initial_condition
   given_residual
   attitude_error
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..alignment.analytic import analytic_alignment
from ..alignment.imu import ImuRecord, Scenario, SensorErrors
from ..alignment.tilt_attitude import attitude_matrix
from ..core.validation import nonnegative, positive
from .covariance import discretise
from .error_model import Site, Source

__all__ = ["ALIGNMENTS", "AlignmentGains", "GivenAlignment", "analytic_gains", "InitialCondition", "initial_condition", "attitude_error", "given_residual"]

#: Alignment methods of the budget by name.
ALIGNMENTS = ("none", "analytic")


def attitude_error(estimate, truth) -> np.ndarray:
    """φ of ``C̃ = (I − [φ×]) C`` from two attitude matrices ``(..., 3, 3)`` (body to NED) [rad].

    Parameters
    ----------
    estimate, truth : array_like
        ``C̃_b^n`` and ``C_b^n``.

    Returns
    -------
    ndarray
        ``(..., 3)``: the axial vector of ``−asym(C̃ Cᵀ)``.
    """
    m = np.einsum("...ij,...kj->...ik", np.asarray(estimate, float), np.asarray(truth, float))
    a = 0.5 * (m - np.swapaxes(m, -1, -2))
    return -np.stack([a[..., 2, 1], a[..., 0, 2], a[..., 1, 0]], axis=-1)


@dataclass(frozen=True)
class AlignmentGains:
    """``φ(0) = L_g δω̄ + L_a δf̄`` of an alignment over ``time`` seconds.

    Attributes
    ----------
    method : str
        Its name.
    time : float
        T [s].
    gyro : ndarray
        ``L_g`` (3, 3) [s].
    accel : ndarray
        ``L_a`` (3, 3) [s²/m].
    """

    method: str
    time: float
    gyro: np.ndarray
    accel: np.ndarray


@dataclass(frozen=True)
class GivenAlignment:
    """An initial attitude error given as standard deviations, independent of the sensor errors.

    Parameters
    ----------
    tilt : float
        1σ of each tilt error [rad].
    heading : float
        1σ of the heading error [rad].
    """

    tilt: float
    heading: float

    def __post_init__(self):
        object.__setattr__(self, "tilt", nonnegative(self.tilt, "tilt"))
        object.__setattr__(self, "heading", nonnegative(self.heading, "heading"))


def analytic_gains(site: Site, time: float) -> AlignmentGains:
    """Gains of the analytic alignment (levelled formula on the outputs averaged over ``time``).

    Central differences of :func:`strapdown.analysis.alignment.analytic.analytic_alignment`
    at the ideal outputs of the site, through the attitude error φ.

    Parameters
    ----------
    site : Site
        Latitude and heading.
    time : float
        Alignment time T [s].

    Returns
    -------
    AlignmentGains

    Examples
    --------
    The heading error of an east gyro bias b is ``−b/(Ω cos φ)``, so ``φ_D = b/(Ω cos φ)``:

    >>> import math
    >>> g = analytic_gains(Site(math.radians(45.0)), 300.0)
    >>> round(float(g.gyro[2, 1]) * 7.292115e-5 * math.cos(math.radians(45.0)), 6)
    1.0
    """
    T = positive(time, "time")
    scenario = Scenario(site.latitude, heading=site.heading, sample_rate=2.0 / T, duration=T)
    w0, f0 = site.body_rate, site.specific_force
    truth = site.attitude
    steps = (1e-9, 1e-6)  # rad/s, m/s²: the method is smooth, these are far above round-off and far below curvature
    cols = []
    for which, step in ((0, steps[0]), (1, steps[1])):
        for axis in range(3):
            phis = []
            for sign in (1.0, -1.0):
                w, f = w0.copy(), f0.copy()
                (w if which == 0 else f)[axis] += sign * step
                dth = np.broadcast_to(w * (T / 2.0), (1, 2, 3)).copy()
                dv = np.broadcast_to(f * (T / 2.0), (1, 2, 3)).copy()
                zero = np.zeros((1, 2, 3))
                rec = ImuRecord(scenario, SensorErrors(), dth, dv, np.array([0.0, T]), zero, zero, zero, np.zeros((1, 3)), np.zeros((1, 3)))
                est = analytic_alignment(rec)
                C = attitude_matrix(np.array([est.heading[0], est.beta[0], est.gamma[0]]))
                phis.append(attitude_error(C, truth))
            cols.append((phis[0] - phis[1]) / (2.0 * step))
    L = np.stack(cols, axis=1)
    return AlignmentGains("analytic", T, L[:, :3], L[:, 3:])


@dataclass(frozen=True)
class InitialCondition:
    """The navigation errors at t = 0 for one source, with its states, and its share of the alignment error.

    Attributes
    ----------
    mean : ndarray
        ``(9 + k,)`` mean of the navigation and source states.
    cov : ndarray
        ``(9 + k, 9 + k)`` their covariance (the source's own part).
    residual : ndarray
        ``(3, 3)`` covariance of the alignment error independent of the source's states.
    """

    mean: np.ndarray
    cov: np.ndarray
    residual: np.ndarray


def initial_condition(source: Source, gains: AlignmentGains | None) -> InitialCondition:
    """Initial navigation errors of ``source`` after the alignment of ``gains`` (None: no alignment).

    Parameters
    ----------
    source : Source
        The source.
    gains : AlignmentGains or None
        The alignment (module docstring); None starts with no attitude error.

    Returns
    -------
    InitialCondition
    """
    k = source.size
    mean = np.zeros(9 + k)
    cov = np.zeros((9 + k, 9 + k))
    cov[np.arange(9), np.arange(9)] = source.start
    if gains is None:
        mean[9:] = source.mean0
        cov[9:, 9:] = source.cov0
        return InitialCondition(mean, cov, np.zeros((3, 3)))
    T = gains.time
    # the window: [x_s, z_g, z_a], from the turn-on state at −T
    n = k + 6
    A = np.zeros((n, n))
    A[:k, :k] = source.F
    A[k : k + 3, :k] = source.G_gyro
    A[k + 3 :, :k] = source.G_accel
    Q = np.zeros((n, n))
    Q[:k, :k] = source.Q
    Q[k : k + 3, k : k + 3] = source.white[0] * np.eye(3)
    Q[k + 3 :, k + 3 :] = source.white[1] * np.eye(3)
    F, Qd = discretise(A, Q, T)
    m0, P0 = np.zeros(n), np.zeros((n, n))
    m0[:k], P0[:k, :k] = source.mean0, source.cov0
    m, P = F @ m0, F @ P0 @ F.T + Qd
    M = np.zeros((3 + k, n))
    M[:3, k : k + 3] = gains.gyro / T
    M[:3, k + 3 :] = gains.accel / T
    M[3:, :k] = np.eye(k)
    mu, Pu = M @ m, M @ P @ M.T
    Pxx, Pfx = Pu[3:, 3:], Pu[:3, 3:]
    K = Pfx @ np.linalg.pinv(Pxx, rcond=1e-12, hermitian=True) if k else np.zeros((3, 0))
    residual = Pu[:3, :3] - K @ Pfx.T
    residual = 0.5 * (residual + residual.T)
    mean[0:3] = mu[:3]
    mean[9:] = mu[3:]
    idx = np.r_[0:3, 9 : 9 + k]
    L = np.vstack([K, np.eye(k)])
    cov[np.ix_(idx, idx)] += L @ Pxx @ L.T
    return InitialCondition(mean, cov, residual)


def given_residual(given: GivenAlignment) -> np.ndarray:
    """The attitude covariance of a :class:`GivenAlignment` (3, 3) [rad²].

    Parameters
    ----------
    given : GivenAlignment
        The given errors.

    Returns
    -------
    ndarray
    """
    return np.diag([given.tilt**2, given.tilt**2, given.heading**2])
