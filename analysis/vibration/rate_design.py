"""Sampling rate and computational load of algorithms in a vibration environment, for a drift budget.

The design of Budennyi, Kalinovsky, Panov et al. (Part 2), Tables 4–5 —
each algorithm at the largest step that meets a drift budget under one
coning motion, costed in operations per second — generalised to an
environment (:mod:`strapdown.analysis.vibration.environment`): lines, spectra
and the sensors' filters, decimation included.

For each algorithm, on a grid of sample rates ``1/h`` (ascending), the drift
magnitude ``|u(h)|`` is the closed form of
:mod:`strapdown.analysis.vibration.drift`.  The *lowest admissible
rate* is the lowest grid rate from which on every higher grid rate meets the
budget, refined by bisection against the rate below it (to
:data:`RATE_TOLERANCE`).  The sensor part of
the drift does not depend on the algorithm: where it alone exceeds the
budget, no rate is admissible.

*Tuned algorithms* (:mod:`strapdown.analysis.vibration.tuning`) are re-tuned at
every rate.  Their mean drift in the nominal environment is zero where the
degrees of freedom allow, so they are judged, like every algorithm here, by
the worst drift over the environment and the environment with every
frequency scaled by ``1 ± margin`` (same amplitudes): a tuning that relies on
knowing the frequencies to better than the margin is not admitted.

The load follows :func:`strapdown.analysis.coning.computational_load.step_load`:
the cost of the increment algorithm (:func:`~strapdown.analysis.coning.computational_load.operation_count`)
plus the quaternion update, whose series length is set by the angle per step
``Ω H`` (Ω: the sum of the line rate amplitudes plus three standard deviations
of the spectra's rates), divided by the time base.

Public API
----------
.. autosummary::

   RateRow
   RateDesign
   rate_design
   rate_design_estimate
   scaled_frequency
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import NamedTuple

import numpy as np

from ...derivations.coning.algorithms import Algorithm, Term
from ...derivations.coning.drift import lag_sums
from ..coning.computational_load import LoadModel, operation_count, quaternion_update_count, series_terms
from ..coning.drift_theory import coning_drift_function, optimal_coning_algorithm
from ..core.budget import RESPONSE_EVALUATION, SPECTRUM_SEGMENT, Estimate, Limits, check
from ..core.validation import as_array, nonnegative, positive
from .aliasing import alias_response
from .drift import quadrature_evaluations, response_integrals, segment_count
from .environment import Environment, Spectrum, VibrationLine
from .tuning import NothingToTune, lag_functions, solve_lag_sums

__all__ = ["RateRow", "RateDesign", "rate_design", "rate_design_estimate", "scaled_frequency", "DEFAULT_RATES", "FREQUENCY_MARGIN"]

#: Grid of algorithm sample rates searched by default [Hz].
DEFAULT_RATES = tuple(float(v) for v in np.geomspace(50.0, 20000.0, 61))
#: Relative width of the bisection's last bracket of the lowest admissible rate [-].
RATE_TOLERANCE = 2e-3
#: Relative frequency margin of the admissibility check [-].
FREQUENCY_MARGIN = 0.05


def scaled_frequency(environment: Environment, factor: float) -> Environment:
    """The environment with every frequency multiplied by ``factor`` (same amplitudes and densities).

    Parameters
    ----------
    environment : Environment
        The environment.
    factor : float
        Scale of the frequencies [-], > 0.

    Returns
    -------
    Environment
    """
    s = positive(factor, "factor")
    lines = tuple(VibrationLine(ln.frequency * s, ln.amplitude, ln.label) for ln in environment.lines)
    spectra = tuple(Spectrum(sp.frequency * s, sp.density, sp.label) for sp in environment.spectra)
    return Environment(lines, spectra, environment.gyro, environment.accelerometer, environment.name, environment.description)


def _rate_bound(environment: Environment) -> float:
    """Σ line rate amplitudes + 3 σ of the spectra's rates [rad/s]."""
    lines = sum(float(np.linalg.norm(ln.amplitude[:3])) for ln in environment.lines)
    var = 0.0
    for s in environment.spectra:
        tr = np.real(np.trace(s.density[:, :3, :3], axis1=1, axis2=2))
        var += float(np.trapezoid(tr, s.frequency))
    return lines + 3.0 * math.sqrt(var)


