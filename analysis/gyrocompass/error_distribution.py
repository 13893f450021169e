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
CDF, and the level by a root finder.  :func:`abs_error_probability` gives the
probability ``P(|e| ≤ x)`` itself, on the half of the same grid that carries
every value of ``sin θ`` (``sin(π − θ) = sin θ``): a search over the size of
the residues for a percentile budget needs one such probability per step,
not a percentile.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..core.validation import as_array, as_float, in_open_interval, nonnegative, positive

__all__ = ["ErrorQuantile", "abs_error_quantile", "abs_error_probability", "rms_of"]

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


def _half_phase_values(c: np.ndarray) -> np.ndarray:
    """``Σ c_i sin θ_i`` with every θ_i on the midpoint grid of (−π/2, π/2): the values of :func:`_phase_values`, each once."""
    c = c[c != 0.0]
    if c.size == 0:
        return np.zeros(1)
    if c.size > 3:
        raise ValueError(f"Expected at most 3 sinusoidal residues, got {c.size}")
    n = _GRID[c.size] // 2
    s = np.sin(math.pi * ((np.arange(n) + 0.5) / n - 0.5))
    total = np.zeros(1)
    for ci in c:
        total = (total[:, None] + ci * s[None, :]).ravel()
    return total


def abs_error_probability(sine_amplitudes, gaussian_sigma: float, x: float, *, mean: float = 0.0) -> float:
    """``P(|μ + Σ c_i sin θ_i + w| ≤ x)``, θ_i uniform and independent, ``w ~ N(0, s²)``, s > 0.

    The phases on the midpoint grid of :func:`abs_error_quantile` (the
    percentile there is the root in x of this probability minus the level),
    folded onto the half period that carries every value of the sine once:
    ``2^K`` times fewer points for K residues, the same mean.

    Parameters
    ----------
    sine_amplitudes : array_like
        Amplitudes ``c_i`` of up to three sinusoidal residues [error units].
    gaussian_sigma : float
        Standard deviation ``s`` of the Gaussian part [error units], > 0.
    x : float
        Bound on ``|e|`` [error units], >= 0.
    mean : float
        Deterministic part μ (a bias) [error units].

    Returns
    -------
    float
        The probability, in [0, 1].

    Raises
    ------
    ValueError
        For a sigma that is not positive, a negative bound or more than three sinusoids.

    Examples
    --------
    A Gaussian alone: the two-sided normal probability.

    >>> round(abs_error_probability([], 1.0, 1.959963985), 6)
    0.95

    The percentile of :func:`abs_error_quantile` is where the probability reaches the level:

    >>> q = abs_error_quantile([1.0, 0.5], 0.3, 0.95, mean=0.1)
    >>> round(abs_error_probability([1.0, 0.5], 0.3, q.value, mean=0.1), 6)
    0.95
    """
    c = np.abs(as_array(sine_amplitudes, "sine_amplitudes").ravel())
    s = positive(gaussian_sigma, "gaussian_sigma")
    x = nonnegative(x, "x")
    mu = as_float(mean, "mean")
    from scipy.special import ndtr

    m = _half_phase_values(c) + mu
    return float(np.mean(ndtr((x - m) / s) - ndtr((-x - m) / s)))
