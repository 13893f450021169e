"""The designer's answer: admissible rocking amplitude against frequency, for each alignment method.

Given an azimuth budget, the latitude, the alignment time and the sensors,
find at each rocking frequency the largest rocking amplitude ``a`` (applied to
the axes in the proportions ``pattern`` = (yaw, β, γ)) for which

* the rms azimuth error stays within the budget, and
* the azimuth error stays within the budget with probability ``level``
  (a percentile of ``|error|``).

To first order the rocking term is linear in ``a`` and independent of the
sensor errors, ``e(a) = e_0 + a u``:

``analytic``
    ``u`` and the sensor part ``e_0`` come from the first-order theory
    (:func:`strapdown.analysis.alignment.theory.analytic_theory`);
    for a sinusoid the residues are bounded sinusoids, and the envelope over
    phase (the worst alignment time in ``[T, T + period]``) smooths the
    whole-period zeros;
``inertial``, ``kalman``
    the response is not linear over the range that matters (the Kalman filter
    models the lever-arm motion to first order, and breaks down at a few
    degrees), so the amplitude is found by a root search on the Monte Carlo
    itself.  At each frequency the trials are drawn once
    (:meth:`strapdown.analysis.alignment.monte_carlo.AlignmentKernel.draw`) and
    the same draws are evaluated at every amplitude (common random numbers,
    passed explicitly): the rms (and the percentile) of their azimuth errors is
    then a smooth function of the amplitude.  Its root is searched in log a
    from the previous frequency's root, by secant steps along the power law of
    the rocking's share of the error (``rms² − rms(0)²``) with bisection as the
    safeguard, until its bracket is ``log(1 + rtol)/2`` wide, the stopping
    rule of Brent's method; the percentile's search starts where the rms
    reaches ``budget · rms/percentile`` and reuses every amplitude simulated
    (:func:`_root`).  The filter
    knows the rocking (its model is rebuilt at each amplitude).  The interval
    of the amplitude maps the 95 % interval of the rms at the root through the
    local slope of log rms against log a, and :func:`design_check` runs an
    independent Monte Carlo there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..core import montecarlo
from ..core.validation import as_array, as_int, in_open_interval, positive
from ..gyrocompass.error_distribution import abs_error_probability, abs_error_quantile
from .base_motion import NarrowbandMotion, SineMotion
from .fine import assumed_disturbance, filter_model
from .imu import Scenario, SensorErrors
from .monte_carlo import METHODS, AlignmentKernel, AlignmentOptions, alignment_monte_carlo
from .theory import analytic_theory

__all__ = ["AdmissibleAlignment", "admissible_rocking", "DesignCheckPoint", "design_check", "ROCKINGS"]

ROCKINGS = ("sine", "narrowband")


@dataclass(frozen=True)
class AdmissibleAlignment:
    """Admissible rocking amplitude against frequency for one method.

    Attributes
    ----------
    method : str
        The alignment method.
    rocking : str
        ``"sine"`` or ``"narrowband"``.
    frequency : ndarray
        ``(K,)`` rocking frequencies [Hz].
    amplitude : ndarray
        ``(K,)`` admissible amplitude by the rms criterion [rad] (0 where the
        sensors alone exceed the budget, ``max_amplitude`` where the rocking does not matter).
    amplitude_ci : ndarray
        ``(K, 2)`` 95 % interval of ``amplitude`` (Monte Carlo methods; equal bounds for the analytic theory).
    amplitude_percentile : ndarray
        ``(K,)`` admissible amplitude by ``P(|error| ≤ budget) ≥ level`` [rad].
    floor : float
        rms azimuth error without rocking [rad].
    unit_rms : ndarray
        ``(K,)`` rms of the rocking term per unit amplitude [rad/rad] (Monte Carlo
        methods: at the admissible amplitude, NaN at the ends).
    budget : float
        The budget [rad].
    level : float
        The percentile level.
    pattern : ndarray
        ``(3,)`` relative amplitudes (yaw, β, γ).
    envelope : bool
        Sine, analytic method: envelope over phase.
    n_trials : int
        Monte Carlo trials per frequency (0 for the analytic theory).
    max_amplitude : float
        Cap of the reported amplitudes [rad].
    """

    method: str
    rocking: str
    frequency: np.ndarray
    amplitude: np.ndarray
    amplitude_ci: np.ndarray
    amplitude_percentile: np.ndarray
    floor: float
    unit_rms: np.ndarray
    budget: float
    level: float
    pattern: np.ndarray
    envelope: bool
    n_trials: int
    max_amplitude: float


def _motion(rocking: str, amplitude, frequency: float, damping: float):
    if rocking == "sine":
        return SineMotion(amplitude, 1.0 / frequency)
    return NarrowbandMotion(amplitude, 1.0 / frequency, damping)


def _trial_errors(scenario, errors, method, options, draws):
    """The azimuth errors of the trials of ``draws`` in ``scenario``, unscored."""
    model, sequence = None, None
    if method == "kalman":
        from ..core import kalman

        model = filter_model(scenario, options.tuning)
        sequence = kalman.filter_sequence(model.F, model.Q, model.H, model.R, model.P0, scenario.n_samples // model.samples_per_epoch)
    kernel = AlignmentKernel(scenario, errors, method, options, (), sequence, model=model, score=False)
    e, _ = kernel.evaluate(draws)
    return e[:, 0]


def _with_motion(scenario, motion, options, method):
    sc = replace(scenario, motion=motion)
    if method == "kalman" and options.tuning.disturbance.kind != "none":
        kind = options.tuning.disturbance.kind
        options = replace(options, tuning=replace(options.tuning, disturbance=assumed_disturbance(motion, sc, kind=kind)))
    return sc, options


def admissible_rocking(
    method: str,
    budget,
    scenario: Scenario,
    frequencies,
    errors: SensorErrors | None = None,
    *,
    rocking: str = "narrowband",
    pattern=(0.0, 1.0, 1.0),
    damping: float = 0.1,
    level: float = 0.95,
    envelope: bool = True,
    options: AlignmentOptions | None = None,
    n_trials: int = 128,
    reference_amplitude: float = math.radians(1.0),
    max_amplitude: float = math.radians(20.0),
    rtol: float = 0.05,
    rng=None,
) -> AdmissibleAlignment:
    """Admissible rocking amplitude against frequency for an azimuth budget.

    Parameters
    ----------
    method : str
        ``"analytic"``, ``"inertial"`` or ``"kalman"``.
    budget : float
        Azimuth error budget [rad], > 0.
    scenario : Scenario
        Latitude, stable attitude, lever arm, sampling and alignment time (its motion is replaced).
    frequencies : array_like
        Rocking frequencies [Hz].
    errors : SensorErrors, optional
        Sensor errors (default ideal).
    rocking : str
        ``"sine"`` or ``"narrowband"``.
    pattern : array_like
        Relative amplitudes (yaw, β, γ); the amplitude a multiplies it.
    damping : float
        Damping ratio of narrow-band rocking.
    level : float
        Percentile level.
    envelope : bool
        Analytic method, sine: envelope over phase.
    options : AlignmentOptions, optional
        Method options (a Kalman disturbance model other than ``"none"`` is
        rebuilt for each rocking: a filter that knows the rocking).
    n_trials : int
        Monte Carlo trials per frequency (inertial, Kalman).
    reference_amplitude : float
        First amplitude of the root search at the first frequency [rad] (the
        next frequencies start at the root of the previous one).
    max_amplitude : float
        Cap of the reported amplitude [rad].
    rtol : float
        Relative width of the final bracket of the root search.
    rng : Generator | SeedSequence | int | None
        Root of the per-frequency streams.

    Returns
    -------
    AdmissibleAlignment

    Raises
    ------
    ValueError
        For an unknown method or rocking, or a bad size.

    Examples
    --------
    >>> sc = Scenario(math.radians(60.0), duration=60.0, sample_rate=10.0)
    >>> d = admissible_rocking("analytic", math.radians(0.1), sc, [0.1, 0.2])
    >>> bool(np.all(d.amplitude < math.radians(0.001)))  # the gyros see the rocking: arc-seconds
    True
    """
    if method not in METHODS:
        raise ValueError(f"Expected `method` in {METHODS}, got {method!r}")
    if rocking not in ROCKINGS:
        raise ValueError(f"Expected `rocking` in {ROCKINGS}, got {rocking!r}")
    budget = positive(budget, "budget")
    level = in_open_interval(level, "level", 0.0, 1.0)
    f = as_array(frequencies, "frequencies").ravel()
    if f.size == 0 or np.any(f <= 0) or np.any(f >= scenario.sample_rate / 8):
        raise ValueError(f"Expected `frequencies` in (0, sample_rate/8) = (0, {scenario.sample_rate / 8:g}) Hz")
    pat = as_array(pattern, "pattern").ravel()
    if pat.size != 3 or np.any(pat < 0) or not np.any(pat):
        raise ValueError(f"Expected `pattern` as three relative amplitudes >= 0, not all 0, got {pat.tolist()}")
    errors = SensorErrors() if errors is None else errors
    options = AlignmentOptions() if options is None else options
    cap = positive(max_amplitude, "max_amplitude")
    K = f.size
    amp, amp_p, unit = np.empty(K), np.empty(K), np.empty(K)
    ci = np.empty((K, 2))
    if method == "analytic":
        floor_t = analytic_theory(replace(scenario, motion=SineMotion(0.0, 8.0)), errors, formula=options.formula)
        floor = floor_t.rms
        for i, fi in enumerate(f):
            th = analytic_theory(replace(scenario, motion=_motion(rocking, pat, fi, damping)), errors, formula=options.formula, envelope=envelope and rocking == "sine")
            unit[i] = th.rocking
            spare = budget * budget - floor * floor
            amp[i] = 0.0 if spare <= 0 else (cap if unit[i] == 0 else min(cap, math.sqrt(spare) / unit[i]))
            ci[i] = amp[i]
            amp_p[i] = _analytic_percentile(th, budget, level, cap, rocking)
        return AdmissibleAlignment(method, rocking, f, amp, ci, amp_p, floor, unit, budget, level, pat, bool(envelope and rocking == "sine"), 0, cap)
    n_trials = as_int(n_trials, "n_trials", minimum=8)
    root = montecarlo.root_seed_sequence(rng)
    start = positive(reference_amplitude, "reference_amplitude")
    floors = []
    for i, fi in enumerate(f):
        sc1, opt1 = _with_motion(scenario, _motion(rocking, pat, fi, damping), options, method)
        draws = AlignmentKernel(sc1, errors, method, opt1).draw(n_trials, np.random.default_rng(montecarlo.block_seed(root, i)))
        simulated = {}

        def errors_at(a, fi=fi, draws=draws, simulated=simulated):
            if a not in simulated:
                sc_a, opt_a = _with_motion(scenario, _motion(rocking, a * pat, fi, damping), options, method)
                simulated[a] = _trial_errors(sc_a, errors, method, opt_a, draws)
            return simulated[a]

        def rms(a):
            e = errors_at(a)
            return math.sqrt(float(np.mean(e * e)))

        def pct(a):
            return float(np.quantile(np.abs(errors_at(a)), level, method="inverted_cdf"))  # an order statistic of the trials

        floors.append(rms(0.0) ** 2)
        amp[i], (lo, hi) = _root(rms, budget, start, cap, rtol)
        start_p = _percentile_start(rms, pct, amp[i], lo, hi, budget) if 0.0 < amp[i] < cap else start
        amp_p[i], _ = _root(pct, budget, start_p, cap, rtol, known=tuple(simulated))
        unit[i] = math.sqrt(max(rms(amp[i]) ** 2 - floors[-1], 0.0)) / amp[i] if 0 < amp[i] < cap else math.nan
        ci[i] = _amplitude_interval(errors_at, amp[i], lo, hi, cap)
        if 0.0 < amp[i] < cap:
            start = amp[i]  # the next frequency's search starts at this root
    floor = math.sqrt(float(np.mean(floors)))
    return AdmissibleAlignment(method, rocking, f, amp, ci, amp_p, floor, unit, budget, level, pat, False, n_trials, cap)


def _root(fn, budget: float, start: float, cap: float, rtol: float, *, known=()) -> tuple:
    """The amplitude in (0, cap] where the increasing ``fn`` reaches ``budget``, and its last bracket.

    The search works in ``x = log a`` and stops, as Brent's method with
    ``xtol = log(1 + rtol)/2`` does, when the bracket of the root is at most
    ``log(1 + rtol)/2`` wide; it returns the end of that bracket where
    ``|log fn − log budget|`` is smaller.  Its steps use what the error is
    made of: with ``fn(0)`` the floor, ``fn(a)² − fn(0)²`` is the rocking's
    share, a power of ``a`` locally (its square for a response linear in
    ``a``), so the root of that power law through the two amplitudes whose
    values lie nearest the budget (or, from one, its square) predicts the
    root closely.  The search
    evaluates just beside the prediction, on the side that lets the next
    evaluation close the bracket, and halves the bracket instead whenever a
    step fails to shrink it by half.  Amplitudes in ``known`` (already
    simulated, cheap to evaluate again) seed the bracket.

    Returns ``(0, (0, 0))`` if ``fn(0)`` already exceeds the budget and
    ``(cap, (cap, cap))`` if ``fn(cap)`` does not reach it; the bracket is the
    pair of amplitudes simulated nearest the root on either side.

    References
    ----------
    Brent, R. P., *Algorithms for Minimization without Derivatives*, 1973, ch. 4
    (the bracketing and its stopping rule, kept here); the power-law
    interpolation is a secant step in the coordinates ``log a``,
    ``log(fn² − fn(0)²)``.
    """
    tol = 0.5 * math.log(1.0 + rtol)
    values = {}

    def f(a):
        if a not in values:
            values[a] = float(fn(a))
        return values[a]

    f0 = f(0.0)
    if f0 > budget:
        return 0.0, (0.0, 0.0)
    for a in known:
        if 0.0 < a <= cap:
            f(float(a))
    share = budget * budget - f0 * f0

    def z(a):
        """log of the rocking's share of fn² at a (None where it is not positive)."""
        d = values[a] ** 2 - f0 * f0
        return math.log(d) if d > 0.0 else None

    def predict(a1, a2=None):
        """log a where the power law through a1 (and a2) reaches the budget (None where it cannot tell)."""
        if share <= 0.0:
            return None
        z1 = z(a1)
        if z1 is None:
            return None
        slope = 2.0
        if a2 is not None and a2 != a1:
            z2 = z(a2)
            if z2 is not None and z2 != z1:
                slope = (z2 - z1) / (math.log(a2) - math.log(a1))
        if not slope > 0.0 or not math.isfinite(slope):
            return None
        return math.log(a1) + (math.log(share) - z1) / slope

    def nearest():
        """The two simulated amplitudes whose values lie nearest the budget (a secant through them, not regula falsi)."""
        near = sorted((abs(math.log(max(v, 1e-300) / budget)), p) for p, v in values.items() if p > 0.0 and z(p) is not None)
        return [p for _, p in near[:2]] + [None] * (2 - min(len(near), 2))

    # bracket: from the nearest simulated amplitudes, a step just past the power-law root (at least tol, at most a factor 16)
    a = min(start, cap)
    while True:
        f(a)
        lows = [p for p, v in values.items() if 0.0 < p and v <= budget]
        highs = [p for p, v in values.items() if v > budget]
        lo = max(lows) if lows else None
        hi = min(highs) if highs else None
        if lo is not None and hi is not None and lo < hi:
            break
        if hi is None:  # every amplitude so far is within the budget: go up
            if lo >= cap:
                return cap, (cap, cap)
            a1, a2 = nearest()
            x = predict(a1, a2) if a1 is not None else None
            x0 = math.log(lo)
            x = x0 + math.log(4.0) if x is None else min(max(x + 0.45 * tol, x0 + tol), x0 + math.log(16.0))
            a = min(math.exp(x), cap)
        else:  # every amplitude so far exceeds it: go down
            if hi < cap * 1e-9:
                return 0.0, (0.0, 0.0)
            a1, a2 = nearest()
            x = predict(a1, a2) if a1 is not None else None
            x0 = math.log(hi)
            x = x0 - math.log(4.0) if x is None else max(min(x - 0.45 * tol, x0 - tol), x0 - math.log(16.0))
            a = math.exp(x)
    # refine: a step beside the power-law root, a halving when a step did not halve the bracket
    xl, xh = math.log(lo), math.log(hi)
    widths = [math.inf, math.inf]  # the bracket's widths before the last two steps
    while xh - xl > tol:
        x = predict(*nearest())
        if x is None or not xl < x < xh or xh - xl > 0.5 * widths[-2]:
            xe = 0.5 * (xl + xh)
        elif x - xl <= xh - x:  # nearer the lower end: just above the prediction closes the bracket if it holds
            xe = min(x + 0.5 * tol, xl + 0.98 * tol) if x - xl <= 0.48 * tol else x - 0.45 * tol
        else:  # nearer the upper end: the mirror image
            xe = max(x - 0.5 * tol, xh - 0.98 * tol) if xh - x <= 0.48 * tol else x + 0.45 * tol
        xe = min(max(xe, xl + 0.2 * tol), xh - 0.2 * tol)  # never a step that cannot shrink the bracket
        widths = [widths[-1], xh - xl]
        a = math.exp(xe)
        if f(a) <= budget:
            lo, xl = a, xe
        else:
            hi, xh = a, xe
    best = lo if abs(math.log(max(values[lo], 1e-300) / budget)) < abs(math.log(max(values[hi], 1e-300) / budget)) else hi
    return best, (lo, hi)


