"""The noise of an IMU at rest, read off the Allan deviation of a static stretch of its log.

The overlapping Allan deviation of each axis is measured
(:func:`strapdown.analysis.alignment.sensor_models.allan_deviation`, which uses
``allantools``), and the three axes of a triad are pooled: their Allan
variances are averaged and their equivalent degrees of freedom add (the axes'
noises are independent), so each point has the χ² interval of the pooled
degrees of freedom (Greenhall & Riley 2003, with the noise type that dominates
at that τ).  The three coefficients of the data sheet (IEEE Std 952-1997,
annex C) are then *read off* the pooled curve, each at one averaging time:

    σ²(τ) = N²/τ + (2 ln 2/π) B² + K² τ/3.

A model is fitted first (:func:`~strapdown.analysis.alignment.sensor_models.fit_allan`,
non-negative least squares weighted by the degrees of freedom); for each
coefficient X, at each τ the other two terms of the fit are subtracted from the
measured variance and from the ends of its interval, and what is left is
divided by X's own term at unit coefficient; among the τ where X's term makes
at least :data:`SHARE` of the fitted variance and the interval excludes zero,
the τ read is the one whose interval for X is the narrowest in ratio.  The
interval of X is then the χ² interval of one Allan-deviation point, whose
coverage is that of Greenhall's degrees of freedom (the uncertainty of the
smaller part subtracted is not added).  A coefficient whose term the record
does not show that way gets the interval from zero to the smallest upper bound
any τ gives (the whole measured variance taken as the term's).

The log must be static (no motion: the stretch is chosen with ``--segment``);
constant parts (the Earth's rate, gravity, turn-on biases) do not enter an
Allan deviation.

Public API
----------
.. autosummary::

   Coefficient
   TriadNoise
   StaticNoise
   static_noise
   allan_read_off
   SHARE
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..alignment.sensor_models import FLICKER_FLOOR, AllanDeviation, AllanFit, DataSheet, SensorSpec, allan_deviation, fit_allan
from ..core import budget
from ..core.validation import in_open_interval
from .imu_log import ImuLog

__all__ = ["Coefficient", "TriadNoise", "StaticNoise", "static_noise", "allan_read_off", "SHARE"]

#: Allan deviation of a log, per sample (six channels, twice each: allantools' octave τ and the degrees of freedom);
#: memory: a few float64 arrays of the record alive at once (rounded up from benchmarks/bench_log_analysis.py).
_ALLAN_SAMPLE = budget.CostModel(seconds_per_unit=3e-6, bytes_per_unit=100.0, fixed_seconds=0.2)


@dataclass(frozen=True)
class Coefficient:
    """One coefficient read off an Allan deviation.

    Attributes
    ----------
    value : float
        The estimate [SI unit of the coefficient].
    low, high : float
        Ends of its interval.
    tau : float
        Averaging time it was read at [s].
    share : float
        Fraction of the fitted Allan variance at ``tau`` that is this term's.
    """

    value: float
    low: float
    high: float
    tau: float
    share: float


@dataclass(frozen=True)
class TriadNoise:
    """The noise of a sensor triad at rest.

    Attributes
    ----------
    axes : tuple of AllanDeviation
        The curve of each axis.
    pooled : AllanDeviation
        The three pooled (Allan variances averaged, degrees of freedom added).
    fit : AllanFit
        The model fitted to the pooled curve.
    random_walk : Coefficient
        N [rad/√s or m/s/√s].
    bias_instability : Coefficient
        B [rad/s or m/s²].
    rate_random_walk : Coefficient
        K [rad/s/√s or m/s²/√s].
    """

    axes: tuple
    pooled: AllanDeviation
    fit: AllanFit
    random_walk: Coefficient
    bias_instability: Coefficient
    rate_random_walk: Coefficient

    def spec(self) -> SensorSpec:
        """The data sheet of the triad (the read-off values; no turn-on bias: a static log cannot tell it from the mean).

        Returns
        -------
        SensorSpec
        """
        return SensorSpec(self.random_walk.value, self.bias_instability.value, self.rate_random_walk.value)


@dataclass(frozen=True)
class StaticNoise:
    """Gyro and accelerometer noise of a static log (:func:`static_noise`).

    Attributes
    ----------
    gyro, accel : TriadNoise
        The two triads.
    duration : float
        Length of the stretch [s].
    sample_interval : float
        h [s].
    level : float
        Coverage of every interval.
    """

    gyro: TriadNoise
    accel: TriadNoise
    duration: float
    sample_interval: float
    level: float

    def data_sheet(self, name: str = "from a static log") -> DataSheet:
        """The IMU as the alignment toolkit takes it.

        Parameters
        ----------
        name : str
            Its name.

        Returns
        -------
        DataSheet
        """
        return DataSheet(name, self.gyro.spec(), self.accel.spec())


def _pool(curves, level: float) -> AllanDeviation:
    import allantools

    var = np.mean([c.adev**2 for c in curves], axis=0)
    edf = np.sum([c.edf for c in curves], axis=0)
    dev = np.sqrt(var)
    ends = np.array([allantools.confidence_interval(d, e, ci=level) for d, e in zip(dev, edf)])
    return AllanDeviation(curves[0].taus, dev, ends[:, 0], ends[:, 1], edf, float(level))


#: Share of the fitted Allan variance a term must have at a τ for the coefficient to be read there.
SHARE = 0.5


def _unit_terms(tau: np.ndarray) -> np.ndarray:
    """Allan variance of each term at unit coefficient, shape (3, τ): 1/τ, (2 ln 2/π), τ/3."""
    return np.stack([1.0 / tau, np.full_like(tau, FLICKER_FLOOR**2), tau / 3.0])


def allan_read_off(curve: AllanDeviation, fit: AllanFit) -> tuple:
    """N, B and K read off ``curve``, each at the τ where its interval is narrowest (module docstring).

    Parameters
    ----------
    curve : AllanDeviation
        A measured curve with its interval.
    fit : AllanFit
        The model fitted to it (the other terms subtracted at each τ).

    Returns
    -------
    tuple of Coefficient
        ``(random walk, bias instability, rate random walk)``.

    Examples
    --------
    A curve of white noise only reads its random walk back at the shortest τ, and no rate random walk:

    >>> t = np.array([1.0, 2.0, 4.0, 8.0])
    >>> a = AllanDeviation(t, 2.0 / np.sqrt(t), 1.9 / np.sqrt(t), 2.1 / np.sqrt(t), np.full(4, 400.0), 0.95)
    >>> n, b, k = allan_read_off(a, AllanFit(2.0, 0.0, 0.0))
    >>> round(n.value, 6), n.tau, k.value
    (2.0, 1.0, 0.0)
    """
    tau = np.asarray(curve.taus, dtype=float)
    unit = _unit_terms(tau)
    coef = np.array([fit.random_walk, fit.bias_instability, fit.rate_random_walk]) ** 2
    model = coef[:, None] * unit  # (3, τ)
    total = np.maximum(model.sum(axis=0), np.finfo(float).tiny)
    out = []
    for k in range(3):
        others = total - model[k]
        mid = np.maximum(curve.adev**2 - others, 0.0) / unit[k]
        low = np.maximum(curve.low**2 - others, 0.0) / unit[k]
        high = np.maximum(curve.high**2 - others, 0.0) / unit[k]
        dominant = (model[k] >= SHARE * total) & (low > 0)
        if not np.any(dominant):  # the record does not show the term: the tightest upper bound any τ gives
            bound = curve.high**2 / unit[k]
            i = int(np.argmin(bound))
            out.append(Coefficient(float(math.sqrt(mid[i])), 0.0, float(math.sqrt(bound[i])), float(tau[i]), float(model[k][i] / total[i])))
            continue
        width = np.where(dominant, np.log(np.where(dominant, high, 1.0)) - np.log(np.where(dominant, low, 1.0)), np.inf)
        i = int(np.argmin(width))
        out.append(Coefficient(float(math.sqrt(mid[i])), float(math.sqrt(low[i])), float(math.sqrt(high[i])), float(tau[i]), float(model[k][i] / total[i])))
    return tuple(out)


def _fit(curve: AllanDeviation) -> AllanFit:
    """The model fitted to the points of ``curve`` that show any noise (none: a constant channel, all zero)."""
    ok = curve.adev > 0
    if not np.any(ok):
        return AllanFit(0.0, 0.0, 0.0)
    return fit_allan(curve.taus[ok], curve.adev[ok], weights=curve.edf[ok])


def _triad(increments: np.ndarray, h: float, level: float) -> TriadNoise:
    rates = increments / h
    first = _pool([allan_deviation(rates[:, c], h, level=level) for c in range(3)], level)
    fit = _fit(first)
    spec = SensorSpec(fit.random_walk, fit.bias_instability, fit.rate_random_walk)
    axes = tuple(allan_deviation(rates[:, c], h, spec=spec, level=level) for c in range(3))  # degrees of freedom by noise type
    pooled = _pool(axes, level)
    fit = _fit(pooled)
    n, b, k = allan_read_off(pooled, fit)
    return TriadNoise(axes, pooled, fit, n, b, k)


def static_noise(segments, *, level: float = 0.95, limits: budget.Limits | None = None) -> StaticNoise:
    """ARW, bias instability and RRW of the gyros, VRW, bias instability and RRW of the accelerometers, with intervals.

    Parameters
    ----------
    segments : ImuLog or sequence of ImuLog
        The static stretch (one gap-free segment: an Allan deviation needs
        consecutive samples; give the longest one).
    level : float, keyword-only
        Coverage of the intervals, in (0, 1).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    StaticNoise

    Raises
    ------
    TypeError
        If ``segments`` holds something else than ImuLog.
    ValueError
        Several segments, fewer than 64 samples, or work beyond ``limits``.

    References
    ----------
    IEEE Std 952-1997, annex C; El-Sheimy, Hou & Niu (2008); Greenhall &
    Riley (2003) (the degrees of freedom).
    """
    if isinstance(segments, ImuLog):
        log = segments
    elif isinstance(segments, Sequence) and len(segments) == 1 and isinstance(segments[0], ImuLog):
        log = segments[0]
    elif isinstance(segments, Sequence) and all(isinstance(s, ImuLog) for s in segments) and segments:
        raise ValueError(f"Expected `segments` to be one gap-free segment (an Allan deviation needs consecutive samples), got {len(segments)}: choose one")
    else:
        raise TypeError(f"Expected `segments` to be an ImuLog, got {type(segments).__name__}")
    p = in_open_interval(level, "level", 0.0, 1.0)
    if log.n_samples < 64:
        raise ValueError(f"Expected `segments` of at least 64 samples for an Allan deviation, got {log.n_samples}")
    budget.check(_ALLAN_SAMPLE.estimate(float(log.n_samples), what=f"`segments` = {log.n_samples:.3g} samples"), limits)
    h = log.dt
    return StaticNoise(_triad(log.dtheta, h, p), _triad(log.dv, h, p), log.n_samples * h, h, p)