@dataclass(frozen=True)
class RateRow:
    """One algorithm at its lowest admissible rate.

    Attributes
    ----------
    algorithm : str
        Name.
    samples : int
        N.
    tuned : bool
        Re-tuned at every rate.
    sample_rate : float or None
        Lowest admissible algorithm sample rate 1/h [Hz] (None: none in the grid).
    drift : float or None
        Worst drift magnitude there (margins included) [rad/s].
    sensor_drift : float or None
        Its sensor part (nominal environment) [rad/s].
    cost : float or None
        Operations per step, increment algorithm plus quaternion update [addition-equivalents].
    load : float or None
        Operations per second [1/s].
    note : str
        Why there is no admissible rate when the cause is not the budget (the
        sensors not defined there, an evaluation that failed), or a remark on
        the rate found.
    """

    algorithm: str
    samples: int
    tuned: bool
    sample_rate: float | None
    drift: float | None
    sensor_drift: float | None
    cost: float | None
    load: float | None
    note: str = ""


@dataclass(frozen=True, eq=False)
class RateDesign:
    """Rows and the drift curves against rate behind them.

    Attributes
    ----------
    budget : float
        Drift budget [rad/s].
    rates : ndarray (R,)
        Sample-rate grid [Hz].
    rows : tuple of RateRow
    curves : ndarray (A, R)
        Worst drift magnitude of each row's algorithm on the grid [rad/s] (NaN where the
        sensors are not defined or the evaluation failed, with the reason in the rows and notes).
    sensor : ndarray (R,)
        Sensor part (nominal) on the grid [rad/s].
    margin : float
        Frequency margin [-].
    notes : tuple of str
        Rates left out of the grid and why.
    """

    budget: float
    rates: np.ndarray
    rows: tuple
    curves: np.ndarray
    sensor: np.ndarray
    margin: float
    notes: tuple = ()


class _Maker(NamedTuple):
    """One row of the design: a fixed algorithm, or an (N, history) tuned at every rate."""

    name: str
    samples: int
    history: int
    algorithm: Algorithm | None


class _Point(NamedTuple):
    """One maker at one rate: worst |drift| over the environments, nominal sensor part, the algorithm, or why not."""

    drift: float
    sensor: float
    algorithm: Algorithm | None
    reason: str = ""


def _sensor_reason(environment: Environment, h: float) -> str:
    """Why the sensors are not defined at the algorithm interval ``h`` ("" if they are): a digital cut-off above the sensor Nyquist frequency."""
    for name, sensor in (("gyro", environment.gyro), ("accelerometer", environment.accelerometer)):
        hs = sensor.sensor_interval(h)
        for axis, ch in zip("xyz", sensor.axes):
            if ch.digital.kind == "butterworth" and ch.digital.cutoff_hz >= 0.5 / hs:
                return f"the {name} {axis} digital cut-off {ch.digital.cutoff_hz:g} Hz lies above the sensor Nyquist frequency {0.5 / hs:g} Hz"
    return ""


def _maker_point(m: _Maker, sl: slice, results, aliases, sensors, col: int, h: float, quantity: str) -> _Point:
    """One maker evaluated from the shared integrals; a ValueError names the maker and the rate."""
    parts = [r.algorithm[sl, :, col].sum(axis=1) for r in results]  # (functions of the maker, 3) per environment
    if m.algorithm is not None:
        coef = np.array([float(c) for c in m.algorithm.pairwise.values()])
        drifts = [sensor + p[0] + a.base[col] + (a.per_pair[col] @ coef if coef.size else 0.0) for sensor, p, a in zip(sensors, parts, aliases[m.name])]
        alg = m.algorithm
    else:
        cs = [sensor + p[0] + a.base[col] for sensor, p, a in zip(sensors, parts, aliases[m.name])]
        Ms = [p[1:].T - a.per_pair[col] for p, a in zip(parts, aliases[m.name])]
        try:
            k, _, _, _, _ = solve_lag_sums(cs[0], Ms[0], m.samples, m.history, quantity=quantity)
        except NothingToTune:  # no coning at all: the classical form, whose lag sums the Taylor conditions alone fix
            k = np.array([float(v) for v in lag_sums(optimal_coning_algorithm(m.samples, history=m.history))])
        if not np.all(np.isfinite(k)):
            raise ValueError(f"the lag sums of {m.name} at {1.0 / h:.6g} Hz are not finite")
        k = np.array([float(Fraction(repr(float(v)))) for v in k])
        drifts = [c - M @ k for c, M in zip(cs, Ms)]
        terms = tuple(Term(Fraction(repr(float(v))), (m.samples - lag, m.samples)) for lag, v in enumerate(k, start=1) if v != 0.0)
        alg = Algorithm(m.name, m.samples, terms, f"tuned at h = {h:g} s", "tuned by strapdown-analysis")
    worst = max(float(np.linalg.norm(d)) for d in drifts)
    if not math.isfinite(worst):
        raise ValueError(f"the drift of {m.name} at {1.0 / h:.6g} Hz is not finite")
    return _Point(worst, float(np.linalg.norm(sensors[0])), alg)


