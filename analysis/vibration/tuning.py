"""Coning and sculling algorithms tuned to a vibration environment.

The mean drift of an N-sample algorithm (``history`` samples of earlier
steps) in an environment is affine in its lag sums ``k_l``, l = 1 … L,
``L = N + history − 1`` (:mod:`strapdown.analysis.vibration.drift`):

    u(k) = u_sensor + ∫ q̃ [φ₀(ωh) − Σ_l k_l φ_l(ωh)] / ω  =  c − M k,

``φ₀(x) = E(Nx)/(Nx)``, ``φ_l(x) = R_l(x)/(Nx)``, the sensors included (q̃
is what they pass; the sensor part is in c).  The same holds for the
rectification of the dual extension, with the sculling vector.

:func:`tune` picks the lag sums:

* the environment's conditions are the components of ``c − M k`` along the
  independent directions of the drift (one for lines about one axis);
* if L is at least their number, the drift is **nulled** and the remaining
  degrees of freedom cancel the lowest Taylor coefficients of the
  algorithm's own D(x) (the second-order condition first): the tuned
  algorithm stays as accurate as it can be for slow motions, which the
  environment does not describe;
* otherwise the drift is **minimised** (least squares over the directions).

Each lag sum is put on the pair ``(N − l, N)``, as in
:func:`strapdown.derivations.coning.drift.optimal_coning_algorithm`
(Ignagni's form), with the coefficient written as the shortest decimal that
round-trips the double.  A tuned algorithm generally misses the second-order
condition (that degree of freedom was spent on the environment): its
algorithm file says so, and loading it needs ``allow_inconsistent=True``
(``--allow-inconsistent``).  For N = 2 and one line the coefficient has the
closed form of :func:`strapdown.derivations.coning.tuned.two_sample_null_coefficient`.

Public API
----------
.. autosummary::

   TunedAlgorithm
   tune
   tuned_drift
   solve_lag_sums
   lag_functions
   drift_across_band
   BandDrift
   CONDITION_LIMIT
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ...derivations.coning.algorithms import Algorithm, Term
from ...derivations.coning.drift import optimal_coning_algorithm
from ..core.validation import as_array, as_int, positive
from .drift import environment_drift, response_integrals
from .environment import Environment, coning_line

__all__ = ["TunedAlgorithm", "tune", "tuned_drift", "solve_lag_sums", "lag_functions", "drift_across_band", "BandDrift", "QUANTITIES", "CONDITION_LIMIT"]

#: Condition number above which a tuned design is called ill-conditioned: its coefficients keep
#: fewer than half of float64's 16 significant digits (and are large and of alternating sign).
CONDITION_LIMIT = 1e8

#: What an algorithm is tuned for.
QUANTITIES = ("coning", "sculling")

#: Largest N and history of a tuned algorithm [count] (the published algorithms have at most 6 samples).
MAX_SAMPLES = 8

#: Below this x = ωh the response functions are summed from their Taylor series.
_SERIES_BELOW = 0.05


def _series_coefficients(samples: int, lag: int, terms: int) -> np.ndarray:
    """Taylor coefficients (of x^{2m}, m = 0 … terms−1) of φ_lag(x) (lag 0: φ₀), exact then rounded."""
    out = []
    for m in range(terms):
        n = 2 * m + 1  # power in the numerator; divided by N x
        if lag == 0:
            c = Fraction(0) if m == 0 else Fraction(-((-1) ** m) * samples**n, 2 * math.factorial(n))
        else:
            c = Fraction((-1) ** m * (2 * lag**n - (lag + 1) ** n - (lag - 1) ** n), math.factorial(n))
        out.append(float(c / samples))
    return np.array(out)


def lag_functions(samples: int, lags: int) -> tuple:
    """``(φ₀, φ₁, …, φ_lags)`` as vectorised functions of x = ωh (module docstring).

    ``φ₀(x) = E(Nx)/(Nx) = (1 − sin(Nx)/(Nx))/2`` and
    ``φ_l(x) = R_l(x)/(Nx) = (2 sin lx − sin(l+1)x − sin(l−1)x)/(Nx)``; below
    x = 0.05 their Taylor series (exact coefficients) avoid the cancellation
    of the closed forms.

    Parameters
    ----------
    samples : int
        N.
    lags : int
        L, the highest lag [count].

    Returns
    -------
    tuple of callable

    Examples
    --------
    >>> f0, f1 = lag_functions(2, 1)
    >>> x = np.array([1e-3, 0.3])
    >>> bool(np.allclose(f0(x) - 2 / 3 * f1(x), [(1e-3) ** 4 / 60, 0.3**4 / 60], rtol=0.05))
    True
    """
    N = as_int(samples, "samples", minimum=1)
    lags = as_int(lags, "lags", minimum=0)
    terms = 14

    def make(lag):
        series = _series_coefficients(N, lag, terms)[::-1]

        def phi(x):
            x = np.asarray(x, dtype=float)
            if lag == 0:
                closed = 0.5 * (1.0 - np.sin(N * x) / (N * x))
            else:
                closed = (2.0 * np.sin(lag * x) - np.sin((lag + 1) * x) - np.sin((lag - 1) * x)) / (N * x)
            return np.where(x < _SERIES_BELOW, np.polyval(series, x * x), closed)

        return phi

    return tuple(make(lag) for lag in range(lags + 1))


def _taylor_row(samples: int, lags: int, m: int) -> tuple:
    """Row and right side of ``Σ_l k_l R_l^{(2m+1)} = E^{(2m+1)}`` (the x^{2m} coefficient of D vanishes)."""
    n = 2 * m + 1
    row = [Fraction((-1) ** m * (2 * lag**n - (lag + 1) ** n - (lag - 1) ** n), math.factorial(n)) for lag in range(1, lags + 1)]
    rhs = Fraction(-((-1) ** m) * samples**n, 2 * math.factorial(n))
    return [float(v) for v in row], float(rhs)


@dataclass(frozen=True, eq=False)
class TunedAlgorithm:
    """An algorithm tuned to an environment.

    Attributes
    ----------
    algorithm : Algorithm
        The tuned algorithm (lag sums on the pairs (N − l, N)).
    quantity : str
        ``"coning"`` or ``"sculling"``.
    lag_sums : tuple of float
        k_l, l = 1 … L.
    nulled : bool
        The environment's drift is nulled (else minimised).
    conditions : int
        Independent drift directions imposed [count].
    taylor_conditions : int
        Low-frequency conditions imposed with the remaining degrees of freedom [count].
    drift : ndarray (3,)
        Drift (coning, rad/s) or rectification error (sculling, m/s²) of the
        tuned algorithm in the environment (closed form).
    classical : Algorithm
        The classical algorithm of the same form (optimal coning, same N and history).
    classical_drift : ndarray (3,)
        Its drift or rectification error in the environment.
    sample_interval : float
        h [s] it was tuned at.
    condition_number : float
        2-norm condition number of the system solved for the lag sums (row-normalised):
        the coefficients lose up to about ``log10(condition_number)`` of float64's
        16 significant digits to round-off.
    """

    algorithm: Algorithm
    quantity: str
    lag_sums: tuple
    nulled: bool
    conditions: int
    taylor_conditions: int
    drift: np.ndarray
    classical: Algorithm
    classical_drift: np.ndarray
    sample_interval: float
    condition_number: float = 1.0

    @property
    def well_conditioned(self) -> bool:
        """Whether the coefficients keep at least half of float64's digits (:data:`CONDITION_LIMIT`)."""
        return bool(self.condition_number <= CONDITION_LIMIT)

    @property
    def coefficients(self) -> dict:
        """``{"i,j": coefficient}`` in the algorithm-file key syntax."""
        return {f"{i},{j}": float(c) for (i, j), c in self.algorithm.pairwise.items()}

    def toml(self) -> str:
        """The tuned algorithm as an algorithm file (``docs/algorithm-files.md``).

        Returns
        -------
        str
        """
        alg = self.algorithm
        keeps = self.taylor_conditions > 0
        lines = [
            f"# Tuned to an environment ({self.quantity}) at h = {self.sample_interval!r} s.",
            "# It keeps the second-order condition." if keeps else "# It trades the second-order condition for the environment:",
        ]
        if not keeps:
            lines.append("# load it with allow_inconsistent=True (--allow-inconsistent).")
        lines += [
            f'name = "{alg.name}"',
            f"samples = {alg.samples}",
            f'description = "{alg.description}"',
            f'reference = "{alg.reference}"',
            "[cross]",
        ]
        for (i, j), c in alg.pairwise.items():
            lines.append(f'"{i},{j}" = "{_decimal(c)}"')
        return "\n".join(lines) + "\n"


