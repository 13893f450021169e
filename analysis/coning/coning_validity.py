"""Where the leading coning term is the drift: the next term in α, and the range of α and ωh where the leading term holds.

Under classical coning (half-cone angle α, coning rate ω, sample interval h)
the drift of an algorithm along the cone axis is

    u = c α² ω (ωh)^m  +  c₄ α⁴ ω (ωh)^k  +  …,

the leading term of :func:`strapdown.derivations.coning.drift.coning_drift`
(coning-drift order m) and the leading α⁴ term of the drift series
(:func:`strapdown.derivations.coning.drift.coning_drift_series` with
``alpha_power=4``, :func:`next_coning_term`).  For a pairwise algorithm k = 4
whatever m is, so for the coning-optimised algorithms (m = 8 … 12) the α⁴ term
overtakes the α² term at small angles: the leading term then overstates or
understates the drift many times (ignagni-1996-5 at α = 1°, ωh = 0.13: 13
times the drift).

:func:`leading_term_range` finds where the leading term is within a relative
tolerance of the exact drift, against
:func:`strapdown.analysis.coning.exact_drift.exact_coning_drift` (one step in
extended precision, every order in α and ωh; nothing from the series): the
largest ωh as α → 0, and at given ωh the largest α.  Each limit is the end of
the range that starts at 0 (the first exit, found on a logarithmic grid of
:data:`GRID_PER_DECADE` points per decade and refined by bisection to
:data:`BISECTION_RATIO`).  The two terms give the approximate law
``α ≲ sqrt(tol |c / c₄|) (ωh)^((m − k)/2)`` (:attr:`LeadingTermRange.law`),
used to place the search.  :func:`coning_case` sets one case (α, ω, h)
against the range.

Public API
----------
:data:`DEFAULT_TOLERANCE`, :class:`NextConingTerm`, :func:`next_coning_term`,
:class:`LeadingTermRange`, :func:`leading_term_range`, :class:`ConingCase`,
:func:`coning_case`.

References
----------
Ignagni (1990, 1996) for the coning-optimised algorithms; Lebedev & Panov (1989), eq. (4.1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ...derivations.coning.drift import coning_drift_series
from ...derivations.coning.series import WEIGHT_LIMIT
from ..core.validation import in_closed_interval, positive
from .drift_theory import coning_drift
from .exact_drift import exact_coning_drift

__all__ = [
    "DEFAULT_TOLERANCE",
    "TOLERANCE_RANGE",
    "OMEGA_H_FLOOR",
    "CONE_ANGLE_FLOOR",
    "NextConingTerm",
    "next_coning_term",
    "LeadingTermRange",
    "leading_term_range",
    "ConingCase",
    "coning_case",
]

#: Relative difference of the leading term and the exact drift within which the leading term holds [-].
DEFAULT_TOLERANCE = 0.1
#: Points per decade of the grid on which the first exit from the tolerance is searched.
GRID_PER_DECADE = 4
#: The bisection stops when the two ends of the bracket are within this ratio [-].
BISECTION_RATIO = 1.001
#: Largest half-cone angle searched [rad] (80°).
MAX_CONE_ANGLE = math.radians(80.0)
#: Largest ωh searched [rad]: the coning rate turns less than π per sample.
MAX_OMEGA_H = 3.0
#: Smallest ωh searched for the ωh limit [rad]; below it the leading term is taken to hold as α → 0.
MIN_OMEGA_H = 1e-3
#: Smallest ωh [rad] and half-cone angle [rad] accepted: below them the drift is far beyond any
#: quoting (α² (ωh)^(m+1) below 10⁻¹⁰⁰ of the rates) and only the float range would be probed.
OMEGA_H_FLOOR = 1e-6
CONE_ANGLE_FLOOR = 1e-8
#: Range of relative tolerances accepted: below the first the search would probe drifts beyond the
#: working precision of the exact drift; above the second "within" says nothing.
TOLERANCE_RANGE = (1e-6, 0.5)
#: Default ωh at which the largest α is given [rad].
DEFAULT_OMEGA_H = (0.01, 0.03, 0.1, 0.3, 1.0)


@dataclass(frozen=True)
class NextConingTerm:
    """The leading α⁴ term of the coning drift, ``c₄ α⁴ ω (ωh)^order`` (exact minus algorithm, along the cone axis).

    Attributes
    ----------
    order : int or None
        k, its power of ωh (None if the α⁴ part vanishes through ``max_weight``).
    coefficient : Fraction or None
        c₄, exact.
    max_weight : int
        Weight of the drift series searched (the power of h it reaches).
    series : tuple of (int, Fraction)
        Every nonzero term of the α⁴ part through ``max_weight``: ``(power of ωh, coefficient)``,
        ``u₄ = α⁴ ω Σ coefficient (ωh)^power``; the first is ``(order, coefficient)``.
    """

    order: int | None
    coefficient: Fraction | None
    max_weight: int
    series: tuple = ()

    def value(self, cone_angle: float, nu: float, sample_interval: float) -> float | None:
        """``c₄ α⁴ ω (ωh)^k`` [rad/s] (None without an α⁴ term).

        Parameters
        ----------
        cone_angle : float
            α [rad].
        nu : float
            ω [rad/s].
        sample_interval : float
            h [s].

        Returns
        -------
        float or None
        """
        if self.order is None:
            return None
        return float(self.coefficient) * cone_angle**4 * nu * (nu * sample_interval) ** self.order


def next_coning_term(algorithm: Algorithm, *, max_weight: int = 13) -> NextConingTerm:
    """The leading α⁴ term of the coning drift of ``algorithm``, from the drift series.

    The series is searched through weights 7, 9, … up to ``max_weight`` until its α⁴
    part has a nonzero term.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    max_weight : int, keyword-only
        Highest weight searched (7 … :data:`~strapdown.derivations.coning.series.WEIGHT_LIMIT`).

    Returns
    -------
    NextConingTerm

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm.
    ValueError
        If ``max_weight`` is outside 7 … WEIGHT_LIMIT.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> t = next_coning_term(get("ignagni-1996-5"))
    >>> t.order, t.coefficient
    (4, Fraction(-1, 224))
    """
    if isinstance(max_weight, bool) or not isinstance(max_weight, int) or not 7 <= max_weight <= WEIGHT_LIMIT:
        raise ValueError(f"Expected `max_weight` an integer in 7..{WEIGHT_LIMIT}, got {max_weight!r}")
    N = algorithm.samples if isinstance(algorithm, Algorithm) else 1
    for K in sorted(set(range(7, max_weight + 1, 2)) | {max_weight}):
        # u = α⁴ ω Σ c_w (ωH)^(w−1), H = N h
        series = tuple((w - 1, c * Fraction(N) ** (w - 1)) for w, c in enumerate(coning_drift_series(algorithm, K, alpha_power=4)) if c)
        if series:
            return NextConingTerm(series[0][0], series[0][1], K, series)
    return NextConingTerm(None, None, max_weight)


def _first_exit(inside, low: float, high: float) -> float:
    """Smallest t in [low, high] where ``inside(t)`` turns false, searched upward on a log grid; inf if never.

    Returns ``low`` when ``inside(low)`` is already false.
    """
    if not inside(low):
        return low
    step = 10.0 ** (1.0 / GRID_PER_DECADE)
    a = low
    while a < high:
        b = min(a * step, high)
        if not inside(b):
            while b / a > BISECTION_RATIO:
                mid = math.sqrt(a * b)
                a, b = (mid, b) if inside(mid) else (a, mid)
            return math.sqrt(a * b)
        a = b
    return math.inf


@dataclass(frozen=True)
class _Terms:
    """The two leading terms of one algorithm's coning drift and the search they guide."""

    algorithm: Algorithm
    order: int
    coefficient: Fraction
    next_term: NextConingTerm

    @classmethod
    def of(cls, algorithm: Algorithm) -> _Terms:
        d = coning_drift(algorithm)
        return cls(algorithm, d.order, d.coefficient, next_coning_term(algorithm))

    def law(self, tolerance: float) -> tuple | None:
        t = self.next_term
        if t.order is None:
            return None
        return math.sqrt(tolerance * abs(float(self.coefficient) / float(t.coefficient))), (self.order - t.order) / 2

    def inside(self, tolerance: float, cone_angle: float, omega_h: float) -> bool:
        """Whether the leading term is within ``tolerance`` of the exact drift at (α, x = ωh) (ω = 1)."""
        exact = exact_coning_drift(self.algorithm, cone_angle=cone_angle, nu=1.0, sample_interval=omega_h)
        lead = float(self.coefficient) * cone_angle**2 * omega_h**self.order
        return exact != 0.0 and abs(lead / exact - 1.0) <= tolerance

    def small_angle(self, tolerance: float, omega_h: float) -> float:
        """An α [rad] so small at ωh that the α⁴ term is below 10⁻⁶ of the tolerance."""
        law = self.law(tolerance)
        return 1e-6 if law is None else min(1e-4, 1e-3 * law[0] * omega_h ** law[1])


