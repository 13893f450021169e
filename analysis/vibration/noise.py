"""Sensor noise and quantization through the algorithm's correction terms: the mean drift and the random walk they add.

A gyro increment is the vibration's sensed increment plus noise,
``p_i = s_i + n_i``.  The algorithm adds ``Σ c_ij p_i × p_j`` to the sum of
the increments; besides the vibration's own products (the coning correction,
whose mean residual :mod:`strapdown.analysis.vibration.drift` gives) it forms

    δC = Σ_ij c_ij (s_i × n_j + n_i × s_j + n_i × n_j),

the noise passed through the correction terms: the difference between the
algorithm run on the noisy increments and on the clean ones, less the noise
itself (``Σ n_i``, the angle random walk that every algorithm integrates
alike, which is not a product).

Noise model
-----------
``n_i`` is white: independent between samples, zero mean, the same variance
``σ²`` on each axis and independent between axes, and independent of the
motion.  Angle random walk N [rad/√s] gives ``σ² = N² h``; quantization of the
increments to a quantum q, with the rounding error uniform and independent
of the signal (a motion spanning many quanta), adds ``q²/12``.  (A sensor
that quantizes its integrated angle and carries the remainder makes the error
increments differences of the remainders, correlated between neighbouring
samples: not this model.)

Mean (derivation)
-----------------
``E[s_i × n_j] = E[s_i] × E[n_j] = 0`` (independence, zero mean), and
``E[n_i × n_j]_a = ε_abc E[n_ib n_jc] = ε_abc σ² δ_ij δ_bc = 0`` (``ε_abb = 0``;
``n_i × n_i = 0`` anyway).  So the noise adds **no mean drift** through the
correction terms under this model; it would take noise correlated between
axes with an antisymmetric lag structure (``E[n_ib n_jc] ≠ E[n_ic n_jb]``).

Random walk (derivation)
------------------------
Collect the terms that hold one sample m: with the pairs ``(i, j)`` of the
algorithm and sample m at index ``r − dN`` of the step d steps after its own
(r its position in its step, d ≥ 0 while the index is one the algorithm
reads),

    δC summed over the steps = Σ_m G_m × n_m + Σ_pairs c_ij n_i × n_j,
    G_m = Σ_{j = r − dN} c_ij s_{m − (j − i)} − Σ_{i = r − dN} c_ij s_{m + (j − i)}.

The two sums are uncorrelated (odd and even in n).  For the first, with
``E[(g × n)(g × n)ᵀ] = σ² (|g|² I − g gᵀ)`` and independent samples, the
variance grows by ``σ² (tr M I − M)`` per sample, ``M = E[G_m G_mᵀ]``.  A line
``s_m = Re(S e^{iωmh})`` with ``S = Θ̃ (1 − e^{−iωh})`` (Θ̃ the sensed angle
amplitude) gives ``G_m = Re(γ_r(ω) S e^{iωmh})`` with

    γ_r(ω) = Σ_{j = r − dN} c_ij e^{−iω(j − i)h} − Σ_{i = r − dN} c_ij e^{iω(j − i)h},

so that, averaged over the positions r and the time,
``M = ⟨|γ_r|²⟩_r |1 − e^{−iωh}|²/ω² Re P̃`` with ``P̃ = conj(H)Hᵀ ⊙ P`` the
sensed cross-power of the rate (``P = ½ conj(A) Aᵀ`` of a line; ``G(f) df``
of a spectrum band, integrated; lines of different frequencies add, their
cross terms averaging out).  For the second sum, each distinct pair of samples
(a cross-step pair that recurs as another pair of a later step is counted
once, with the coefficients summed) adds ``E[(a × b)(a × b)ᵀ] = 2σ⁴ I`` times
its coefficient squared per step.  The random walk of the error is then

    Q = (σ²/h)(tr M I − M) + (2σ⁴/H) Σ c̃² I          [rad²/s],

the variance of each component of the accumulated error growing as
``Q_aa t``; its equivalent random-walk coefficient ``√(tr Q / 3)`` [rad/√s]
compares with the sensor's own N.

Against the coning residual
---------------------------
Over a time T the algorithm's mean residual (its part of the environment
drift) accumulates ``|u| T``, the products' random walk ``√(tr Q T)`` (1σ of
the error's length).  Where the random walk is the larger, a higher-order
algorithm, which lowers ``|u|``, buys nothing the noise does not already
hide: :attr:`NoiseThroughAlgorithm.products_dominate`, and
:attr:`NoiseThroughAlgorithm.crossover_time` ``T* = tr Q / |u|²`` (below it the
noise products dominate).

Public API
----------
.. autosummary::

   SensorNoise
   NoiseThroughAlgorithm
   noise_through_algorithm
   NoiseMonteCarlo
   noise_monte_carlo

References
----------
Savage (1998), part 1 (the coning correction terms); IEEE Std 952-1997
(angle random walk, quantization noise q²/12 of the angle increments).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..coning.evaluation import increment
from ..coning.simulator import step_windows
from ..core import budget
from ..core.validation import as_int, nonnegative, positive
from .drift import environment_drift
from .environment import Environment

__all__ = ["SensorNoise", "NoiseThroughAlgorithm", "noise_through_algorithm", "NoiseMonteCarlo", "noise_monte_carlo"]


@dataclass(frozen=True)
class SensorNoise:
    """White noise of the gyro increments: angle random walk and quantization.

    Attributes
    ----------
    angle_random_walk : float
        N [rad/√s], ≥ 0.
    quantization : float
        Quantum q of the increments [rad], ≥ 0 (uniform rounding error, variance q²/12).
    """

    angle_random_walk: float = 0.0
    quantization: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "angle_random_walk", nonnegative(self.angle_random_walk, "angle_random_walk"))
        object.__setattr__(self, "quantization", nonnegative(self.quantization, "quantization"))

    def variance(self, sample_interval: float) -> float:
        """σ² = N² h + q²/12 per axis and sample [rad²].

        Parameters
        ----------
        sample_interval : float
            h [s], > 0.

        Returns
        -------
        float
        """
        return self.angle_random_walk**2 * positive(sample_interval, "sample_interval") + self.quantization**2 / 12.0


@dataclass(frozen=True, eq=False)
class NoiseThroughAlgorithm:
    """The noise passed through an algorithm's correction terms, beside the environment's coning residual.

    Attributes
    ----------
    algorithm : str
        Name.
    sample_interval : float
        h [s].
    variance : float
        σ² per axis and sample [rad²].
    mean : ndarray (3,)
        Mean drift the products add [rad/s] (zero under the white-noise model; module docstring).
    random_walk : ndarray (3, 3)
        Q [rad²/s]: vibration × noise plus noise × noise.
    vibration_noise : ndarray (3, 3)
        Its vibration × noise part [rad²/s].
    noise_noise : ndarray (3, 3)
        Its noise × noise part [rad²/s].
    residual : ndarray (3,)
        The algorithm part of the environment's coning drift [rad/s] (body axes).
    angle_random_walk : float
        The sensor's own N [rad/√s], for scale.
    """

    algorithm: str
    sample_interval: float
    variance: float
    mean: np.ndarray
    random_walk: np.ndarray
    vibration_noise: np.ndarray
    noise_noise: np.ndarray
    residual: np.ndarray
    angle_random_walk: float

    @property
    def equivalent_random_walk(self) -> float:
        """``√(tr Q / 3)`` [rad/√s]: the products' random walk per axis."""
        return math.sqrt(max(0.0, float(np.trace(self.random_walk))) / 3.0)

    @property
    def crossover_time(self) -> float:
        """``T* = tr Q / |u|²`` [s]: below it the products' random walk exceeds the accumulated residual (inf: no residual)."""
        u2 = float(self.residual @ self.residual)
        return math.inf if u2 == 0.0 else float(np.trace(self.random_walk)) / u2

    def products_dominate(self, duration: float) -> bool:
        """Whether over ``duration`` the products' random walk (1σ) exceeds the accumulated residual ``|u| T``.

        Parameters
        ----------
        duration : float
            T [s], > 0.

        Returns
        -------
        bool
        """
        return positive(duration, "duration") < self.crossover_time


