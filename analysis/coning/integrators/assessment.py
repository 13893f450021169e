"""One integrator, assessed: identified, checked for consistency, analysed, and run against the exact solution.

:func:`assess` chains the steps of this subpackage on one black box:

1. :func:`~.identification.identify`: the exact linear and bilinear part and
   the measured remainder (coning, and sculling when the integrator takes
   accelerometer increments);
2. consistency, reported and never a refusal (:class:`Consistency`): the
   first-order condition (the linear part is ``P = p_1 + … + p_N``) and the
   second-order condition ``Σ c_ij (j − i) = N³/12``
   (:func:`strapdown.derivations.coning.algorithms.second_order_defect`);
3. the exact local-error series of the identified algorithm
   (:func:`strapdown.derivations.coning.series.local_error`), its order ρ and
   leading term (:func:`strapdown.derivations.coning.series.error_coefficients`), and
   the closed-form coning drift (:func:`strapdown.derivations.coning.drift.coning_drift`);
   with a linear part other than P, the order is that of the linear part's
   error, whose leading weight is the first nonzero moment
   ``Σ_j (a_j − δ_j)(j^w − (j−1)^w)`` (:func:`linear_error_weight`), and the
   coning drift has no α² closed form;
4. the sculling part as data (:class:`~.sculling_terms.ScullingTerms`) and
   where it departs from the dual extension of the coning part;
5. the integrator itself against the exact solution
   (:mod:`.verification`): simulated coning drift and sculling rate against
   the closed forms, and the measured local-error exponent against ρ + 1.

:func:`work` estimates what an assessment costs before it starts.

Public API
----------
:class:`Consistency`, :class:`ScullingAssessment`, :class:`Assessment`,
:func:`linear_error_weight`, :func:`verification_samples`, :func:`work`, :func:`assess`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ....derivations.coning import series as S
from ....derivations.coning.algorithms import Algorithm, second_order_defect
from ....derivations.coning.drift import ConingDrift
from ...core import budget
from ..drift_theory import coning_drift
from .identification import DEFAULT_MAX_PREVIOUS, TOLERANCE, Identification, Remainder, identify, probe_samples
from .interface import Integrator, step_increments
from .sculling_terms import ScullingTerms
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
)

__all__ = ["Consistency", "ScullingAssessment", "Assessment", "linear_error_weight", "verification_samples", "work", "assess"]


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
        ``{j: a_j}``, the identified linear part (nonzero entries).
    linear_weight : int or None
        :func:`linear_error_weight` (None: the linear part is P).
    second_order_sum : Fraction
        ``Σ c_ij (j − i)`` of the identified pairwise terms.
    second_order_expected : Fraction
        ``N³/12``.
    """

    linear: dict
    linear_weight: int | None
    second_order_sum: Fraction
    second_order_expected: Fraction

    @property
    def first_order(self) -> bool:
        """The linear part is ``P = p_1 + … + p_N``."""
        return self.linear_weight is None

    @property
    def second_order(self) -> bool:
        """``Σ c_ij (j − i) = N³/12``."""
        return self.second_order_sum == self.second_order_expected

    @property
    def consistent(self) -> bool:
        """Both conditions hold."""
        return self.first_order and self.second_order


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
    """

    terms: ScullingTerms
    defect: tuple
    remainder: Remainder
    check: Check | None

    @property
    def dual_extension(self) -> bool:
        """The sculling part is the dual extension of the coning part (with the rotation term)."""
        return not self.defect


@dataclass(frozen=True)
class Assessment:
    """Everything the package says about one integrator.

    Attributes
    ----------
    identification : Identification
        Coefficients, uncertainties, remainder.
    algorithm : Algorithm
        The identified algorithm (``P`` plus the pairwise terms).
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
        linear part is not P).
    local_error_exponent : float or None
        Measured exponent of the integrator's own one-step error (None: not verified).
    check : Check or None
        The integrator's simulated coning drift against the closed form (None: not verified).
    sculling : ScullingAssessment or None
        For integrators that take accelerometer increments.
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
            "exact": ident.exact,
            "isotropic": ident.isotropic,
            "terms": ident.terms,
            "linear": {str(j): _text(a) for j, a in sorted(ident.linear_part.items())},
            "coefficients": {f"{i},{j}": _coefficient(c) for (i, j), c in ident.pairwise.items() if c.fraction or c.exact is None},
            "consistent": con.consistent,
            "conditions": {
                "first_order": con.first_order,
                "linear_error_weight": con.linear_weight,
                "second_order": con.second_order,
                "second_order_sum": _text(con.second_order_sum),
                "second_order_expected": _text(con.second_order_expected),
                "second_order_defect": _text(con.second_order_sum - con.second_order_expected),
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
            "sculling": None,
            "probe_samples": ident.probe_samples,
        }
        if self.coning is not None:
            c, ch = self.coning.coefficient, self.coning.step_coefficient
            out.update(coning_drift_order=self.coning.order, coefficient=_text(c), coefficient_float=float(c), step_coefficient=_text(ch), exact_function=str(self.coning.function))
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
    """ρ of the series, through weight 5 first (the parts are computed on demand and kept), then the default weight."""
    for weight in (5, S.DEFAULT_MAX_WEIGHT):
        order = S.local_error(algorithm, weight).order
        if order is not None:
            return order
    return None


