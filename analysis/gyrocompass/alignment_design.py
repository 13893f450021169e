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
    (:func:`strapdown.analysis.gyrocompass.alignment_theory.analytic_theory`);
    for a sinusoid the residues are bounded sinusoids, and the envelope over
    phase (the worst alignment time in ``[T, T + period]``) smooths the
    whole-period zeros;
``inertial``, ``kalman``
    the response is not linear over the range that matters (the Kalman filter
    models the lever-arm motion to first order, and breaks down at a few
    degrees), so the amplitude is found by a root search on the Monte Carlo
    itself: the rms (and the percentile) of the azimuth error of the same
    trials — common random numbers: the same rocking phases or amplitudes,
    biases, noise and initial errors at every amplitude — started at
    ``reference_amplitude`` at the first frequency and at the previous
    frequency's root after it, and narrowed by a secant search in log a (from
    one point, the model ``rms² = floor² + (u a)^p`` with p = 2 at the first
    frequency and the previous frequency's local slope after it) to a bracket
    of relative width ``rtol``; the percentile search starts from every
    amplitude the rms search simulated, and places its runs where the
    percentile of the trials' errors, each interpolated between the amplitudes
    simulated, crosses the budget.  The
    filter knows the rocking (its model is rebuilt at each amplitude).  The
    interval of the amplitude maps the 95 % interval of the rms at the root
    through the local slope of log rms against log a, and
    :func:`design_check` runs an independent Monte Carlo there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..core import montecarlo
from ..core.validation import as_array, as_int, in_open_interval, positive
from .alignment_monte_carlo import METHODS, AlignmentKernel, AlignmentOptions, alignment_monte_carlo
from .alignment_theory import analytic_theory
from .base_motion import NarrowbandMotion, SineMotion
from .error_distribution import abs_error_probability, abs_error_quantile
from .fine_alignment import assumed_disturbance, filter_model
from .imu import Scenario, SensorErrors

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


