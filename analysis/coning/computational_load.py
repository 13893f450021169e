"""Computational load of strapdown attitude computation: operation counts, step and load.

One step of the attitude computation is the rotation-vector algorithm
(:func:`operation_count`) followed by one quaternion update
``Λ ← Λ ∘ λ(Δφ)`` (:func:`quaternion_update`): the squared angle ``x = |Δφ|²``,
the cosine and the sine of half the rotation angle by their series in x
truncated after K terms, ``λ = (c, s Δφ)`` and the quaternion product.  An
operation is one addition, a multiplication counts as ``m`` additions, and a
step costs ``σ = s + m u`` (Budennyi, Kalinovsky, Panov et al., eq. (6)).

Two rules close the model, both stated here and both parameters of
:class:`LoadModel`:

* **Series length.**  Truncating the half-angle series after K terms changes
  the rotation angle of a step by ``δθ_K ≈ 4K (φ/2)^(2K+1) / (2K+1)!``
  (:func:`truncation_error`), φ = ``|Δφ|`` ≈ ``|ω|`` H the angle turned in a step.
  K is the smallest number of terms whose error, spread over the step,
  stays below a fraction f of the drift budget: ``δθ_K / H ≤ f [u]``
  (:func:`series_terms`; f = 0.1 by default, the order-of-magnitude margin the
  paper asks of algorithm errors against gyro errors).
* **Time base.**  The load is the cost of a step divided by a time: the step H
  (``"step"``: the work spread over the step, the average load) or the sample
  interval h = H/N (``"sample"``: the work of a step done within one sample
  interval after its last sample, the peak load).  The paper does not state
  which; ``"sample"`` is the default.

The largest step for a drift budget follows from the asymptotic drift
``u_a = K H^ρ`` (:func:`largest_step`); :func:`step_load` costs a given step and
:func:`design` ranks algorithms.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eqs. (3), (6), Tables 2, 4, 5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import NamedTuple

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ...derivations.coning.registry import get, names
from ..core.validation import as_int, nonnegative, positive
from .drift_theory import asymptotic_drift, asymptotic_order
from .precession import RegularPrecession

__all__ = [
    "OperationCount",
    "operation_count",
    "Operation",
    "quaternion_update",
    "quaternion_update_count",
    "truncation_error",
    "series_terms",
    "TIME_BASES",
    "LoadModel",
    "StepLimit",
    "largest_step",
    "DesignRow",
    "step_load",
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

    def __add__(self, other: OperationCount) -> OperationCount:
        return OperationCount(self.additions + other.additions, self.multiplications + other.multiplications)


def _cross_count(expr) -> tuple:
    if isinstance(expr, int):
        return 0, 0
    a, b = expr
    aa, am = _cross_count(a)
    ba, bm = _cross_count(b)
    return aa + ba + 3, am + bm + 6


def _bilinear_factors(items: dict):
    """``(left, right)`` if ``Σ sign_ij p_i × p_j = (Σ_left ± p) × (Σ_right ± p)``, else None."""
    idx = sorted({k for pair in items for k in pair})
    for mask in range(1, 2 ** len(idx) - 1):
        left = [k for n, k in enumerate(idx) if mask >> n & 1]
        right = [k for n, k in enumerate(idx) if not mask >> n & 1]
        if len(left) * len(right) != len(items):
            continue
        coef = {}
        for (i, j), sign in items.items():
            if i in left and j in right:
                coef[(i, j)] = sign
            elif j in left and i in right:
                coef[(j, i)] = -sign
        if len(coef) != len(items):
            continue
        b = {r: coef[(left[0], r)] for r in right}
        a = {k: coef[(k, right[0])] * b[right[0]] for k in left}
        if all(coef[(k, r)] == a[k] * b[r] for k in left for r in right):
            return left, right
    return None


def operation_count(algorithm: Algorithm) -> OperationCount:
    """Operation count of one step of ``algorithm`` (the rotation-vector increment).

    ``P = Σ p_j`` takes ``3(N−1)`` additions.  Pairwise terms are grouped by
    the magnitude of their coefficient; a group is summed and then scaled once
    (3 multiplications) and added to the total (3 additions).  A group that
    factors by bilinearity, ``Σ ± p_i × p_j = (Σ ± p_i) × (Σ ± p_j)``, costs
    the vector sums of its two factors and one cross product; any other group
    costs one cross product per term (6 multiplications, 3 additions) and the
    additions that sum them.  Nested cross products and dot-product factors
    are counted term by term (a dot product: 3 multiplications, 2 additions;
    a scalar factor on a vector: 3 multiplications).

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.

    Returns
    -------
    OperationCount
        Per step.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), Table 2 (the counts s, u of
    the five algorithms, which this count reproduces).

    Examples
    --------
    >>> operation_count(get("panov-4s-3"))
    OperationCount(additions=33, multiplications=24)
    """
    adds = 3 * (algorithm.samples - 1)
    mults = 0
    pair_groups: dict = {}
    for (i, j), c in algorithm.pairwise.items():
        pair_groups.setdefault(abs(c), {})[(i, j)] = 1 if c > 0 else -1
    groups: dict = {}
    for c, items in pair_groups.items():
        factors = _bilinear_factors(items) if len(items) > 1 else None
        if factors is None:
            groups.setdefault(c, []).extend((3, 6) for _ in items)
        else:
            left, right = factors
            groups.setdefault(c, []).append((3 * (len(left) - 1) + 3 * (len(right) - 1) + 3, 6))
    for t in algorithm.terms:
        if not t.dots and isinstance(t.cross[0], int) and isinstance(t.cross[1], int):
            continue
        a, m = _cross_count(t.cross)
        for _ in t.dots:
            a, m = a + 2, m + 3 + 3
        groups.setdefault(abs(t.coefficient), []).append((a, m))
    for items in groups.values():
        for a, m in items:
            adds += a
            mults += m
        adds += 3 * (len(items) - 1) + 3
        mults += 3
    return OperationCount(adds, mults)


class Operation(NamedTuple):
    """One line of an operation count.

    Attributes
    ----------
    name : str
        What is computed.
    additions : int
        Additions.
    multiplications : int
        Multiplications.
    """

    name: str
    additions: int
    multiplications: int


_SUPERSCRIPT = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


def _series_text(first: Fraction, coefficient, terms: int) -> str:
    """``1 − x/8 + x²/384 …``: a K-term series in x with the coefficients ``coefficient(k)``."""
    text = str(first)
    for k in range(1, terms):
        c = coefficient(k)
        power = "x" if k == 1 else "x" + str(k).translate(_SUPERSCRIPT)
        text += f" {'−' if c < 0 else '+'} {power}/{abs(1 / c)}"
    return text


def quaternion_update(terms: int) -> tuple:
    """The operations of one quaternion update ``Λ ← Λ ∘ λ(Δφ)`` with K-term half-angle series.

    With ``x = |Δφ|²``, ``cos(φ/2) = Σ_{k<K} (−1)^k x^k / (4^k (2k)!)`` and
    ``sin(φ/2)/φ = Σ_{k<K} (−1)^k x^k / (2 · 4^k (2k+1)!)``; the powers
    ``x², …, x^{K−1}`` are formed once and shared, each series term costs one
    multiplication by its constant and one addition.  Then ``λ = (c, s Δφ)``
    and the quaternion product (16 multiplications, 12 additions).  No
    normalisation.

    Parameters
    ----------
    terms : int
        K ≥ 1, terms kept in each series (K = 1: c = 1, s = 1/2).

    Returns
    -------
    tuple of Operation

    Raises
    ------
    ValueError
        If ``terms`` < 1.

    Examples
    --------
    >>> [op.name for op in quaternion_update(3)]
    ['x = |Δφ|²', 'x²', 'c = cos(φ/2) ≈ 1 − x/8 + x²/384', 's = sin(φ/2)/φ ≈ 1/2 − x/48 + x²/3840', 'λ = (c, s Δφ)', 'Λ ∘ λ']
    """
    k = as_int(terms, "terms", minimum=1)
    cos_text = _series_text(Fraction(1), lambda j: Fraction((-1) ** j, 4**j * math.factorial(2 * j)), k)
    sin_text = _series_text(Fraction(1, 2), lambda j: Fraction((-1) ** j, 2 * 4**j * math.factorial(2 * j + 1)), k)
    ops = [Operation("x = |Δφ|²", 2, 3)]
    if k > 2:
        ops.append(Operation("x²" if k == 3 else f"x², …, x{str(k - 1).translate(_SUPERSCRIPT)}", 0, k - 2))
    ops += [
        Operation(f"c = cos(φ/2) ≈ {cos_text}", k - 1, k - 1),
        Operation(f"s = sin(φ/2)/φ ≈ {sin_text}", k - 1, k - 1),
        Operation("λ = (c, s Δφ)", 0, 3),
        Operation("Λ ∘ λ", 12, 16),
    ]
    return tuple(ops)


def quaternion_update_count(terms: int = 3) -> OperationCount:
    """Operation count of :func:`quaternion_update`.

    Parameters
    ----------
    terms : int
        K, terms of each half-angle series.

    Returns
    -------
    OperationCount
        ``12 + 2K`` additions and ``18 + 3K`` multiplications for K ≥ 2.

    Examples
    --------
    >>> quaternion_update_count(3)
    OperationCount(additions=18, multiplications=27)
    >>> [quaternion_update_count(k).cost(5) for k in (2, 4)]
    [136, 170]
    """
    ops = quaternion_update(terms)
    return OperationCount(sum(op.additions for op in ops), sum(op.multiplications for op in ops))


def truncation_error(angle, terms):
    """Leading error of the rotation angle when the half-angle series keep K terms.

    ``δθ_K = 4K (φ/2)^(2K+1) / (2K+1)!``: the angle of ``λ = (c_K, s_K Δφ)``
    minus φ, to leading order in φ (both series are cut after their
    ``x^{K−1}`` terms).

    Parameters
    ----------
    angle : float or array_like
        φ = ``|Δφ|`` [rad], ≥ 0.
    terms : int
        K ≥ 1.

    Returns
    -------
    float or ndarray
        ``|δθ_K|`` [rad].

    Examples
    --------
    >>> float(truncation_error(0.1, 1)) == 0.1**3 / 12    # λ = (1, Δφ/2): θ = 2 atan(φ/2)
    True
    """
    k = as_int(terms, "terms", minimum=1)
    phi = np.asarray(angle, dtype=float)
    if np.any(phi < 0) or not np.all(np.isfinite(phi)):
        raise ValueError(f"Expected `angle` finite and >= 0, got {angle!r}")
    return 4 * k * (phi / 2) ** (2 * k + 1) / math.factorial(2 * k + 1)


def series_terms(angle: float, step: float, required_drift: float, *, fraction: float = 0.1, max_terms: int = 12) -> int:
    """Smallest K whose truncation error, spread over the step, stays below ``fraction`` of the budget.

    ``δθ_K(φ) / H ≤ f [u]`` with :func:`truncation_error`.

    Parameters
    ----------
    angle : float
        φ, the angle turned in one step [rad], ≥ 0.
    step : float
        H [s], > 0.
    required_drift : float
        [u] [rad/s], > 0.
    fraction : float, keyword-only
        f > 0.
    max_terms : int, keyword-only
        Largest K tried.

    Returns
    -------
    int
        K.

    Raises
    ------
    ValueError
        For bad input, or if no K up to ``max_terms`` meets the rule.

    Examples
    --------
    >>> series_terms(0.35, 3.7e-3, 4.85e-9)        # precession, f = 10 Hz: K = 5
    5
    """
    step = positive(step, "step")
    u = positive(required_drift, "required_drift")
    f = positive(fraction, "fraction")
    top = as_int(max_terms, "max_terms", minimum=1)
    for k in range(1, top + 1):
        if truncation_error(angle, k) / step <= f * u:
            return k
    raise ValueError(f"Expected a series of at most {top} terms to meet the accuracy rule, got angle {angle:g} rad per step {step:g} s")


#: Time bases of the load: ``"step"`` (β = σ / H) and ``"sample"`` (β = σ / h, h = H/N).
TIME_BASES = ("step", "sample")


@dataclass(frozen=True)
class LoadModel:
    """The rules that turn operation counts into a load.

    Attributes
    ----------
    m : float
        Cost of a multiplication in additions (eq. (6)), ≥ 0.
    time_base : str
        ``"sample"`` (β = σ/h) or ``"step"`` (β = σ/H), see the module docstring.
    truncation_fraction : float
        f of the series rule (:func:`series_terms`), > 0.

    Examples
    --------
    >>> LoadModel(time_base="hour")
    Traceback (most recent call last):
    ...
    ValueError: Expected `time_base` among step, sample, got 'hour'
    """

    m: float = 5.0
    time_base: str = "sample"
    truncation_fraction: float = 0.1

    def __post_init__(self):
        object.__setattr__(self, "m", nonnegative(self.m, "m"))
        if self.time_base not in TIME_BASES:
            raise ValueError(f"Expected `time_base` among {', '.join(TIME_BASES)}, got {self.time_base!r}")
        object.__setattr__(self, "truncation_fraction", positive(self.truncation_fraction, "truncation_fraction"))

    def time(self, step: float, samples: int) -> float:
        """The time the cost of a step is divided by [s].

        Parameters
        ----------
        step : float
            H [s].
        samples : int
            N.

        Returns
        -------
        float
            H or H/N.
        """
        return step if self.time_base == "step" else step / samples


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


def _as_motion(motion) -> RegularPrecession:
    if not isinstance(motion, RegularPrecession):
        raise TypeError(f"Expected `motion` to be a RegularPrecession, got {type(motion).__name__}")
    positive(motion.nu, "motion.nu")
    return motion


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
    >>> m = RegularPrecession(-1.0, 2 * math.pi * 10, rad(1.0))
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


@dataclass(frozen=True)
class DesignRow:
    """One algorithm costed at one step.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    order : int
        ρ of the drift at the motion.
    step : float
        H [s].
    sample_rate : float
        Gyro sampling rate N / H [Hz].
    angle : float
        φ = ``|ω|`` H, the angle turned in a step [rad].
    series_terms : int
        K, terms of each half-angle series (0 when a fixed quaternion cost was given).
    algorithm_cost : float
        σ_alg = s + m u of the increment algorithm [addition-equivalents].
    quaternion_cost : float
        σ_q of the quaternion update [addition-equivalents].
    cost : float
        σ_alg + σ_q [addition-equivalents].
    load : float
        β = cost / time base [operations per second].
    """

    algorithm: str
    order: int
    step: float
    sample_rate: float
    angle: float
    series_terms: int
    algorithm_cost: float
    quaternion_cost: float
    cost: float
    load: float


def _algorithm(a) -> Algorithm:
    return get(a) if isinstance(a, str) else a


def step_load(algorithm, step: float, required_drift: float, motion: RegularPrecession, *, order: int | None = None,
              model: LoadModel | None = None, count: OperationCount | None = None, quaternion_cost: float | None = None) -> DesignRow:  # fmt: skip
    """Cost and load of ``algorithm`` run at ``step`` for a drift budget.

    Parameters
    ----------
    algorithm : str or Algorithm
        Registry name or algorithm.
    step : float
        H [s], > 0.
    required_drift : float
        [u] [rad/s], > 0 (sets the series length).
    motion : RegularPrecession
        The motion (4.1) (sets the angle per step, φ = ``|ω|`` H).
    order : int, keyword-only, optional
        ρ to report; default the order of the drift at the motion.
    model : LoadModel, keyword-only, optional
        Default ``LoadModel()``.
    count : OperationCount, keyword-only, optional
        Operations of the increment algorithm; default :func:`operation_count`.
    quaternion_cost : float, keyword-only, optional
        A fixed σ_q [addition-equivalents] in place of :func:`quaternion_update_count` with
        :func:`series_terms`.

    Returns
    -------
    DesignRow

    Raises
    ------
    ValueError, TypeError
        For bad input.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (6), Tables 4–5.
    """
    alg = _algorithm(algorithm)
    motion = _as_motion(motion)
    model = model or LoadModel()
    step = positive(step, "step")
    if order is None:
        order = int(asymptotic_order(alg, motion.eps, motion.nutation))
    angle = float(np.linalg.norm(motion.omega(0.0))) * step
    if quaternion_cost is None:
        terms = series_terms(angle, step, required_drift, fraction=model.truncation_fraction)
        sigma_q = quaternion_update_count(terms).cost(model.m)
    else:
        terms, sigma_q = 0, nonnegative(quaternion_cost, "quaternion_cost")
    sigma_alg = (count or operation_count(alg)).cost(model.m)
    cost = sigma_alg + sigma_q
    return DesignRow(alg.name, order, step, alg.samples / step, angle, terms, sigma_alg, sigma_q, cost, cost / model.time(step, alg.samples))


def design(required_drift, motion: RegularPrecession, *, algorithms=None, model: LoadModel | None = None, quaternion_cost=None, counts=None) -> list:
    """Rank algorithms by computational load for a drift budget (Tables 4–5).

    Each algorithm runs at its largest step (:func:`largest_step`) and is
    costed there (:func:`step_load`).

    Parameters
    ----------
    required_drift : float
        Required constant drift rate [u] [rad/s], > 0.
    motion : RegularPrecession
        The motion (4.1): ε, ν [rad/s] and ϑ [rad].
    algorithms : sequence of str or Algorithm, keyword-only, optional
        Default: the whole registry.
    model : LoadModel, keyword-only, optional
        Default ``LoadModel()``.
    quaternion_cost : float, keyword-only, optional
        A fixed σ_q per step [addition-equivalents] instead of the counted update.
    counts : mapping, keyword-only, optional
        ``{name: OperationCount}`` overriding :func:`operation_count`.

    Returns
    -------
    list of DesignRow
        Sorted by load (lowest first).

    Raises
    ------
    ValueError
        For a non-positive drift budget, a negative ``quaternion_cost``, or an unknown algorithm name.
    TypeError
        If ``motion`` is not a :class:`RegularPrecession`.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (6), Tables 4–5.

    Examples
    --------
    >>> from strapdown.analysis.core.units import rad, rad_per_s
    >>> coning = RegularPrecession(-1.0, 2 * math.pi * 10, rad(1.0))
    >>> best = design(rad_per_s(1e-3), coning, algorithms=[f"panov-4s-{k}" for k in range(1, 6)])[0]
    >>> best.algorithm, best.series_terms, round(best.load / 1e3)
    ('panov-4s-3', 2, 99)
    """
    u = positive(required_drift, "required_drift")
    motion = _as_motion(motion)
    model = model or LoadModel()
    rows = []
    for alg in (_algorithm(a) for a in (algorithms if algorithms is not None else names())):
        H, rho = largest_step(alg, u, motion)
        rows.append(step_load(alg, H, u, motion, order=rho, model=model, count=(counts or {}).get(alg.name), quaternion_cost=quaternion_cost))
    return sorted(rows, key=lambda r: (r.load, r.algorithm))