def verification_samples(samples: int, history: int, *, omega_h=OMEGA_H, velocity: bool = False) -> int:
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

    Returns
    -------
    int
    """
    warm = -(-history // samples) + 1
    total = len(omega_h) * len(CONE_ANGLES) * (warm + STEPS) * samples + 9 * (warm + 1) * samples
    if velocity:
        total += sum(len(ANGLE_AMPLITUDES) * (warm + round(2 * math.pi / x) * PERIODS) * samples for x in sculling_points(samples))
    return int(total)


#: Time of the symbolic work of an assessment (series, closed-form drift) on the reference machine [s], rounded up.
SYMBOLIC_SECONDS = 3.0


def work(integrator: Integrator, samples_per_step, *, max_previous=DEFAULT_MAX_PREVIOUS, verify: bool = True, omega_h=OMEGA_H) -> budget.Estimate:
    """Estimated time and memory of :func:`assess`, from one timed call of the integrator.

    The integrator is timed on a record of random increments as long as one
    call of the identification (or 4096 samples, whichever is smaller), and its
    time per sample is scaled to every sample the assessment feeds it.

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

    Returns
    -------
    strapdown.analysis.core.budget.Estimate

    Raises
    ------
    IntegratorError
        If the timing call fails (the integrator raised or returned a wrong shape).
    """
    n = int(samples_per_step)
    fed = probe_samples(n, max_previous, velocity=integrator.velocity)
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


def assess(
    integrator: Integrator,
    samples_per_step,
    *,
    max_previous=DEFAULT_MAX_PREVIOUS,
    tolerance: float = TOLERANCE,
    verify: bool = True,
    omega_h=OMEGA_H,
    drift_tolerance: float = DRIFT_TOLERANCE,
    name: str | None = None,
    rng=None,
) -> Assessment:
    """Identify ``integrator``, check its consistency, analyse the identified algorithm and run the integrator against the exact solution.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    max_previous : int, keyword-only
        K, earlier samples probed.
    tolerance : float, keyword-only
        Rational reconstruction tolerance [dimensionless].
    verify : bool, keyword-only
        Run the integrator against the exact solution (coning drift, sculling
        rate, local-error exponent).
    omega_h : sequence of float, keyword-only
        ωh of the coning check [rad].
    drift_tolerance : float, keyword-only
        Relative tolerance of the checks [dimensionless].
    name : str, optional, keyword-only
        Name of the identified algorithm (default: the integrator's).
    rng : numpy.random.Generator, int or None, keyword-only
        Random windows of the remainder measurement.

    Returns
    -------
    Assessment

    Raises
    ------
    TypeError, ValueError
        Bad arguments.
    IntegratorError
        The integrator raised, returned a wrong shape, NaN or infinity, or is not deterministic.

    Examples
    --------
    >>> from .recursions import recursion
    >>> a = assess(recursion(alpha_lag=2), 4, max_previous=4, verify=False)
    >>> a.identification.terms["1,2"], a.consistency.second_order, a.order, a.coning.order
    ('1/12', False, 2, 2)
    """
    ident = identify(integrator, samples_per_step, max_previous=max_previous, tolerance=tolerance, rng=rng)
    alg = ident.algorithm(name)
    n = ident.samples
    weight = linear_error_weight(ident.linear_part, n)
    consistency = Consistency(ident.linear_part, weight, second_order_defect(alg) + Fraction(n**3, 12), Fraction(n**3, 12))
    order = _order(alg)
    if weight is not None:
        order = weight - 1 if order is None else min(order, weight - 1)
    coning = coning_drift(alg) if weight is None else None
    series = S.error_coefficients(alg) if weight is None and order is not None else None
    history = max(ident.history, ident.max_previous)  # warm-up: steady state for any memory probed
    check = exponent = None
    if verify:
        exponent = local_error_exponent(integrator, n, history=history)
        if coning is not None:
            check = coning_drift_check(integrator, n, alg, omega_h=omega_h, tolerance=drift_tolerance, history=history)
    sculling = None
    if ident.sculling is not None:
        terms = ident.sculling.terms(n)
        s_check = sculling_check(integrator, n, terms, history=history, tolerance=drift_tolerance) if verify else None
        sculling = ScullingAssessment(terms, terms.defect(alg), ident.sculling.remainder, s_check)
    return Assessment(ident, alg, consistency, order, series, coning, exponent, check, sculling)