def _trial_errors(scenario, errors, method, options, n_trials, seed):
    model, sequence = None, None
    if method == "kalman":
        from ..core import kalman

        model = filter_model(scenario, options.tuning)
        sequence = kalman.filter_sequence(model.F, model.Q, model.H, model.R, model.P0, scenario.n_samples // model.samples_per_epoch)
    kernel = AlignmentKernel(scenario, errors, method, options, (), sequence, model=model, score=False)
    e, _ = kernel(n_trials, np.random.default_rng(seed))
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
    a_ref = positive(reference_amplitude, "reference_amplitude")
    floors = []
    hint = (a_ref, 2.0)  # where the rms search starts, and the exponent of its one-point model: from the previous frequency
    for i, fi in enumerate(f):
        seed = montecarlo.block_seed(root, i)
        cache = {}

        def errors_at(a, fi=fi, seed=seed, cache=cache):
            if a not in cache:
                sc1, opt1 = _with_motion(scenario, _motion(rocking, a * pat, fi, damping), options, method)
                cache[a] = _trial_errors(sc1, errors, method, opt1, n_trials, seed)
            return cache[a]

        def rms(a):
            e = errors_at(a)
            return math.sqrt(float(np.mean(e * e)))

        def pct(a):
            return float(np.quantile(np.abs(errors_at(a)), level))

        e0 = errors_at(0.0)
        floors.append(float(np.mean(e0 * e0)))
        amp[i], (lo, hi) = _search(rms, budget, hint[0], cap, rtol, exponent=hint[1])
        hint = _next_hint(rms, hint, floors[-1], amp[i], (lo, hi), cap)
        amp_p[i], _ = _search(pct, budget, a_ref, cap, rtol, known=tuple(cache), estimate=lambda lo, hi, cache=cache: _trial_root(cache, level, budget, lo, hi))
        unit[i] = math.sqrt(max(rms(amp[i]) ** 2 - floors[-1], 0.0)) / amp[i] if 0 < amp[i] < cap else math.nan
        ci[i] = _amplitude_interval(errors_at, amp[i], lo, hi, budget, cap)
    floor = math.sqrt(float(np.mean(floors)))
    return AdmissibleAlignment(method, rocking, f, amp, ci, amp_p, floor, unit, budget, level, pat, False, n_trials, cap)


def _next_hint(fn, hint, floor_sq, a, bracket, cap):
    """Start and exponent for the search at the next frequency: this root, and the slope of log(fn² − fn(0)²) across its bracket."""
    lo, hi = bracket
    if not 0.0 < lo < hi < cap:
        return hint if not 0.0 < a < cap else (a, hint[1])
    y_lo, y_hi = fn(lo) ** 2 - floor_sq, fn(hi) ** 2 - floor_sq
    if y_lo <= 0.0 or y_hi <= y_lo:
        return a, hint[1]
    p = math.log(y_hi / y_lo) / math.log(hi / lo)
    return a, min(max(p, 0.5), 8.0)


def _trial_root(errors, level, budget, lo, hi):
    """Log of the amplitude where the ``level`` percentile of ``|error|`` reaches the budget, each trial's error
    interpolated linearly in ``a^q`` between the amplitudes simulated (``errors``: amplitude → per-trial
    errors, 0 among them; q the exponent of the rocking's part of the rms, from the two smallest nonzero
    amplitudes), searched in ``(lo, hi)`` (above ``hi``/64 without a lower end; up to four times the
    largest amplitude simulated, extrapolated, without an upper end); None if the percentile does not cross
    the budget there, or fewer than three amplitudes are known."""
    A = np.array(sorted(errors))
    if A.size < 3 or A[0] != 0.0:
        return None
    E = np.array([errors[a] for a in A])
    # the exponent q of the rocking's part, rms² − rms(0)² ∝ a^(2q), from the two smallest amplitudes
    m = np.mean(E * E, axis=1) - np.mean(E[0] * E[0])
    q = math.log(m[2] / m[1]) / (2.0 * math.log(A[2] / A[1])) if m[1] > 0.0 and m[2] > m[1] else 1.0
    S = A ** min(max(q, 0.5), 4.0)

    def pct(a):
        s = a ** min(max(q, 0.5), 4.0)
        j = min(max(int(np.searchsorted(S, s)), 1), A.size - 1)  # within [A[j-1], A[j]], or beyond the last
        w = (s - S[j - 1]) / (S[j] - S[j - 1])
        return float(np.quantile(np.abs((1.0 - w) * E[j - 1] + w * E[j]), level))

    top = A[-1] * 4.0 if hi is None else hi
    x0, x1 = math.log(lo if lo > 0.0 else top / 64.0), math.log(top)
    if not x0 < x1 or pct(math.exp(x0)) > budget or pct(math.exp(x1)) <= budget:
        return None
    for _ in range(30):  # bisection on the interpolated percentile, to 1e-9 of the bracket in log a
        xm = 0.5 * (x0 + x1)
        if pct(math.exp(xm)) <= budget:
            x0 = xm
        else:
            x1 = xm
    return 0.5 * (x0 + x1)


def _search(fn, budget, start, cap, rtol, known=(), exponent=2.0, estimate=None):
    """Largest a in (0, cap] with fn(a) ≤ budget, fn increasing: interpolation in log–log with a bracket.

    ``known`` lists amplitudes whose ``fn`` is cheap (already simulated: the
    percentile search starts from every point of the rms search); ``start``
    is the first amplitude when none is known; ``estimate(lo, hi)``, if given,
    estimates the root in log a from what has been simulated (the percentile
    search: from each trial's error, :func:`_trial_root`), falling back to the
    curve below when it returns None.  The next
    amplitude is the root of the curve through the (up to) three points
    nearest the budget in ``(log a, log(fn(a)² − fn(0)²))`` — a straight line
    of slope ``exponent`` through one, ``fn² = fn(0)² + (u a)^p``,
    a straight line through two, a parabola through three — moved
    half the final width past the root (toward the nearer end of a bracket), so
    that two evaluations close a bracket around a good estimate; where the
    root is estimated within the final width of a known point, the next one
    goes a final width from it, where it closes the bracket if it lands on the
    other side of the root.  Until the
    root is bracketed a step is at most ×16 (×4 where the curve gives no
    root); inside a bracket ``[lo, hi]`` a step shrinks it to at most
    ``(hi/lo)^0.9`` or by the factor ``1 + rtol``, and to ``√(hi/lo)`` once
    ``hi/lo ≤ (1 + rtol)²``.  The
    search ends when ``hi/lo ≤ 1 + rtol``.

    Returns the root ``lo`` and its bracket ``(lo, hi)``; (0, 0) or (cap, cap) at the ends.
    """
    values = {}

    def f(a):
        if a not in values:
            values[a] = fn(a)
        return values[a]

    for a in known:
        if 0.0 < a <= cap:
            f(a)
    f0 = f(0.0)
    if f0 > budget:
        return 0.0, (0.0, 0.0)
    half = 0.5 * math.log(1.0 + rtol)
    close = 0.999 * math.log(1.0 + rtol)  # a step that closes the bracket
    if not any(a > 0.0 for a in values):
        f(min(start, cap))
    while True:
        above = [a for a, v in values.items() if v > budget]
        hi = min(above) if above else None
        lo = max(a for a, v in values.items() if v <= budget and (hi is None or a < hi))  # 0.0 at least
        if hi is not None and (hi <= lo * (1.0 + rtol) or (lo == 0.0 and hi <= cap * 1e-9)):
            return (lo, (lo, hi)) if lo > 0.0 else (0.0, (0.0, 0.0))
        if hi is None and lo >= cap:
            return cap, (cap, cap)
        c = None if estimate is None else estimate(lo, hi)
        if c is None:
            c = _log_root(values, f0, budget, exponent)
        if hi is None:
            nxt = min(cap, 4.0 * lo if c is None else min(16.0 * lo, max(math.exp(c + half), lo * math.exp(close))))
        elif lo == 0.0:
            nxt = hi / 4.0 if c is None else max(hi / 16.0, min(math.exp(c - half), hi * math.exp(-close)))
        elif hi <= lo * math.exp(4.0 * half):
            nxt = math.sqrt(lo * hi)
        else:
            x0, x1 = math.log(lo), math.log(hi)
            lo_x, hi_x = x0 + 0.1 * (x1 - x0), x1 - 0.1 * (x1 - x0)  # a step shrinks the bracket by a tenth at least
            if c is None:
                x = 0.5 * (x0 + x1)
            else:
                c = min(max(c, x0), x1)
                if c - x0 > x1 - c:  # toward hi: a point within the final width of hi closes the bracket if below the root
                    x = max(c - half, x1 - close) if c > x1 - close else min(max(c - half, lo_x), hi_x)
                else:
                    x = min(c + half, x0 + close) if c < x0 + close else min(max(c + half, lo_x), hi_x)
            nxt = math.exp(x)
        f(nxt)


def _log_root(values, floor, budget, exponent=2.0):
    """Root in log a of the curve through the points nearest the budget in (log a, log(fn² − floor²)); None if there is none."""
    target = budget * budget - floor * floor
    pts = sorted((abs(math.log(v * v - floor * floor) - math.log(target)), math.log(a), math.log(v * v - floor * floor)) for a, v in values.items() if a > 0.0 and v * v > floor * floor)
    pts = sorted((x, y) for _, x, y in pts[:3])
    y_t = math.log(target) if target > 0.0 else None
    if y_t is None or len(pts) < 1:
        return None
    if len(pts) == 1:  # the power law through the floor: fn² − floor² ∝ a^exponent
        return pts[0][0] + (y_t - pts[0][1]) / exponent
    if len(pts) == 3:
        (xa, ya), (xb, yb), (xc, yc) = pts
        # the parabola y(x) through the three points, solved for y = y_t on the branch where it rises
        d1, d2 = (yb - ya) / (xb - xa), (yc - yb) / (xc - xb)
        k = (d2 - d1) / (xc - xa)
        bq = d1 - k * (xa + xb)
        aq, cq = k, ya - d1 * xa + k * xa * xb - y_t
        if abs(aq) > 1e-12:
            disc = bq * bq - 4.0 * aq * cq
            if disc >= 0.0:
                roots = [(-bq + sgn * math.sqrt(disc)) / (2.0 * aq) for sgn in (1.0, -1.0)]
                rising = [x for x in roots if 2.0 * aq * x + bq > 0.0]
                if rising:
                    return min(rising, key=lambda x: abs(x - xb))
        pts = pts[1:] if abs(yc - y_t) < abs(ya - y_t) else pts[:2]
    (xa, ya), (xb, yb) = pts[0], pts[-1]
    if yb <= ya:
        return None
    return xa + (y_t - ya) * (xb - xa) / (yb - ya)


def _amplitude_interval(errors_at, a, lo, hi, budget, cap):
    """95 % interval of the amplitude: the rms interval at the root through the local slope."""
    if not 0.0 < a < cap or hi <= lo:
        return np.array([a, a])
    e_lo, e_hi = errors_at(lo), errors_at(hi)
    r_lo, r_hi = math.sqrt(float(np.mean(e_lo**2))), math.sqrt(float(np.mean(e_hi**2)))
    slope = math.log(r_hi / r_lo) / math.log(hi / lo) if r_hi > r_lo else math.inf
    m = e_lo * e_lo
    se = float(np.std(m, ddof=1)) / math.sqrt(m.size) / (2.0 * math.sqrt(float(np.mean(m))))  # SE of the rms
    rel = 1.96 * se / max(r_lo, 1e-300)
    if not math.isfinite(slope) or slope <= 0:
        return np.array([lo, hi])
    return np.array([a * (1.0 - rel) ** (1.0 / slope), min(cap, a * (1.0 + rel) ** (1.0 / slope))])


def _analytic_percentile(th, budget, level, cap, rocking):
    """Largest a whose first-order ``|error|`` percentile is within the budget (rocking term linear in a).

    With a Gaussian part the percentile reaches the budget where
    ``P(|e| ≤ budget)`` falls to the level: one probability per step of the
    root search in a (:func:`.error_distribution.abs_error_probability`), not a
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
