"""Verdicts that can fail: "yes", "no" or "not resolved", each with its criterion, margin and interval.

A Monte Carlo (or any estimate with a standard error) answers a yes-or-no
question only as far as its interval allows.  A verdict here is always a test
of whether the true value of a quantity lies in an *acceptance region*
``[low, high]`` named before the run (a margin around a reference, a bound),
read from the two-sided ``level`` confidence interval of the estimate:

``"yes"``
    the whole interval lies inside the region.  For a region
    ``[r − m, r + m]`` this is the two one-sided tests (TOST) of
    equivalence within the margin ``m``, each at ``α = (1 − level)/2``
    (Schuirmann 1987); for a one-sided region (a bound) it is the one-sided
    test at the same α.
``"no"``
    the whole interval lies outside the region: the quantity is resolved
    beyond the margin.
``"not resolved"``
    the interval straddles an end of the region: the data cannot tell.  The
    verdict then says how many more trials would resolve it, at the observed
    spread: the half-width ``z·s/√N`` shrinks to the distance ``d`` between the
    estimate and the nearest end when ``N = ⌈(z·s/d)²⌉``, with ``s`` the
    per-trial standard deviation (``s = se·√n``).  An estimate that sits on an
    end cannot be resolved by more trials at all (``more_trials`` is None).

So "no evidence of a difference" never reads as "yes": a small Monte Carlo
whose wide interval covers the reference says "not resolved", and a verdict
that says "yes" has an interval narrower than its region.  An interval
"of stated width" is the same test read the other way: the region's width is
the largest interval that could say yes.

Rms quantities are tested on their mean square, whose estimate is a mean of
independent per-trial squares (:func:`rms_within`); a comparison of two
quantities measured on the same trials is tested on the per-trial
differences (:func:`mean_within` of the differences), so that the sampling
error of both enters.

A check that has no sampling error of its own but a band that already
accounts for it (a mean NEES against its χ² band) is stated with
:func:`in_band`; several verdicts that must all hold combine with
:func:`all_of`.

References
----------
Schuirmann, D. J. (1987), A comparison of the two one-sided tests procedure
and the power approach for assessing the equivalence of average
bioavailability, *J. Pharmacokinetics and Biopharmaceutics* 15(6), 657–680.
Wellek, S. (2010), *Testing Statistical Hypotheses of Equivalence and
Noninferiority*, 2nd ed., Chapman & Hall/CRC, ch. 1–2.

Public API
----------
.. autosummary::

   Verdict
   OUTCOMES
   within
   equivalence
   mean_within
   rms_within
   mean_square_within
   rms_equivalence
   in_band
   all_of
   trials_needed

Examples
--------
A Monte Carlo mean of 1.02 ± 0.01 (standard error, 100 trials) against the
reference 1 within ±5 %:

>>> v = equivalence(1.02, 0.01, 100, reference=1.0, margin=0.05, criterion="within 5 % of 1")
>>> v.outcome
'yes'

The same estimate from 4 trials (standard error 0.05) cannot tell:

>>> v = equivalence(1.02, 0.05, 4, reference=1.0, margin=0.05, criterion="within 5 % of 1")
>>> str(v)
'not resolved: 39 more trials needed'
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from statistics import NormalDist

import numpy as np

from .validation import as_array, as_float, as_int

__all__ = ["OUTCOMES", "Verdict", "within", "equivalence", "mean_within", "rms_within", "mean_square_within", "rms_equivalence", "in_band", "all_of", "trials_needed"]

#: The three outcomes of a verdict.
OUTCOMES = ("yes", "no", "not resolved")


def _finite_or_none(x):
    x = float(x)
    return x if math.isfinite(x) else None


@dataclass(frozen=True)
class Verdict:
    """The answer to one yes-or-no question, with what it rests on.

    Attributes
    ----------
    outcome : str
        ``"yes"``, ``"no"`` or ``"not resolved"``.
    criterion : str
        The question in words, with its margin and level (what a report prints
        beside the answer).
    estimate : float
        Point estimate of the tested quantity [its units] (NaN for a combined verdict).
    interval : tuple of float
        Its two-sided ``level`` confidence interval [its units].
    region : tuple of float
        The acceptance region ``(low, high)`` named before the run [its units];
        an infinite end for a one-sided criterion.
    margin : float
        The named margin [its units]: the half-width of the region for an
        equivalence, the bound's distance from the reference otherwise (NaN
        when the criterion names none).
    level : float
        Confidence of ``interval`` (the one-sided tests are at ``(1 − level)/2``).
    n : int
        Trials behind the estimate [count].
    more_trials : int or None
        Not resolved: further trials that would resolve it at the observed
        spread [count]; 0 when resolved; None when no number of trials can (the
        estimate sits on an end of the region, or it has no spread).
    trial : str
        What one independent trial is, in the plural (``"trials"``, ``"pairs"``), for the words.

    Notes
    -----
    A verdict is not a bool: ``if verdict:`` raises :class:`TypeError`, so
    that "not resolved" is never read as "yes".  Ask ``verdict.outcome``, or
    :attr:`yes`, :attr:`no`, :attr:`resolved`.
    """

    outcome: str
    criterion: str
    estimate: float
    interval: tuple
    region: tuple
    margin: float
    level: float
    n: int
    more_trials: int | None
    trial: str = "trials"

    def __post_init__(self):
        if self.outcome not in OUTCOMES:
            raise ValueError(f"Expected `outcome` in {OUTCOMES}, got {self.outcome!r}")

    def __bool__(self):
        raise TypeError("A Verdict has three outcomes; test `verdict.outcome` (or `.yes`, `.no`, `.resolved`), not its truth value")

    @property
    def yes(self) -> bool:
        """The outcome is ``"yes"``."""
        return self.outcome == "yes"

    @property
    def no(self) -> bool:
        """The outcome is ``"no"``."""
        return self.outcome == "no"

    @property
    def resolved(self) -> bool:
        """The outcome is ``"yes"`` or ``"no"``."""
        return self.outcome != "not resolved"

    def __str__(self) -> str:
        if self.resolved:
            return self.outcome
        if self.more_trials is None:
            return "not resolved: the estimate sits on the margin"
        word = self.trial[:-1] if self.more_trials == 1 and self.trial.endswith("s") else self.trial
        return f"not resolved: {self.more_trials} more {word} needed"

    def label(self) -> str:
        """The outcome for a Markdown table: ``yes``, ``**no**`` or ``not resolved: N more trials needed``.

        Returns
        -------
        str
        """
        return "**no**" if self.no else str(self)

    def as_dict(self, scale: float = 1.0) -> dict:
        """The verdict as a JSON-safe dict (infinite or NaN numbers become None).

        Parameters
        ----------
        scale : float
            Factor applied to ``estimate``, ``interval``, ``region`` and
            ``margin`` (a unit conversion at the edge, e.g. rad → deg).

        Returns
        -------
        dict
            Keys ``outcome``, ``criterion``, ``estimate``, ``interval``,
            ``region``, ``margin``, ``level``, ``n_trials``, ``more_trials_needed``
            and ``text`` (what :func:`str` prints).
        """
        s = float(scale)
        return {
            "outcome": self.outcome,
            "criterion": self.criterion,
            "estimate": _finite_or_none(self.estimate * s),
            "interval": [_finite_or_none(x * s) for x in self.interval],
            "region": [_finite_or_none(x * s) for x in self.region],
            "margin": _finite_or_none(self.margin * s),
            "level": self.level,
            "n_trials": self.n,
            "more_trials_needed": self.more_trials,
            "text": str(self),
        }


def _z(level: float) -> float:
    level = as_float(level, "level")
    if not 0.0 < level < 1.0:
        raise ValueError(f"Expected `level` in (0, 1), got {level:g}")
    return NormalDist().inv_cdf(0.5 + level / 2.0)


def trials_needed(standard_deviation: float, distance: float, *, level: float = 0.95) -> int | None:
    """Trials whose ``level`` interval half-width ``z·s/√N`` is at most ``distance``.

    Parameters
    ----------
    standard_deviation : float
        Per-trial standard deviation ``s`` of the quantity averaged [its units].
    distance : float
        The half-width to reach: the distance between the estimate and the
        nearest end of the acceptance region [its units].
    level : float, keyword-only
        Confidence of the two-sided interval.

    Returns
    -------
    int or None
        ``⌈(z·s/d)²⌉``; None when ``distance`` is 0 (no number of trials
        resolves an estimate on the boundary).

    >>> trials_needed(1.0, 0.1)
    385
    """
    s = as_float(standard_deviation, "standard_deviation")
    d = abs(as_float(distance, "distance"))
    if d == 0.0 or s <= 0.0:
        return None
    return int(math.ceil((_z(level) * s / d) ** 2))


def within(estimate, standard_error, n, *, low: float = -math.inf, high: float = math.inf, criterion: str, margin: float = math.nan, level: float = 0.95) -> Verdict:
    """Does the true value lie in ``[low, high]``? Read from the ``level`` interval ``estimate ± z·se``.

    Parameters
    ----------
    estimate : float
        Point estimate (a mean over ``n`` independent trials) [its units].
    standard_error : float
        Its standard error, ≥ 0 [its units].
    n : int
        Trials behind it, ≥ 1 [count].
    low, high : float, keyword-only
        The acceptance region, ``low < high`` (either end may be infinite) [its units].
    criterion : str, keyword-only
        The question in words (printed with the answer).
    margin : float, keyword-only
        The named margin, for the record [its units].
    level : float, keyword-only
        Confidence of the two-sided interval (0.95: each one-sided test at 2.5 %).

    Returns
    -------
    Verdict
        ``"yes"`` if the interval lies inside the region, ``"no"`` if it lies
        wholly outside, else ``"not resolved"`` with the trials needed.

    Raises
    ------
    ValueError
        For a negative ``standard_error``, ``n`` below 1, an empty region or a
        ``level`` outside (0, 1).

    References
    ----------
    Schuirmann (1987); Wellek (2010), sec. 1.6 (TOST as an interval inclusion).

    >>> within(0.3, 0.1, 50, high=1.0, criterion="at most 1").outcome
    'yes'
    >>> within(1.5, 0.1, 50, high=1.0, criterion="at most 1").outcome
    'no'
    """
    est = as_float(estimate, "estimate")
    se = as_float(standard_error, "standard_error")
    if se < 0.0:
        raise ValueError(f"Expected `standard_error` >= 0, got {se:g}")
    n = as_int(n, "n", minimum=1)
    lo_r, hi_r = float(low), float(high)
    if math.isnan(lo_r) or math.isnan(hi_r) or not lo_r < hi_r:
        raise ValueError(f"Expected `low` < `high` (the acceptance region), got [{lo_r:g}, {hi_r:g}]")
    z = _z(level)
    lo, hi = est - z * se, est + z * se
    if lo_r <= lo and hi <= hi_r:
        outcome, more = "yes", 0
    elif hi < lo_r or lo > hi_r:
        outcome, more = "no", 0
    else:
        outcome = "not resolved"
        d = min(est - lo_r, hi_r - est) if lo_r <= est <= hi_r else max(lo_r - est, est - hi_r)
        need = trials_needed(se * math.sqrt(n), d, level=level)
        more = None if need is None else max(need - n, 1)
    return Verdict(outcome, str(criterion), est, (lo, hi), (lo_r, hi_r), float(margin), float(level), n, more)


def equivalence(estimate, standard_error, n, *, reference: float, margin: float, criterion: str | None = None, level: float = 0.95) -> Verdict:
    """TOST: does the true value lie within ``±margin`` of ``reference``?

    Parameters
    ----------
    estimate : float
        Point estimate (a mean over ``n`` trials) [its units].
    standard_error : float
        Its standard error [its units].
    n : int
        Trials [count].
    reference : float, keyword-only
        The value it should equal (a theory, a closed form) [its units].
    margin : float, keyword-only
        The equivalence margin, > 0 [its units].
    criterion : str, keyword-only, optional
        The question in words (default: ``"within ±margin of reference (TOST, level)"``).
    level : float, keyword-only
        Confidence of the two-sided interval.

    Returns
    -------
    Verdict

    Raises
    ------
    ValueError
        For a margin that is not positive, or as :func:`within`.

    References
    ----------
    Schuirmann (1987).

    >>> equivalence(0.0, 1.0, 10, reference=0.5, margin=0.1).outcome
    'not resolved'
    """
    ref = as_float(reference, "reference")
    m = as_float(margin, "margin")
    if m <= 0.0:
        raise ValueError(f"Expected `margin` > 0, got {m:g}")
    text = criterion if criterion is not None else f"within ±{m:.3g} of {ref:.6g} (TOST, {level:.0%})"
    return within(estimate, standard_error, n, low=ref - m, high=ref + m, criterion=text, margin=m, level=level)


def _mean_and_se(values, name: str) -> tuple:
    x = as_array(values, name).ravel()
    if x.size < 2:
        raise ValueError(f"Expected `{name}` of at least 2 trials, got {x.size}")
    return float(x.mean()), float(x.std(ddof=1)) / math.sqrt(x.size), x.size


def mean_within(values, *, low: float = -math.inf, high: float = math.inf, criterion: str, margin: float = math.nan, level: float = 0.95) -> Verdict:
    """Does the mean of independent per-trial values lie in ``[low, high]``?

    Parameters
    ----------
    values : array_like
        ``(n,)`` one value per independent trial, n ≥ 2 (for a paired
        comparison, the per-trial differences) [their units].
    low, high : float, keyword-only
        Acceptance region of the mean [their units].
    criterion : str, keyword-only
        The question in words.
    margin : float, keyword-only
        The named margin, for the record.
    level : float, keyword-only
        Confidence of the two-sided interval.

    Returns
    -------
    Verdict

    Raises
    ------
    ValueError
        For fewer than 2 values, or as :func:`within`.

    >>> mean_within([0.9, 1.1, 1.0, 1.0], low=0.5, high=1.5, criterion="in [0.5, 1.5]").outcome
    'yes'
    """
    m, se, n = _mean_and_se(values, "values")
    return within(m, se, n, low=low, high=high, criterion=criterion, margin=margin, level=level)


def rms_within(values, *, low: float = 0.0, high: float = math.inf, criterion: str, margin: float = math.nan, level: float = 0.95) -> Verdict:
    """Does the rms of independent per-trial values lie in ``[low, high]``? Tested on the mean square.

    The mean square is a mean of independent squares, so its interval is
    ``ms ± z·se(x²)``; the region becomes ``[low², high²]``.  The verdict
    states the rms and the square root of that interval (a negative lower end
    is 0).

    Parameters
    ----------
    values : array_like
        ``(n,)`` one value per independent trial, n ≥ 2 [their units].
    low, high : float, keyword-only
        Acceptance region of the rms, ``0 ≤ low < high`` [their units].
    criterion : str, keyword-only
        The question in words.
    margin : float, keyword-only
        The named margin, for the record [their units].
    level : float, keyword-only
        Confidence of the two-sided interval.

    Returns
    -------
    Verdict
        In rms units; ``more_trials`` from the spread of the squares.

    Raises
    ------
    ValueError
        For fewer than 2 values, a negative ``low``, or as :func:`within`.

    >>> rms_within([1.0, -1.0] * 50, high=1.5, criterion="rms at most 1.5").outcome
    'yes'
    """
    x = as_array(values, "values").ravel()
    m, se, n = _mean_and_se(x * x, "values")
    return mean_square_within(m, se, n, low=low, high=high, criterion=criterion, margin=margin, level=level)


def mean_square_within(mean_square, standard_error, n, *, low: float = 0.0, high: float = math.inf, criterion: str, margin: float = math.nan, level: float = 0.95) -> Verdict:
    """Does the rms lie in ``[low, high]``, from a mean square and its standard error (a Monte Carlo summary)?

    Parameters
    ----------
    mean_square : float
        Mean of independent per-trial squares [units²].
    standard_error : float
        Its standard error [units²].
    n : int
        Trials [count].
    low, high : float, keyword-only
        Acceptance region of the rms, ``0 ≤ low < high`` [units].
    criterion : str, keyword-only
        The question in words.
    margin : float, keyword-only
        The named margin, for the record [units].
    level : float, keyword-only
        Confidence of the two-sided interval.

    Returns
    -------
    Verdict
        In rms units: the estimate ``√ms``, the interval the square roots of
        that of ``ms`` (a negative end is 0).

    Raises
    ------
    ValueError
        For a negative ``low`` or mean square, or as :func:`within`.

    >>> mean_square_within(1.0, 0.01, 200, low=0.9, high=1.1, criterion="rms 1 ± 10 %").outcome
    'yes'
    """
    lo_r, hi_r = float(low), float(high)
    if lo_r < 0.0:
        raise ValueError(f"Expected `low` >= 0 (an rms), got {lo_r:g}")
    m = as_float(mean_square, "mean_square")
    if m < 0.0:
        raise ValueError(f"Expected `mean_square` >= 0, got {m:g}")
    v = within(m, standard_error, n, low=lo_r * lo_r, high=hi_r * hi_r, criterion=criterion, margin=margin, level=level)
    root = lambda t: math.sqrt(max(t, 0.0))  # noqa: E731
    return Verdict(v.outcome, v.criterion, root(m), (root(v.interval[0]), root(v.interval[1])), (lo_r, hi_r), float(margin), v.level, v.n, v.more_trials)


def rms_equivalence(mean_square, standard_error, n, *, reference: float, relative_margin: float, criterion: str | None = None, level: float = 0.95) -> Verdict:
    """Is the rms within a relative margin of a reference rms (a theory, a filter's σ)? TOST on the mean square.

    Parameters
    ----------
    mean_square : float
        Mean of independent per-trial squares [units²].
    standard_error : float
        Its standard error [units²].
    n : int
        Trials [count].
    reference : float, keyword-only
        The rms it should equal, > 0 [units].
    relative_margin : float, keyword-only
        The margin as a fraction of ``reference``, in (0, 1): the region is
        ``reference·(1 ± relative_margin)``.
    criterion : str, keyword-only, optional
        The question in words (default names the reference and the margin).
    level : float, keyword-only
        Confidence of the two-sided interval.

    Returns
    -------
    Verdict
        In rms units; ``margin`` is ``relative_margin · reference``.

    Raises
    ------
    ValueError
        For a reference that is not positive or a relative margin outside (0, 1).

    >>> str(rms_equivalence(1.0, 0.2, 10, reference=1.0, relative_margin=0.1))
    'not resolved: 33 more trials needed'
    """
    ref = as_float(reference, "reference")
    if ref <= 0.0:
        raise ValueError(f"Expected `reference` > 0 (an rms), got {ref:g}")
    r = as_float(relative_margin, "relative_margin")
    if not 0.0 < r < 1.0:
        raise ValueError(f"Expected `relative_margin` in (0, 1), got {r:g}")
    text = criterion if criterion is not None else f"rms within ±{r:.0%} of {ref:.4g} (TOST, {level:.0%})"
    return mean_square_within(mean_square, standard_error, n, low=ref * (1.0 - r), high=ref * (1.0 + r), criterion=text, margin=r * ref, level=level)


def in_band(statistic, band, *, n: int, criterion: str, level: float = 0.95) -> Verdict:
    """Does every value of a statistic lie inside a band that already holds its sampling spread?

    For a mean NEES or NIS over ``n`` trials against its two-sided χ² band
    (:func:`strapdown.analysis.core.kalman.chi2_band`): the band is the
    acceptance region of the test of consistency, so the verdict is ``"yes"``
    or ``"no"``, never "not resolved".  Its power grows with ``n`` (the band
    narrows as ``1/√n``).

    Parameters
    ----------
    statistic : array_like
        Values (one per check epoch) [their units].
    band : tuple of float
        ``(low, high)`` [their units].
    n : int, keyword-only
        Trials behind each value [count].
    criterion : str, keyword-only
        The question in words.
    level : float, keyword-only
        Confidence of the band, for the record.

    Returns
    -------
    Verdict
        ``estimate`` the value farthest from the band's centre, ``interval``
        the range of the values.

    Raises
    ------
    ValueError
        For an empty statistic or a band with ``low >= high``.

    >>> in_band([2.9, 3.1], (2.5, 3.5), n=100, criterion="NIS in band").outcome
    'yes'
    """
    x = as_array(statistic, "statistic", nonempty=True).ravel()
    lo_b, hi_b = (float(b) for b in band)
    if not lo_b < hi_b:
        raise ValueError(f"Expected `band` as (low, high) with low < high, got {band!r}")
    inside = bool(np.all((x >= lo_b) & (x <= hi_b)))
    far = float(x[np.argmax(np.abs(x - 0.5 * (lo_b + hi_b)))])
    return Verdict("yes" if inside else "no", str(criterion), far, (float(x.min()), float(x.max())), (lo_b, hi_b), 0.5 * (hi_b - lo_b), float(level), as_int(n, "n", minimum=1), 0)


def all_of(verdicts: Sequence[Verdict], *, criterion: str) -> Verdict:
    """Several verdicts that must all say yes: ``"no"`` if any says no, ``"yes"`` if all say yes, else not resolved.

    Parameters
    ----------
    verdicts : sequence of Verdict
        At least one.
    criterion : str, keyword-only
        The joint question in words.

    Returns
    -------
    Verdict
        NaN estimate and interval; ``n`` the smallest of the parts;
        ``more_trials`` the largest of the unresolved parts (None if any of
        them cannot be resolved).

    Raises
    ------
    TypeError
        If an element is not a :class:`Verdict`.
    ValueError
        For no verdicts.
    """
    vs = list(verdicts)
    if not vs:
        raise ValueError("Expected `verdicts` to hold at least one Verdict, got none")
    for v in vs:
        if not isinstance(v, Verdict):
            raise TypeError(f"Expected `verdicts` of Verdict, got {type(v).__name__}")
    nan = math.nan
    n = min(v.n for v in vs)
    level = min(v.level for v in vs)
    if any(v.no for v in vs):
        return Verdict("no", str(criterion), nan, (nan, nan), (nan, nan), nan, level, n, 0)
    open_ = [v for v in vs if not v.resolved]
    if not open_:
        return Verdict("yes", str(criterion), nan, (nan, nan), (nan, nan), nan, level, n, 0)
    more = None if any(v.more_trials is None for v in open_) else max(v.more_trials for v in open_)
    return Verdict("not resolved", str(criterion), nan, (nan, nan), (nan, nan), nan, level, n, more)
