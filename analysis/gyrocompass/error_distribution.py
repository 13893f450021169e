"""Distribution of a linear error made of random-phase sinusoids and Gaussian noise.

To first order, the azimuth error of an alignment on a base rocking with
sinusoids of random phases is ``e = Σ_i c_i sin θ_i + w``: the sinusoidal
residues of the rocking (one per axis, phases θ_i independent and uniform)
plus Gaussian noise ``w ~ N(0, s²)`` from the sensors (and from narrow-band or
white rocking, which is Gaussian).  Its rms is ``√(Σ c_i²/2 + s²)``, but a
designer also asks for percentiles of ``|e|``: a sinusoid's residue is bounded
(arcsine distributed) and a Gaussian one is not, so the 95th and 99th
percentiles differ from ``z·rms`` in opposite directions.

The percentiles are computed deterministically: the phases on a midpoint grid
(exact for the arcsine law up to the grid spacing), the Gaussian part by its
CDF, and the level by a root finder.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..core.validation import as_array, as_float, in_open_interval, nonnegative

__all__ = ["ErrorQuantile", "abs_error_quantile", "rms_of"]

#: grid points per phase (midpoint rule: the quantile of a single sinusoid is exact to about 1/n²)
_GRID = {1: 8192, 2: 384, 3: 64}


class ErrorQuantile(NamedTuple):
    """A percentile of ``|e|`` with the rms of ``e``.

    Attributes
    ----------
    level : float
        Probability ``P(|e| ≤ value)``.
    value : float
        The percentile of ``|e|`` [error units].
    rms : float
        ``√E e²`` [error units].
    """

    level: float
    value: float
    rms: float


def rms_of(sine_amplitudes, gaussian_sigma: float = 0.0) -> float:
    """``√(Σ c_i²/2 + s²)``: the rms of ``Σ c_i sin θ_i + N(0, s²)``.

    Parameters
    ----------
    sine_amplitudes : array_like
        Amplitudes ``c_i`` of the sinusoidal residues [error units].
    gaussian_sigma : float
        Standard deviation ``s`` of the Gaussian part [error units].

    Returns
    -------
    float

    >>> round(rms_of([math.sqrt(2.0)], 0.0), 12)
    1.0
    """
    c = as_array(sine_amplitudes, "sine_amplitudes").ravel()
    s = nonnegative(gaussian_sigma, "gaussian_sigma")
    return math.sqrt(float(np.sum(c * c)) / 2.0 + s * s)


def _phase_values(c: np.ndarray) -> np.ndarray:
    """``Σ c_i sin θ_i`` on a midpoint grid of the phases (all combinations)."""
    c = c[c != 0.0]
    if c.size == 0:
        return np.zeros(1)
    if c.size > 3:
        raise ValueError(f"Expected at most 3 sinusoidal residues, got {c.size}")
    n = _GRID[c.size]
    s = np.sin(2.0 * math.pi * (np.arange(n) + 0.5) / n)
    total = np.zeros(1)
    for ci in c:
        total = (total[:, None] + ci * s[None, :]).ravel()
    return total


def abs_error_quantile(sine_amplitudes, gaussian_sigma: float, level: float, *, mean: float = 0.0) -> ErrorQuantile:
    """Percentile of ``|μ + Σ c_i sin θ_i + w|``, θ_i uniform and independent, ``w ~ N(0, s²)``.

    Parameters
    ----------
    sine_amplitudes : array_like
        Amplitudes ``c_i`` of up to three sinusoidal residues [error units].
    gaussian_sigma : float
        Standard deviation ``s`` of the Gaussian part [error units].
    level : float
        Probability in (0, 1), e.g. 0.95.
    mean : float
        Deterministic part μ (a bias) [error units].

    Returns
    -------
    ErrorQuantile
        With ``rms = √(μ² + Σ c_i²/2 + s²)``.

    Raises
    ------
    ValueError
        For a level outside (0, 1), a negative sigma or more than three sinusoids.

    Examples
    --------
    A single sinusoid of amplitude 1: ``P(|sin θ| ≤ x) = (2/π) arcsin x``.

    >>> q = abs_error_quantile([1.0], 0.0, 0.5)
    >>> round(q.value, 4), round(math.sin(math.pi / 4), 4)
    (0.7071, 0.7071)

    A Gaussian alone: the two-sided normal quantile.

    >>> round(abs_error_quantile([], 1.0, 0.95).value, 4)
    1.96
    """
    c = np.abs(as_array(sine_amplitudes, "sine_amplitudes").ravel())
    s = nonnegative(gaussian_sigma, "gaussian_sigma")
    p = in_open_interval(level, "level", 0.0, 1.0)
    mu = as_float(mean, "mean")
    rms = math.hypot(rms_of(c, s), mu)
    if rms == 0.0:
        return ErrorQuantile(p, 0.0, 0.0)
    m = _phase_values(c) + mu
    if s == 0.0:
        return ErrorQuantile(p, float(np.quantile(np.abs(m), p)), rms)
    from scipy.optimize import brentq
    from scipy.special import ndtr

    def cdf(x):
        return float(np.mean(ndtr((x - m) / s) - ndtr((-x - m) / s))) - p

    hi = float(np.max(np.abs(m))) + 10.0 * s
    return ErrorQuantile(p, as_float(brentq(cdf, 0.0, hi, xtol=1e-8 * hi), "quantile"), rms)
