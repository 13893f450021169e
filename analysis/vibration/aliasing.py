"""Lines whose sum or difference frequency is a multiple of the step rate: the phase-locked mean drift of their cross terms.

Two deterministic lines of different frequencies f₁ ≠ f₂ do not simply add
their drifts.  Their cross terms in the algorithm's bilinear operations
(``½ Θ × P`` of the step composition, ``c_ij p_i × p_j`` of the algorithm)
oscillate at ``f₁ ± f₂``, and the algorithm samples them once per step
``H = N h``: where ``f₁ + f₂`` or ``|f₁ − f₂|`` is a multiple of the step rate
``1/H``, the oscillation is sampled at the same phase at every step and
leaves a mean.  This module gives that mean in closed form.

Derivation (second order in the vibration amplitude, exact in ωh)
------------------------------------------------------------------
Write a line's sensed rotation angle (the integral of its sensed rate
``Re(Ã e^{iωt})``, :mod:`strapdown.analysis.vibration.drift`) as
``θ(t) = Re(Θ e^{iωt})``, ``Θ = Ã/(iω)``.  A real sinusoid is also
``Re(Θ̄ e^{−iωt})``, so one line may be written with ω or −ω.  Steps begin at
``t_l = l H``; the increments of the step after ``t_l`` are
``p_i = Re(Θ e^{iωt_l} g_i(ω))`` with ``g_i(ω) = e^{iωih}(1 − e^{−iωh})`` for
every sample index i of the algorithm (``i ≤ 0``: samples of earlier steps),
the step's sum ``P = Re(Θ e^{iωt_l} E(ω))`` with ``E(ω) = e^{iωH} − 1``, and
``θ(t_l) = Re(Θ e^{iωt_l})``.

*Truth.*  The exact rotation vector grows by ``½∫θ × ω dt`` at second order.
The cross terms of two lines oscillate at ``ω₁ ± ω₂ ≠ 0``: they stay bounded
and leave no mean rate, at any sampling.

*Algorithm.*  The computed attitude is the product of the step rotations,
whose rotation vector grows per step by ``½ θ(t_l) × P + Σ c_ij p_i × p_j``
(the Baker–Campbell–Hausdorff term of the composition and the algorithm's
pairwise terms; nested and dot terms are of third order).  For two lines
``(Θ₁, ω₁)``, ``(Θ₂, ω₂)``, using
``Re(a) × Re(b) = ½ Re(a × b) + ½ Re(a × b̄)``, the cross terms of both
orders are ``½ Re[(Θ₁ × Θ₂) K(ω₁, ω₂) e^{i(ω₁+ω₂)t_l}]`` plus the same with
line 2 written at ``−ω₂`` (``Θ₂ → Θ̄₂``), where

    K(ω₁, ω₂) = ½ [E(ω₂) − E(ω₁)] + Σ_ij c_ij [g_i(ω₁) g_j(ω₂) − g_i(ω₂) g_j(ω₁)]

(the ``½ θ × P`` terms give the first bracket, the pairwise terms the sum,
with ``a × b = −b × a``).  Averaged over the steps, ``e^{i(ω₁+ω₂)lH}`` has
mean 1 when ``(f₁ + f₂) H`` is a whole number k, and 0 otherwise.  So a pair
with ``f₁ + σ f₂ = k/H`` (σ = +1: the sum, σ = −1: the difference) drifts at

    u = −(1/(2H)) Re[(Θ₁ × Θ₂^σ) K(ω₁, σω₂)],      Θ^{+1} = Θ, Θ^{−1} = Θ̄,

exact minus algorithm (the truth has no mean), in the body axes.  It is the
algorithm's own error on the sensed motion (the sensor part, a difference of
two continuous-time truths, has none), and it depends on the lines' phases
*relative to the step clock*: the phases of an environment file are those at
t = 0, where a step begins; over a uniformly random clock offset the mean is
zero.  Unlike a single line's drift it depends on each pairwise coefficient
``c_ij``, not only on the lag sums: two algorithms with the same lag sums
(the registry's ``optimal-3`` and Ignagni's form of the same lag sums) drift
alike under one line but not under an aliasing pair.  A single line with
itself has ``Θ × Θ = 0``: a line at half the step rate adds nothing.

*Sculling.*  The velocity algorithm is the dual extension (transfer
principle, Lebedev & Panov 1989, eq. (2.5)): ``Θ → Θ + s V`` with
``V = B̃/(iω)`` the sensed velocity amplitude, so the rectification error of
the pair is the same expression with ``Θ₁ × V₂^σ + V₁ × Θ₂^σ`` in place of
``Θ₁ × Θ₂^σ`` [m/s²].

*Near an alias.*  When ``f₁ + σ f₂ = k/H + δ`` with a small offset δ, the
term turns slowly: over a stretch of flight short against the *beat period*
``1/|δ|`` the pair drifts at ``Re[V e^{i2πδt}]`` (V the complex vector of the
formula above), a vector whose length swings up to
``√(½(|V|² + |V·V|))`` (:attr:`AliasPair.amplitude`); its mean over many beats
is zero.  :func:`alias_pairs` lists such pairs with their beat period; they are
not part of the mean drift.

*Sensor rate.*  The sensor chain (analog filter, integration, digital
filter, decimation) is linear: the algorithm receives exactly the increments
of ``Re(H(ω) A e^{iωt})`` for every ω, the response of a digital filter
being periodic in ω (a line above the sensor's Nyquist frequency is aliased
by it, and ``H`` says how).  The only bilinear operations are the
algorithm's, at its samples and steps; and the sensor rate ``1/h_s = N M / H``
is itself a multiple of the step rate, so a pair that aliases with the sensor
rate aliases with the step rate and is covered.

*Spectra.*  A stationary random vibration has uncorrelated components at
different frequencies (``E[X(f₁) X̄(f₂)] = 0`` for f₁ ≠ f₂ and
``E[X(f₁) X(f₂)] = 0`` for f₁ ≠ −f₂), and a spectrum is independent of the
lines, so neither a spectrum with itself nor a spectrum with a line adds an
aliasing mean: only deterministic lines do.

Public API
----------
.. autosummary::

   AliasPair
   AliasResponse
   alias_pairs
   alias_response
   ALIAS_TOLERANCE
   NEAR_ALIAS_BEAT

References
----------
Lebedev & Panov (1989), eq. (2.5) (transfer principle); Savage (1998), part 1
(the bilinear coning terms of a step); Bendat & Piersol (2010), ch. 5
(stationary processes: components at different frequencies are uncorrelated).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core.validation import as_int, positive
from .environment import Environment

__all__ = ["AliasPair", "AliasResponse", "alias_pairs", "alias_response", "ALIAS_TOLERANCE", "NEAR_ALIAS_BEAT"]

#: A pair is exactly aliased when ``|f₁ ± f₂ − k/H|`` is at most this fraction of the step rate 1/H [-].
ALIAS_TOLERANCE = 1e-9
#: Pairs whose beat period exceeds this are listed as near an alias [s] (offset below 10 Hz).
NEAR_ALIAS_BEAT = 0.1


@dataclass(frozen=True, eq=False)
class AliasPair:
    """Two lines whose sum or difference frequency is at or near a multiple of the step rate.

    Attributes
    ----------
    labels : tuple of str
        The two lines (lines of one frequency are one coherent line, their labels joined).
    frequencies : tuple of float
        f₁, f₂ [Hz].
    kind : str
        ``"sum"`` (f₁ + f₂ ≈ k/H) or ``"difference"`` (``|f₁ − f₂| ≈ k/H``).
    multiple : int
        k [count].
    offset : float
        ``f₁ ± f₂ − k/H`` [Hz] (signed; 0 for an exact alias).
    beat_period : float
        ``1/|offset|`` [s] (inf for an exact alias).
    exact : bool
        Aliased to within :data:`ALIAS_TOLERANCE`: the drift is part of the mean.
    drift : ndarray (3,)
        Coning drift of the pair with the phases of t = 0 [rad/s] (exact minus
        algorithm, body axes): the mean for an exact alias; for a near one, the
        drift over a stretch of flight short against the beat period, at t = 0.
    amplitude : float
        Largest ``|drift|`` over the pair's phase relative to the step clock [rad/s].
    sculling : ndarray (3,)
        Rectification error of the pair, as ``drift`` [m/s²].
    sculling_amplitude : float
        Largest ``|sculling|`` over the phase [m/s²].
    """

    labels: tuple
    frequencies: tuple
    kind: str
    multiple: int
    offset: float
    beat_period: float
    exact: bool
    drift: np.ndarray
    amplitude: float
    sculling: np.ndarray
    sculling_amplitude: float


@dataclass(frozen=True, eq=False)
class AliasResponse:
    """The exactly aliased pairs' drift as an affine function of an algorithm's pairwise coefficients.

    ``drift = base + per_pair @ c`` for coefficients ``c`` of the pairs
    ``pairs`` (coning [rad/s] in row 0, rectification [m/s²] in row 1).

    Attributes
    ----------
    pairs : tuple of (int, int)
        Sample-index pairs (i, j) of the terms ``c_ij p_i × p_j``.
    base : ndarray (2, 3)
        Drift with no pairwise term (the composition's ``½ θ × P``).
    per_pair : ndarray (2, 3, P)
        Drift per unit coefficient of each pair.
    """

    pairs: tuple
    base: np.ndarray
    per_pair: np.ndarray


def _groups(environment: Environment, h: float):
    """Frequencies [Hz], sensed angle and velocity amplitudes Θ̃ = H A/(iω), Ṽ = H B/(iω), labels, per coherent group."""
    groups: dict = {}
    for ln in environment.lines:
        groups.setdefault(ln.frequency, []).append(ln)
    freq = np.array(list(groups), dtype=float)
    if freq.size == 0:
        return freq, np.zeros((0, 3), complex), np.zeros((0, 3), complex), []
    amp = np.stack([sum(ln.amplitude for ln in g) for g in groups.values()])
    omega = 2.0 * math.pi * freq
    sensed = amp * environment.response(omega, h)
    theta = sensed[:, :3] / (1j * omega[:, None])
    vel = sensed[:, 3:] / (1j * omega[:, None])
    labels = [" + ".join(ln.label for ln in g) for g in groups.values()]
    return freq, theta, vel, labels


def _candidates(freq: np.ndarray, step: float, beat: float):
    """Pairs (a < b, σ) with ``f_a + σ f_b`` within ``1/beat`` of a multiple of 1/H: indices, σ, k, offset."""
    n = freq.size
    if n < 2:
        return []
    rate = 1.0 / step
    window = max(1.0 / beat, ALIAS_TOLERANCE * rate)
    a, b = np.triu_indices(n, 1)
    out = []
    for sigma in (1, -1):
        s = freq[a] + sigma * freq[b]
        k = np.rint(s / rate)
        off = s - k * rate
        hit = np.nonzero(np.abs(off) <= window)[0]
        for m in hit:
            if sigma == 1 or k[m] != 0:  # a difference of 0 is one frequency: the coherent group's own term
                exact = abs(off[m]) <= ALIAS_TOLERANCE * rate
                out.append((int(a[m]), int(b[m]), sigma, int(k[m]), 0.0 if exact else float(off[m]), exact))
    return out


def _kernels(omega1: float, omega2: float, h: float, samples: int, pairs) -> tuple:
    """``½[E(ω₂) − E(ω₁)]`` and ``g_i(ω₁)g_j(ω₂) − g_i(ω₂)g_j(ω₁)`` for each pair (module docstring)."""
    step = samples * h

    def E(w):
        return np.exp(1j * w * step) - 1.0

    def g(i, w):
        return np.exp(1j * w * i * h) * (1.0 - np.exp(-1j * w * h))

    base = 0.5 * (E(omega2) - E(omega1))
    kappa = np.array([g(i, omega1) * g(j, omega2) - g(i, omega2) * g(j, omega1) for i, j in pairs], dtype=complex)
    return base, kappa


def _swing(v: np.ndarray) -> float:
    """``max_φ |Re(v e^{iφ})|`` of a complex 3-vector."""
    return math.sqrt(max(0.0, 0.5 * (float(np.vdot(v, v).real) + abs(complex(v @ v)))))


def _pair_vectors(theta, vel, a, b, sigma):
    t2 = theta[b] if sigma > 0 else np.conj(theta[b])
    v2 = vel[b] if sigma > 0 else np.conj(vel[b])
    return np.cross(theta[a], t2), np.cross(theta[a], v2) + np.cross(vel[a], t2)


def _check(environment, sample_interval):
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    return positive(sample_interval, "sample_interval")


def alias_pairs(algorithm: Algorithm, environment: Environment, sample_interval: float, *, min_beat_period: float = NEAR_ALIAS_BEAT) -> tuple:
    """Pairs of lines at or near an alias with the step rate, with their phase-locked drift (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (its pairwise coefficients; nested and dot terms are of third order).
    environment : Environment
        Lines (spectra add no aliasing mean) and sensors.
    sample_interval : float
        Algorithm sample interval h [s], > 0 (step H = N h).
    min_beat_period : float, keyword-only
        A pair is listed as near an alias when its beat period exceeds this [s], > 0.

    Returns
    -------
    tuple of AliasPair
        Exact aliases first, then near ones by decreasing beat period.

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm or ``environment`` not an Environment.
    ValueError
        A non-positive ``sample_interval`` or ``min_beat_period``.

    References
    ----------
    Savage (1998), part 1; Lebedev & Panov (1989), eq. (2.5).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> from strapdown.analysis.vibration.environment import VibrationLine
    >>> d = math.radians(5.0)
    >>> env = Environment((VibrationLine(60.0, [d, 0, 0, 0, 0, 0]), VibrationLine(140.0, [0, 1j * d, 0, 0, 0, 0])))
    >>> (p,) = alias_pairs(get("two-sample"), env, 1 / 400)
    >>> p.kind, p.multiple, round(float(p.drift[2]) * 180 / math.pi * 3600, 4)    # deg/h, about z
    ('sum', 1, -0.1502)
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    h = _check(environment, sample_interval)
    beat = positive(min_beat_period, "min_beat_period")
    N = algorithm.samples
    step = N * h
    freq, theta, vel, labels = _groups(environment, h)
    pairs = list(algorithm.pairwise)
    coef = np.array([float(c) for c in algorithm.pairwise.values()])
    out = []
    for a, b, sigma, k, off, exact in _candidates(freq, step, beat):
        w1, w2 = 2.0 * math.pi * freq[a], sigma * 2.0 * math.pi * freq[b]
        base, kappa = _kernels(w1, w2, h, N, pairs)
        kk = base + (kappa @ coef if pairs else 0.0)
        x, xs = _pair_vectors(theta, vel, a, b, sigma)
        v, vs = -x * kk / (2.0 * step), -xs * kk / (2.0 * step)
        out.append(
            AliasPair(
                (labels[a], labels[b]),
                (float(freq[a]), float(freq[b])),
                "sum" if sigma > 0 else "difference",
                abs(k),
                off,
                math.inf if exact else 1.0 / abs(off),
                exact,
                np.real(v),
                _swing(v),
                np.real(vs),
                _swing(vs),
            )  # fmt: skip
        )
    out.sort(key=lambda p: (not p.exact, -p.beat_period if math.isfinite(p.beat_period) else 0.0))
    return tuple(out)


def alias_response(environment: Environment, sample_interval: float, samples: int, pairs) -> AliasResponse:
    """Drift of the exactly aliased line pairs, affine in the pairwise coefficients (for tuning).

    Parameters
    ----------
    environment : Environment
        Lines and sensors.
    sample_interval : float
        h [s], > 0.
    samples : int
        N, samples per step [count].
    pairs : sequence of (int, int)
        Sample-index pairs (i, j) of the terms ``c_ij p_i × p_j``.

    Returns
    -------
    AliasResponse

    Raises
    ------
    TypeError
        If ``environment`` is not an Environment.
    ValueError
        A non-positive ``sample_interval`` or ``samples``.
    """
    h = _check(environment, sample_interval)
    N = as_int(samples, "samples", minimum=1)
    pairs = tuple((int(i), int(j)) for i, j in pairs)
    step = N * h
    freq, theta, vel, _ = _groups(environment, h)
    base = np.zeros((2, 3))
    per = np.zeros((2, 3, len(pairs)))
    for a, b, sigma, _, _, exact in _candidates(freq, step, math.inf):
        if not exact:
            continue
        b0, kappa = _kernels(2.0 * math.pi * freq[a], sigma * 2.0 * math.pi * freq[b], h, N, pairs)
        for row, x in enumerate(_pair_vectors(theta, vel, a, b, sigma)):
            base[row] += np.real(-x * b0) / (2.0 * step)
            if pairs:
                per[row] += np.real(-x[:, None] * kappa[None, :]) / (2.0 * step)
    return AliasResponse(pairs, base, per)
