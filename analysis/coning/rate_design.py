"""Sampling rate and computational load of algorithms in a vibration environment, for a drift budget.

The design of Budennyi, Kalinovsky, Panov et al. (Part 2), Tables 4–5 —
each algorithm at the largest step that meets a drift budget under one
coning motion, costed in operations per second — generalised to an
environment (:mod:`strapdown.analysis.coning.environment`): lines, spectra
and the sensors' filters, decimation included.

For each algorithm, on a grid of sample rates ``1/h`` (ascending), the drift
magnitude ``|u(h)|`` is the closed form of
:mod:`strapdown.analysis.coning.vibration_drift`.  The *lowest admissible
rate* is the lowest grid rate from which on every higher grid rate meets the
budget, refined by bisection against the rate below it.  The sensor part of
the drift does not depend on the algorithm: where it alone exceeds the
budget, no rate is admissible.

*Tuned algorithms* (:mod:`strapdown.analysis.coning.tuning`) are re-tuned at
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
   scaled_frequency
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.validation import as_array, nonnegative, positive
from .computational_load import LoadModel, operation_count, quaternion_update_count, series_terms
from .environment import Environment, Spectrum, VibrationLine
from .tuning import tune, tuned_drift
from .vibration_drift import environment_drift

__all__ = ["RateRow", "RateDesign", "rate_design", "scaled_frequency", "DEFAULT_RATES", "FREQUENCY_MARGIN"]

#: Grid of algorithm sample rates searched by default [Hz].
DEFAULT_RATES = tuple(float(v) for v in np.geomspace(50.0, 20000.0, 61))
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
    """

    algorithm: str
    samples: int
    tuned: bool
    sample_rate: float | None
    drift: float | None
    sensor_drift: float | None
    cost: float | None
    load: float | None


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
        Worst drift magnitude of each row's algorithm on the grid [rad/s] (NaN: not defined there).
    sensor : ndarray (R,)
        Sensor part (nominal) on the grid [rad/s].
    margin : float
        Frequency margin [-].
    """

    budget: float
    rates: np.ndarray
    rows: tuple
    curves: np.ndarray
    sensor: np.ndarray
    margin: float


def _worst_fixed(algorithm, environments, h):
    """Worst |drift| over the environments, the nominal sensor part, and the algorithm at h."""
    try:
        ds = [environment_drift(algorithm, e, h) for e in environments]
    except ValueError:  # e.g. a digital filter's cut-off above the sensor Nyquist frequency at this rate
        return math.nan, math.nan, None
    return max(float(np.linalg.norm(d.total_vector)) for d in ds), float(np.linalg.norm(ds[0].sensor_vector)), algorithm


def _worst_tuned(samples, history, name, environments, h, quantity):
    """As :func:`_worst_fixed` for the algorithm tuned to the nominal environment at h."""
    try:
        t = tune(environments[0], samples, h, history=history, quantity=quantity, name=name)
        drifts = [t.drift] + [tuned_drift(e, samples, h, t.lag_sums, history=history, quantity=quantity) for e in environments[1:]]
        sensor = environment_drift(t.classical, environments[0], h).sensor_vector
    except ValueError:
        return math.nan, math.nan, None
    return max(float(np.linalg.norm(d)) for d in drifts), float(np.linalg.norm(sensor)), t.algorithm


def rate_design(environment: Environment, budget: float, *, algorithms=(), tuned=((2, 0), (3, 0)), rates=DEFAULT_RATES,
                margin: float = FREQUENCY_MARGIN, model: LoadModel | None = None, quantity: str = "coning") -> RateDesign:  # fmt: skip
    """Lowest admissible sample rate and load of each algorithm (module docstring).

    Parameters
    ----------
    environment : Environment
        Lines, spectra and sensors.
    budget : float
        Drift budget [rad/s], > 0.
    algorithms : sequence of Algorithm, keyword-only
        Fixed algorithms (registry or files).
    tuned : sequence of (int, int), keyword-only
        ``(N, history)`` of algorithms re-tuned at every rate.
    rates : array_like, keyword-only
        Algorithm sample rates searched [Hz], > 0.
    margin : float, keyword-only
        Relative frequency margin, ≥ 0 (0: nominal environment only).
    model : LoadModel, keyword-only
        Load rules (default ``LoadModel()``).
    quantity : str, keyword-only
        Tune for ``"coning"`` (the only quantity whose budget is checked here).

    Returns
    -------
    RateDesign

    Raises
    ------
    ValueError
        A non-positive budget or rate.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (6), Tables 4–5.
    """
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    u = positive(budget, "budget")
    grid = np.sort(as_array(rates, "rates").ravel())
    if np.any(grid <= 0):
        raise ValueError("Expected `rates` > 0")
    margin = nonnegative(margin, "margin")
    model = model or LoadModel()
    envs = [environment] + ([scaled_frequency(environment, 1 - margin), scaled_frequency(environment, 1 + margin)] if margin > 0 else [])
    makers = [(a.name, a.samples, False, (lambda h, a=a: _worst_fixed(a, envs, h))) for a in algorithms]
    for n, k in tuned:
        label = f"tuned-{n}" if k == 0 else f"tuned-{n}+{k}"
        makers.append((label, n, True, (lambda h, n=n, k=k, label=label: _worst_tuned(n, k, label, envs, h, quantity))))
    omega_bound = _rate_bound(environment)
    rows, curves, sensor = [], [], None
    for name, n, is_tuned, make in makers:
        values = [make(1.0 / r) for r in grid]
        curve = np.array([v[0] for v in values])
        curves.append(curve)
        if sensor is None:
            sensor = np.array([v[1] for v in values])
        ok = curve <= u
        admissible = None
        for i in range(grid.size - 1, -1, -1):
            if not ok[i]:
                break
            admissible = i
        if admissible is None:
            rows.append(RateRow(name, n, is_tuned, None, None, None, None, None))
            continue
        rate = float(grid[admissible])
        if admissible > 0:  # bisect between the failing rate below and the admissible one
            lo, hi = float(grid[admissible - 1]), rate
            for _ in range(30):
                mid = math.sqrt(lo * hi)
                if make(1.0 / mid)[0] <= u:
                    hi = mid
                else:
                    lo = mid
                if hi / lo < 1 + 1e-3:
                    break
            rate = hi
        h = 1.0 / rate
        worst, sens, alg = make(h)
        step = n * h
        terms = series_terms(omega_bound * step, step, u, fraction=model.truncation_fraction) if omega_bound > 0 else 1
        cost = operation_count(alg).cost(model.m) + quaternion_update_count(terms).cost(model.m)
        rows.append(RateRow(name, n, is_tuned, rate, worst, sens, cost, cost / model.time(step, n)))
    return RateDesign(u, grid, tuple(rows), np.array(curves), sensor if sensor is not None else np.zeros(grid.size), margin)