def _evaluate(makers, environments, h, quantity) -> list:
    """Each maker at h (:class:`_Point`), each in its own guarded call.

    One :func:`response_integrals` per environment serves every maker: the
    closed form D of each fixed algorithm and the lag responses of each tuned
    form are integrated together; the aliasing pairs of lines
    (:func:`strapdown.analysis.vibration.aliasing.alias_response`) are added
    per maker.  A rate at which the sensors are not defined, or a maker whose
    evaluation fails, gets its reason instead of a number.
    """
    reason = _sensor_reason(environments[0], h) or next((_sensor_reason(e, h) for e in environments[1:] if _sensor_reason(e, h)), "")
    if reason:
        return [_Point(math.nan, math.nan, None, f"{1.0 / h:.6g} Hz: {reason}") for _ in makers]
    col = 0 if quantity == "coning" else 1
    functions, slices = [], []
    for m in makers:
        start = len(functions)
        if m.algorithm is not None:
            functions.append(coning_drift_function(m.algorithm))
        else:
            functions.extend(lag_functions(m.samples, m.samples + m.history - 1))
        slices.append(slice(start, len(functions)))
    try:
        results = [response_integrals(e, h, functions) for e in environments]
    except ValueError as exc:
        return [_Point(math.nan, math.nan, None, f"{1.0 / h:.6g} Hz: {exc}") for _ in makers]
    aliases = {}
    for m in makers:
        pairs = list(m.algorithm.pairwise) if m.algorithm is not None else [(m.samples - lag, m.samples) for lag in range(1, m.samples + m.history)]
        aliases[m.name] = [alias_response(e, h, m.samples, pairs) for e in environments]
    sensors = [(r.true[:, col] - r.sensed[:, col]).sum(axis=0) for r in results]
    out = []
    for m, sl in zip(makers, slices):
        try:
            out.append(_maker_point(m, sl, results, aliases, sensors, col, h, quantity))
        except ValueError as exc:
            out.append(_Point(math.nan, math.nan, None, f"{m.name} at {1.0 / h:.6g} Hz: {exc}"))
    return out


def rate_design_estimate(environment: Environment, rates: int, *, makers: int = 5, margin: float = FREQUENCY_MARGIN) -> Estimate:
    """Estimated time and memory of :func:`rate_design` before it starts.

    The spectra's product-integration weights are computed once per
    environment (the nominal one and the two with scaled frequencies), each
    costing per table segment; each rate then takes one response integral per
    environment, and the bisections about 7 more per maker.

    Parameters
    ----------
    environment : Environment
        The environment.
    rates : int
        Sample rates on the grid [count].
    makers : int, keyword-only
        Algorithms, fixed and tuned [count].
    margin : float, keyword-only
        Frequency margin (0: the nominal environment only).

    Returns
    -------
    strapdown.analysis.core.budget.Estimate
    """
    envs = 1 if margin == 0 else 3
    segments = sum(float(segment_count(s)) for s in environment.spectra)
    integrals = envs * (float(rates) + 7.0 * makers)
    nodes = integrals * sum(quadrature_evaluations(s) for s in environment.spectra)
    rows = sum(s.frequency.size for s in environment.spectra)
    what = (f"`rates` = {rates} sample rates × {envs} environments ({makers} algorithms), spectra of {rows} table rows "
            f"({segments:.3g} segments, {integrals:.3g} response integrals)")  # fmt: skip
    seg = SPECTRUM_SEGMENT.estimate(envs * segments, what=what)
    ev = RESPONSE_EVALUATION.estimate(nodes * max(1, makers), what=what)
    return Estimate(seg.seconds + ev.seconds, max(seg.memory, ev.memory), what)