def _pair_groups(algorithm: Algorithm) -> dict:
    """Pairwise coefficients with the pairs that recur in later steps merged: ``{(i, j) with i in 1 − N … 0 shifted: c̃}``."""
    N = algorithm.samples
    out: dict = {}
    for (i, j), c in algorithm.pairwise.items():
        d = (N - j) // N  # shift so that j lies in the current step (1 … N)
        key = (i + d * N, j + d * N)
        out[key] = out.get(key, 0.0) + float(c)
    return out


def _gamma2(algorithm: Algorithm, omega: np.ndarray, h: float) -> np.ndarray:
    """``⟨|γ_r(ω)|²⟩_r`` over the positions r = 1 … N (module docstring)."""
    N = algorithm.samples
    pairs = [(i, j, float(c)) for (i, j), c in algorithm.pairwise.items()]
    total = np.zeros_like(omega)
    for r in range(1, N + 1):
        g = np.zeros(omega.shape, dtype=complex)
        for i, j, c in pairs:
            if (r - j) % N == 0 and j <= r:
                g += c * np.exp(-1j * omega * (j - i) * h)
            if (r - i) % N == 0 and i <= r:
                g -= c * np.exp(1j * omega * (j - i) * h)
        total += np.abs(g) ** 2
    return total / N