@cache
def _omega_h_limit(terms: _Terms, tolerance: float) -> float:
    return _first_exit(lambda x: terms.inside(tolerance, terms.small_angle(tolerance, x), x), MIN_OMEGA_H, MAX_OMEGA_H)


@cache
def _half_angle_limit(terms: _Terms, tolerance: float, omega_h: float) -> float:
    if not omega_h < _omega_h_limit(terms, tolerance):
        return 0.0

    def inside(alpha):
        return terms.inside(tolerance, alpha, omega_h)

    small = terms.small_angle(tolerance, omega_h)
    law = terms.law(tolerance)
    start = small if law is None else min(MAX_CONE_ANGLE, max(small, 0.01 * law[0] * omega_h ** law[1]))
    return _first_exit(inside, start if inside(start) else small, MAX_CONE_ANGLE)


@dataclass(frozen=True)
class LeadingTermRange:
    """Where ``c α² ω (ωh)^m`` is within ``tolerance`` of the exact coning drift (:func:`leading_term_range`).

    Attributes
    ----------
    algorithm : str
        Name of the algorithm.
    tolerance : float
        Relative tolerance [-].
    coning_drift_order : int
        m.
    coefficient : Fraction
        c.
    next_term : NextConingTerm
        The leading α⁴ term.
    omega_h_limit : float
        Largest ωh [rad] up to which the leading term holds as α → 0; inf if it
        holds up to :data:`MAX_OMEGA_H`.
    omega_h : tuple of float
        ωh [rad] at which the largest α is given.
    half_angle_limits : tuple of float
        Largest α [rad] at each of ``omega_h`` up to which the leading term
        holds; 0 where ωh is beyond ``omega_h_limit``, inf where it holds up to
        :data:`MAX_CONE_ANGLE`.
    law : tuple or None
        ``(factor [rad], power)`` of the two-term law ``α ≲ factor · (ωh)^power``,
        where the α⁴ term reaches ``tolerance`` of the leading one:
        ``factor = sqrt(tolerance |c / c₄|)``, ``power = (m − k)/2``; None
        without an α⁴ term.
    """

    algorithm: str
    tolerance: float
    coning_drift_order: int
    coefficient: Fraction
    next_term: NextConingTerm
    omega_h_limit: float
    omega_h: tuple
    half_angle_limits: tuple
    law: tuple | None


