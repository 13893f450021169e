"""The sculling part of an integrator as data, and its rectification error in closed form.

An integrator's velocity increment over a step, in the body axes at the start
of the step, is to second order in the increments

    Δv = Σ_j a°_j b_j + Σ_{i,j} m_ij p_i × b_j,

with exact fractions ``a°_j`` and ``m_ij`` (indices ≤ 0: samples of earlier
steps).  The package's velocity algorithms are the dual extension of a
rotation-vector algorithm (Lebedev & Panov 1989, eq. (2.5)): the term
``c p_i × p_j`` gives ``c (p_i × b_j + b_i × p_j)``, and the biquaternion step
adds the rotation term ``½ P × V`` (``P``, ``V`` the sums of the step), so

    a°_j = 1 (j = 1 … N),     m_ij = ½ [i, j in the step] + c_ij − c_ji

(:meth:`ScullingTerms.dual_extension`, with ``c_ij`` the coefficient of
``p_i × p_j``, i < j).  An integrator whose sculling part differs is not the
dual extension of its coning part; :meth:`ScullingTerms.defect` says where.

Under classical sculling (:class:`~strapdown.analysis.coning.sculling_motion.ScullingMotion`:
rotation θ₀ sin(νt + φ_θ) about ``e_r``, specific force A sin(νt + φ_a) along
``e_a``) the increments are ``p_j ∥ e_r`` and ``b_j ∥ e_a``, and along
``e_n = e_r × e_a`` a step starting at angle ``θ_k`` adds in frame I, to first
order in θ₀ A,

    θ_k Σ_j a°_j b_j + Σ_{i,j} m_ij p_i b_j,

against the exact ``∫ θ a dt``.  Every factor is a sinusoid of the step's
start, so the mean over the steps is ``½ Re(x̂ ȳ)`` of their complex
amplitudes; the rectification error rate (exact minus algorithm) follows
exactly in ν h, for any coefficients (:meth:`ScullingTerms.rectification_error`;
for a dual extension it is
:func:`strapdown.analysis.coning.sculling_motion.rectification_error`, which
the tests check).  Amplitudes are evaluated in :mod:`mpmath` at
:data:`DIGITS` digits: the rates of high-order algorithms are differences of
O(1) terms.

Velocity accuracy order.  With the rate and the specific force expanded at
the start of the step, ``ω = Σ_k ω_k τ^k/k!`` and ``a = Σ_l a_l τ^l/l!``, a
sample's increments are ``p_i = Σ_k ω_k h^(k+1) P_k(i)`` and
``b_j = Σ_l a_l h^(l+1) P_l(j)`` with ``P_k(i) = (i^(k+1) − (i−1)^(k+1))/(k+1)!``.
The exact velocity increment over the step, ``∫_0^H C(τ) a(τ) dτ`` in the body
axes at its start, is to second order ``∫ a + ∫ φ(τ) × a(τ) dτ``, whose term
``ω_k × a_l`` has the coefficient ``H^(k+l+2) / ((k+1)! l! (k+l+2))``.  The
error of the linear and bilinear part at weight w (the power of h) is then

    Σ_j a°_j P_(w−1)(j) − N^w/w!                       (the term a_(w−1)),
    Σ_{i,j} m_ij P_k(i) P_l(j) − N^w/((k+1)! l! w)      (the term ω_k × a_l, k + l = w − 2),

in exact fractions (:meth:`ScullingTerms.error_weight`).  The first weight where
one of them is not zero is that of the local velocity error, O(h^w), when
w ≤ 2; from h³ on, the terms of degree three (ω × (ω × a) and their like, in
the identified remainder) count as well, and the integrator's own error,
measured against the exact increment
(:func:`~.verification.velocity_error_exponent`), decides.  A departure from the
dual extension alone makes an error at the weight of its own moments
(:func:`departure_weight`): a missing rotation term ½ P × V, ``m_ij`` short by
½ over the step, already at h² (accuracy order 1).

Public API
----------
:data:`DIGITS`, :data:`MAX_WEIGHT`, :class:`ScullingTerms`, :class:`ScullingError`,
:func:`departure_weight`.

References
----------
Lebedev & Panov (1989), eq. (2.5); Savage (1998), part 2; Ignagni (1998).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import mpmath

from ....derivations.coning.algorithms import Algorithm
from ...core.validation import as_int, positive
from ..sculling_motion import ScullingMotion

__all__ = ["DIGITS", "MAX_WEIGHT", "ScullingTerms", "ScullingError", "departure_weight"]

#: Working precision of the closed form [decimal digits].
DIGITS = 60
#: Highest weight (power of h) of the velocity error examined.
MAX_WEIGHT = 8


def _moment(k: int, i: int) -> Fraction:
    """``P_k(i) = (i^(k+1) − (i−1)^(k+1)) / (k+1)!``: the weight of ``ω_k`` (or ``a_k``) in sample i's increment."""
    return Fraction(i ** (k + 1) - (i - 1) ** (k + 1), math.factorial(k + 1))


