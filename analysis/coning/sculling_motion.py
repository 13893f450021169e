"""Classical sculling: angular vibration about one body axis, linear vibration along another.

The body turns about its axis ``e_r`` by the angle

    θ(t) = θ₀ sin(νt + φ_θ),       ω(t) = θ₀ ν cos(νt + φ_θ) e_r,

while the accelerometers sense the specific force

    a(t) = A sin(νt + φ_a) e_a       (e_a ⟂ e_r, body frame E).

The rotation is about a fixed axis, so everything has a closed form: the
attitude ``Q(t) = (cos θ/2, sin θ/2 e_r)`` (``2Q' = Q ∘ ω``), the gyro
increments ``p_j = (θ(t_j) − θ(t_{j−1})) e_r`` and the velocity increments
``b_j = ∫ a dt``.  The apparent velocity ``W_I = ∫ Q a Q̄ dt`` (Lebedev & Panov
1989, eq. (1.3): ``W_I = 2 vect(M ∘ Λ̄)`` with ``2θ' = θ ∘ (ω + s a)``) is a sum
of Bessel functions by the Jacobi–Anger expansion; the series is summed until
its terms are below round-off, so it is exact to machine precision.  Its
constant part is the rectified specific force

    ⟨Q a Q̄⟩ = A J₁(θ₀) cos(φ_a − φ_θ) (e_r × e_a),

which a velocity algorithm must reproduce; what it gets wrong accumulates as a
constant velocity-error rate, the *sculling* (rectification) error.  Like
every error of the package it is exact minus algorithm (package docstring,
"Errors"): the rate of ``W_I* − W_I``, positive when the algorithm
under-rectifies.
:func:`rectification_error` gives it for any algorithm from one step, exactly
to first order in θ₀ A (the small-amplitude limit used by Ignagni 1998 and
Savage 1998); :func:`strapdown.analysis.coning.simulator.simulate` gives it
at any amplitude.

The motion offers the interface the simulator needs (``grid_increments``,
``attitude``, ``biquaternion``), the same as
:class:`~strapdown.analysis.coning.precession.RegularPrecession`.

References
----------
Savage (1998), "Strapdown inertial navigation integration algorithm design part 2:
velocity and position algorithms", sculling motion.
Ignagni (1998), "Duality of optimal strapdown sculling and coning compensation
algorithms".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mpmath
import numpy as np
from scipy.special import jv

from ...derivations.coning.algorithms import Algorithm
from ..core import budget
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.validation import as_array, as_float, as_int, positive

__all__ = ["ScullingMotion", "RectificationError", "rectification_error"]


def _axis(index: int, name: str) -> np.ndarray:
    i = as_int(index, name)
    if i not in (0, 1, 2):
        raise ValueError(f"Expected `{name}` to be 0, 1 or 2 (x, y, z), got {i}")
    e = np.zeros(3)
    e[i] = 1.0
    return e


@dataclass(frozen=True)
class ScullingMotion:
    """Angular vibration about body axis ``rotation_axis`` with linear vibration along ``accel_axis``.

    Parameters
    ----------
    angle_amplitude : float
        θ₀, amplitude of the angular vibration [rad].
    accel_amplitude : float
        A, amplitude of the specific force [m/s²].
    nu : float
        Angular frequency ν of both vibrations [rad/s], > 0.
    angle_phase : float, optional
        φ_θ, phase of the angular vibration [rad] (default 0).
    accel_phase : float, optional
        φ_a, phase of the linear vibration [rad] (default 0: in phase).
    rotation_axis : int, optional
        Body axis e_r of the rotation: 0, 1, 2 for x, y, z (default 0).
    accel_axis : int, optional
        Body axis e_a of the specific force, ≠ ``rotation_axis`` (default 1).

    Raises
    ------
    ValueError
        Non-finite values, ν ≤ 0, an axis outside 0…2 or equal axes.
    TypeError
        Non-numeric values.

    Examples
    --------
    >>> m = ScullingMotion(0.01, 1.0, 2 * np.pi * 10)
    >>> bool(np.allclose(m.rectified_acceleration(), [0, 0, 1.0 * float(jv(1, 0.01))]))
    True
    """

    angle_amplitude: float
    accel_amplitude: float
    nu: float
    angle_phase: float = 0.0
    accel_phase: float = 0.0
    rotation_axis: int = 0
    accel_axis: int = 1

    def __post_init__(self):
        object.__setattr__(self, "angle_amplitude", as_float(self.angle_amplitude, "angle_amplitude"))
        object.__setattr__(self, "accel_amplitude", as_float(self.accel_amplitude, "accel_amplitude"))
        object.__setattr__(self, "nu", positive(self.nu, "nu"))
        object.__setattr__(self, "angle_phase", as_float(self.angle_phase, "angle_phase"))
        object.__setattr__(self, "accel_phase", as_float(self.accel_phase, "accel_phase"))
        _axis(self.rotation_axis, "rotation_axis")
        _axis(self.accel_axis, "accel_axis")
        if int(self.rotation_axis) == int(self.accel_axis):
            raise ValueError(f"Expected `accel_axis` different from `rotation_axis`, got both {int(self.rotation_axis)}")

    # ----------------------------------------------------------- helpers
    @property
    def e_r(self) -> np.ndarray:
        """Unit rotation axis e_r in E."""
        return _axis(self.rotation_axis, "rotation_axis")

    @property
    def e_a(self) -> np.ndarray:
        """Unit specific-force axis e_a in E."""
        return _axis(self.accel_axis, "accel_axis")

    @property
    def is_dual(self) -> bool:
        """True when the motion carries translation (A ≠ 0)."""
        return self.accel_amplitude != 0.0

    def angle(self, t):
        """θ(t) = θ₀ sin(νt + φ_θ) [rad].

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        return self.angle_amplitude * np.sin(self.nu * _time(t) + self.angle_phase)

    # ----------------------------------------------------------- rates
    def omega(self, t):
        """Body rate ω(t) in E [rad/s]; shape ``t.shape + (3,)``.

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        t = _time(t)
        return (self.angle_amplitude * self.nu * np.cos(self.nu * t + self.angle_phase))[..., None] * self.e_r

    def accel(self, t):
        """Specific force a(t) in E [m/s²]; shape ``t.shape + (3,)``.

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        t = _time(t)
        return (self.accel_amplitude * np.sin(self.nu * t + self.accel_phase))[..., None] * self.e_a

    def dual_rate(self, t) -> Dual:
        """Dual rate ``ω + s a``.

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        return Dual(self.omega(t), self.accel(t))

    # ----------------------------------------------------------- exact solution
    def attitude(self, t):
        """Particular solution ``Q(t) = (cos θ/2, sin θ/2 e_r)`` of ``2Q' = Q ∘ ω``.

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        half = 0.5 * self.angle(t)
        return np.concatenate([np.cos(half)[..., None], np.sin(half)[..., None] * self.e_r], axis=-1)

    def apparent_velocity(self, t):
        """Particular apparent velocity ``W(t) = ∫₀ᵗ Q a Q̄ dt`` in the frame of Q [m/s].

        Jacobi–Anger: with ``u = νt + φ_θ``, ``δ = φ_a − φ_θ``,
        ``cos(θ₀ sin u) = J₀ + 2 Σ J_{2k} cos 2ku`` and
        ``sin(θ₀ sin u) = 2 Σ J_{2k+1} sin (2k+1)u``; each product with
        ``sin(u + δ)`` integrates in closed form.  Terms are kept while
        ``J_n(θ₀)`` is above 1e-18 of the leading one.

        Parameters
        ----------
        t : array_like
            Times [s].

        Returns
        -------
        ndarray, shape ``t.shape + (3,)``
        """
        t = _time(t)
        th0, nu, amp = self.angle_amplitude, self.nu, self.accel_amplitude
        u = nu * t + self.angle_phase
        u0 = self.angle_phase
        delta = self.accel_phase - self.angle_phase

        def f_sin(n):  # ∫₀ᵗ sin(n u + δ) dt
            if n == 0:
                return math.sin(delta) * t
            return -(np.cos(n * u + delta) - math.cos(n * u0 + delta)) / (n * nu)

        def f_cos(n):  # ∫₀ᵗ cos(n u + δ) dt
            if n == 0:
                return math.cos(delta) * t
            return (np.sin(n * u + delta) - math.sin(n * u0 + delta)) / (n * nu)

        n_max = _bessel_terms(th0)
        # along e_a: sin(u+δ) cos θ
        along = float(jv(0, th0)) * f_sin(1)
        for k in range(1, n_max // 2 + 1):
            along = along + float(jv(2 * k, th0)) * (f_sin(1 + 2 * k) + f_sin(1 - 2 * k))
        # along e_r × e_a: sin(u+δ) sin θ
        normal = 0.0 * t
        for k in range(0, n_max // 2 + 1):
            m = 2 * k + 1
            normal = normal + float(jv(m, th0)) * (f_cos(1 - m) - f_cos(1 + m))
        e_n = np.cross(self.e_r, self.e_a)
        return amp * (along[..., None] * self.e_a + normal[..., None] * e_n)

    def biquaternion(self, t) -> Dual:
        """Particular solution ``P = Q + s R`` of ``2P' = P ∘ (ω + s a)``: ``R = ½ W ∘ Q``.

        Parameters
        ----------
        t : array_like
            Times [s].
        """
        q = self.attitude(t)
        w = self.apparent_velocity(t)
        return Dual(q, 0.5 * quat.multiply(quat.vector_to_quat(w), q))

    def rectified_acceleration(self):
        """Constant part ``A J₁(θ₀) cos(φ_a − φ_θ) (e_r × e_a)`` of ``Q a Q̄`` [m/s²], shape (3,)."""
        value = self.accel_amplitude * float(jv(1, self.angle_amplitude)) * math.cos(self.accel_phase - self.angle_phase)
        return value * np.cross(self.e_r, self.e_a)

    # ----------------------------------------------------------- increments
    def increments(self, t0, t1) -> Dual:
        """Exact integrals ``p + s b = ∫ (ω + s a) dt`` over ``[t0, t1]``.

        Parameters
        ----------
        t0, t1 : array_like
            Interval ends [s], broadcast together.

        Returns
        -------
        Dual, shape (..., 3)
            ``p`` [rad] (along e_r), ``b`` [m/s] (along e_a).
        """
        t0, t1 = np.broadcast_arrays(_time(t0), _time(t1))
        p = (self.angle(t1) - self.angle(t0))[..., None] * self.e_r
        nu, ph = self.nu, self.accel_phase
        b = (self.accel_amplitude / nu * (np.cos(nu * t0 + ph) - np.cos(nu * t1 + ph)))[..., None] * self.e_a
        return Dual(p, b)

    def grid_increments(self, sample_interval: float, first: int, count: int, *, dual: bool = False, limits: budget.Limits | None = None):
        """Increments over the uniform samples ``[(k−1)h, kh]``, k = first+1 … first+count.

        Written about the sample midpoint ``t_m`` (no cancellation):
        ``p = 2 θ₀ sin(νh/2) cos(νt_m + φ_θ) e_r`` and
        ``b = (2A/ν) sin(νh/2) sin(νt_m + φ_a) e_a``.  ``first`` may be negative:
        samples before t = 0 come from the same exact motion.

        Parameters
        ----------
        sample_interval : float
            Sample interval h [s].
        first : int
            Index of the first sample (it starts at ``first · h``).
        count : int
            Number of samples.
        dual : bool, keyword-only
            Return ``p + s b`` (:class:`Dual`) instead of ``p`` [rad].

        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        ndarray or Dual, shape (count, 3)

        Examples
        --------
        >>> m = ScullingMotion(0.02, 3.0, 2 * np.pi, angle_phase=0.3, accel_phase=1.0)
        >>> t = np.arange(-2, 3) * 0.01
        >>> q = m.grid_increments(0.01, -2, 4, dual=True)
        >>> ref = m.increments(t[:-1], t[1:])
        >>> bool(np.allclose(q.re, ref.re, rtol=1e-13, atol=0) and np.allclose(q.du, ref.du, rtol=1e-13, atol=0))
        True
        """
        budget.check(budget.arrays(3.0 * float(count), what=f"`count` = {count:.3g} samples", copies=12.0 if dual else 6.0), limits)
        h = float(sample_interval)
        t_mid = (np.arange(first, first + count) + 0.5) * h
        s = 2.0 * math.sin(0.5 * self.nu * h)
        p = (self.angle_amplitude * s * np.cos(self.nu * t_mid + self.angle_phase))[:, None] * self.e_r
        if not dual:
            return p
        b = (self.accel_amplitude * s / self.nu * np.sin(self.nu * t_mid + self.accel_phase))[:, None] * self.e_a
        return Dual(p, b)


def _bessel_terms(x: float) -> int:
    """Highest Bessel order needed so that J_n(x) is below 1e-18 · max(``|J_0|``, ``|J_1|``)."""
    ref = max(abs(float(jv(0, x))), abs(float(jv(1, x))), 1e-300)
    n = 1
    while n < 10 or abs(float(jv(n, x))) > 1e-18 * ref or n < abs(x):
        n += 1
        if n > 4000:
            raise ValueError(f"Expected a moderate `angle_amplitude`, got {x}")
    return n + 1


def _time(t):
    arr = np.asarray(t)
    if np.iscomplexobj(arr):
        return arr
    return as_array(t, "t")


# ---------------------------------------------------------------------------
# Rectification (sculling) error of an algorithm, first order in θ₀ A
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class RectificationError:
    """Constant velocity-error rate of an algorithm's dual extension under sculling.

    Attributes
    ----------
    algorithm : Algorithm
        The rotation-vector algorithm (its dual extension is the velocity algorithm).
    sample_interval : float
        h [s].
    nu_h : float
        ν h [rad], the frequency in units of the sample rate.
    rate : float
        Error rate of the apparent velocity along ``e_r × e_a`` [m/s²], exact
        minus algorithm (the rate of ``W_I* − W_I``, as
        :attr:`strapdown.analysis.coning.simulator.SimulationResult.velocity_error_rate`),
        to first order in θ₀ A.
    relative : float
        ``rate`` over the exact rectified acceleration ``½ θ₀ A cos(φ_a − φ_θ)``
        (the same order), [-]; NaN when that vanishes.
    exact_rate : float
        That exact rectified acceleration along ``e_r × e_a``, first order in θ₀ A [m/s²].
    """

    algorithm: Algorithm
    sample_interval: float
    nu_h: float
    rate: float
    relative: float
    exact_rate: float


def _phasors(motion: ScullingMotion, h, index):
    """Complex amplitudes of p_j (along e_r) and b_j (along e_a) of sample j of a step starting at t_k.

    A quantity ``x_k = Im(x̂ e^{iνt_k})``; sample j covers ``[t_k + (j−1)h, t_k + jh]``.
    Evaluated in :mod:`mpmath` (the differences of nearby exponentials cancel).
    """
    nu = mpmath.mpf(motion.nu)
    j = mpmath.mpf(int(index))
    lo, hi = mpmath.expj(nu * (j - 1) * h), mpmath.expj(nu * j * h)
    p = motion.angle_amplitude * mpmath.expj(motion.angle_phase) * (hi - lo)
    b = motion.accel_amplitude / nu * 1j * mpmath.expj(motion.accel_phase) * (lo - hi)
    return p, b


def _mean(x, y):
    """Mean over the steps of ``Im(x e^{iνt_k}) Im(y e^{iνt_k})`` (ν H not a multiple of π)."""
    return mpmath.re(x * mpmath.conj(y)) / 2


#: Working precision [decimal digits] of :func:`rectification_error`: the error of a
#: high-order algorithm is a difference of O(1) terms that cancel to (ν h)^10 and below.
RECTIFICATION_DIGITS = 60


def rectification_error(algorithm: Algorithm, motion: ScullingMotion, sample_interval: float) -> RectificationError:
    """Sculling (rectification) error of the dual extension of ``algorithm``, first order in θ₀ A.

    All increments lie along e_r (gyro) and e_a (accelerometer), so the
    algorithm's attitude is exact and only the bilinear terms matter.  Along
    ``e_n = e_r × e_a`` one step adds, seen from frame I (Q at the start of
    the step, angle θ_k):

        θ_k V + ½ P V + Σ c_ij (p_i b_j − b_i p_j)

    (``P``, ``V``: sums of the p_j, b_j of the step; ``½ P × V`` is the rotation
    term of the biquaternion step ``exp(ΔΦ/2)``; the sum is the dual part of the
    pairwise terms, indices ≤ 0 reaching into earlier steps), against the exact
    ``∫ θ a dt``.  Every factor is a sinusoid of the step start t_k, so the mean
    over the steps is ``½ Re(x̂ ȳ)`` of the complex amplitudes; divided by the
    step H it is the rate of the algorithm's rectified velocity, and the exact
    rectified acceleration minus it is the error rate (exact minus algorithm).
    Terms of degree 3 and higher (nested and dot
    terms) contribute at order θ₀² A and beyond, and are left out.

    Parameters
    ----------
    algorithm : Algorithm
        The rotation-vector algorithm; its dual extension is the velocity algorithm.
    motion : ScullingMotion
        The sculling motion.
    sample_interval : float
        Sample interval h [s], > 0; ν H must not be a multiple of π.

    Returns
    -------
    RectificationError

    Raises
    ------
    ValueError
        Non-positive h, or ν H a multiple of π (the step samples the vibration
        at a fixed phase, and the error is not a constant rate).
    TypeError
        If ``algorithm`` is not an :class:`Algorithm` or ``motion`` not a :class:`ScullingMotion`.

    References
    ----------
    Ignagni (1998); Savage (1998), part 2; Lebedev & Panov (1989), eq. (2.5) (dual extension).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> m = ScullingMotion(1e-3, 1.0, 2 * np.pi * 10)
    >>> e = rectification_error(get("two-sample"), m, 0.005)
    >>> e.relative > 0   # exact minus algorithm: the two-sample sculling algorithm under-rectifies
    True
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not isinstance(motion, ScullingMotion):
        raise TypeError(f"Expected `motion` to be a ScullingMotion, got {type(motion).__name__}")
    h = positive(sample_interval, "sample_interval")
    n = algorithm.samples
    big_h = n * h
    if abs(math.sin(motion.nu * big_h)) < 1e-9:
        raise ValueError(f"Expected ν H not a multiple of π, got ν H = {motion.nu * big_h:g}")
    with mpmath.workdps(RECTIFICATION_DIGITS):
        hm = mpmath.mpf(h)
        phasors = {}  # by sample index: each is needed by several pairs

        def at(index):
            if index not in phasors:
                phasors[index] = _phasors(motion, hm, index)
            return phasors[index]

        cur = [at(j) for j in range(1, n + 1)]
        p_sum, b_sum = sum(p for p, _ in cur), sum(b for _, b in cur)
        theta_k = motion.angle_amplitude * mpmath.expj(motion.angle_phase)
        total = _mean(theta_k, b_sum) + _mean(p_sum, b_sum) / 2
        for (i, j), c in algorithm.pairwise.items():
            pi, bi = at(i)
            pj, bj = at(j)
            total += mpmath.mpf(c.numerator) / c.denominator * (_mean(pi, bj) - _mean(bi, pj))
        exact_rate = mpmath.mpf(motion.angle_amplitude) * motion.accel_amplitude * mpmath.cos(mpmath.mpf(motion.accel_phase) - motion.angle_phase) / 2
        rate = exact_rate - total / (n * hm)
        relative = float(rate / exact_rate) if exact_rate != 0 else float("nan")
        return RectificationError(algorithm, h, motion.nu * h, float(rate), relative, float(exact_rate))

