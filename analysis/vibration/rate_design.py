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
   scaled_frequency
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import NamedTuple

import numpy as np

from ...derivations.coning.algorithms import Algorithm, Term
from ..coning.computational_load import LoadModel, operation_count, quaternion_update_count, series_terms
from ..coning.drift_theory import coning_drift_function
from ..core.validation import as_array, nonnegative, positive
from .drift import response_integrals
from .environment import Environment, Spectrum, VibrationLine
from .tuning import lag_functions, solve_lag_sums

__all__ = ["RateRow", "RateDesign", "rate_design", "scaled_frequency", "DEFAULT_RATES", "FREQUENCY_MARGIN"]

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


class _Maker(NamedTuple):
    """One row of the design: a fixed algorithm, or an (N, history) tuned at every rate."""

    name: str
    samples: int
    history: int
    algorithm: Algorithm | None


def _evaluate(makers, environments, h, quantity):
    """Worst |drift| over the environments, nominal sensor part and algorithm, for each maker at h.

    One :func:`response_integrals` per environment serves every maker: the
    closed form D of each fixed algorithm and the lag responses of each tuned
    form are integrated together.
    """
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
    except ValueError:  # e.g. a digital filter's cut-off above the sensor Nyquist frequency at this rate
        return [(math.nan, math.nan, None) for _ in makers]
    sensors = [(r.true[:, col] - r.sensed[:, col]).sum(axis=0) for r in results]
    out = []
    for m, sl in zip(makers, slices):
        parts = [r.algorithm[sl, :, col].sum(axis=1) for r in results]  # (functions of the maker, 3) per environment
        if m.algorithm is not None:
            drifts = [sensor + p[0] for sensor, p in zip(sensors, parts)]
            alg = m.algorithm
        else:
            cs = [sensor + p[0] for sensor, p in zip(sensors, parts)]
            Ms = [p[1:].T for p in parts]
            try:
                k, _, _, _, _ = solve_lag_sums(cs[0], Ms[0], m.samples, m.history, quantity=quantity)
            except ValueError:
                out.append((math.nan, math.nan, None))
                continue
            k = np.array([float(Fraction(repr(float(v)))) for v in k])
            drifts = [c - M @ k for c, M in zip(cs, Ms)]
            terms = tuple(Term(Fraction(repr(float(v))), (m.samples - lag, m.samples)) for lag, v in enumerate(k, start=1) if v != 0.0)
            alg = Algorithm(m.name, m.samples, terms, f"tuned at h = {h:g} s", "tuned by strapdown-analysis")
        out.append((max(float(np.linalg.norm(d)) for d in drifts), float(np.linalg.norm(sensors[0])), alg))
    return out


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
    makers = [_Maker(a.name, a.samples, a.history, a) for a in algorithms]
    makers += [_Maker(f"tuned-{n}" if k == 0 else f"tuned-{n}+{k}", n, k, None) for n, k in tuned]
    omega_bound = _rate_bound(environment)
    table = [_evaluate(makers, envs, 1.0 / r, quantity) for r in grid]  # table[rate][maker]
    curves = np.array([[table[i][j][0] for i in range(grid.size)] for j in range(len(makers))])
    sensor = np.array([table[i][0][1] for i in range(grid.size)]) if makers else np.zeros(grid.size)
    rows = []
    for j, m in enumerate(makers):
        curve = curves[j]
        admissible = None
        for i in range(grid.size - 1, -1, -1):
            if not curve[i] <= u:
                break
            admissible = i
        if admissible is None:
            rows.append(RateRow(m.name, m.samples, m.algorithm is None, None, None, None, None, None))
            continue
        rate = float(grid[admissible])
        if admissible > 0:  # bisect between the failing rate below and the admissible one
            lo, hi = float(grid[admissible - 1]), rate
            while hi / lo > 1 + RATE_TOLERANCE:
                mid = math.sqrt(lo * hi)
                if _evaluate([m], envs, 1.0 / mid, quantity)[0][0] <= u:
                    hi = mid
                else:
                    lo = mid
            rate = hi
        h = 1.0 / rate
        worst, sens, alg = _evaluate([m], envs, h, quantity)[0]
        step = m.samples * h
        terms = series_terms(omega_bound * step, step, u, fraction=model.truncation_fraction) if omega_bound > 0 else 1
        cost = operation_count(alg).cost(model.m) + quaternion_update_count(terms).cost(model.m)
        rows.append(RateRow(m.name, m.samples, m.algorithm is None, rate, worst, sens, cost, cost / model.time(step, m.samples)))
    return RateDesign(u, grid, tuple(rows), curves, sensor, margin)
