"""Sampling and cost design: the largest step that meets a drift budget, and its load.

Given a required constant drift rate [u], the asymptotic drift
``u_a = K H^ρ`` (:func:`strapdown.analysis.coning.drift_theory.asymptotic_drift`) gives the
largest algorithm step ``H_max = ([u]/K)^(1/ρ)``.  The computational load is
the number of operations per second, an operation being one addition and a
multiplication counting as ``m`` additions (Budennyi, Kalinovsky, Panov et
al., eq. (6)):

    β = (σ_alg + σ_q) / H_max,    σ = s + m u,

with ``s, u`` the additions and multiplications of the increment algorithm
per step and ``σ_q`` the cost of the full quaternion update per step.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (6), Tables 2, 4, 5.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

from ...derivations.coning.algorithms import Algorithm
from ...derivations.coning.registry import get, names
from ..core.validation import nonnegative, positive
from .drift_theory import asymptotic_drift, asymptotic_order
from .precession import RegularPrecession

__all__ = [
    "OperationCount",
    "operation_count",
    "QUATERNION_UPDATE",
    "quaternion_update_count",
    "StepLimit",
    "largest_step",
    "DesignRow",
    "design",
]


@dataclass(frozen=True)
class OperationCount:
    """Additions ``s`` and multiplications ``u`` of one piece of computation.

    Attributes
    ----------
    additions : int
        s: additions and subtractions.
    multiplications : int
        u: multiplications (and divisions).
    """

    additions: int
    multiplications: int

    def cost(self, m: float = 5.0) -> float:
        """``σ = s + m u`` in addition-equivalents (Budennyi, Kalinovsky, Panov et al., eq. (6)).

        Parameters
        ----------
        m : float
            Cost of a multiplication in additions [-].

        Returns
        -------
        float
            σ [addition-equivalents].
        """
        return self.additions + m * self.multiplications


def _cross_count(expr) -> tuple:
    if isinstance(expr, int):
        return 0, 0
    a, b = expr
    aa, am = _cross_count(a)
    ba, bm = _cross_count(b)
    return aa + ba + 3, am + bm + 6


def operation_count(algorithm: Algorithm) -> OperationCount:
    """Straightforward operation count of one step of ``algorithm``.

    ``P = Σ p_j`` takes ``3(N−1)`` additions.  Terms sharing a coefficient are
    summed before one scaling (3 multiplications) and one vector addition to
    the total; a cross product costs 6 multiplications and 3 additions, a dot
    product 3 and 2, a scalar factor on a vector 3 multiplications.  No
    factoring by bilinearity is attempted, so hand-optimised counts (such as
    Table 2 of Budennyi, Kalinovsky, Panov et al.) can be lower.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.

    Returns
    -------
    OperationCount
        Per step.

    Examples
    --------
    >>> operation_count(get("panov-4s-1"))
    OperationCount(additions=15, multiplications=9)
    """
    adds = 3 * (algorithm.samples - 1)
    mults = 0
    groups: dict = {}
    for c in algorithm.pairwise.values():
        groups.setdefault(abs(c), []).append((0, 6, 3))
    for t in algorithm.terms:
        if not t.dots and isinstance(t.cross[0], int) and isinstance(t.cross[1], int):
            continue
        a, m = _cross_count(t.cross)
        for _ in t.dots:
            a, m = a + 2, m + 3 + 3
        groups.setdefault(abs(t.coefficient), []).append((0, m, a))
    for items in groups.values():
        for _, m, a in items:
            mults += m
            adds += a
        adds += 3 * (len(items) - 1) + 3
        mults += 3
    return OperationCount(adds, mults)


#: The full quaternion update per step, as (operation, additions, multiplications):
#: the step quaternion from Δφ by its series to |Δφ|⁴, then Λ ∘ λ.
QUATERNION_UPDATE = (
    ("|Δφ|²", 2, 3),
    ("|Δφ|⁴", 0, 1),
    ("λ0 = 1 − |Δφ|²/8 + |Δφ|⁴/384", 2, 2),
    ("c = 1/2 − |Δφ|²/48 + |Δφ|⁴/3840", 2, 2),
    ("λ = c Δφ", 0, 3),
    ("Λ ∘ λ", 12, 16),
)


def quaternion_update_count() -> OperationCount:
    """Operation count of :data:`QUATERNION_UPDATE`.

    Returns
    -------
    OperationCount
        Per step.

    Examples
    --------
    >>> quaternion_update_count()
    OperationCount(additions=18, multiplications=27)
    """
    return OperationCount(sum(a for _, a, _ in QUATERNION_UPDATE), sum(m for _, _, m in QUATERNION_UPDATE))


class StepLimit(NamedTuple):
    """The largest step that meets a drift budget.

    Attributes
    ----------
    step : float
        H_max [s] (inf if the drift vanishes through weight 7).
    order : int
        ρ of the drift at the motion (−1 if it vanishes through weight 7).
    """

    step: float
    order: int


def largest_step(algorithm: Algorithm, required_drift, motion: RegularPrecession) -> StepLimit:
    """Largest step H [s] whose asymptotic drift equals ``required_drift``.

    With ``u_a = K H^ρ`` (:func:`strapdown.analysis.coning.drift_theory.asymptotic_drift`),
    ``H_max = ([u] / K)^(1/ρ)``.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.
    required_drift : float
        Required constant drift rate [u] [rad/s], > 0.
    motion : RegularPrecession
        The motion (4.1): ε, ν [rad/s] and ϑ [rad].

    Returns
    -------
    StepLimit

    Raises
    ------
    ValueError
        If ``required_drift`` is not positive.
    TypeError
        If ``motion`` is not a :class:`RegularPrecession`.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Tables 4–5.

    Examples
    --------
    >>> from strapdown.analysis.core.units import rad, rad_per_s
    >>> m = RegularPrecession(-1.0, 2 * 3.141592653589793 * 10, rad(1.0))
    >>> limit = largest_step(get("panov-4s-3"), rad_per_s(1e-3), m)
    >>> limit.order, round(limit.step * 1e3, 2)
    (6, 11.66)
    """
    u = positive(required_drift, "required_drift")
    motion = _as_motion(motion)
    rho = int(asymptotic_order(algorithm, motion.eps, motion.nutation))
    if rho < 0:
        return StepLimit(float("inf"), rho)
    k = float(asymptotic_drift(algorithm, eps=motion.eps, nu=motion.nu, nutation=motion.nutation, step=1.0))
    return StepLimit((u / k) ** (1.0 / rho), rho)


def _as_motion(motion) -> RegularPrecession:
    if not isinstance(motion, RegularPrecession):
        raise TypeError(f"Expected `motion` to be a RegularPrecession, got {type(motion).__name__}")
    positive(motion.nu, "motion.nu")
    return motion


@dataclass(frozen=True)
class DesignRow:
    """One algorithm of a design ranking.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    order : int
        ρ of the drift at the design point.
    step : float
        H_max [s].
    sample_rate : float
        Gyro sampling rate N / H_max [Hz].
    cost : float
        σ_alg + σ_q per step [addition-equivalents].
    load : float
        β = cost / H_max [operations per second].
    """

    algorithm: str
    order: int
    step: float
    sample_rate: float
    cost: float
    load: float


def design(required_drift, motion: RegularPrecession, *, algorithms=None, m=5.0, quaternion_cost=None, counts=None) -> list:
    """Rank algorithms by computational load for a drift budget (Tables 4–5).

    Parameters
    ----------
    required_drift : float
        Required constant drift rate [u] [rad/s], > 0.
    motion : RegularPrecession
        The motion (4.1): ε, ν [rad/s] and ϑ [rad].
    algorithms : sequence of str or Algorithm, keyword-only, optional
        Default: the whole registry.
    m : float, keyword-only
        Cost of a multiplication in additions (eq. (6)), ≥ 0.
    quaternion_cost : float, keyword-only, optional
        σ_q per step [addition-equivalents]; default :func:`quaternion_update_count` ``.cost(m)``.
    counts : mapping, keyword-only, optional
        ``{name: OperationCount}`` overriding :func:`operation_count`.

    Returns
    -------
    list of DesignRow
        Sorted by load (lowest first).

    Raises
    ------
    ValueError
        For a non-positive drift budget, a negative ``m`` or ``quaternion_cost``, or an unknown algorithm name.
    TypeError
        If ``motion`` is not a :class:`RegularPrecession`.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (6), Tables 4–5.
    """
    u = positive(required_drift, "required_drift")
    motion = _as_motion(motion)
    m = nonnegative(m, "m")
    sigma_q = quaternion_update_count().cost(m) if quaternion_cost is None else nonnegative(quaternion_cost, "quaternion_cost")
    algs = [get(a) if isinstance(a, str) else a for a in (algorithms if algorithms is not None else names())]
    rows = []
    for alg in algs:
        H, rho = largest_step(alg, u, motion)
        count = (counts or {}).get(alg.name) or operation_count(alg)
        cost = count.cost(m) + sigma_q
        rows.append(DesignRow(alg.name, rho, H, alg.samples / H, cost, cost / H))
    return sorted(rows, key=lambda r: (r.load, r.algorithm))