def _percentile_start(rms, pct, a: float, lo: float, hi: float, budget: float) -> float:
    """Where the percentile search starts: the amplitude whose rms is ``budget · rms(a)/pct(a)``.

    The ratio of the percentile to the rms changes slowly with the amplitude
    (it is a property of the error's distribution), so the percentile reaches
    the budget about where the rms reaches ``budget/κ``, ``κ = pct(a)/rms(a)``
    at the rms root ``a``; the rms there follows the power law of its share
    ``rms² − rms(0)²`` through the bracket ``lo``, ``hi`` of the rms root.
    Returns ``a`` where that cannot be told.
    """
    f0, r, q = rms(0.0), rms(a), pct(a)
    if not (q > 0.0 and 0.0 < lo < hi and r > f0):
        return a
    shares = [rms(x) ** 2 - f0 * f0 for x in (lo, hi)]
    target = (budget * r / q) ** 2 - f0 * f0
    if min(shares) <= 0.0 or target <= 0.0 or shares[1] <= shares[0]:
        return a
    slope = math.log(shares[1] / shares[0]) / math.log(hi / lo)
    return a * (target / (r * r - f0 * f0)) ** (1.0 / slope)


def _amplitude_interval(errors_at, a, lo, hi, cap):
    """95 % interval of the amplitude: the rms interval at the root through the local slope of log rms in log a."""
    if not 0.0 < a < cap or not 0.0 < lo < hi:
        return np.array([a, a])
    e_lo, e_hi = errors_at(lo), errors_at(hi)
    r_lo, r_hi = math.sqrt(float(np.mean(e_lo**2))), math.sqrt(float(np.mean(e_hi**2)))
    slope = math.log(r_hi / r_lo) / math.log(hi / lo) if r_hi > r_lo else math.inf
    e = errors_at(a)
    m = e * e
    rms = math.sqrt(float(np.mean(m)))
    se = float(np.std(m, ddof=1)) / math.sqrt(m.size) / (2.0 * max(rms, 1e-300))  # SE of the rms
    rel = 1.96 * se / max(rms, 1e-300)
    if not math.isfinite(slope) or slope <= 0:
        return np.array([lo, hi])
    return np.array([a * max(1.0 - rel, 0.0) ** (1.0 / slope), min(cap, a * (1.0 + rel) ** (1.0 / slope))])


