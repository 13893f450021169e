"""Regular precession and its dual analogue: closed-form test motions.

Lebedev & Panov (1989), section 4.  The body rate (4.1) is

    ω(t) = (εν sin ϑ sin νt,  εν sin ϑ cos νt,  ν(1 + ε cos ϑ)),   ε = μ/ν,

with spin rate ν, precession rate μ = εν and nutation ϑ; ε = −1 is coning.
The dual analogue (4.2) replaces ν and ϑ by dual numbers ``ν + s ν°`` and
``ϑ + s ϑ°``; its dual part is the apparent acceleration ``a`` (4.3).

Every formula below is written once, for real arguments, and evaluated with
:class:`strapdown.analysis.core.dual.Dual` parameters to produce the dual analogue: the
acceleration (4.3), the biquaternion ``P = Q + s R`` (4.4)–(4.5) and the
increments ``b`` of (2.1) are *dual parts*, not separately typed formulas.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import budget
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.validation import as_array, as_float, as_quaternion, as_vector, in_open_interval

__all__ = ["RegularPrecession", "ExactState", "exact_state", "initial_biquaternion"]


@dataclass(frozen=True)
class RegularPrecession:
    """Regular precession (4.1), optionally with dual parts (4.2)–(4.3).

    Parameters
    ----------
    eps : float
        Ratio ε = μ/ν of precession to spin rate [-]; ε = −1 is coning.
    nu : float
        Spin rate ν [rad/s], nonzero.
    nutation : float
        Nutation angle ϑ [rad], in (0, π).
    nu_dual : float, optional
        Dual part ν° of the spin rate [m/s²] (Lebedev & Panov 1989, eq. 4.2).
    nutation_dual : float, optional
        Dual part ϑ° of the nutation [m/s].

    Examples
    --------
    >>> m = RegularPrecession(eps=-1.0, nu=2 * np.pi, nutation=0.1)
    >>> m.omega(0.0).shape
    (3,)
    """

    eps: float
    nu: float
    nutation: float
    nu_dual: float = 0.0
    nutation_dual: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "eps", as_float(self.eps, "eps"))
        nu = as_float(self.nu, "nu")
        if nu == 0.0:
            raise ValueError("Expected `nu` (spin rate, rad/s) to be nonzero, got 0")
        object.__setattr__(self, "nu", nu)
        object.__setattr__(self, "nutation", in_open_interval(self.nutation, "nutation", 0.0, np.pi, text="(0, π)"))
        object.__setattr__(self, "nu_dual", as_float(self.nu_dual, "nu_dual"))
        object.__setattr__(self, "nutation_dual", as_float(self.nutation_dual, "nutation_dual"))

    # ----------------------------------------------------------- parameters
    @property
    def is_dual(self) -> bool:
        """True when the motion carries translation (ν° or ϑ° nonzero)."""
        return self.nu_dual != 0.0 or self.nutation_dual != 0.0

    def _dual_params(self):
        return Dual(self.nu, self.nu_dual), Dual(self.nutation, self.nutation_dual)

    # ----------------------------------------------------------- generic formulas
    def _rate(self, t, nu, nut):
        e = self.eps
        zero = t * 0.0
        return np.stack(
            [e * nu * np.sin(nut) * np.sin(nu * t), e * nu * np.sin(nut) * np.cos(nu * t), nu * (1.0 + e * np.cos(nut)) + zero],
            axis=-1,
        )

    def _attitude(self, t, nu, nut):
        e = self.eps
        c, s = np.cos(nut / 2.0), np.sin(nut / 2.0)
        a, b = (1.0 + e) * nu * t / 2.0, (1.0 - e) * nu * t / 2.0
        return np.stack([c * np.cos(a), s * np.cos(b), -s * np.sin(b), c * np.sin(a)], axis=-1)

    def _integral(self, t0, t1, nu, nut):
        e = self.eps
        return np.stack(
            [
                -e * np.sin(nut) * (np.cos(nu * t1) - np.cos(nu * t0)),
                e * np.sin(nut) * (np.sin(nu * t1) - np.sin(nu * t0)),
                nu * (1.0 + e * np.cos(nut)) * (t1 - t0),
            ],
            axis=-1,
        )

    # ----------------------------------------------------------- public API
    def omega(self, t):
        """Body rate ω(t) in E [rad/s], eq. (4.1); shape ``t.shape + (3,)``.

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        return self._rate(_time(t), self.nu, self.nutation)

    def dual_rate(self, t) -> Dual:
        """Dual rate ``Ω = ω + s a`` (4.2); the dual part is (4.3) [m/s²].

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        nu, nut = self._dual_params()
        return self._rate(_time(t), nu, nut)

    def accel(self, t):
        """Apparent acceleration a(t) in E [m/s²], eq. (4.3).

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        return self.dual_rate(t).du

    def attitude(self, t):
        """Particular solution Q(t) of ``2Q' = Q ∘ ω`` with Q(0) as printed in (4.4).

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        return self._attitude(_time(t), self.nu, self.nutation)

    def precession_axis(self, attitude0=(1.0, 0.0, 0.0, 0.0)) -> np.ndarray:
        """Unit precession axis n in frame I of a run started at ``Λ(0) = attitude0``.

        In the frame of the particular solution (4.4) the body precesses at the
        rate μ = εν about a fixed axis; in the body axes at t = 0 it is
        ``(0, sin ϑ, cos ϑ)``, and in frame I it is that vector turned by Λ(0).
        The secular part of the attitude error of an algorithm lies along n
        (Lebedev & Panov 1989, eqs. (5.2)–(5.3)); under coning (ε = −1, ν > 0)
        the cone axis, along the mean inertial angular velocity, is −n.

        Parameters
        ----------
        attitude0 : array_like, shape (4,)
            Initial attitude Λ(0), unit quaternion (E → I).

        Returns
        -------
        ndarray, shape (3,)
            n, components in frame I [-].

        Raises
        ------
        ValueError
            If ``attitude0`` is not a unit quaternion of shape (4,).

        Examples
        --------
        >>> RegularPrecession(-1.0, 2 * np.pi, np.pi / 2).precession_axis().round(12)
        array([0., 1., 0.])
        """
        lam0 = as_quaternion(attitude0, "attitude0", unit=True)
        if lam0.shape != (4,):
            raise ValueError(f"Expected `attitude0` of shape (4,), got {lam0.shape}")
        return quat.rotate(lam0, np.array([0.0, np.sin(self.nutation), np.cos(self.nutation)]))

    def biquaternion(self, t) -> Dual:
        """Particular solution ``P = Q + s R`` of ``2P' = P ∘ (ω + s a)``, eqs. (4.4)–(4.5).

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        nu, nut = self._dual_params()
        return self._attitude(_time(t), nu, nut)

    def increments(self, t0, t1) -> Dual:
        """Exact integrals ``p + s b = ∫ (ω + s a) dt`` over ``[t0, t1]`` (2.1).

        Parameters
        ----------
        t0, t1 : array_like
            Interval ends [s], broadcast together.

        Returns
        -------
        Dual, shape (..., 3)
            Real part ``p`` [rad]; dual part ``b`` [m/s].
        """
        nu, nut = self._dual_params()
        t0, t1 = np.broadcast_arrays(_time(t0), _time(t1))
        return self._integral(t0, t1, nu, nut)

    def angle_increments(self, t0, t1):
        """Real part of :meth:`increments`, computed without dual arithmetic [rad].

        Parameters
        ----------
        t0, t1 : array_like
            Interval ends [s], broadcast together.
        """
        t0, t1 = np.broadcast_arrays(_time(t0), _time(t1))
        return self._integral(t0, t1, self.nu, self.nutation)

    def grid_increments(self, sample_interval: float, first: int, count: int, *, dual: bool = False, limits: budget.Limits | None = None):
        """Increments (2.1) over the uniform samples ``[(k−1)h, kh]``, k = first+1 … first+count.

        The same integrals as :meth:`increments`, written about the sample
        midpoint ``t_m``: the transverse components of (4.1) are sinusoids of
        ``νt``, so ``p = (σ ω_1(t_m), σ ω_2(t_m), h ω_3)`` with
        ``σ = 2 sin(νh/2)/ν``.  This form needs two sines per sample instead of
        four and has no cancellation between nearly equal cosines.  With dual
        ν and ϑ the same formula gives ``p + s b``.

        Parameters
        ----------
        sample_interval : float
            Sample interval h [s].
        first : int
            Index of the first sample (it starts at ``first · h``).
        count : int
            Number of samples.
        dual : bool, keyword-only
            Return ``p + s b`` (:class:`Dual`, ``b`` in m/s) instead of ``p`` [rad].

        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        ndarray or Dual, shape (count, 3)

        Examples
        --------
        >>> m = RegularPrecession(eps=0.5, nu=2 * np.pi, nutation=0.2)
        >>> t = np.arange(4) * 0.01
        >>> bool(np.allclose(m.grid_increments(0.01, 0, 3), m.angle_increments(t[:-1], t[1:]), rtol=1e-13, atol=0))
        True
        """
        budget.check(budget.arrays(3.0 * float(count), what=f"`count` = {count:.3g} samples", copies=20.0 if dual else 10.0), limits)
        h = float(sample_interval)
        t_mid = (np.arange(first, first + count) + 0.5) * h
        nu, nut = self._dual_params() if dual else (self.nu, self.nutation)
        rate = self._rate(t_mid, nu, nut)
        sigma = 2.0 * np.sin(0.5 * h * nu) / nu
        scale = np.stack([sigma, sigma, sigma * 0.0 + h], axis=-1)
        return rate * scale