def _decimal(c: Fraction) -> str:
    text = repr(float(c))
    return text if Fraction(text) == c else f"{c.numerator}/{c.denominator}"


def _environment_model(environment: Environment, samples: int, history: int, sample_interval: float, quantity: str):
    L = samples + history - 1
    r = response_integrals(environment, sample_interval, lag_functions(samples, L))
    col = 0 if quantity == "coning" else 1
    sensor = (r.true[:, col] - r.sensed[:, col]).sum(axis=0)
    c = sensor + r.algorithm[0, :, col].sum(axis=0)
    M = np.stack([r.algorithm[lag, :, col].sum(axis=0) for lag in range(1, L + 1)], axis=1) if L else np.zeros((3, 0))
    return c, M


def solve_lag_sums(c: np.ndarray, M: np.ndarray, samples: int, history: int, *, quantity: str = "coning") -> tuple:
    """Lag sums that null ``c − M k`` where the degrees of freedom allow, else minimise it (module docstring).

    Parameters
    ----------
    c : ndarray (3,)
        Drift of the algorithm with no pairwise terms, sensor part included.
    M : ndarray (3, L)
        Drift removed per unit lag sum.
    samples, history : int
        N and the samples of earlier steps (L = N + history − 1).
    quantity : str, keyword-only
        For the message only.

    Returns
    -------
    tuple
        ``(k, nulled, conditions, taylor_conditions, condition_number)``: the
        last is the 2-norm condition number of the (row-normalised) system
        solved, which bounds how many of float64's 16 digits ``k`` loses.

    Raises
    ------
    ValueError
        When there is nothing to tune to (c and M zero).
    """
    L = samples + history - 1
    augmented = np.concatenate([M, c[:, None]], axis=1)
    scale = float(np.max(np.abs(augmented))) if augmented.size else 0.0
    if scale == 0.0:
        raise ValueError(f"Expected an environment with {quantity} to tune to, got none (no {quantity} vector in any line or spectrum)")
    u, s, _ = np.linalg.svd(augmented)
    directions = u[:, : s.size][:, s > 1e-12 * s[0]]
    r = directions.shape[1]
    A_env = directions.T @ M
    b_env = directions.T @ c
    if r <= L:
        rows, rhs = [a / np.linalg.norm(a) for a in A_env], [b / np.linalg.norm(a) for a, b in zip(A_env, b_env)]
        for m in range(1, L - r + 1):
            row, value = _taylor_row(samples, L, m)
            norm = math.sqrt(sum(v * v for v in row))
            rows.append(np.array(row) / norm)
            rhs.append(value / norm)
        system = np.array(rows)
        return np.linalg.solve(system, np.array(rhs)), True, r, L - r, float(np.linalg.cond(system))
    return np.linalg.lstsq(A_env, b_env, rcond=None)[0], False, r, 0, float(np.linalg.cond(A_env))