def _rate_moment(algorithm: Algorithm, environment: Environment, h: float) -> np.ndarray:
    """``M = E[G Gᵀ]`` (3, 3) [rad²] over the lines and spectra (module docstring)."""
    M = np.zeros((3, 3))

    def weight(omega):
        return _gamma2(algorithm, omega, h) * np.abs(1.0 - np.exp(-1j * omega * h)) ** 2 / omega**2

    def sensed(power, omega):
        r = environment.gyro.response(omega, h)
        return np.real(np.conj(r)[..., :, None] * r[..., None, :] * power[..., :3, :3])

    for ln in environment.lines:
        w = np.array([ln.omega])
        M += float(weight(w)[0]) * sensed(ln.power[None], w)[0]
    for sp in environment.spectra:
        u = np.log(sp.frequency)
        x, wq = np.polynomial.legendre.leggauss(8)
        sub = np.linspace(u[0], u[-1], max(64, 8 * u.size))
        edges = np.union1d(u, sub)
        lo, hi = edges[:-1], edges[1:]
        nodes = (0.5 * (lo + hi))[:, None] + (0.5 * (hi - lo))[:, None] * x[None, :]
        f = np.exp(nodes.ravel())
        om = 2.0 * math.pi * f
        vals = weight(om)[:, None, None] * sensed(sp.at(f), om) * f[:, None, None]
        M += np.einsum("n,nab->ab", (0.5 * (hi - lo))[:, None].repeat(8, 1).ravel() * np.tile(wq, lo.size), vals)
    return M