def _analytic_percentile(th, budget, level, cap, rocking):
    """Largest a whose first-order ``|error|`` percentile is within the budget (rocking term linear in a).

    With a Gaussian part the percentile reaches the budget where
    ``P(|e| ≤ budget)`` falls to the level: one probability per step of the
    root search in a (:func:`~strapdown.analysis.gyrocompass.error_distribution.abs_error_probability`), not a
    percentile (itself a root search); without one, the percentile of the
    phase grid.
    """
    from scipy.optimize import brentq

    sines = rocking == "sine" and th.rocking_sine_amplitudes.size
    if th.sensor_sigma > 0.0:
        unit_sines, gauss = th.rocking_sine_amplitudes, th.sensor_sigma

        def q(a):
            if sines:
                return level - abs_error_probability(a * unit_sines, gauss, budget, mean=th.mean)
            return level - abs_error_probability([], math.hypot(gauss, a * th.rocking), budget, mean=th.mean)
    elif sines:

        def q(a):
            return abs_error_quantile(a * th.rocking_sine_amplitudes, 0.0, level, mean=th.mean).value - budget
    else:

        def q(a):
            return abs_error_quantile([], a * th.rocking, level, mean=th.mean).value - budget

    if q(0.0) >= 0:
        return 0.0
    if q(cap) <= 0:
        return cap
    return brentq(q, 0.0, cap, xtol=1e-12 * cap, rtol=1e-10)