def rate_design(environment: Environment, budget: float, *, algorithms=(), tuned=((2, 0), (3, 0)), rates=DEFAULT_RATES,
                margin: float = FREQUENCY_MARGIN, model: LoadModel | None = None, quantity: str = "coning", limits: Limits | None = None) -> RateDesign:  # fmt: skip
    """Lowest admissible sample rate and load of each algorithm (module docstring).

    Parameters
    ----------
    environment : Environment
        Lines, spectra and sensors (at least one line or spectrum).
    budget : float
        Drift budget [rad/s], > 0.
    algorithms : sequence of Algorithm, keyword-only
        Fixed algorithms (registry or files).
    tuned : sequence of (int, int), keyword-only
        ``(N, history)`` of algorithms re-tuned at every rate.
    rates : array_like, keyword-only
        Algorithm sample rates searched [Hz], > 0.
    margin : float, keyword-only
        Relative frequency margin, in [0, 1) (0: nominal environment only).
    model : LoadModel, keyword-only
        Load rules (default ``LoadModel()``).
    quantity : str, keyword-only
        Tune for ``"coning"`` (the only quantity whose budget is checked here).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s): a design
        beyond them (:func:`rate_design_estimate`) raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded` naming ``rates``.

    Returns
    -------
    RateDesign
        Rows with the reason where an algorithm has no admissible rate for a
        cause other than the budget; notes on the rates left out (sensors not
        defined there).

    Raises
    ------
    ValueError
        A non-positive budget or rate, a margin outside [0, 1), an environment
        without vibration, sensors defined at no rate of the grid, or a design
        beyond ``limits``.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (6), Tables 4–5.
    """
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    u = positive(budget, "budget")
    if not environment.has_motion:
        raise ValueError(
            "Expected an `environment` with motion (a line or spectrum with a nonzero amplitude), got no motion: no line or spectrum, "
            "or every amplitude and density zero; without motion every algorithm would meet any budget"
        )
    grid = np.sort(as_array(rates, "rates", nonempty=True).ravel())
    if np.any(grid <= 0):
        raise ValueError("Expected `rates` > 0")
    margin = nonnegative(margin, "margin")
    if margin >= 1.0:
        raise ValueError(f"Expected `margin` in [0, 1) (the frequencies are scaled by 1 ± margin), got {margin:g}")
    model = model or LoadModel()
    makers = [_Maker(a.name, a.samples, a.history, a) for a in algorithms]
    makers += [_Maker(f"tuned-{n}" if k == 0 else f"tuned-{n}+{k}", n, k, None) for n, k in tuned]
    check(rate_design_estimate(environment, grid.size, makers=max(1, len(makers)), margin=margin), limits)
    defined = np.array([not _sensor_reason(environment, 1.0 / r) for r in grid])
    notes = []
    if not defined.any():
        raise ValueError(f"Expected `rates` at which the sensors are defined, got none in {grid[0]:g}–{grid[-1]:g} Hz: {_sensor_reason(environment, 1.0 / grid[-1])}")
    if not defined.all():
        skipped = grid[~defined]
        notes.append(f"rates {skipped[0]:.4g}–{skipped[-1]:.4g} Hz left out: {_sensor_reason(environment, 1.0 / skipped[-1])}")
    envs = [environment] + ([scaled_frequency(environment, 1 - margin), scaled_frequency(environment, 1 + margin)] if margin > 0 else [])
    omega_bound = _rate_bound(environment)
    table = [_evaluate(makers, envs, 1.0 / r, quantity) for r in grid]  # table[rate][maker]
    curves = np.array([[table[i][j].drift for i in range(grid.size)] for j in range(len(makers))]).reshape(len(makers), grid.size)
    sensor = np.array([table[i][0].sensor for i in range(grid.size)]) if makers else np.zeros(grid.size)
    rows = []
    for j, m in enumerate(makers):
        curve = curves[j]
        admissible = None
        for i in range(grid.size - 1, -1, -1):
            if not curve[i] <= u:
                break
            admissible = i
        if admissible is None:
            top = next((table[i][j] for i in range(grid.size - 1, -1, -1) if defined[i]), table[-1][j])
            reason = top.reason or f"the drift at the highest rate exceeds the budget ({top.drift:.3g} rad/s > {u:.3g} rad/s)"
            rows.append(RateRow(m.name, m.samples, m.algorithm is None, None, None, None, None, None, reason))
            continue
        rate = float(grid[admissible])
        note = ""
        if admissible > 0 and defined[admissible - 1]:  # bisect between the failing rate below and the admissible one
            lo, hi = float(grid[admissible - 1]), rate
            while hi / lo > 1 + RATE_TOLERANCE:
                mid = math.sqrt(lo * hi)
                if _evaluate([m], envs, 1.0 / mid, quantity)[0].drift <= u:
                    hi = mid
                else:
                    lo = mid
            rate = hi
        elif admissible > 0:
            note = f"the lowest rate at which the sensors are defined on the grid; {table[admissible - 1][j].reason}"
        h = 1.0 / rate
        point = _evaluate([m], envs, h, quantity)[0]
        step = m.samples * h
        terms = series_terms(omega_bound * step, step, u, fraction=model.truncation_fraction) if omega_bound > 0 else 1
        cost = operation_count(point.algorithm).cost(model.m) + quaternion_update_count(terms).cost(model.m)
        rows.append(RateRow(m.name, m.samples, m.algorithm is None, rate, point.drift, point.sensor, cost, cost / model.time(step, m.samples), note))
    return RateDesign(u, grid, tuple(rows), curves, sensor, margin, tuple(notes))
