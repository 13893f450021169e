"""Admissible rocking for an azimuth budget in the tilt channel (Hrechka & Koroliov, conclusion 4).

Problem.  The alignment estimates the stable tilts by the sample means (16)
of ``n = T·f_s`` accelerometer samples and the azimuth of the stable position
by ``σ(β̂0, γ̂0)``; the gyros see the stable position only (the paper's
setting).  The rocking that remains in the means makes the alignment error
``Δ = σ(β̂0, γ̂0) − σ(β0, γ0)``.  Given a budget on Δ, the latitude and T,
find the largest rocking amplitude ``a`` at each rocking frequency f.
(:mod:`strapdown.analysis.alignment.design` answers the same
question for the whole system, with the rocking in the gyros.)

Model.  Both tilts rock with amplitude ``a`` (standard deviation ``a/√2``)
and frequency f, with independent phases: a sinusoid, or narrow-band rocking
with period ``1/f`` and damping ζ (amplitude meaning ``σ√2`` there).  The
sample mean keeps the variance ``v(f, T) Dξ``:

* narrow-band: ``v`` from the autocorrelation
  (:func:`strapdown.analysis.gyrocompass.rocking.mean_variance_factor`);
* sine: the mean of ``a sin(ωt + θ)`` over n samples is
  ``a D_n sin(θ')`` with the Dirichlet factor
  ``D_n = sin(nωh/2) / (n sin(ωh/2))``, which vanishes when T holds a whole
  number of periods.  That is an artefact of choosing T to the period: the
  designer knows neither exactly.  The chart uses the envelope over the phase
  the rocking advances over the window, ``E_n = max_{m ∈ [n, n + 1/(fh)]} |D_m|``:
  the worst case over alignment times at least T (about ``1/(n sin(ωh/2))``
  once the window holds half a period).  ``envelope=False`` gives the exact ``D_n``.

Criteria.  The rms of Δ (second-order theory of
:mod:`strapdown.derivations.gyrocompass.azimuth_error`, with ``Dξ → v Dξ``;
its first-order value in closed form), and percentiles of ``|Δ|`` to first order
(:mod:`strapdown.analysis.gyrocompass.error_distribution`: arcsine residues
for the sine, Gaussian for narrow-band rocking).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.validation import as_array, as_float, in_open_interval, positive
from .azimuth import check_latitude, gradient, second_order_theory
from .error_distribution import abs_error_quantile
from .rocking import NarrowbandRocking, mean_variance_factor

__all__ = ["AdmissibleRocking", "admissible_amplitude", "sine_mean_factor"]


def sine_mean_factor(frequency, n_samples: int, dt: float, *, envelope: bool = True):
    """Amplitude factor of the mean of ``n`` samples of a unit sinusoid: ``|D_n|`` or its envelope.

    ``D_n = sin(nπfh) / (n sin(πfh))``.  The envelope is the largest ``|D_m|``
    over ``m`` from n to one rocking period more: the worst case over alignment
    times at least T (beyond a period the peaks only decrease).

    Parameters
    ----------
    frequency : array_like
        Rocking frequency f [Hz], below the Nyquist frequency ``1/(2 dt)``.
    n_samples : int
        Samples averaged.
    dt : float
        Sample interval [s].
    envelope : bool
        Return the envelope instead of ``|D_n|``.

    Returns
    -------
    ndarray
        The amplitude of the sinusoidal residue of the mean, per unit amplitude.

    >>> float(sine_mean_factor(0.1, 100, 0.1, envelope=False)) < 1e-12
    True
    >>> round(float(sine_mean_factor(0.1, 100, 0.1)), 4)  # about 1/(1.5 π): the next peak, half a period later
    0.2173
    """
    f = np.atleast_1d(as_array(frequency, "frequency")).astype(float)
    x = np.pi * f * positive(dt, "dt")
    n = int(n_samples)

    def dirichlet(m):
        den = m * np.abs(np.sin(x))
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(den > 0, np.abs(np.sin(m * x)) / np.where(den > 0, den, 1.0), 1.0)

    if not envelope:
        out = dirichlet(n)
    else:
        per_period = np.ceil(1.0 / (f * dt)).astype(int)
        out = np.array([np.max(_dirichlet_one(n, xi, int(p))) for xi, p in zip(x, per_period)])
    return out.reshape(np.shape(frequency)) if np.ndim(frequency) else out[0]


def _dirichlet_one(n: int, x: float, span: int) -> np.ndarray:
    """``|D_m|`` for ``m = n, ..., n + span`` at one ``x = π f h``."""
    m = np.arange(n, n + span + 1, dtype=float)
    s = abs(math.sin(x))
    return np.abs(np.sin(m * x)) / (m * s) if s > 0 else np.ones_like(m)


@dataclass(frozen=True)
class AdmissibleRocking:
    """Largest admissible rocking amplitude against frequency.

    Attributes
    ----------
    frequency : ndarray
        Rocking frequencies [Hz].
    amplitude : ndarray
        Admissible amplitude by the rms criterion, second-order theory [rad].
    amplitude_first_order : ndarray
        The same at first order [rad].
    amplitude_percentile : ndarray
        Admissible amplitude by the percentile criterion ``P(|Δ| ≤ budget) ≥ level``, first order [rad].
    variance_factor : ndarray
        ``Var(mean)/Var`` of the rocking used (for the sine, the square of the
        mean factor: :func:`sine_mean_factor`).
    level : float
        Percentile level of ``amplitude_percentile``.
    samples : int
        Samples averaged, ``n = T·f_s``.
    rocking : str
        ``"sine"`` or ``"narrowband"``.
    envelope : bool
        Whether the sine uses the envelope over phase.
    max_amplitude : float
        Cap of the reported amplitudes [rad].
    """

    frequency: np.ndarray
    amplitude: np.ndarray
    amplitude_first_order: np.ndarray
    amplitude_percentile: np.ndarray
    variance_factor: np.ndarray
    level: float
    samples: int
    rocking: str
    envelope: bool
    max_amplitude: float


def admissible_amplitude(
    budget,
    latitude,
    averaging_time,
    frequencies,
    *,
    rocking: str = "sine",
    damping: float = 0.1,
    sample_rate: float = 10.0,
    beta0: float = 0.0,
    gamma0: float = 0.0,
    max_amplitude: float = math.radians(20.0),
    level: float = 0.95,
    envelope: bool = True,
) -> AdmissibleRocking:
    """Largest admissible rocking amplitude against rocking frequency (tilt channel).

    Parameters
    ----------
    budget : float
        Azimuth error budget δmax [rad], > 0 (on the rms, and on the percentile).
    latitude : float
        Latitude φ [rad], ``|φ|`` < π/2.
    averaging_time : float
        Averaging time T of the estimates (16) [s].
    frequencies : array_like
        Rocking frequencies f [Hz], in (0, f_s/2).
    rocking : str
        ``"sine"`` or ``"narrowband"``.
    damping : float
        Damping ratio ζ of narrow-band rocking.
    sample_rate : float
        Accelerometer sample rate f_s [Hz].
    beta0, gamma0 : float
        Stable tilts [rad].
    max_amplitude : float
        Cap of the reported amplitude [rad] (also where the series is no longer trusted).
    level : float
        Percentile level of the percentile criterion, in (0, 1).
    envelope : bool
        Sine only: envelope over phase (default) or the exact Dirichlet factor.

    Returns
    -------
    AdmissibleRocking

    Raises
    ------
    ValueError
        For a non-positive budget, time, rate or frequency, a frequency at or
        above the Nyquist frequency, ``|latitude|`` ≥ 90°, or an unknown rocking model.

    References
    ----------
    Hrechka & Koroliov, eq. (16) and conclusion 4.

    Examples
    --------
    >>> d = admissible_amplitude(math.radians(0.1), math.radians(45), 60.0, [0.05, 0.2], rocking="narrowband")
    >>> bool(d.amplitude[1] > d.amplitude[0])
    True
    """
    budget = positive(budget, "budget")
    latitude = check_latitude(latitude)
    T = positive(averaging_time, "averaging_time")
    fs = positive(sample_rate, "sample_rate")
    dt = 1.0 / fs
    if T < dt:
        raise ValueError(f"Expected `averaging_time` >= 1/sample_rate = {dt:g} s, got {T:g}")
    f = as_array(frequencies, "frequencies").ravel()
    if f.size == 0:
        raise ValueError("Expected at least one frequency, got none")
    if np.any(f <= 0) or np.any(f >= fs / 2):
        raise ValueError(f"Expected `frequencies` in (0, sample_rate/2) = (0, {fs / 2:g}) Hz, got {f.min():g} .. {f.max():g}")
    if rocking not in ("sine", "narrowband"):
        raise ValueError(f"Expected `rocking` in ('sine', 'narrowband'), got {rocking!r}")
    cap = positive(max_amplitude, "max_amplitude")
    level = in_open_interval(level, "level", 0.0, 1.0)
    beta0, gamma0 = as_float(beta0, "beta0"), as_float(gamma0, "gamma0")
    n = max(1, int(round(T * fs)))
    g = gradient(latitude, beta0, gamma0)
    if rocking == "sine":
        v = sine_mean_factor(f, n, dt, envelope=envelope) ** 2
        kappa = 1.5
    else:
        v = np.array([mean_variance_factor(NarrowbandRocking(1.0, 1.0, 1.0 / fi, damping), n, dt) for fi in f])
        kappa = 3.0
    a1, a2, ap = np.empty(f.size), np.empty(f.size), np.empty(f.size)
    for i in range(f.size):  # a few dozen frequencies: not a hot path
        # first order: Δ = g_β ξ̄ + g_γ η̄ with Var ξ̄ = v a²/2
        s2 = (g.d_beta**2 + g.d_gamma**2) * v[i]
        a1[i] = cap if s2 <= 0 else min(cap, budget * math.sqrt(2.0 / s2))
        if rocking == "sine":  # residues a·√v·sin θ per axis, θ uniform
            unit = abs_error_quantile([g.d_beta * math.sqrt(v[i]), g.d_gamma * math.sqrt(v[i])], 0.0, level).value
        else:
            unit = abs_error_quantile([], math.sqrt(s2 / 2.0), level).value
        ap[i] = cap if unit <= 0 else min(cap, budget / unit)
        a2[i] = _second_order_root(budget, latitude, beta0, gamma0, math.sqrt(v[i] / 2.0), kappa, a1[i], cap)
    return AdmissibleRocking(f, a2, a1, ap, v, level, n, rocking, bool(envelope) and rocking == "sine", cap)


def _second_order_root(budget, latitude, beta0, gamma0, sd_per_amplitude, kappa, first_order, cap) -> float:
    """The amplitude at which the second-order rms of Δ equals the budget (capped)."""
    from scipy.optimize import brentq

    def excess(a):
        s = a * sd_per_amplitude
        return second_order_theory(latitude, beta0, gamma0, s, s, kappa_xi=kappa, kappa_eta=kappa).rms - budget

    if excess(cap) <= 0:
        return cap
    lo = min(first_order, cap) * 1e-3
    return brentq(excess, lo, cap, xtol=1e-12 * cap) if excess(lo) < 0 else lo