def _error_terms(linear: dict, bilinear: dict, weight: int, exact_samples: int | None) -> list:
    """The nonzero error terms at ``weight``: ``("a", l)`` and ``("w×a", k, l)`` with their coefficients.

    ``exact_samples`` N subtracts the exact increment's terms (None: the moments of ``linear`` and ``bilinear`` alone).
    """
    out = []
    lin = sum((c * _moment(weight - 1, j) for j, c in linear.items()), Fraction(0))
    if exact_samples is not None:
        lin -= Fraction(exact_samples**weight, math.factorial(weight))
    if lin:
        out.append((("a", weight - 1), lin))
    for k in range(weight - 1):
        l_ = weight - 2 - k
        total = sum((c * _moment(k, i) * _moment(l_, j) for (i, j), c in bilinear.items()), Fraction(0))
        if exact_samples is not None:
            total -= Fraction(exact_samples**weight, math.factorial(k + 1) * math.factorial(l_) * weight)
        if total:
            out.append((("w×a", k, l_), total))
    return out


def departure_weight(departures, max_weight: int = MAX_WEIGHT) -> int | None:
    """The lowest weight w (power of h) at which ``departures`` alone change the velocity increment.

    Parameters
    ----------
    departures : iterable of (str, tuple, Fraction)
        ``("linear", (j,), d)`` and ``("bilinear", (i, j), d)`` as
        :meth:`ScullingTerms.defect` gives them.
    max_weight : int
        Highest weight examined.

    Returns
    -------
    int or None
        None: no change through ``max_weight``.

    Examples
    --------
    >>> departure_weight([("bilinear", (1, 1), Fraction(-1, 2))])   # the rotation term ½ P × V missing, N = 1
    2
    >>> departure_weight([("bilinear", (0, 1), Fraction(1)), ("bilinear", (1, 0), Fraction(-1))])
    3
    """
    linear = {key[0]: d for kind, key, d in departures if kind == "linear"}
    bilinear = {tuple(key): d for kind, key, d in departures if kind == "bilinear"}
    for w in range(1, as_int(max_weight, "max_weight", minimum=1) + 1):
        if _error_terms(linear, bilinear, w, None):
            return w
    return None


@dataclass(frozen=True)
class ScullingError:
    """Constant velocity-error rate of a sculling part under classical sculling, first order in θ₀ A.

    Attributes
    ----------
    nu_h : float
        ν h [rad].
    rate : float
        Rate of ``W_I* − W_I`` along ``e_r × e_a`` [m/s²], exact minus algorithm.
    exact_rate : float
        The exact rectified acceleration ``½ θ₀ A cos(φ_a − φ_θ)`` [m/s²].
    """

    nu_h: float
    rate: float
    exact_rate: float

    @property
    def relative(self) -> float:
        """``rate / exact_rate`` [dimensionless] (NaN when the exact rate vanishes)."""
        return self.rate / self.exact_rate if self.exact_rate else math.nan


