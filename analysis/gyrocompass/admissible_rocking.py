"""Admissible rocking for an azimuth budget (the open question of Hrechka & Koroliov, conclusion 4).

Problem.  The alignment estimates the stable tilts by the sample means (16)
over an averaging time T, and the azimuth of the stable position by
``σ(β̂0, γ̂0)``.  The rocking that remains in the means makes the alignment
error ``Δ = σ(β̂0, γ̂0) − σ(β0, γ0)``; with one sample (T → one instant) Δ is
the error (12) bounded by (14), (15).  Given a budget ``δmax`` on rms Δ, the
latitude and T, find the largest rocking amplitude ``a`` at each rocking
frequency f.

Model.  Both tilts rock with amplitude ``a`` (standard deviation ``a/√2``)
and frequency f: a sinusoid with random phases, or narrow-band rocking with
period ``1/f`` and damping ζ (amplitude meaning ``σ√2`` there).  The sample
mean keeps the variance ``v(f, T) Dξ`` (:func:`strapdown.analysis.gyrocompass.rocking.mean_variance_factor`),
so the second-order theory of :mod:`strapdown.derivations.gyrocompass.azimuth_error` applies with
``Dξ → v Dξ``:

* first order: ``a₁ = δmax √2 / √(σ_β² vξ + σ_γ² vη)`` (σ_β, σ_γ the
  sensitivities of σ at (β0, γ0));
* second order: the root of ``rms(a) = δmax`` with the mean square to fourth
  order.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from ..core.validation import as_array, as_float, positive
from .azimuth import check_latitude, gradient, second_order_theory
from .rocking import NarrowbandRocking, SineRocking, mean_variance_factor

__all__ = ["admissible_amplitude"]


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
) -> dict:
    """Largest admissible rocking amplitude against rocking frequency.

    Parameters
    ----------
    budget : float — rms azimuth error budget δmax [rad], > 0
    latitude : float — latitude φ [rad], |φ| < π/2
    averaging_time : float — averaging time T of the estimates (16) [s]
    frequencies : array_like — rocking frequencies f [Hz], > 0
    rocking : str — ``"sine"`` or ``"narrowband"``
    damping : float — damping ratio ζ of narrow-band rocking
    sample_rate : float — accelerometer sample rate [Hz]
    beta0, gamma0 : float — stable tilts [rad]
    max_amplitude : float — cap of the reported amplitude [rad] (also where the
        series is no longer trusted)

    Returns
    -------
    dict
        ``frequency`` [Hz], ``variance_factor`` v(f, T), ``amplitude_first_order``
        and ``amplitude`` (second-order theory) [rad], both capped at
        ``max_amplitude``.

    Raises
    ------
    ValueError
        For a non-positive budget, time, rate or frequency, |latitude| ≥ 90°,
        or an unknown rocking model.

    Examples
    --------
    >>> d = admissible_amplitude(math.radians(0.1), math.radians(45), 60.0, [0.05, 0.2], rocking="narrowband")
    >>> bool(d["amplitude"][1] > d["amplitude"][0])
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
    if f.size == 0 or np.any(f <= 0):
        raise ValueError("Expected `frequencies` > 0 Hz, got a non-positive entry" if f.size else "Expected at least one frequency, got none")
    if rocking not in ("sine", "narrowband"):
        raise ValueError(f"Expected `rocking` in ('sine', 'narrowband'), got {rocking!r}")
    cap = positive(max_amplitude, "max_amplitude")
    beta0, gamma0 = as_float(beta0, "beta0"), as_float(gamma0, "gamma0")
    n = max(1, int(round(T * fs)))
    gb, gg = gradient(latitude, beta0, gamma0)
    kappa = 1.5 if rocking == "sine" else 3.0
    v = np.empty(f.size)
    a1 = np.empty(f.size)
    a2 = np.empty(f.size)
    for i, freq in enumerate(f):  # a few dozen frequencies: not a hot path
        model = SineRocking(1.0, 1.0, 1.0 / freq, 1.0 / freq) if rocking == "sine" else NarrowbandRocking(1.0, 1.0, 1.0 / freq, damping)
        v[i] = mean_variance_factor(model, n, dt)
        s2 = gb * gb * v[i] + gg * gg * v[i]
        a1[i] = cap if s2 <= 0 else min(cap, budget * math.sqrt(2.0 / s2))
        sd = math.sqrt(v[i] / 2.0)

        def excess(a, sd=sd):
            return second_order_theory(latitude, beta0, gamma0, a * sd, a * sd, kappa_xi=kappa, kappa_eta=kappa)["rms"] - budget

        if excess(cap) <= 0:
            a2[i] = cap
        else:
            lo = min(a1[i], cap) * 1e-3
            a2[i] = brentq(excess, lo, cap, xtol=1e-12 * cap) if excess(lo) < 0 else lo
    return {"frequency": f, "variance_factor": v, "amplitude_first_order": a1, "amplitude": a2, "samples": n}
