"""The leading term of the drift under regular precession: two estimates, and the coning limits.

Budennyi, Kalinovsky, Panov et al. estimate the constant drift of an
algorithm by eq. (3): the leading local error, projected on the precession
axis at the middle of the step and divided by the step (Lebedev & Panov 1989,
(5.2)–(5.3)).  The symbolic drift series of
:func:`strapdown.derivations.coning.drift.drift_coefficients` gives the full
coefficient of the same power of the step: where the leading error cancels
(algorithms 3 and 5 under coning, whose weight-5 projection vanishes), the
weight-7 drift also receives the *transport* of the weight-5 error (the
weight-5 error turned by the attitude between the start and the middle of the
step), which the mid-step projection leaves out.  :func:`leading_drift`
returns both, so the numbers of Table 3 can be set against each.

For pure coning and a small cone angle the leading drift of the optimal
N-sample class is ``α² ν (νH)^{2N} / C_N`` (Ignagni 1990); :func:`optimal_coning`
and :func:`small_cone_limit` give the constants from the closed form and as a
special case of the general series.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Table 3.
Lebedev & Panov (1989), eqs. (5.2)–(5.3).
Ignagni (1990), "Optimal strapdown attitude integration algorithms".
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import NamedTuple

import sympy as sp

from . import drift as D
from . import series as S
from .algorithms import Algorithm

__all__ = ["LeadingDrift", "leading_drift", "same_transport", "OptimalConing", "optimal_coning", "small_cone_limit"]


@dataclass(frozen=True)
class LeadingDrift:
    """Two estimates of the weight-w drift coefficient of one algorithm (ν = 1, H = 1).

    The drift rate along the precession axis is ``c(ε, ϑ) ν^w H^(w−1)`` [rad/s]
    for either coefficient c (exact minus algorithm, the package's convention).

    Attributes
    ----------
    algorithm : str
        Name of the algorithm.
    weight : int
        w = ρ + 1 of the leading term.
    mid_step : sympy.Expr
        Projection of the weight-w local error on the precession axis at the
        middle of the step, ``n·δφ_w`` in ε and ϑ: the estimate of the papers.
    full : sympy.Expr
        ``d_w(ε, ϑ)`` of the drift series, which adds the transport of the
        lower-weight errors.
    """

    algorithm: str
    weight: int
    mid_step: sp.Expr
    full: sp.Expr

    @property
    def transport(self) -> sp.Expr:
        """``full − mid_step``: what the transport of the lower-weight errors adds (sin²ϑ reduced)."""
        return sp.expand(sp.expand(self.full - self.mid_step).subs(D.SIN**2, 1 - D.COS**2))


@cache
def leading_drift(algorithm: Algorithm, weight: int) -> LeadingDrift:
    """Mid-step projection and full coefficient of the weight-``weight`` drift of ``algorithm``.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.
    weight : int
        Weight w ≤ 7 of the drift term (ρ + 1 of the leading term: 5 for a
        fourth-order drift, 7 where the fourth-order drift cancels).

    Returns
    -------
    LeadingDrift

    Raises
    ------
    ValueError
        If ``weight`` is not in 1 … 7.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3); Lebedev & Panov (1989), (5.3).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> est = leading_drift(get("panov-4s-3"), 7)
    >>> sp.expand(est.transport - leading_drift(get("panov-4s-5"), 7).transport)
    0
    """
    if not isinstance(weight, int) or not 1 <= weight <= S.MAX_WEIGHT:
        raise ValueError(f"Expected `weight` an integer in 1…{S.MAX_WEIGHT}, got {weight!r}")
    _, y, z = D.precession_value(S.local_error(algorithm).parts[weight])
    mid_step = y * D.SIN + z * D.COS
    return LeadingDrift(algorithm.name, weight, mid_step, D.drift_coefficients(algorithm)[weight])


def same_transport(first: Algorithm, second: Algorithm, weight: int) -> bool:
    """True if the transport terms of the weight-``weight`` drift of two algorithms are the same expression.

    Parameters
    ----------
    first, second : Algorithm
        Rotation-vector algorithms.
    weight : int
        Weight of the drift term.

    Returns
    -------
    bool

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> same_transport(get("panov-4s-3"), get("panov-4s-5"), 7), same_transport(get("panov-4s-3"), get("panov-4s-1"), 7)
    (True, False)
    """
    difference = leading_drift(first, weight).transport - leading_drift(second, weight).transport
    return sp.expand(difference) == 0


class OptimalConing(NamedTuple):
    """The optimal N-sample coning algorithm and its leading drift ``α² ν (νH)^exponent / constant``.

    Attributes
    ----------
    samples : int
        N.
    lag_sums : tuple of Fraction
        ``k_l = Σ_{j−i=l} c_ij``, l = 1 … N − 1.
    exponent : int
        Power of νH in the leading drift (2N).
    constant : int
        C_N.
    """

    samples: int
    lag_sums: tuple
    exponent: int
    constant: int


def optimal_coning(samples: int) -> OptimalConing:
    """Lag sums and drift constant of the optimal ``samples``-sample coning class.

    Parameters
    ----------
    samples : int
        N ≥ 2.

    Returns
    -------
    OptimalConing

    References
    ----------
    Ignagni (1990).

    Examples
    --------
    >>> optimal_coning(2).constant
    960
    """
    exponent, constant = D.coning_constant(samples)
    lags = tuple(Fraction(k) for k in D.lag_sums(D.optimal_coning_algorithm(samples)))
    return OptimalConing(samples, lags, exponent, constant)


@cache
def small_cone_limit(algorithm: Algorithm, weight: int) -> sp.Expr:
    """``lim_{α→0} d_w(ε = −1, ϑ = α) / α²``: the leading coning drift coefficient for a small cone angle.

    For the optimal N-sample class at w = 2N + 1 this is ``−1/C_N``: the drift
    is along the precession axis n (exact minus algorithm), and the cone axis of
    classical coning (ε = −1, the direction of the mean inertial rate) is −n.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.
    weight : int
        Weight w ≤ 7 of the drift term.

    Returns
    -------
    sympy.Expr
        An exact rational.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> small_cone_limit(get("two-sample"), 5)
    -1/960
    """
    alpha = sp.Symbol("alpha", positive=True)
    d = D.drift_coefficients(algorithm)[weight]
    return sp.limit(d.subs(D.EPS, -1).subs(D.THETA, alpha) / alpha**2, alpha, 0)
