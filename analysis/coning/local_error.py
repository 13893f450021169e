"""Local error of an algorithm over one step, on a motion with no symmetry.

The regular precession has a rate of constant magnitude (``ω·ω' = 0``), so
some error terms vanish on it identically.  :class:`TumblingMotion` is a
closed-form attitude with none of that structure: ``Λ(t)`` is a product of two
rotation-vector exponentials with polynomial and trigonometric arguments,
the body rate ``ω = 2 vect(Λ̄ ∘ Λ')`` comes from the dual extension of
``Λ(t)`` (exact forward-mode derivative), and the increments ``p_j`` are
Gauss–Legendre integrals of ω (error far below round-off at the steps used).

:func:`local_error` gives ``δφ = Δφ_exact − Δφ_alg`` over one step;
:func:`error_coefficients` fits the ``h⁵`` coefficients of the local error of
a fourth-order algorithm in the basis ``x03, x12, x002, x110, x0001`` of
Budennyi, Kalinovsky, Panov et al., eq. (2), whose printed values (Table 2)
are ``δ4 · k``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.validation import as_float, positive
from .evaluation import increment

__all__ = ["TumblingMotion", "local_error", "error_coefficients", "BUDENNYI_BASIS"]

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(12)

#: Names of the basis vectors of the local error (2) of Budennyi et al.
BUDENNYI_BASIS = ("x03", "x12", "x002", "x110", "x0001")


@dataclass(frozen=True)
class TumblingMotion:
    """Closed-form tumbling attitude ``Λ(t) = Λ(a(t)) ∘ Λ(b(t))`` with

    ``a = (0.7 sin 1.3t + 0.2t, 0.4 cos 0.9t, 0.5t² + 0.3t)``,
    ``b = (0.1, 0.6 sin 2.1t, −0.3t)`` [rad], scaled in time by ``rate``.

    Parameters
    ----------
    rate : float
        Time scale factor [-]: the motion is ``Λ(rate · t)``.
    """

    rate: float = 1.0

    def __post_init__(self):
        object.__setattr__(self, "rate", as_float(self.rate, "rate"))

    def attitude(self, t):
        """Attitude Λ(t) (E → I).

        Parameters
        ----------
        t : array_like or Dual
            Time(s) [s]; a :class:`~strapdown.analysis.core.dual.Dual` time gives Λ and its derivative.

        Returns
        -------
        ndarray or Dual, shape ``t.shape + (4,)``
        """
        t = (t if isinstance(t, Dual) else np.asarray(t, dtype=float)) * self.rate
        z = t * 0.0
        a = np.stack([0.7 * np.sin(1.3 * t) + 0.2 * t, 0.4 * np.cos(0.9 * t) + z, 0.5 * t * t + 0.3 * t], axis=-1)
        b = np.stack([z + 0.1, 0.6 * np.sin(2.1 * t), -0.3 * t], axis=-1)
        return quat.multiply(quat.rotvec_to_quat(a, validate=False), quat.rotvec_to_quat(b, validate=False))

    def omega(self, t):
        """Body rate ``ω = 2 vect(Λ̄ ∘ Λ')``, with Λ' from the dual extension (exact derivative).

        Parameters
        ----------
        t : array_like
            Time(s) [s].

        Returns
        -------
        ndarray, shape ``t.shape + (3,)``
            ω [rad/s] in E.
        """
        t = np.asarray(t, dtype=float)
        lam = self.attitude(Dual(t, np.ones_like(t)))
        return 2.0 * quat.vect(quat.multiply(quat.conjugate(lam.re), lam.du))

    def increments(self, t0, sample_interval, samples):
        """Angle increments ``p_j = ∫ ω dt`` over ``[t0 + (j−1)h, t0 + jh]``, j = 1 … N (Gauss–Legendre, 12 nodes).

        Parameters
        ----------
        t0 : float
            Start of the first sample [s].
        sample_interval : float
            h [s].
        samples : int
            N.

        Returns
        -------
        ndarray, shape (N, 3)
            [rad].
        """
        h = float(sample_interval)
        starts = t0 + h * np.arange(samples)
        nodes = starts[:, None] + 0.5 * h * (_NODES + 1.0)
        return 0.5 * h * np.einsum("k,jkc->jc", _WEIGHTS, self.omega(nodes))


def local_error(algorithm: Algorithm, motion: TumblingMotion, t_mid, step):
    """Local error ``δφ = Δφ_exact − Δφ_alg`` over the step ``[t_mid − H/2, t_mid + H/2]``.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.
    motion : TumblingMotion
        The motion.
    t_mid : float
        Middle of the step [s].
    step : float
        Step H = N h [s], > 0.

    Returns
    -------
    ndarray, shape (3,)
        δφ [rad].

    Raises
    ------
    ValueError
        For a non-positive ``step``.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> e = [np.linalg.norm(local_error(get("lebedev-panov-4"), TumblingMotion(), 1.0, H)) for H in (0.1, 0.05)]
    >>> round(float(np.log2(e[0] / e[1])))   # order 4: local error O(H⁵)
    5
    """
    step = positive(step, "step")
    t0 = as_float(t_mid, "t_mid") - 0.5 * step
    if type(motion) is TumblingMotion:  # the step's increments and exact rotation do not depend on the algorithm: shared
        p, exact = _step_terms(motion, t0, step, algorithm.samples)
    else:
        p, exact = _compute_step_terms(motion, t0, step, algorithm.samples)
    return exact - increment(algorithm, p)


def _compute_step_terms(motion, t0: float, step: float, samples: int):
    """The increments ``p_j`` (N, 3) and the exact rotation vector (3,) of the step ``[t0, t0 + step]``."""
    p = motion.increments(t0, step / samples, samples)
    exact = quat.quat_to_rotvec(quat.multiply(quat.conjugate(motion.attitude(t0)), motion.attitude(t0 + step)), validate=False)
    return p, exact


@lru_cache(maxsize=4096)
def _step_terms(motion: TumblingMotion, t0: float, step: float, samples: int):
    """:func:`_compute_step_terms`, kept per motion and step (read-only arrays), for the many algorithms run on the same steps."""
    p, exact = _compute_step_terms(motion, t0, step, samples)
    p.flags.writeable = False
    exact.flags.writeable = False
    return p, exact


def _rate_derivatives(motion: TumblingMotion, t, order: int = 3, radius: float = 0.05):
    """ω and its first ``order`` derivatives at ``t`` from a Chebyshev fit, shape (order+1, 3)."""
    nodes = t + radius * np.cos(np.pi * (np.arange(41) + 0.5) / 41)
    w = motion.omega(nodes)
    out = np.empty((order + 1, 3))
    for c in range(3):
        fit = np.polynomial.Chebyshev.fit(nodes, w[:, c], 20, domain=[t - radius, t + radius])
        for k in range(order + 1):
            out[k, c] = fit.deriv(k)(t) if k else fit(t)
    return out


def _budennyi_basis(motion, t):
    """The basis vectors of eq. (2) at ``t``, shape (3, 5); kept per motion and time for a :class:`TumblingMotion` (read-only)."""
    if type(motion) is TumblingMotion:
        return _shared_budennyi_basis(motion, float(t))
    return _compute_budennyi_basis(motion, t)


@lru_cache(maxsize=1024)
def _shared_budennyi_basis(motion: TumblingMotion, t: float):
    out = _compute_budennyi_basis(motion, t)
    out.flags.writeable = False
    return out


def _compute_budennyi_basis(motion, t):
    w0, w1, w2, w3 = _rate_derivatives(motion, t)
    cr = np.cross
    return np.stack([cr(w0, w3), cr(w1, w2), cr(w0, cr(w0, w2)), cr(w1, cr(w1, w0)), cr(w0, cr(w0, cr(w0, w1)))], axis=-1)


def error_coefficients(algorithm: Algorithm, *, motion: TumblingMotion | None = None, times=None, steps=(0.08, 0.04, 0.02)):
    """Coefficients ``c`` of the local error ``δφ = h⁵ Σ c_i x_i + O(h⁶)`` of a four-sample algorithm.

    At each middle time the local error is computed for the steps ``H`` in
    ``steps`` and fitted per component by ``c5 h⁵ + c6 h⁶ + c7 h⁷`` (h = H/N);
    the ``h⁵`` coefficients of all times are then fitted, by least squares,
    to the basis of Budennyi, Kalinovsky, Panov et al., eq. (2):
    ``x03 = ω × ω‴``, ``x12 = ω' × ω''``, ``x002 = ω × (ω × ω'')``,
    ``x110 = ω' × (ω' × ω)``, ``x0001 = ω × (ω × (ω × ω'))``, derivatives
    at the middle of the step.  Their Table 2 prints ``δ4`` and ``k``; the
    fitted ``c`` is ``δ4 · k``.

    Parameters
    ----------
    algorithm : Algorithm
        Four-sample rotation-vector algorithm.
    motion : TumblingMotion, keyword-only
        Default ``TumblingMotion()``.
    times : array_like, keyword-only
        Middle times [s]; default 12 points in [0.2, 3].
    steps : sequence of 3 float, keyword-only
        Steps H [s].

    Returns
    -------
    coefficients : ndarray, shape (5,)
        ``c`` in the order of :data:`BUDENNYI_BASIS` [rad⁻⁴ s⁵ … as the basis requires].
    residual : float
        Relative residual of the least-squares fit (small when the basis describes the error).

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (2), Table 2.
    """
    motion = motion or TumblingMotion()
    times = np.linspace(0.2, 3.0, 12) if times is None else np.asarray(times, dtype=float)
    hs = np.asarray(steps, dtype=float) / algorithm.samples
    design = np.stack([hs**5, hs**6, hs**7], axis=1)
    rows, rhs = [], []
    for t in times:
        errors = np.array([local_error(algorithm, motion, t, H) for H in steps])
        rhs.append(np.linalg.solve(design, errors)[0])
        rows.append(_budennyi_basis(motion, t))
    a, y = np.concatenate(rows), np.concatenate(rhs)
    coef = np.linalg.lstsq(a, y, rcond=None)[0]
    return coef, float(np.linalg.norm(a @ coef - y) / np.linalg.norm(y))
