"""One integrator, assessed: its assumptions tested, identified, checked for consistency, analysed, run against the exact solution.

:func:`assess` chains the steps of this subpackage on one black box:

1. the identification's own assumptions (:mod:`.assumptions`), each a verdict
   that can say no: time invariance (the run's first record repeated as its
   last call, and its blocks reordered and shifted), float precision (the
   code's measured noise floor, from which every uncertainty follows), the
   linearity range (saturation; the probe amplitude is chosen inside it
   unless given), and the memory length (K raised to the farthest sample the
   integrator reads, up to ``max_previous_limit``);
2. :func:`~.identification.identify`: every entry of the linear and bilinear
   tensors as exact fractions, and the measured remainder (coning, and
   sculling when the integrator takes accelerometer increments); isotropy is
   a verdict too, and an integrator that treats the axes differently is
   described per axis (:mod:`.anisotropy`);
3. consistency, reported and never a refusal (:class:`Consistency`): the
   first-order condition (the linear part is ``P = p_1 + … + p_N`` on every
   axis) and the second-order condition ``Σ c_ij (j − i) = N³/12``
   (:func:`strapdown.derivations.coning.algorithms.second_order_defect`),
   each with the bound the measurement puts on it: a coefficient that is not
   an exact fraction carries its uncertainty into the sums, and a condition is
   *decided* only when the sum is exact or its distance from the condition
   exceeds that bound (:class:`DriftOrder`);
4. the exact local-error series of the identified algorithm
   (:func:`strapdown.derivations.coning.series.local_error`), its order ρ and
   leading term (:func:`strapdown.derivations.coning.series.error_coefficients`), and
   the closed-form coning drift (:func:`strapdown.derivations.coning.drift.coning_drift`);
   with a linear part other than P, the order is that of the linear part's
   error, whose leading weight is the first nonzero moment
   ``Σ_j (a_j − δ_j)(j^w − (j−1)^w)`` (:func:`linear_error_weight`), and the
   coning drift has no α² closed form;
5. the sculling part as data (:class:`~.sculling_terms.ScullingTerms`), where
   it departs from the dual extension of the coning part and what each
   departure costs in orders, and its velocity accuracy order;
6. the integrator itself against the exact solution
   (:mod:`.verification`): simulated coning drift (per axis when the axes
   differ) and sculling rate against the closed forms, at cone angles inside
   the linearity range and small enough for the largest coefficient, and the
   measured local-error exponents (attitude and velocity).

:func:`work` estimates what an assessment costs before it starts.

Public API
----------
:class:`Consistency`, :class:`DriftOrder`, :class:`Assumptions`, :class:`ScullingAssessment`, :class:`Assessment`,
:func:`linear_error_weight`, :func:`verification_samples`, :func:`verification_cone_angles`, :func:`assumption_samples`, :func:`work`, :func:`assess`.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ....derivations.coning import series as S
from ....derivations.coning.algorithms import Algorithm, second_order_defect
from ....derivations.coning.drift import ConingDrift
from ...core import budget
from ...core.cache import derived
from ..drift_theory import algorithm_key, coning_drift
from .anisotropy import Isotropy, axis_corrections
from .assumptions import LONGEST_MEMORY, Linearity, Memory, Precision, TimeInvariance, TimeInvarianceRun, linearity_range, memory_length, precision
from .identification import DEFAULT_MAX_PREVIOUS, DEFAULT_SEED, PROBE_AMPLITUDE, TOLERANCE, Identification, Remainder, identify, probe_samples
from .identification import work as identification_work
from .interface import Integrator, step_increments
from .probes import NoiseFloor
from .sculling_terms import ScullingTerms, departure_weight
from .verification import (
    ANGLE_AMPLITUDES,
    CONE_ANGLES,
    DRIFT_TOLERANCE,
    OMEGA_H,
    PERIODS,
    STEPS,
    Check,
    coning_drift_check,
    local_error_exponent,
    sculling_check,
    sculling_points,
    velocity_error_exponent,
)

__all__ = [
    "Consistency",
    "DriftOrder",
    "Assumptions",
    "ScullingAssessment",
    "Assessment",
    "linear_error_weight",
    "verification_samples",
    "verification_cone_angles",
    "assumption_samples",
    "work",
    "assess",
]

#: Amplitude of the time-invariance blocks and of the precision rays [rad, m/s] (far inside any useful linear range).
CHECK_AMPLITUDE = 2e-3


def _text(f: Fraction) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


def linear_error_weight(linear: dict, samples: int) -> int | None:
    """Leading weight w of the error of a linear part ``Σ a_j p_j`` against ``P`` (None when it is P).

    With ``p_j = ∫ ω`` over ``[(j−1)h, jh]`` and ω expanded in powers of τ, the
    error ``Σ_j (a_j − δ_j) p_j`` (``δ_j = 1`` for j = 1 … N, else 0) has at
    weight w the factor ``Σ_j (a_j − δ_j)(j^w − (j−1)^w)``; the first w where it
    is nonzero leads, and the local error is then ``O(h^w)``: order w − 1.

    Parameters
    ----------
    linear : dict
        ``{j: a_j}`` as Fractions.
    samples : int
        N.

    Returns
    -------
    int or None

    Examples
    --------
    >>> linear_error_weight({1: Fraction(1), 2: Fraction(1)}, 2) is None
    True
    >>> linear_error_weight({1: Fraction(2), 2: Fraction(0)}, 2)   # the right sum, the wrong first moment
    2
    """
    d = {j: linear.get(j, Fraction(0)) - (1 if 1 <= j <= samples else 0) for j in set(linear) | set(range(1, samples + 1))}
    d = {j: v for j, v in d.items() if v}
    if not d:
        return None
    for w in range(1, len(d) + 2):
        if sum(v * (Fraction(j) ** w - Fraction(j - 1) ** w) for j, v in d.items()):
            return w
    return None  # pragma: no cover - the moments of a nonzero d cannot all vanish (Vandermonde)


@dataclass(frozen=True)
class Consistency:
    """The first- and second-order conditions of an identified integrator (reported, never a refusal).

    Attributes
    ----------
    linear : dict
        ``{j: a_j}``, the identified isotropic linear part (nonzero entries).
    linear_weight : int or None
        :func:`linear_error_weight` (None: the linear part is P).
    second_order_sum : Fraction
        ``Σ c_ij (j − i)`` of the identified pairwise terms.
    second_order_expected : Fraction
        ``N³/12``.
    linear_tensor_is_sum : bool
        Every ``L_j`` is the identity for j = 1 … N and zero elsewhere, on every axis.
    second_order_bound : float
        Largest error of :attr:`second_order_sum` the measurement allows:
        ``Σ |j − i| · bound(c_ij)`` (0 when every coefficient is exact).
    linear_bound : float
        Largest error of any ``a_j`` the measurement allows (0 when exact).
    """

    linear: dict
    linear_weight: int | None
    second_order_sum: Fraction
    second_order_expected: Fraction
    linear_tensor_is_sum: bool = True
    second_order_bound: float = 0.0
    linear_bound: float = 0.0

    @property
    def first_order(self) -> bool:
        """The linear part is ``P = p_1 + … + p_N`` on every axis."""
        return self.linear_weight is None and self.linear_tensor_is_sum

    @property
    def second_order(self) -> bool:
        """``Σ c_ij (j − i) = N³/12``."""
        return self.second_order_sum == self.second_order_expected

    @property
    def consistent(self) -> bool:
        """Both conditions hold."""
        return self.first_order and self.second_order

    @property
    def second_order_defect(self) -> Fraction:
        """``Σ c_ij (j − i) − N³/12``."""
        return self.second_order_sum - self.second_order_expected


@dataclass(frozen=True)
class DriftOrder:
    """Whether the orders follow from the measured coefficients, not from a rounding of them.

    Attributes
    ----------
    defect : Fraction
        ``Σ c_ij (j − i) − N³/12`` of the fractions used.
    bound : float
        Its largest error the measurement allows (0: every coefficient exact).
    linear_bound : float
        The same for the linear part.
    order : int or None
        The accuracy order ρ stated.
    coning_order : int or None
        The coning-drift order stated.
    """

    defect: Fraction
    bound: float
    linear_bound: float
    order: int | None
    coning_order: int | None

    @property
    def holds(self) -> bool:
        """Decided: the coefficients are exact, or the defect (zero or not) is told from zero by more than its bound."""
        if self.bound == 0.0 and self.linear_bound == 0.0:
            return True
        return bool(self.defect) and abs(float(self.defect)) > self.bound

    def summary(self) -> str:
        """One line.

        Returns
        -------
        str
        """
        if self.bound == 0.0 and self.linear_bound == 0.0:
            return f"from exact fractions: second-order defect {_text(self.defect)}"
        if self.holds:
            return f"decided: the second-order defect {float(self.defect):.3g} exceeds its bound {self.bound:.1e} (coning-drift order {self.coning_order})"
        return (
            f"NOT decided: the second-order defect {float(self.defect):.3g} is within its bound {self.bound:.1e} "
            f"(the orders stated assume the simplest fractions within the uncertainties)"
        )

    def as_dict(self) -> dict:
        """JSON-able verdict.

        Returns
        -------
        dict
        """
        return {"holds": self.holds, "defect": _text(self.defect), "defect_float": float(self.defect), "bound": self.bound, "linear_bound": self.linear_bound, "summary": self.summary()}


@dataclass(frozen=True)
class Assumptions:
    """The verdicts on the identification's own assumptions (module docstring).

    Attributes
    ----------
    time_invariance : TimeInvariance
    memory : Memory
    isotropy : Isotropy
    linearity : Linearity
    precision : Precision
    drift_order : DriftOrder
    """

    time_invariance: TimeInvariance
    memory: Memory
    isotropy: Isotropy
    linearity: Linearity
    precision: Precision
    drift_order: DriftOrder

    def items(self) -> tuple:
        """(key, verdict) in the order they are printed.

        Returns
        -------
        tuple of (str, object)
        """
        return (
            ("time_invariance", self.time_invariance),
            ("memory", self.memory),
            ("isotropy", self.isotropy),
            ("linearity", self.linearity),
            ("precision", self.precision),
            ("drift_order", self.drift_order),
        )

    @property
    def trusted(self) -> bool:
        """Time invariant and every sample read probed: the coefficients describe one integrator."""
        return self.time_invariance.holds and self.memory.holds and self.linearity.holds

    def as_dict(self) -> dict:
        """JSON-able verdicts.

        Returns
        -------
        dict
        """
        return {key: v.as_dict() for key, v in self.items()}


@dataclass(frozen=True)
class ScullingAssessment:
    """The sculling part of an integrator.

    Attributes
    ----------
    terms : ScullingTerms
        The identified sculling part.
    defect : tuple
        Where it departs from the dual extension of the identified coning part
        (:meth:`~.sculling_terms.ScullingTerms.defect`; empty: it is that dual extension).
    remainder : Remainder
        Of ``Δv`` against the identified model.
    check : Check or None
        Simulated against closed-form rectification error.
    error_weight : int or None
        Lowest weight w at which the linear and bilinear part differs from the
        exact velocity increment (:meth:`~.sculling_terms.ScullingTerms.error_weight`).
    consequences : tuple
        For each departure: ``(kind, key, difference, weight)``, the weight at
        which it alone changes the velocity increment (:func:`~.sculling_terms.departure_weight`).
    departures_weight : int or None
        The same for all the departures together.
    corrected_weight : int or None
        :attr:`error_weight` of the dual extension of the coning part: the
        linear and bilinear part with every departure corrected.
    velocity_exponent : float or None
        The integrator's measured one-step velocity error exponent (None: not verified).
    """

    terms: ScullingTerms
    defect: tuple
    remainder: Remainder
    check: Check | None
    error_weight: int | None = None
    consequences: tuple = ()
    departures_weight: int | None = None
    corrected_weight: int | None = None
    velocity_exponent: float | None = None

    @property
    def dual_extension(self) -> bool:
        """The sculling part is the dual extension of the coning part (with the rotation term)."""
        return not self.defect

    @property
    def velocity_order(self) -> int | None:
        """The velocity accuracy order: local velocity error O(h^(order+1)).

        From the linear and bilinear part when their error leads at h or h²;
        from h³ on the terms of degree three count too, and the measured
        exponent decides (None when it was not measured).
        """
        if self.error_weight is not None and self.error_weight <= 2:
            return self.error_weight - 1
        if self.velocity_exponent is None or not math.isfinite(self.velocity_exponent):
            return None
        w = int(round(self.velocity_exponent))
        if self.error_weight is not None:
            w = min(w, self.error_weight)
        return w - 1

    @property
    def decided_by(self) -> str:
        """``"bilinear part"`` (exact fractions) or ``"measured exponent"``."""
        return "bilinear part" if self.error_weight is not None and self.error_weight <= 2 else "measured exponent"


@dataclass(frozen=True)
class Assessment:
    """Everything the package says about one integrator.

    Attributes
    ----------
    identification : Identification
        Coefficients, uncertainties, remainder.
    algorithm : Algorithm
        The identified algorithm (``P`` plus the isotropic pairwise terms).
    consistency : Consistency
        First- and second-order conditions.
    order : int or None
        ρ, the accuracy order: local error ``O(h^(ρ+1))`` (series of the identified algorithm, or
        the linear part's error when it leads); None when zero through h⁷.
    local_error : ErrorCoefficients or None
        The leading term of the exact local-error series of the identified
        algorithm, ``δ h^(ρ+1) Σ k_w x_w`` in nested products of the rate
        derivatives (:func:`strapdown.derivations.coning.series.error_coefficients`;
        None when the linear part is not P).
    coning : ConingDrift or None
        Closed-form coning drift of the identified algorithm (None when the
        linear part is not P, or the integrator is not isotropic: see
        :attr:`assumptions` for each axis).
    local_error_exponent : float or None
        Measured exponent of the integrator's own one-step error (None: not verified).
    check : Check or None
        The integrator's simulated coning drift against the closed form (None: not verified).
    sculling : ScullingAssessment or None
        For integrators that take accelerometer increments.
    assumptions : Assumptions or None
        The verdicts on the identification's assumptions.
    cone_angles : tuple
        Half-cone angles of the drift checks [rad].
    """

    identification: Identification
    algorithm: Algorithm
    consistency: Consistency
    order: int | None
    local_error: S.ErrorCoefficients | None
    coning: ConingDrift | None
    local_error_exponent: float | None
    check: Check | None
    sculling: ScullingAssessment | None
    assumptions: Assumptions | None = None
    cone_angles: tuple = CONE_ANGLES

    def as_dict(self) -> dict:
        """JSON-able summary: every key of ``strapdown identify --json`` (fractions as ``"p/q"``, no NaN).

        Returns
        -------
        dict
        """
        ident = self.identification
        con = self.consistency
        out = {
            "integrator": ident.name,
            "samples": ident.samples,
            "max_previous": ident.max_previous,
            "history": ident.history,
            "history_at_limit": ident.at_limit,
            "tolerance": ident.tolerance,
            "max_denominator": ident.max_denominator,
            "probe_amplitude": ident.amplitude,
            "exact": ident.exact,
            "isotropic": ident.isotropic,
            "trusted": None if self.assumptions is None else self.assumptions.trusted,
            "terms": ident.terms,
            "linear": {str(j): _text(a) for j, a in sorted(ident.linear_part.items())},
            "coefficients": {f"{i},{j}": _coefficient(c) for (i, j), c in ident.pairwise.items() if c.fraction or c.exact is None},
            "consistent": con.consistent,
            "conditions": {
                "first_order": con.first_order,
                "linear_error_weight": con.linear_weight,
                "linear_tensor_is_sum": con.linear_tensor_is_sum,
                "second_order": con.second_order,
                "second_order_sum": _text(con.second_order_sum),
                "second_order_expected": _text(con.second_order_expected),
                "second_order_defect": _text(con.second_order_defect),
                "second_order_bound": con.second_order_bound,
            },
            "accuracy_order": self.order,
            "local_error_order": None if self.order is None else self.order + 1,
            "local_error": _series(self.local_error),
            "local_error_exponent": _finite(self.local_error_exponent),
            "coning_drift_order": None,
            "coefficient": None,
            "coefficient_float": None,
            "step_coefficient": None,
            "drift_note": "coning drift u = coefficient * alpha^2 * omega * (omega*h)^coning_drift_order, exact minus integrator, along the cone axis (as derive coning-drift)",
            "remainder": _remainder(ident.remainder),
            "verification": _check(self.check),
            "cone_angles": list(self.cone_angles),
            "assumptions": None if self.assumptions is None else self.assumptions.as_dict(),
            "sculling": None,
            "probe_samples": ident.probe_samples,
        }
        if self.coning is not None:
            c, ch = self.coning.coefficient, self.coning.step_coefficient
            out.update(coning_drift_order=self.coning.order, coefficient=_text(c), coefficient_float=float(c), step_coefficient=_text(ch), exact_function=str(self.coning.function))
        elif not ident.isotropic:
            out["drift_note"] = "the integrator treats the axes differently: the drift of a cone about each axis is under assumptions.isotropy.per_axis"
        else:
            out["drift_note"] = "no alpha^2 closed form: the linear part is not p_1 + ... + p_N"
        if self.sculling is not None:
            sc = self.sculling
            out["sculling"] = {
                "linear": {str(j): _text(a) for j, a in sorted(sc.terms.linear.items())},
                "terms": {f"{i},{j}": _text(m) for (i, j), m in sorted(sc.terms.bilinear.items())},
                "terms_note": "coefficient of p_i x b_j in the velocity increment (body axes at the start of the step)",
                "dual_extension": sc.dual_extension,
                "defect": {f"{kind} {','.join(str(x) for x in key)}": _text(d) for kind, key, d in sc.defect},
                "consequences": [
                    {"departure": f"{kind} {','.join(str(x) for x in key)}", "difference": _text(d), "velocity_error_weight": w, "velocity_local_error": None if w is None else f"O(h^{w})"}
                    for kind, key, d, w in sc.consequences
                ],
                "departures_velocity_error_weight": sc.departures_weight,
                "corrected_velocity_error_weight": sc.corrected_weight,
                "velocity_error_weight": sc.error_weight,
                "velocity_accuracy_order": sc.velocity_order,
                "velocity_local_error_order": None if sc.velocity_order is None else sc.velocity_order + 1,
                "velocity_order_decided_by": sc.decided_by,
                "velocity_error_exponent": _finite(sc.velocity_exponent),
                "remainder": _remainder(sc.remainder),
                "verification": _check(sc.check),
            }
        return out


def _series(e) -> dict | None:
    if e is None or e.order is None:
        return None
    return {
        "convention": "exact minus integrator, delta * h^(accuracy_order+1) * sum k_w x_w, h the sample interval, x_w nested products of the rate derivatives (as derive local-error)",
        "delta": _text(e.delta),
        "coefficients": {"x" + "".join(str(k) for k in w): _text(c) for w, c in e.coefficients.items() if c},
        "latex": e.latex(),
    }


def _coefficient(c) -> dict:
    return {"value": c.value, "uncertainty": c.uncertainty, "tolerance": c.tolerance, "exact": c.exact is not None, "fraction": _text(c.fraction)}


def _finite(x):
    return None if x is None or not math.isfinite(x) else float(x)


def _remainder(r: Remainder) -> dict:
    return {
        "degree": r.degree,
        "slope": _finite(r.slope),
        "coefficient": _finite(r.coefficient),
        "above_roundoff": r.above_roundoff,
        "constant": r.constant,
        "scales": list(r.scales),
        "sizes": list(r.sizes),
        "floors": list(r.floors),
        "summary": r.summary(),
    }


def _check(check: Check | None):
    if check is None:
        return None
    return {
        "quantity": check.quantity,
        "holds": check.holds,
        "consistent_within_uncertainty": check.consistent,
        "tolerance": check.points[0].tolerance if check.points else None,
        "largest_difference": check.largest_difference,
        "amplitudes": list(check.amplitudes),
        "points": [
            {
                "x": p.x,
                "closed_form": p.closed_form,
                "simulated": p.simulated,
                "relative_difference": _finite(p.relative_difference),
                "uncertainty": p.uncertainty,
                "resolved": p.resolved,
                "agrees": p.agrees,
            }
            for p in check.points
        ],
    }


def _order(algorithm: Algorithm) -> int | None:
    """ρ of the series, through weight 5 first (the parts are computed on demand and kept), then the default weight.

    Derived once per algorithm content and kept in the cache of derived
    results (:func:`~strapdown.analysis.core.cache.derived`), as
    :func:`~strapdown.analysis.coning.drift_theory.coning_drift` is.
    """

    def derive():
        for weight in (5, S.DEFAULT_MAX_WEIGHT):
            order = S.local_error(algorithm, weight).order
            if order is not None:
                return order
        return None

    return derived(f"integrators:accuracy-order:v1:{algorithm_key(algorithm)}", derive)


def _error_coefficients(algorithm: Algorithm) -> S.ErrorCoefficients:
    """:func:`strapdown.derivations.coning.series.error_coefficients`, derived once per algorithm content (cache of derived results)."""
    return derived(f"integrators:error-coefficients:v1:{algorithm_key(algorithm)}", lambda: S.error_coefficients(algorithm))


def verification_samples(samples: int, history: int, *, omega_h=OMEGA_H, velocity: bool = False, axes: int = 1) -> int:
    """Samples the verification of :func:`assess` feeds an integrator.

    Parameters
    ----------
    samples : int
        N.
    history : int
        Samples before a step the integrator reads.
    omega_h : sequence of float, keyword-only
        ωh of the coning check [rad].
    velocity : bool, keyword-only
        With the sculling check.
    axes : int, keyword-only
        Cone axes checked (3 for an integrator that treats the axes differently).

    Returns
    -------
    int
    """
    warm = -(-history // samples) + 1
    total = axes * len(omega_h) * len(CONE_ANGLES) * (warm + STEPS) * samples + 9 * (warm + 1) * samples
    if velocity:
        total += sum(len(ANGLE_AMPLITUDES) * (warm + round(2 * math.pi / x) * PERIODS) * samples for x in sculling_points(samples))
        total += 12 * (warm + 1) * samples
    return int(total)


def verification_cone_angles(linear_range: float, largest_coefficient: float, omega_h=OMEGA_H) -> tuple:
    """Half-cone angles of the drift checks: the defaults, lowered to stay in the linear range and small beside the largest coefficient.

    An increment of classical coning is at most about ``2α sin(ωh/2)``: the
    largest angle keeps it below half the linearity range.  A bilinear term
    ``c p_i × p_j`` is small beside the linear part only while ``|c| |p| ≪ 1``:
    the angles are divided by the largest coefficient where it exceeds 1.

    Parameters
    ----------
    linear_range : float
        The integrator's linearity range [rad].
    largest_coefficient : float
        The largest magnitude of an identified coefficient [dimensionless].
    omega_h : sequence of float
        ωh of the checks [rad].

    Returns
    -------
    tuple of float
        Four angles halving from the largest [rad].

    Examples
    --------
    >>> verification_cone_angles(0.32, 0.5) == CONE_ANGLES
    True
    >>> verification_cone_angles(0.32, 1e6)[0]
    4e-08
    """
    top = CONE_ANGLES[0]
    spread = 2 * math.sin(min(max(omega_h), math.pi) / 2)
    top = min(top, 0.5 * linear_range / max(spread, 1e-12), top / max(1.0, float(largest_coefficient)))
    return tuple(top / 2**k for k in range(len(CONE_ANGLES)))


#: Time of the symbolic work of an assessment (series, closed-form drift) on the reference machine [s], rounded up.
SYMBOLIC_SECONDS = 3.0
def assumption_samples(samples: int, max_previous: int, max_previous_limit: int = LONGEST_MEMORY) -> int:
    """Samples the assumption tests of :func:`assess` feed an integrator (for work estimates).

    The time-invariance blocks (16, and their gaps) keep twice the longest
    memory probed clear; the memory scan feeds two windows per sample probed,
    each a record of its own; the precision rays (36 blocks) and the
    linearity sweep (73) keep clear the memory found, bounded here by the
    longest probed.

    Parameters
    ----------
    samples : int
        N.
    max_previous : int
        K asked for.
    max_previous_limit : int
        The longest memory probed.

    Returns
    -------
    int

    Examples
    --------
    >>> assumption_samples(4, 4)
    14668
    """
    n, k, limit = int(samples), int(max_previous), max(int(max_previous_limit), int(max_previous))

    def length(reach):
        return (-(-reach // n) + 1) * n

    scan = 2 * sum(length(m) for m in list(range(k, limit + 1)) + [2 * limit])
    return 16 * length(2 * limit) + 16 * n + scan + (36 + 73) * length(limit)




def work(integrator: Integrator, samples_per_step, *, max_previous=DEFAULT_MAX_PREVIOUS, verify: bool = True, omega_h=OMEGA_H, max_previous_limit: int = LONGEST_MEMORY) -> budget.Estimate:
    """Estimated time and memory of :func:`assess`, from one timed call of the integrator.

    The integrator is timed on a record of random increments as long as one
    call of the identification (or 4096 samples, whichever is smaller), and its
    time per sample is scaled to every sample the assessment feeds it (the
    assumption tests, the probes at ``max_previous``, the verification).

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    max_previous : int, keyword-only
        K.
    verify : bool, keyword-only
        Include the verification.
    omega_h : sequence of float, keyword-only
        ωh of the coning check [rad].
    max_previous_limit : int, keyword-only
        The longest memory probed.

    Returns
    -------
    strapdown.analysis.core.budget.Estimate

    Raises
    ------
    IntegratorError
        If the timing call fails (the integrator raised or returned a wrong shape).
    """
    n = int(samples_per_step)
    fed = probe_samples(n, max_previous, velocity=integrator.velocity) + assumption_samples(n, max_previous, max_previous_limit)
    if verify:
        fed += verification_samples(n, max_previous, omega_h=omega_h, velocity=integrator.velocity)
    probe = max(n, min(4096, fed) // n * n)
    rng = np.random.default_rng(0)
    gyro = 1e-3 * rng.standard_normal((probe, 3))
    start = time.perf_counter()
    step_increments(integrator, gyro, n, 1e-3 * rng.standard_normal((probe, 3)) if integrator.velocity else None)
    per_sample = (time.perf_counter() - start) / probe
    what = f"identifying {integrator.name!r} ({fed:,} samples fed to it at {per_sample * 1e6:.3g} µs each)"
    model = budget.CostModel(seconds_per_unit=1.2 * per_sample + 2e-6, bytes_per_unit=0.0, fixed_seconds=SYMBOLIC_SECONDS, fixed_bytes=64 * 8 * (1 << 18) * 3)
    return model.estimate(fed, what=what)


def _seeds(rng, count: int) -> list:
    """``count`` independent streams from ``rng`` (a Generator, a seed or None): :meth:`numpy.random.SeedSequence.spawn`."""
    if isinstance(rng, np.random.Generator):
        root = np.random.SeedSequence(int(rng.integers(2**63)))
    elif isinstance(rng, np.random.SeedSequence):
        root = rng
    else:
        root = np.random.SeedSequence(DEFAULT_SEED if rng is None else rng)
    return [np.random.default_rng(s) for s in root.spawn(count)]


def _consistency(ident: Identification, alg: Algorithm) -> Consistency:
    n = ident.samples
    weight = linear_error_weight(ident.linear_part, n)
    expected = {(j, u, u): Fraction(1) for j in range(1, n + 1) for u in range(3)}
    bound = sum(abs(j - i) * c.bound for (i, j), c in ident.pairwise.items())
    linear_bound = max((c.bound for c in ident.linear.values()), default=0.0)
    total = second_order_defect(alg) + Fraction(n**3, 12)
    return Consistency(ident.linear_part, weight, total, Fraction(n**3, 12), ident.linear_tensor == expected, float(bound), float(linear_bound))


def _largest(ident: Identification) -> float:
    values = [abs(float(c)) for c in ident.quadratic_tensor.values()] + [abs(float(c)) for c in ident.linear_tensor.values()]
    return max(values, default=1.0)


def _sculling(integrator, ident, alg, n, history, verify, drift_tolerance) -> ScullingAssessment:
    terms = ident.sculling.terms(n)
    defect = terms.defect(alg)
    consequences = tuple((kind, key, d, departure_weight([(kind, key, d)])) for kind, key, d in defect)
    together = departure_weight(defect) if defect else None
    corrected = ScullingTerms.dual_extension(alg).error_weight()
    check = exponent = None
    if verify:
        check = sculling_check(integrator, n, terms, history=history, tolerance=drift_tolerance)
        exponent = velocity_error_exponent(integrator, n, history=history)
    return ScullingAssessment(terms, defect, ident.sculling.remainder, check, terms.error_weight(), consequences, together, corrected, exponent)


def assess(
    integrator: Integrator,
    samples_per_step,
    *,
    max_previous=DEFAULT_MAX_PREVIOUS,
    max_previous_limit: int = LONGEST_MEMORY,
    tolerance: float = TOLERANCE,
    amplitude: float | None = None,
    verify: bool = True,
    omega_h=OMEGA_H,
    drift_tolerance: float = DRIFT_TOLERANCE,
    name: str | None = None,
    rng=None,
    limits: budget.Limits | None = None,
) -> Assessment:
    """Test the assumptions, identify ``integrator``, check its consistency, analyse it and run it against the exact solution.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    max_previous : int, keyword-only
        K, earlier samples probed at first; raised to what the memory test finds.
    max_previous_limit : int, keyword-only
        The farthest sample the memory test probes, and the largest K it raises to.
    tolerance : float, keyword-only
        Rational reconstruction tolerance [dimensionless].
    amplitude : float, optional, keyword-only
        ε_0, the largest probe amplitude [rad, m/s] (default: 0.02, lowered to
        half the linearity range when that is smaller).
    verify : bool, keyword-only
        Run the integrator against the exact solution (coning drift, sculling
        rate, local-error exponents).
    omega_h : sequence of float, keyword-only
        ωh of the coning check [rad].
    drift_tolerance : float, keyword-only
        Relative tolerance of the checks [dimensionless].
    name : str, optional, keyword-only
        Name of the identified algorithm (default: the integrator's).
    rng : numpy.random.Generator, int or None, keyword-only
        Random blocks and windows of the tests (independent streams, ``SeedSequence.spawn``).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the identification; K is not
        raised beyond what they allow (the memory verdict then says no).

    Returns
    -------
    Assessment

    Raises
    ------
    TypeError, ValueError
        Bad arguments.
    IntegratorError
        The integrator raised, or returned a wrong shape, NaN or infinity
        (:class:`~.interface.IntegratorStopped` when run by :class:`~.isolation.Isolated`
        and stopped or dead).

    Examples
    --------
    >>> from .recursions import recursion
    >>> a = assess(recursion(alpha_lag=2), 4, max_previous=4, verify=False)
    >>> a.identification.terms["1,2"], a.consistency.second_order, a.order, a.coning.order
    ('1/12', False, 2, 2)
    >>> a.assumptions.time_invariance.holds, a.assumptions.memory.needed, a.assumptions.precision.holds
    (True, 1, True)
    """
    if not isinstance(integrator, Integrator):
        raise TypeError(f"Expected `integrator` to be an Integrator, got {type(integrator).__name__}")
    n = int(samples_per_step)
    k0 = int(max_previous)
    longest = max(int(max_previous_limit), k0)
    streams = _seeds(rng, 5)
    invariance = TimeInvarianceRun(integrator, n, reach=2 * longest, amplitude=CHECK_AMPLITUDE, rng=streams[0])
    invariance.first()  # the run's first call
    # an unread sample leaves the output bit for bit unchanged: the memory scan needs no measured noise floor
    memory = memory_length(integrator, n, start=k0, longest=longest, amplitude=CHECK_AMPLITUDE, noise=NoiseFloor(attitude=integrator.output != "rotation_vector"), rng=streams[3])
    guard = 2 * longest if memory.needed is None else memory.needed  # the blocks below keep the memory found clear
    prec = precision(integrator, n, reach=k0, amplitude=CHECK_AMPLITUDE, guard=guard, rng=streams[1])
    lin = linearity_range(integrator, n, reach=k0, noise=prec.noise, amplitude=amplitude, default=PROBE_AMPLITUDE, guard=guard, rng=streams[2])
    eps0 = lin.probe_amplitude
    k = k0
    if memory.needed is not None and memory.needed > k0:
        try:
            budget.check(identification_work(n, memory.needed, velocity=integrator.velocity), limits)
            k = memory.needed
        except budget.BudgetExceeded:
            k = k0
    ident = identify(integrator, n, max_previous=k, tolerance=tolerance, amplitude=eps0, noise=prec.noise, rng=streams[4], limits=limits)
    invariance.shifted()
    invariance.last()  # the run's last call before the verification
    tinv = invariance.verdict()
    prec = dataclasses.replace(prec, decided=tinv.holds)
    needed = ident.history if memory.needed is not None and memory.needed <= k0 else memory.needed
    memory = dataclasses.replace(memory, needed=needed, used=k, decided=tinv.holds)

    alg = ident.algorithm(name)
    consistency = _consistency(ident, alg)
    weight = consistency.linear_weight
    order = _order(alg)
    if weight is not None:
        order = weight - 1 if order is None else min(order, weight - 1)
    isotropic = ident.isotropic
    coning = coning_drift(alg) if weight is None and consistency.linear_tensor_is_sum and isotropic else None
    series = _error_coefficients(alg) if weight is None and order is not None else None
    history = max(ident.history, ident.max_previous)  # warm-up: steady state for any memory probed
    angles = verification_cone_angles(lin.range, _largest(ident), omega_h)
    check = exponent = None
    corrections, checks, simulated = (), (), ()
    if not isotropic:
        corrections = axis_corrections(ident, name)
    if verify:
        exponent = local_error_exponent(integrator, n, history=history)
        if coning is not None:
            check = coning_drift_check(integrator, n, alg, omega_h=omega_h, cone_angles=angles, tolerance=drift_tolerance, history=history)
        if corrections:
            checks, simulated = _per_axis(integrator, n, corrections, omega_h, angles, drift_tolerance, history)
    departure = max([c.spread for c in ident.pairwise.values()] + [c.spread for c in ident.linear.values()] + [ident.self_spread])
    iso = Isotropy(isotropic, float(departure), corrections, checks, simulated)
    drift_order = DriftOrder(consistency.second_order_defect, consistency.second_order_bound, consistency.linear_bound, order, None if coning is None else coning.order)
    assumptions = Assumptions(tinv, memory, iso, lin, prec, drift_order)
    sculling = _sculling(integrator, ident, alg, n, history, verify, drift_tolerance) if ident.sculling is not None else None
    return Assessment(ident, alg, consistency, order, series, coning, exponent, check, sculling, assumptions, angles)


def _per_axis(integrator, n, corrections, omega_h, angles, tolerance, history) -> tuple:
    """Each axis's drift check against its closed form (or, without one, the simulated drift alone)."""
    checks, simulated = [], []
    for c in corrections:
        closed = c.drift_function()
        chk = coning_drift_check(integrator, n, c.algorithm, omega_h=omega_h, cone_angles=angles, tolerance=tolerance, history=history, axis=c.axis, closed_form=closed or _nothing)
        checks.append(chk if closed is not None else None)
        simulated.append(tuple((p.x, p.simulated) for p in chk.points))
    return tuple(checks), tuple(simulated)


def _nothing(x):
    """A closed form that is never resolved against (an axis without one: only its simulation is kept)."""
    return 0.0