def tune(environment: Environment, samples: int, sample_interval: float, *, history: int = 0, quantity: str = "coning", name: str | None = None) -> TunedAlgorithm:
    """Tune an N-sample algorithm to ``environment`` (module docstring).

    Parameters
    ----------
    environment : Environment
        Lines, spectra and sensors.
    samples : int
        N, 1 … 8.
    sample_interval : float
        Algorithm sample interval h [s], > 0.
    history : int, keyword-only
        Samples of earlier steps the algorithm may read, 0 … 8; N + history ≥ 2.
    quantity : str, keyword-only
        ``"coning"`` (the attitude drift) or ``"sculling"`` (the rectification
        error of the dual extension, the velocity algorithm).
    name : str, keyword-only
        Name of the tuned algorithm (default ``tuned-<quantity>-N[+K]``).

    Returns
    -------
    TunedAlgorithm

    Raises
    ------
    ValueError
        Bad N, history, h or quantity; an environment with nothing to tune to.

    References
    ----------
    Ignagni (1990); Mark & Tazartes (1996).

    Examples
    --------
    >>> env = Environment((coning_line(10.0, math.radians(1.0)),))
    >>> t = tune(env, 2, 1e-3)
    >>> round(t.lag_sums[0], 8)                    # → 2/3 as ωh → 0
    0.66679833
    """
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    N = as_int(samples, "samples", minimum=1)
    K = as_int(history, "history", minimum=0)
    if N + K < 2:
        raise ValueError(f"Expected samples + history >= 2 (one lag sum at least), got {N} and {K}")
    if N > MAX_SAMPLES or K > MAX_SAMPLES:
        raise ValueError(f"Expected `samples` and `history` at most {MAX_SAMPLES} each, got {N} and {K}")
    if quantity not in QUANTITIES:
        raise ValueError(f"Expected `quantity` among {', '.join(QUANTITIES)}, got {quantity!r}")
    h = positive(sample_interval, "sample_interval")
    c, M = _environment_model(environment, N, K, h, quantity)
    k, nulled, r, taylor, condition = solve_lag_sums(c, M, N, K, quantity=quantity)
    suffix = f"{N}" if K == 0 else f"{N}+{K}"
    terms = tuple(Term(Fraction(repr(float(v))), (N - lag, N)) for lag, v in enumerate(k, start=1) if v != 0.0)
    alg = Algorithm(name or f"tuned-{quantity}-{suffix}", N, terms, f"{N}-sample algorithm tuned to {environment.name} ({quantity}, h = {h:g} s)", "tuned by strapdown-analysis")
    classical = optimal_coning_algorithm(N, history=K)
    d_c = environment_drift(classical, environment, h)
    lag_sums = tuple(float(Fraction(repr(float(v)))) for v in k)
    drift = c - M @ np.array(lag_sums)
    return TunedAlgorithm(alg, quantity, lag_sums, nulled, r, taylor, drift, classical, d_c.total_vector if quantity == "coning" else d_c.sculling_vector, h, condition)


