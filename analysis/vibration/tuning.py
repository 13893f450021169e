"""Coning and sculling algorithms tuned to a vibration environment.

The mean drift of an N-sample algorithm (``history`` samples of earlier
steps) in an environment is affine in its lag sums ``k_l``, l = 1 … L,
``L = N + history − 1`` (:mod:`strapdown.analysis.vibration.drift`):

    u(k) = u_sensor + ∫ q̃ [φ₀(ωh) − Σ_l k_l φ_l(ωh)] / ω  (+ aliasing pairs)  =  c − M k,

``φ₀(x) = E(Nx)/(Nx)``, ``φ_l(x) = R_l(x)/(Nx)``, the sensors included (q̃
is what they pass; the sensor part is in c).  Pairs of lines that alias with
the step rate (:mod:`strapdown.analysis.vibration.aliasing`) add a drift that
depends on where each coefficient sits, not only on the lag sums; with the
lag sum k_l on the pair (N − l, N) it is affine in k as well, and enters c and
M.  The same holds for the
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
   classical_algorithm
   NothingToTune
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
from ...derivations.coning.drift import lag_sums
from ...derivations.coning.registry import get, names
from ..coning.drift_theory import coning_drift_function, optimal_coning_algorithm
from ..core.validation import as_array, as_int, positive
from .aliasing import alias_response
from .drift import environment_drift, response_integrals
from .environment import Environment, coning_line

__all__ = ["NothingToTune", "TunedAlgorithm", "tune", "classical_algorithm", "tuned_drift", "solve_lag_sums", "lag_functions", "drift_across_band", "BandDrift", "QUANTITIES", "CONDITION_LIMIT"]

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
        The classical algorithm of the same N and history (optimal coning lag
        sums; :func:`classical_algorithm`).
    classical_drift : ndarray (3,)
        Its drift or rectification error in the environment.
    sample_interval : float
        h [s] it was tuned at.
    classical_in_registry : bool
        ``classical`` is a registry algorithm (its name is a registry name).
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
    classical_in_registry: bool = True
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
    # pairs of lines that alias with the step rate: affine in the coefficients of the pairs (N − l, N)
    alias = alias_response(environment, sample_interval, samples, [(samples - lag, samples) for lag in range(1, L + 1)])
    return c + alias.base[col], M - alias.per_pair[col]


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
    NothingToTune
        When there is nothing to tune to (c and M zero), a ValueError.
    ValueError
        A model that is not finite.
    """
    L = samples + history - 1
    augmented = np.concatenate([M, c[:, None]], axis=1)
    if not np.all(np.isfinite(augmented)):
        raise ValueError(f"Expected a finite drift model to tune to, got {augmented.tolist()}")
    scale = float(np.max(np.abs(augmented))) if augmented.size else 0.0
    if scale == 0.0:
        raise NothingToTune(f"Expected an environment with {quantity} to tune to, got none (no {quantity} vector in any line or spectrum)")
    u, s, _ = np.linalg.svd(augmented)
    directions = u[:, : s.size][:, s > 1e-12 * s[0]]
    A_env = directions.T @ M
    b_env = directions.T @ c
    # A direction the lag sums do not reach (the algorithm's responses vanish there, e.g. a line at the
    # sample rate) cannot be nulled: it is left out of the conditions, and the drift is minimised, not nulled.
    reach = np.linalg.norm(A_env, axis=1) > 1e-12 * scale
    unreachable = bool(np.any(~reach & (np.abs(b_env) > 1e-12 * scale)))
    A_env, b_env = A_env[reach], b_env[reach]
    r = A_env.shape[0]
    if r == 0:
        rows, rhs = zip(*(_taylor_row(samples, L, m) for m in range(1, L + 1)))
        return _taylor_solution(samples, L), False, 0, L, float(np.linalg.cond(np.array(rows, dtype=float)))
    if r <= L:
        rows, rhs = [a / np.linalg.norm(a) for a in A_env], [b / np.linalg.norm(a) for a, b in zip(A_env, b_env)]
        for m in range(1, L - r + 1):
            row, value = _taylor_row(samples, L, m)
            norm = math.sqrt(sum(v * v for v in row))
            rows.append(np.array(row) / norm)
            rhs.append(value / norm)
        system = np.array(rows)
        return np.linalg.solve(system, np.array(rhs)), not unreachable, r, L - r, float(np.linalg.cond(system))
    return np.linalg.lstsq(A_env, b_env, rcond=None)[0], False, r, 0, float(np.linalg.cond(A_env))


def _taylor_solution(samples: int, lags: int) -> np.ndarray:
    """Lag sums of the classical form: the first ``lags`` low-frequency conditions (:func:`_taylor_row`)."""
    rows, rhs = zip(*(_taylor_row(samples, lags, m) for m in range(1, lags + 1)))
    return np.linalg.solve(np.array(rows), np.array(rhs))


class NothingToTune(ValueError):
    """The environment has none of the quantity (coning or sculling) that a tuning would null."""


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
    classical, in_registry = classical_algorithm(N, K)
    d_c = environment_drift(classical, environment, h)
    sums = tuple(float(Fraction(repr(float(v)))) for v in k)
    drift = c - M @ np.array(sums)
    return TunedAlgorithm(alg, quantity, sums, nulled, r, taylor, drift, classical, d_c.total_vector if quantity == "coning" else d_c.sculling_vector, h, in_registry, condition)