def leading_term_range(algorithm: Algorithm, *, omega_h=DEFAULT_OMEGA_H, tolerance: float = DEFAULT_TOLERANCE) -> LeadingTermRange:
    """The range of α and ωh where the leading coning term is within ``tolerance`` of the exact drift.

    Against :func:`strapdown.analysis.coning.exact_drift.exact_coning_drift`
    (independent of the series): the largest ωh as α → 0, and the largest α at
    each of ``omega_h``, each the end of the range that starts at 0.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    omega_h : sequence of float, keyword-only
        x = ωh [rad], each in [:data:`OMEGA_H_FLOOR`, :data:`MAX_OMEGA_H`] (default :data:`DEFAULT_OMEGA_H`).
    tolerance : float, keyword-only
        Relative tolerance [-], in :data:`TOLERANCE_RANGE` (default :data:`DEFAULT_TOLERANCE`).

    Returns
    -------
    LeadingTermRange

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm.
    ValueError
        For a tolerance outside TOLERANCE_RANGE or an ωh outside [OMEGA_H_FLOOR, MAX_OMEGA_H].

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> r = leading_term_range(get("ignagni-1996-5"), omega_h=(0.1,))
    >>> round(math.degrees(r.half_angle_limits[0]), 3), round(r.omega_h_limit, 2)
    (0.101, 0.59)
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    tolerance = in_closed_interval(tolerance, "tolerance", *TOLERANCE_RANGE)
    xs = tuple(in_closed_interval(x, "omega_h", OMEGA_H_FLOOR, MAX_OMEGA_H, text=f"[{OMEGA_H_FLOOR:g}, {MAX_OMEGA_H:g}] rad") for x in np.atleast_1d(np.asarray(omega_h, dtype=float)))
    terms = _Terms.of(algorithm)
    return LeadingTermRange(
        algorithm.name,
        tolerance,
        terms.order,
        terms.coefficient,
        terms.next_term,
        _omega_h_limit(terms, tolerance),
        xs,
        tuple(_half_angle_limit(terms, tolerance, x) for x in xs),
        terms.law(tolerance),
    )


@dataclass(frozen=True)
class ConingCase:
    """One case of classical coning set against the leading term's range (:func:`coning_case`).

    All drift rates along the cone axis, exact minus algorithm (positive: the
    computed attitude lags the coning rotation).

    Attributes
    ----------
    cone_angle : float
        α [rad].
    nu : float
        ω [rad/s].
    sample_interval : float
        h [s].
    leading : float
        ``c α² ω (ωh)^m`` [rad/s].
    next_term : float or None
        ``c₄ α⁴ ω (ωh)^k`` [rad/s] (None without an α⁴ term).
    exact : float
        The exact drift [rad/s] (:func:`strapdown.analysis.coning.exact_drift.exact_coning_drift`).
    range : LeadingTermRange
        The range at this case's ωh.
    """

    cone_angle: float
    nu: float
    sample_interval: float
    leading: float
    next_term: float | None
    exact: float
    range: LeadingTermRange

    @property
    def omega_h(self) -> float:
        """x = ωh [rad]."""
        return self.nu * self.sample_interval

    @property
    def ratio(self) -> float:
        """Leading term over the exact drift [-] (inf if the exact drift vanishes)."""
        return self.leading / self.exact if self.exact != 0.0 else math.inf

    @property
    def within(self) -> bool:
        """Whether the leading term is within the tolerance of the exact drift here."""
        return abs(self.ratio - 1.0) <= self.range.tolerance


def coning_case(algorithm: Algorithm, *, cone_angle: float, nu: float, sample_interval: float, tolerance: float = DEFAULT_TOLERANCE) -> ConingCase:
    """The leading term, the next term in α and the exact drift of one case of classical coning.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    cone_angle : float, keyword-only
        Half-cone angle α [rad], in [:data:`CONE_ANGLE_FLOOR`, :data:`MAX_CONE_ANGLE`].
    nu : float, keyword-only
        Coning rate ω [rad/s], > 0.
    sample_interval : float, keyword-only
        Sample interval h [s], > 0, with ωh in [:data:`OMEGA_H_FLOOR`, :data:`MAX_OMEGA_H`].
    tolerance : float, keyword-only
        Relative tolerance of the range [-], in :data:`TOLERANCE_RANGE` (default :data:`DEFAULT_TOLERANCE`).

    Returns
    -------
    ConingCase

    Raises
    ------
    ValueError
        For α, ω, h or ωh out of range.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> case = coning_case(get("ignagni-1996-5"), cone_angle=math.radians(1.0), nu=2 * math.pi * 10, sample_interval=1 / 480)
    >>> round(case.ratio, 1), case.within
    (13.1, False)
    """
    alpha = in_closed_interval(cone_angle, "cone_angle", CONE_ANGLE_FLOOR, MAX_CONE_ANGLE, text=f"[{CONE_ANGLE_FLOOR:g}, {MAX_CONE_ANGLE:.4g}] rad")
    nu = positive(nu, "nu")
    h = positive(sample_interval, "sample_interval")
    rng = leading_term_range(algorithm, omega_h=(nu * h,), tolerance=tolerance)
    leading = float(rng.coefficient) * alpha**2 * nu * (nu * h) ** rng.coning_drift_order
    exact = exact_coning_drift(algorithm, cone_angle=alpha, nu=nu, sample_interval=h)
    return ConingCase(alpha, nu, h, leading, rng.next_term.value(alpha, nu, h), exact, rng)