@dataclass(frozen=True)
class DesignCheckPoint:
    """An independent Monte Carlo at an admissible amplitude.

    Attributes
    ----------
    frequency : float
        Rocking frequency [Hz].
    amplitude : float
        The admissible amplitude (rms criterion) [rad].
    result : MonteCarloResult
        The azimuth error there [rad]; its rms should equal the budget.
    """

    frequency: float
    amplitude: float
    result: montecarlo.MonteCarloResult


def design_check(
    design: AdmissibleAlignment,
    scenario: Scenario,
    errors: SensorErrors | None = None,
    *,
    indices=(0, -1),
    damping: float = 0.1,
    options: AlignmentOptions | None = None,
    n_trials: int = 200,
    rng=None,
) -> tuple:
    """Monte Carlo at some admissible amplitudes of a design (independent streams).

    Parameters
    ----------
    design : AdmissibleAlignment
        The chart to check.
    scenario : Scenario
        The scenario it was computed for.
    errors : SensorErrors, optional
        Its sensor errors.
    indices : sequence of int
        Frequencies to check.
    damping : float
        Damping ratio of narrow-band rocking.
    options : AlignmentOptions, optional
        Method options.
    n_trials : int
        Trials per check.
    rng : Generator | SeedSequence | int | None
        Root of the per-check streams.

    Returns
    -------
    tuple of DesignCheckPoint
    """
    options = AlignmentOptions() if options is None else options
    root = montecarlo.root_seed_sequence(rng)
    out = []
    for k, i in enumerate(indices):
        i = int(i) % design.frequency.size
        a = float(design.amplitude[i])
        if not 0.0 < a < design.max_amplitude:
            continue
        sc, opt = _with_motion(scenario, _motion(design.rocking, a * design.pattern, float(design.frequency[i]), damping), options, design.method)
        mc = alignment_monte_carlo(sc, errors, method=design.method, n_trials=n_trials, rng=montecarlo.block_seed(root, k), options=opt)
        out.append(DesignCheckPoint(float(design.frequency[i]), a, mc.result))
    return tuple(out)