@dataclass(frozen=True)
class ScullingTerms:
    """``Δv = Σ a°_j b_j + Σ m_ij p_i × b_j`` with exact fractions (module docstring).

    Attributes
    ----------
    samples : int
        N, samples per step.
    linear : dict
        ``{j: a°_j}``, Fractions (nonzero entries).
    bilinear : dict
        ``{(i, j): m_ij}``, Fractions, coefficient of ``p_i × b_j`` (nonzero entries).
    """

    samples: int
    linear: dict = field(default_factory=dict)
    bilinear: dict = field(default_factory=dict)

    def __post_init__(self):
        as_int(self.samples, "samples", minimum=1)
        for key, c in list(self.linear.items()) + list(self.bilinear.items()):
            if not isinstance(c, Fraction):
                raise TypeError(f"Expected exact Fraction coefficients, got {c!r} at {key}")

    @classmethod
    def dual_extension(cls, algorithm: Algorithm) -> ScullingTerms:
        """The sculling part of ``algorithm``'s dual extension with the biquaternion step's rotation term.

        Parameters
        ----------
        algorithm : Algorithm
            A rotation-vector algorithm (pairwise terms count; nested and dot
            terms are of degree three and more).

        Returns
        -------
        ScullingTerms

        Examples
        --------
        >>> from strapdown.derivations.coning.registry import get
        >>> ScullingTerms.dual_extension(get("savage-1+1")).bilinear
        {(1, 1): Fraction(1, 2), (0, 1): Fraction(1, 12), (1, 0): Fraction(-1, 12)}
        """
        n = algorithm.samples
        m: dict = {}
        for i in range(1, n + 1):
            for j in range(1, n + 1):
                m[(i, j)] = Fraction(1, 2)
        for (i, j), c in algorithm.pairwise.items():
            m[(i, j)] = m.get((i, j), Fraction(0)) + c
            m[(j, i)] = m.get((j, i), Fraction(0)) - c
        return cls(n, {j: Fraction(1) for j in range(1, n + 1)}, {k: v for k, v in m.items() if v})

    def defect(self, algorithm: Algorithm) -> tuple:
        """Where this sculling part differs from the dual extension of ``algorithm`` (:meth:`dual_extension`).

        Parameters
        ----------
        algorithm : Algorithm
            The coning part it is compared with.

        Returns
        -------
        tuple of (str, tuple, Fraction)
            ``("linear", (j,), a°_j − expected)`` and ``("bilinear", (i, j), m_ij − expected)``, nonzero only.
        """
        ref = ScullingTerms.dual_extension(algorithm)
        out = []
        for j in sorted(set(self.linear) | set(ref.linear)):
            d = self.linear.get(j, Fraction(0)) - ref.linear.get(j, Fraction(0))
            if d:
                out.append(("linear", (j,), d))
        for key in sorted(set(self.bilinear) | set(ref.bilinear)):
            d = self.bilinear.get(key, Fraction(0)) - ref.bilinear.get(key, Fraction(0))
            if d:
                out.append(("bilinear", key, d))
        return tuple(out)

    def error_weight(self, max_weight: int = MAX_WEIGHT) -> int | None:
        """The lowest weight w at which the linear and bilinear part differs from the exact velocity increment (module docstring).

        Parameters
        ----------
        max_weight : int
            Highest weight examined.

        Returns
        -------
        int or None
            The local velocity error of the linear and bilinear part is
            O(h^w); None: none through ``max_weight``.

        Examples
        --------
        >>> from strapdown.derivations.coning.registry import get
        >>> ScullingTerms.dual_extension(get("two-sample")).error_weight()
        5
        >>> ScullingTerms(1, {1: Fraction(1)}, {}).error_weight()   # no sculling term: ½ ω_0 × a_0 h² missed
        2
        """
        for w in range(1, as_int(max_weight, "max_weight", minimum=1) + 1):
            if _error_terms(self.linear, self.bilinear, w, self.samples):
                return w
        return None

    def rectification_error(self, motion: ScullingMotion, sample_interval: float) -> ScullingError:
        """Rectification error rate under ``motion`` at sample interval h, first order in θ₀ A, exact in ν h.

        Parameters
        ----------
        motion : ScullingMotion
            Classical sculling.
        sample_interval : float
            h [s], > 0; ν N h must not be a multiple of π.

        Returns
        -------
        ScullingError

        Raises
        ------
        TypeError
            If ``motion`` is not a :class:`ScullingMotion`.
        ValueError
            Non-positive h, or ν N h a multiple of π (the step samples the
            vibration at a fixed phase: the error is not a constant rate).

        References
        ----------
        Savage (1998), part 2; Ignagni (1998).
        """
        if not isinstance(motion, ScullingMotion):
            raise TypeError(f"Expected `motion` to be a ScullingMotion, got {type(motion).__name__}")
        h = positive(sample_interval, "sample_interval")
        if abs(math.sin(motion.nu * self.samples * h)) < 1e-9:
            raise ValueError(f"Expected ν N h not a multiple of π, got ν N h = {motion.nu * self.samples * h:g}")
        with mpmath.workdps(DIGITS):
            nu, hm = mpmath.mpf(motion.nu), mpmath.mpf(h)

            def p(j):  # complex amplitude of p_j along e_r, for a step starting at t_k: x_k = Im(x̂ e^{iνt_k})
                return motion.angle_amplitude * mpmath.expj(motion.angle_phase) * (mpmath.expj(nu * j * hm) - mpmath.expj(nu * (j - 1) * hm))

            def b(j):  # along e_a
                return motion.accel_amplitude / nu * 1j * mpmath.expj(motion.accel_phase) * (mpmath.expj(nu * (j - 1) * hm) - mpmath.expj(nu * j * hm))

            def mean(x, y):
                return mpmath.re(x * mpmath.conj(y)) / 2

            theta_k = motion.angle_amplitude * mpmath.expj(motion.angle_phase)
            v_lin = sum((mpmath.mpf(c.numerator) / c.denominator * b(j) for j, c in self.linear.items()), mpmath.mpc(0))
            total = mean(theta_k, v_lin)
            for (i, j), c in self.bilinear.items():
                total += mpmath.mpf(c.numerator) / c.denominator * mean(p(i), b(j))
            exact = mpmath.mpf(motion.angle_amplitude) * motion.accel_amplitude * mpmath.cos(mpmath.mpf(motion.accel_phase) - motion.angle_phase) / 2
            rate = exact - total / (self.samples * hm)
            return ScullingError(motion.nu * h, float(rate), float(exact))