def tuned_drift(environment: Environment, samples: int, sample_interval: float, lag_sums, *, history: int = 0, quantity: str = "coning") -> np.ndarray:
    """Drift (or rectification error) vector of the pairwise algorithm with ``lag_sums`` in ``environment``.

    The linear model of the module docstring, ``c − M k``: the same value as
    :func:`strapdown.analysis.vibration.drift.environment_drift` for
    that algorithm, without deriving its closed form symbolically (cheap for
    many coefficient sets).

    Parameters
    ----------
    environment : Environment
        Lines, spectra, sensors.
    samples : int
        N.
    sample_interval : float
        h [s].
    lag_sums : sequence of float
        k_l, l = 1 … N + history − 1.
    history : int, keyword-only
        Samples of earlier steps.
    quantity : str, keyword-only
        ``"coning"`` [rad/s] or ``"sculling"`` [m/s²].

    Returns
    -------
    ndarray (3,)
    """
    N = as_int(samples, "samples", minimum=1)
    K = as_int(history, "history", minimum=0)
    if quantity not in QUANTITIES:
        raise ValueError(f"Expected `quantity` among {', '.join(QUANTITIES)}, got {quantity!r}")
    k = np.asarray(lag_sums, dtype=float).ravel()
    if k.size != N + K - 1:
        raise ValueError(f"Expected {N + K - 1} lag sums, got {k.size}")
    c, M = _environment_model(environment, N, K, positive(sample_interval, "sample_interval"), quantity)
    return c - M @ k


@dataclass(frozen=True, eq=False)
class BandDrift:
    """Drift of algorithms against the frequency of one coning line, through an environment's sensors.

    Attributes
    ----------
    frequency : ndarray (F,)
        Line frequencies [Hz].
    half_angle : float
        Half-cone angle α of the line [rad].
    names : tuple of str
        Algorithm names.
    total : ndarray (A, F)
        Signed drift along the cone axis, sensor part included [rad/s].
    sensor : ndarray (F,)
        The sensor part alone (the same for every algorithm) [rad/s].
    """

    frequency: np.ndarray
    half_angle: float
    names: tuple
    total: np.ndarray
    sensor: np.ndarray


def drift_across_band(algorithms, environment: Environment, sample_interval: float, frequency, *, half_angle: float) -> BandDrift:
    """Drift of each algorithm for one classical coning line swept across ``frequency``.

    Parameters
    ----------
    algorithms : sequence of Algorithm
        The algorithms.
    environment : Environment
        Supplies the sensors (its lines and spectra are not used).
    sample_interval : float
        h [s].
    frequency : array_like
        Line frequencies [Hz], > 0.
    half_angle : float, keyword-only
        α [rad].

    Returns
    -------
    BandDrift

    Raises
    ------
    ValueError
        An empty or non-positive ``frequency``.
    """
    f = as_array(frequency, "frequency", nonempty=True).ravel()
    if np.any(f <= 0):
        raise ValueError("Expected `frequency` > 0")
    lines = tuple(coning_line(v, half_angle) for v in f)
    env = Environment(lines, (), environment.gyro, environment.accelerometer, environment.name)
    totals, sensor = [], None
    for a in algorithms:
        d = environment_drift(a, env, sample_interval)
        totals.append([p.total @ d.coning_axis for p in d.parts])
        sensor = np.array([p.sensor @ d.coning_axis for p in d.parts])
    return BandDrift(f, float(half_angle), tuple(a.name for a in algorithms), np.array(totals), sensor)