def noise_through_algorithm(algorithm: Algorithm, environment: Environment, sample_interval: float, noise: SensorNoise) -> NoiseThroughAlgorithm:
    """Mean and random walk that the noise adds through the correction terms, beside the coning residual (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (its pairwise terms; nested and dot terms add products of third order).
    environment : Environment
        Lines, spectra and the gyro (its filters shape the vibration's increments; the noise is added after them).
    sample_interval : float
        h [s], > 0.
    noise : SensorNoise
        Angle random walk and quantization of the increments.

    Returns
    -------
    NoiseThroughAlgorithm

    Raises
    ------
    TypeError
        Wrong argument types.
    ValueError
        A non-positive ``sample_interval``, an environment without motion.

    References
    ----------
    Savage (1998), part 1; IEEE Std 952-1997.
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not isinstance(noise, SensorNoise):
        raise TypeError(f"Expected `noise` to be a SensorNoise, got {type(noise).__name__}")
    h = positive(sample_interval, "sample_interval")
    d = environment_drift(algorithm, environment, h)
    s2 = noise.variance(h)
    M = _rate_moment(algorithm, environment, h)
    qa = (s2 / h) * (np.trace(M) * np.eye(3) - M)
    qb = (2.0 * s2**2 / (algorithm.samples * h)) * sum(c * c for c in _pair_groups(algorithm).values()) * np.eye(3)
    return NoiseThroughAlgorithm(algorithm.name, h, s2, np.zeros(3), qa + qb, qa, qb, d.algorithm_vector, noise.angle_random_walk)


@dataclass(frozen=True, eq=False)
class NoiseMonteCarlo:
    """Monte Carlo of the noise passed through the correction terms.

    Attributes
    ----------
    mean : ndarray (3,)
        Mean drift of the products [rad/s].
    mean_standard_error : ndarray (3,)
        Its standard error [rad/s].
    random_walk_trace : float
        Estimate of ``tr Q`` [rad²/s].
    random_walk_trace_standard_error : float
        Its standard error [rad²/s].
    realisations : int
        [count].
    duration : float
        Time per realisation [s].
    """

    mean: np.ndarray
    mean_standard_error: np.ndarray
    random_walk_trace: float
    random_walk_trace_standard_error: float
    realisations: int
    duration: float


def noise_monte_carlo(algorithm: Algorithm, environment: Environment, sample_interval: float, noise: SensorNoise, *, realisations: int, steps: int,
                      rng=None, limits: budget.Limits | None = None) -> NoiseMonteCarlo:  # fmt: skip
    """Run ``algorithm`` on noisy and clean increments of the environment's lines and measure what the products add.

    Each realisation draws a uniform random phase per line (lines of one
    frequency share it) and white Gaussian noise of variance σ² per axis and
    sample (:meth:`SensorNoise.variance`); the sensed increments are exact
    (``Re(H A e^{iωt})`` integrated over each sample, the gyro's responses
    applied per line).  The algorithm's step increments on ``s + n`` less
    those on ``s`` less ``Σ n`` are summed over ``steps`` steps: their mean
    over the realisations, divided by the time, is the mean drift, and the
    variance of the sums (trace), divided by the time, the random walk.
    Nothing is taken from the closed form.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    environment : Environment
        Lines (spectra are not drawn here) and the gyro.
    sample_interval : float
        h [s], > 0.
    noise : SensorNoise
        The noise.
    realisations : int, keyword-only
        [count], ≥ 2.
    steps : int, keyword-only
        Steps per realisation [count], ≥ 1.
    rng : numpy.random.Generator, int or None, keyword-only
        Seed or generator; each realisation gets its own spawned stream.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time; beyond them
        :class:`~strapdown.analysis.core.budget.BudgetExceeded` names ``realisations``.

    Returns
    -------
    NoiseMonteCarlo

    Raises
    ------
    ValueError
        An environment with spectra or without lines, bad sizes, or a run beyond ``limits``.
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    if environment.spectra or not environment.lines:
        raise ValueError(f"Expected an environment of lines only, got {len(environment.lines)} lines and {len(environment.spectra)} spectra")
    h = positive(sample_interval, "sample_interval")
    R = as_int(realisations, "realisations", minimum=2)
    K = as_int(steps, "steps", minimum=1)
    N, W = algorithm.samples, algorithm.window
    n_samples = algorithm.history + K * N
    what = f"`realisations` = {R} runs of {K} steps ({n_samples} samples each)"
    budget.check(budget.ARRAY_ELEMENT.estimate(float(R) * n_samples * 3 * (10 + 2 * W), what=what), limits)
    seed = rng if isinstance(rng, np.random.SeedSequence) else np.random.SeedSequence(rng.integers(2**63) if isinstance(rng, np.random.Generator) else rng)
    streams = [np.random.default_rng(c) for c in seed.spawn(R)]
    groups: dict = {}
    for ln in environment.lines:
        groups.setdefault(ln.frequency, []).append(ln)
    freq = np.array(list(groups))
    omega = 2.0 * math.pi * freq
    amp = np.stack([sum(ln.amplitude for ln in g)[:3] for g in groups.values()]) * environment.gyro.response(omega, h)
    theta = amp / (1j * omega[:, None])
    t = (np.arange(n_samples + 1) - algorithm.history) * h
    sigma = math.sqrt(noise.variance(h))
    totals = np.empty((R, 3))
    for k, g in enumerate(streams):
        phase = np.exp(1j * g.uniform(0.0, 2.0 * math.pi, size=freq.size))
        angle = np.real(np.exp(1j * omega[None, :] * t[:, None]) @ (theta * phase[:, None]))  # (samples + 1, 3)
        s = np.diff(angle, axis=0)
        n = sigma * g.standard_normal(s.shape)
        clean = increment(algorithm, step_windows(s, N, algorithm.history))
        noisy = increment(algorithm, step_windows(s + n, N, algorithm.history))
        totals[k] = (noisy - clean).sum(axis=0) - n[algorithm.history :].sum(axis=0)
    T = K * N * h
    mean = totals.mean(axis=0) / T
    se = totals.std(axis=0, ddof=1) / math.sqrt(R) / T
    sq = np.sum(totals**2, axis=1)  # the error's length squared; its mean is tr Q T (zero mean)
    return NoiseMonteCarlo(mean, se, float(sq.mean() / T), float(sq.std(ddof=1) / math.sqrt(R) / T), R, T)