def _time(t):
    if isinstance(t, Dual):
        return t
    arr = np.asarray(t)
    if np.iscomplexobj(arr):  # complex-step differentiation in tests
        return arr
    return as_array(t, "t")


@dataclass(frozen=True)
class ExactState:
    """Exact attitude and apparent velocity at given times.

    Attributes
    ----------
    attitude : ndarray, shape (..., 4)
        Λ(t), mapping E to I.
    biquaternion : Dual, shape (..., 4)
        θ(t) = Λ + s M.
    w_body : ndarray, shape (..., 3)
        W_E(t) [m/s], eq. (1.10).
    w_inertial : ndarray, shape (..., 3)
        W_I(t) [m/s], eq. (1.11).
    """

    attitude: np.ndarray
    biquaternion: Dual
    w_body: np.ndarray
    w_inertial: np.ndarray


def initial_biquaternion(attitude0, w_inertial0) -> Dual:
    """Unit biquaternion ``θ0 = Λ0 + s M0`` with ``M0 = ½ {0, W_I(0)} ∘ Λ0``.

    This inverts (1.3): ``W_I = 2 vect(M ∘ Λ̄)`` with ``scal(M ∘ Λ̄) = 0``.

    Parameters
    ----------
    attitude0 : array_like, shape (4,)
        Unit quaternion Λ(0).
    w_inertial0 : array_like, shape (3,)
        W_I(0) [m/s].
    """
    lam = as_quaternion(attitude0, "attitude0", unit=True)
    w = as_vector(w_inertial0, "w_inertial0")
    m = 0.5 * quat.multiply(quat.vector_to_quat(w), lam)
    return Dual(lam, m)