def classical_algorithm(samples: int, history: int = 0) -> tuple:
    """The classical algorithm a tuned one is compared with: optimal coning lag sums, from the registry where it has them.

    A registry algorithm with the lag sums of
    :func:`strapdown.derivations.coning.drift.optimal_coning_algorithm` (the
    same drift under any single line) is preferred, first one whose pairwise
    coefficients are those of Ignagni's form (the tuned algorithm's form:
    ``two-sample`` for N = 2, ``compressed-3`` for N = 3), then any with the
    same lag sums; without one, the generated algorithm, which no registry name
    reaches.

    Parameters
    ----------
    samples : int
        N [count].
    history : int, optional
        Samples of earlier steps [count].

    Returns
    -------
    tuple
        ``(Algorithm, in_registry)``.

    Examples
    --------
    >>> [classical_algorithm(n)[0].name for n in (2, 3)]
    ['two-sample', 'compressed-3']
    >>> classical_algorithm(7)[1]      # no seven-sample algorithm in the registry
    False
    """
    generated = optimal_coning_algorithm(samples, history=history)
    target = lag_sums(generated)
    same_sums = []
    for name in names(library=True):
        a = get(name)
        if a.samples != samples or a.history != history or any(t.dots or not isinstance(t.cross[1], int) or not isinstance(t.cross[0], int) for t in a.terms):
            continue
        if a.pairwise == generated.pairwise:
            return a, True
        if lag_sums(a) == target:
            same_sums.append(a)
    if same_sums:
        return same_sums[0], True
    return generated, False


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
        Half-cone angle α of the line [rad] (NaN: a fixed rate amplitude instead).
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


def drift_across_band(algorithms, environment: Environment, sample_interval: float, frequency, *, half_angle: float | None = None,
                      rate_amplitude: float | None = None) -> BandDrift:  # fmt: skip
    """Drift of each algorithm for one classical coning line swept across ``frequency``.

    The line has either one half-cone angle α at every frequency, or one rate
    amplitude Ω (then ``α = asin(Ω/ω)``, the same angular-rate vibration at
    every frequency: a fixed α is a rate ``αω`` that grows with frequency, 63
    deg/s at 10 Hz for α = 1°).

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
        α [rad] (or give ``rate_amplitude``).
    rate_amplitude : float, keyword-only
        Ω [rad/s], below 2π times the lowest frequency (or give ``half_angle``).

    Returns
    -------
    BandDrift
        Its ``half_angle`` is NaN for a rate amplitude.

    Raises
    ------
    ValueError
        An empty or non-positive ``frequency``.
    TypeError
        An element of ``algorithms`` that is not an :class:`~strapdown.derivations.coning.algorithms.Algorithm`.
    """
    f = as_array(frequency, "frequency", nonempty=True).ravel()
    if np.any(f <= 0):
        raise ValueError("Expected `frequency` > 0")
    if (half_angle is None) == (rate_amplitude is None):
        raise ValueError("Expected exactly one of `half_angle` and `rate_amplitude`, got " + ("both" if half_angle is not None else "neither"))
    if rate_amplitude is not None:
        rate = positive(rate_amplitude, "rate_amplitude")
        if rate >= 2.0 * math.pi * f.min():
            raise ValueError(f"Expected `rate_amplitude` below 2π × the lowest frequency ({2.0 * math.pi * f.min():.6g} rad/s), got {rate:g}")
        lines = tuple(coning_line(v, math.asin(rate / (2.0 * math.pi * v))) for v in f)
        half_angle = math.nan
    else:
        lines = tuple(coning_line(v, half_angle) for v in f)
    env = Environment(lines, (), environment.gyro, environment.accelerometer, environment.name)
    algorithms = tuple(algorithms)
    for a in algorithms:
        if not isinstance(a, Algorithm):
            raise TypeError(f"Expected `algorithms` of Algorithm, got a {type(a).__name__}")
    if algorithms and env.has_motion:
        # Each line is read alone, so the pairs of lines that alias with the step rate (which
        # environment_drift also lists) are not needed: one pass of the response integrals, the
        # algorithms' drift functions side by side, gives every part.
        r = response_integrals(env, sample_interval, [coning_drift_function(a) for a in algorithms])
        primary = r.true[:, 0].sum(axis=0)
        norm = float(np.linalg.norm(primary))
        if norm > 0.0:  # the cone axis of environment_drift (its fallback, the total, is never needed for coning lines)
            axis = primary / norm
            parts = [i for i, part in enumerate(r.parts) if part[0] == "line"]
            sensor = np.array([(r.true[i, 0] - r.sensed[i, 0]) @ axis for i in parts])
            totals = [[((r.true[i, 0] - r.sensed[i, 0]) + r.algorithm[j, i, 0]) @ axis for i in parts] for j in range(len(algorithms))]
            return BandDrift(f, float(half_angle), tuple(a.name for a in algorithms), np.array(totals), sensor)
    totals, sensor = [], None
    for a in algorithms:
        d = environment_drift(a, env, sample_interval)
        own = [p for p in d.parts if p.kind == "line"]  # each line alone: the swept lines are not one flight's lines
        totals.append([p.total @ d.coning_axis for p in own])
        sensor = np.array([p.sensor @ d.coning_axis for p in own])
    return BandDrift(f, float(half_angle), tuple(a.name for a in algorithms), np.array(totals), sensor)