def exact_state(motion: RegularPrecession, t, attitude0=(1.0, 0.0, 0.0, 0.0), w_inertial0=(0.0, 0.0, 0.0)) -> ExactState:
    """Exact state of the (dual) regular precession from given initial conditions.

    The general solution (1.5) is ``θ(t) = C ∘ P(t)`` with the constant
    biquaternion ``C = θ(0) ∘ P̄(0)``; W_E and W_I follow from (1.3), which is
    equivalent to (1.10)–(1.11).

    Parameters
    ----------
    motion : RegularPrecession
    t : array_like
        Times [s].
    attitude0 : array_like, shape (4,)
        Λ(0), unit quaternion.
    w_inertial0 : array_like, shape (3,)
        W_I(0) [m/s].
    """
    theta0 = initial_biquaternion(attitude0, w_inertial0)
    p0 = motion.biquaternion(0.0)
    c = quat.multiply(theta0, quat.conjugate(p0))
    theta = quat.multiply(c, motion.biquaternion(t))
    lam, m = theta.re, theta.du
    w_body = 2.0 * quat.vect(quat.multiply(quat.conjugate(lam), m))
    w_inertial = 2.0 * quat.vect(quat.multiply(m, quat.conjugate(lam)))
    return ExactState(attitude=lam, biquaternion=theta, w_body=w_body, w_inertial=w_inertial)
