"""Sensor errors as a data sheet specifies them, their simulation, and their Allan deviation.

A data sheet gives each sensor's noise as the coefficients of its Allan
deviation (IEEE Std 952-1997, annex C):

==================  =========================  ==================================
term                coefficient (gyro/accel)   Allan variance σ²(τ)
==================  =========================  ==================================
random walk         N [rad/√s], [m/s/√s]       N²/τ
bias instability    B [rad/s], [m/s²]          (2 ln 2/π) B², flat (flicker noise)
rate random walk    K [rad/s/√s], [m/s²/√s]    K² τ/3
==================  =========================  ==================================

plus a turn-on bias (a constant per run) and, optionally, the output quantum.
Flicker noise has no finite-dimensional state model; it is approximated here
over a band of correlation times ``[τ_lo, τ_hi]`` by a sum of first-order
Gauss–Markov processes with log-spaced correlation times and equal variances
``(B²/π) ln r`` (r the ratio between neighbours): their spectra add up to
``B²/(π f)`` (one-sided) inside the band, whose Allan variance is the flat
floor.  The Allan variance of a Gauss–Markov term of variance q and correlation
time T is

    σ²(τ) = (2 q T²/τ²) [τ/T − 3/2 + 2 e^{−τ/T} − ½ e^{−2τ/T}]

(rate random walk for τ ≪ T, white for τ ≫ T), so :meth:`SensorSpec.allan_variance`
is the closed form of the model the simulation draws from.

:func:`simulate_sensor_errors` draws the error increments of every term
exactly over each sample interval (the integral of each first-order process
over the interval jointly with its end value, from the exact discretisation of
the pair), vectorised over trials, axes and samples;
:func:`allan_deviation` measures the overlapping Allan deviation of rate
samples with ``allantools`` and its confidence interval from Greenhall's
equivalent degrees of freedom; :func:`fit_allan` reads N, B and K back from a
measured curve (non-negative least squares on the three terms).

References
----------
IEEE Std 952-1997, *IEEE Standard Specification Format Guide and Test Procedure
for Single-Axis Interferometric Fiber Optic Gyros*, annex C (Allan variance).
El-Sheimy, N., Hou, H., Niu, X., "Analysis and modeling of inertial sensors
using Allan variance", *IEEE Trans. Instrum. Meas.* 57(1), 2008, 140–149.
Greenhall, C. A., Riley, W. J., "Uncertainty of stability variances based on
finite differences", *Proc. 35th PTTI Meeting*, 2003 (equivalent degrees of freedom).

Public API
----------
SensorSpec, DataSheet, GRADES, SensorErrorIncrements, simulate_sensor_errors,
add_sensor_errors, AllanDeviation, allan_deviation, AllanFit, fit_allan
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..core import budget, kalman
from ..core.units import DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S, rad_per_s
from ..core.validation import as_int, nonnegative, positive
from ..gyrocompass.rocking import as_generator
from . import kernels
from .imu import ImuRecord

__all__ = [
    "SensorSpec",
    "DataSheet",
    "GRADES",
    "SensorErrorIncrements",
    "simulate_sensor_errors",
    "add_sensor_errors",
    "AllanDeviation",
    "allan_deviation",
    "AllanFit",
    "fit_allan",
    "FLICKER_FLOOR",
]

#: Allan deviation floor of flicker noise per unit bias instability, √(2 ln 2/π) ≈ 0.664.
FLICKER_FLOOR = math.sqrt(2.0 * math.log(2.0) / math.pi)


@dataclass(frozen=True)
class SensorSpec:
    """One sensor triad (three identical axes) as a data sheet specifies it, SI units.

    Parameters
    ----------
    random_walk : float
        N: angle random walk [rad/√s] or velocity random walk [m/s/√s].
    bias_instability : float
        B: the flicker floor of the Allan deviation is ``0.664 B`` [rad/s or m/s²].
    rate_random_walk : float
        K [rad/s/√s or m/s²/√s].
    turn_on_bias : float
        Standard deviation of the constant bias of a run [rad/s or m/s²].
    flicker_band : tuple of float
        ``(τ_lo, τ_hi)``: correlation times spanned by the Gauss–Markov sum [s].
    terms_per_decade : int
        Gauss–Markov terms per decade of correlation time.
    """

    random_walk: float = 0.0
    bias_instability: float = 0.0
    rate_random_walk: float = 0.0
    turn_on_bias: float = 0.0
    flicker_band: tuple = (1.0, 3000.0)
    terms_per_decade: int = 3

    def __post_init__(self):
        for name in ("random_walk", "bias_instability", "rate_random_walk", "turn_on_bias"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))
        lo, hi = (positive(x, "flicker_band") for x in self.flicker_band)
        if not lo < hi:
            raise ValueError(f"Expected `flicker_band` as (τ_lo, τ_hi) with τ_lo < τ_hi [s], got {self.flicker_band}")
        object.__setattr__(self, "flicker_band", (lo, hi))
        object.__setattr__(self, "terms_per_decade", as_int(self.terms_per_decade, "terms_per_decade", minimum=1))

    def gauss_markov(self) -> tuple:
        """``(correlation_times [s], variances)`` of the Gauss–Markov terms that stand for the flicker noise.

        Returns
        -------
        tuple of ndarray
            Empty without bias instability.
        """
        if not self.bias_instability:
            return np.zeros(0), np.zeros(0)
        lo, hi = self.flicker_band
        k = max(1, int(math.ceil(self.terms_per_decade * math.log10(hi / lo))))
        taus = np.geomspace(lo, hi, k + 1)
        ratio = (hi / lo) ** (1.0 / k)
        return taus, np.full(taus.size, self.bias_instability**2 / math.pi * math.log(ratio))

    def allan_variance(self, tau) -> np.ndarray:
        """Allan variance of the model at averaging times τ (closed form, every term) [unit²].

        Parameters
        ----------
        tau : array_like
            Averaging times [s].

        Returns
        -------
        ndarray

        Examples
        --------
        Inside its band the Gauss–Markov sum has the flat floor of flicker noise, 0.664 B:

        >>> s = SensorSpec(bias_instability=1.0, flicker_band=(1.0, 1e5), terms_per_decade=4)
        >>> bool(abs(math.sqrt(float(s.allan_variance(300.0))) / FLICKER_FLOOR - 1.0) < 0.03)
        True
        """
        return sum(self.allan_terms(tau).values())

    def datasheet_allan_variance(self, tau) -> np.ndarray:
        """The data sheet's Allan variance: ``N²/τ + (0.664 B)² + K²τ/3`` at every τ (IEEE Std 952-1997, annex C) [unit²].

        The curve a data sheet's three numbers mean, with the flat flicker floor
        at every averaging time.  The simulated sensor has it only inside the
        band of its Gauss–Markov sum (:meth:`allan_variance` is the model's own
        curve, which falls below this one towards the band's ends).

        Parameters
        ----------
        tau : array_like
            Averaging times [s].

        Returns
        -------
        ndarray

        References
        ----------
        IEEE Std 952-1997, *IEEE Standard Specification Format Guide and Test
        Procedure for Single-Axis Interferometric Fiber Optic Gyros*, annex C
        (Allan variance: angle random walk, bias instability, rate random walk).

        >>> s = SensorSpec(bias_instability=1.0)
        >>> bool(abs(float(s.datasheet_allan_variance(1e6)) - FLICKER_FLOOR**2) < 1e-15)
        True
        """
        t = np.asarray(tau, dtype=float)
        return self.random_walk**2 / t + (FLICKER_FLOOR * self.bias_instability) ** 2 + self.rate_random_walk**2 * t / 3.0

    def allan_terms(self, tau) -> dict:
        """The Allan variance of each term at τ: ``"random walk"``, ``"flicker"`` (the Gauss–Markov sum), ``"rate random walk"``.

        Parameters
        ----------
        tau : array_like
            Averaging times [s].

        Returns
        -------
        dict of ndarray
        """
        t = np.asarray(tau, dtype=float)
        out = {"random walk": self.random_walk**2 / t, "flicker": np.zeros_like(t), "rate random walk": self.rate_random_walk**2 * t / 3.0}
        for T, q in zip(*self.gauss_markov()):
            out["flicker"] = out["flicker"] + 2.0 * q * _gm_shape(t / T)
        return out


def _gm_shape(x):
    """``[x − 3/2 + 2e^{−x} − ½e^{−2x}]/x²``, by its series below x = 0.05 (the closed form cancels there)."""
    x = np.asarray(x, dtype=float)
    small = x < 0.05
    xs = np.where(small, x, 0.05)
    series = xs * (1.0 / 3.0 + xs * (-1.0 / 4.0 + xs * (7.0 / 60.0 + xs * (-1.0 / 24.0 + xs * (31.0 / 2520.0 - xs * 1.0 / 320.0)))))
    xl = np.where(small, 1.0, x)
    closed = (xl + 2.0 * np.expm1(-xl) - 0.5 * np.expm1(-2.0 * xl)) / (xl * xl)
    return np.where(small, series, closed)


@dataclass(frozen=True)
class DataSheet:
    """Gyro and accelerometer triads of an IMU.

    Parameters
    ----------
    name : str
        Its grade or part name.
    gyro : SensorSpec
        The gyros [rad/s …].
    accel : SensorSpec
        The accelerometers [m/s² …].
    """

    name: str
    gyro: SensorSpec = field(default_factory=SensorSpec)
    accel: SensorSpec = field(default_factory=SensorSpec)


def _grade(name, gyro_bias_deg_h, arw_deg_rt_h, bi_deg_h, rrw_deg_h_rt_h, accel_bias, vrw_m_s_rt_h, accel_bi, accel_rrw):
    return DataSheet(
        name,
        SensorSpec(arw_deg_rt_h * DEG_PER_RT_H_TO_RAD_PER_RT_S, rad_per_s(bi_deg_h), rad_per_s(rrw_deg_h_rt_h) / 60.0, rad_per_s(gyro_bias_deg_h)),
        SensorSpec(vrw_m_s_rt_h * M_S_PER_RT_H_TO_M_S_PER_RT_S, accel_bi, accel_rrw / 60.0, accel_bias),
    )


#: Typical IMU grades (turn-on gyro bias; ARW; bias instability; RRW — and the accelerometers' counterparts),
#: the middle of the ranges of Groves (2013), table 4.1 and sec. 4.4; illustrations, not a vendor's figures.
GRADES = (
    _grade("marine", 0.001, 0.0005, 0.0005, 1e-4, 2e-5, 0.003, 1e-5, 1e-6),
    _grade("navigation", 0.01, 0.002, 0.005, 1e-3, 1e-4, 0.006, 5e-5, 1e-5),
    _grade("intermediate", 0.1, 0.01, 0.05, 1e-2, 5e-4, 0.02, 2e-4, 5e-5),
    _grade("tactical", 1.0, 0.05, 0.5, 0.1, 2e-3, 0.06, 1e-3, 2e-4),
)


@dataclass(frozen=True)
class SensorErrorIncrements:
    """Error increments of one sensor triad over ``n`` runs.

    Attributes
    ----------
    increments : ndarray
        ``(n, N, 3)`` the error added to each sample's increment [rad or m/s].
    turn_on : ndarray
        ``(n, 3)`` the turn-on bias of each run.
    mean_bias : ndarray
        ``(n, 3)`` the whole bias (turn-on, flicker, rate random walk) averaged over the record.
    """

    increments: np.ndarray
    turn_on: np.ndarray
    mean_bias: np.ndarray


def _first_order(g, shape, dt: float, tau: float, variance: float, compiled: bool | None = None, *, total=None, draws=None):
    """Exact increments ``∫ x dt`` over each interval of a stationary first-order process (or a random walk from zero).

    ``x' = −x/τ + w``; τ = inf is the random walk with ``E w² = variance`` per second.
    Returns ``(increments, mean level)``.  ``compiled``: the fused loop of
    :func:`~strapdown.analysis.alignment.kernels.first_order_loop` or the numpy form (None: whichever pays off,
    :func:`~strapdown.analysis.alignment.kernels.use_compiled`); both give the same bits.
    ``total``: an ``(n, N, k)`` array the increments are added to in place and that is
    returned in their stead (the same bits as ``total += increments``; compiled, in the pass that
    makes them, :func:`~strapdown.analysis.alignment.kernels.first_order_add`).  ``draws``: a ``(2, n, N, k)``
    array the unit draws are written into instead of a new one (the same draws).
    """
    from scipy.signal import lfilter

    n, N, k = shape
    if math.isinf(tau):
        A, Qc, x0 = np.array([[0.0, 0.0], [1.0, 0.0]]), np.diag([variance, 0.0]), np.zeros((n, 1, k))
    else:
        A, Qc = np.array([[-1.0 / tau, 0.0], [1.0, 0.0]]), np.diag([2.0 * variance / tau, 0.0])
        x0 = math.sqrt(variance) * g.standard_normal((n, 1, k))
    F, Q = kalman.discretise(A, Qc, dt)
    L = np.linalg.cholesky(Q + 1e-300 * np.eye(2))
    e = g.standard_normal((2, n, N, k)) if draws is None else g.standard_normal(out=draws)
    phi, c = F[0, 0], F[1, 0]
    if kernels.use_compiled(compiled, n * N * k):  # the same operations fused in one pass, equal to the last bit
        if total is not None and k > 1:  # numpy sums over the samples in order only for k > 1 (pairwise for k = 1)
            return total, kernels.first_order_add(e, x0, phi, c, L, total) / (N * dt)
        inc = kernels.first_order_loop(e, x0, phi, c, L)
    else:
        e1, e2 = L[0, 0] * e[0], L[1, 0] * e[0] + L[1, 1] * e[1]
        # x_{j+1} = φ x_j + e1_j from x_0: the levels at the interval starts
        drive = np.concatenate([x0, e1[:, :-1]], axis=1)
        x = lfilter([1.0], [1.0, -phi], drive, axis=1)
        inc = c * x + e2
    mean = inc.sum(axis=1) / (N * dt)
    if total is None:
        return inc, mean
    total += inc
    return total, mean


def simulate_sensor_errors(spec: SensorSpec, *, n_trials: int, n_samples: int, dt: float, rng=None, limits: budget.Limits | None = None) -> SensorErrorIncrements:
    """Draw the error increments of a sensor triad: turn-on bias, random walk, flicker (Gauss–Markov sum), rate random walk.

    Parameters
    ----------
    spec : SensorSpec
        The data sheet.
    n_trials : int, keyword-only
        Independent runs.
    n_samples : int, keyword-only
        Samples per run.
    dt : float, keyword-only
        Sample interval [s].
    rng : Generator | SeedSequence | int | None, keyword-only
        Random stream.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    SensorErrorIncrements

    Raises
    ------
    ValueError
        Sizes below 1, a non-positive ``dt``, or increments beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``n_trials`` and ``n_samples``).

    Examples
    --------
    White noise of N √h per increment:

    >>> e = simulate_sensor_errors(SensorSpec(random_walk=2.0), n_trials=1, n_samples=40000, dt=0.25, rng=1)
    >>> round(float(e.increments.std()) / (2.0 * 0.5), 1)
    1.0
    """
    if not isinstance(spec, SensorSpec):
        raise TypeError(f"Expected `spec` to be a SensorSpec, got {type(spec).__name__}")
    n, N = as_int(n_trials, "n_trials", minimum=1), as_int(n_samples, "n_samples", minimum=1)
    h = positive(dt, "dt")
    terms = list(zip(*spec.gauss_markov()))
    if spec.rate_random_walk:
        terms.append((math.inf, spec.rate_random_walk**2))
    n_terms = len(terms) + int(bool(spec.random_walk))
    what = f"`n_trials` = {n:.3g} runs of `n_samples` = {N:.3g} samples ({3.0 * n * N:.3g} elements, {n_terms} noise terms)"
    budget.check(budget.sensor_errors(3.0 * n * N, n_terms, what=what), limits)
    g = as_generator(rng)
    turn_on = spec.turn_on_bias * g.standard_normal((n, 3))
    inc = np.broadcast_to(turn_on[:, None, :] * h, (n, N, 3)).copy()
    mean = turn_on.copy()
    if spec.random_walk:
        inc += spec.random_walk * math.sqrt(h) * g.standard_normal((n, N, 3))
    # every term's draws in one buffer, its increments added to `inc` as they are made (the same bits
    # as a new array per term): no (2, n, N, 3) and (n, N, 3) temporaries per term
    draws = np.empty((2, n, N, 3)) if terms else None
    for tau, q in terms:
        _, m = _first_order(g, (n, N, 3), h, float(tau), float(q), total=inc, draws=draws)
        mean += m
    return SensorErrorIncrements(inc, turn_on, mean)


def add_sensor_errors(record: ImuRecord, sheet: DataSheet, *, rng=None) -> ImuRecord:
    """A record with a data sheet's errors added to its increments (its biases: each run's whole bias averaged over the record).

    Parameters
    ----------
    record : ImuRecord
        Usually ideal (:func:`strapdown.analysis.alignment.imu.simulate_imu` without errors).
    sheet : DataSheet
        The IMU.
    rng : Generator | SeedSequence | int | None, keyword-only
        Random stream.

    Returns
    -------
    ImuRecord
    """
    g = as_generator(rng)
    n, N, _ = record.dtheta.shape
    dt = record.scenario.dt
    gy = simulate_sensor_errors(sheet.gyro, n_trials=n, n_samples=N, dt=dt, rng=g)
    ac = simulate_sensor_errors(sheet.accel, n_trials=n, n_samples=N, dt=dt, rng=g)
    return replace(record, dtheta=record.dtheta + gy.increments, dv=record.dv + ac.increments, gyro_bias=record.gyro_bias + gy.mean_bias, accel_bias=record.accel_bias + ac.mean_bias)


@dataclass(frozen=True)
class AllanDeviation:
    """A measured overlapping Allan deviation with its confidence interval.

    Attributes
    ----------
    taus : ndarray
        Averaging times [s].
    adev : ndarray
        Allan deviation [unit].
    low, high : ndarray
        Ends of the confidence interval.
    edf : ndarray
        Equivalent degrees of freedom of each point.
    level : float
        Coverage of the interval.
    """

    taus: np.ndarray
    adev: np.ndarray
    low: np.ndarray
    high: np.ndarray
    edf: np.ndarray
    level: float


def allan_deviation(rates, dt: float, *, spec: SensorSpec | None = None, level: float = 0.95, taus="octave") -> AllanDeviation:
    """Overlapping Allan deviation of rate samples (``allantools.oadev``) with its confidence interval.

    Parameters
    ----------
    rates : array_like
        ``(N,)`` rate samples (increments over dt) [unit].
    dt : float
        Sample interval [s].
    spec : SensorSpec, optional, keyword-only
        The model whose dominant term at each τ sets the noise type of the
        interval (Greenhall's equivalent degrees of freedom); default white noise throughout.
    level : float, keyword-only
        Coverage of the interval.
    taus : str or array_like, keyword-only
        ``allantools`` τ selection (default octaves).

    Returns
    -------
    AllanDeviation

    References
    ----------
    Greenhall & Riley (2003) (the degrees of freedom); ``allantools`` (oadev, edf_greenhall).
    """
    import allantools

    x = np.asarray(rates, dtype=float).ravel()
    h = positive(dt, "dt")
    t, adev, _, _ = allantools.oadev(x, rate=1.0 / h, data_type="freq", taus=taus)
    lo, hi, dof = np.empty_like(adev), np.empty_like(adev), np.empty_like(adev)
    for i, (tau, dev) in enumerate(zip(t, adev)):
        alpha = 0
        if spec is not None:
            terms = spec.allan_terms(tau)
            alpha = {"random walk": 0, "flicker": -1, "rate random walk": -2}[max(terms, key=lambda k: float(terms[k]))]
        m = int(round(tau / h))
        dof[i] = allantools.edf_greenhall(alpha=alpha, d=2, m=m, N=x.size + 1, overlapping=True, modified=False)
        lo[i], hi[i] = allantools.confidence_interval(dev, dof[i], ci=level)
    return AllanDeviation(np.asarray(t), np.asarray(adev), lo, hi, dof, float(level))


@dataclass(frozen=True)
class AllanFit:
    """The three data-sheet coefficients read back from an Allan deviation.

    Attributes
    ----------
    random_walk : float
        N [unit·√s].
    bias_instability : float
        B [unit] (the floor over 0.664).
    rate_random_walk : float
        K [unit/√s].
    """

    random_walk: float
    bias_instability: float
    rate_random_walk: float


def fit_allan(taus, adev, *, weights=None) -> AllanFit:
    """N, B and K of ``σ²(τ) = N²/τ + (2 ln 2/π) B² + K² τ/3`` fitted to a measured Allan deviation.

    Non-negative least squares on the Allan variance, each point divided by its
    own value (relative errors), so that every decade of τ counts alike, and
    weighted by ``weights`` (its degrees of freedom, so that the few long
    clusters of the largest τ count little).

    Parameters
    ----------
    taus, adev : array_like
        The measured curve [s, unit].
    weights : array_like, optional, keyword-only
        Relative weights of the points (e.g. their degrees of freedom).

    Returns
    -------
    AllanFit

    Examples
    --------
    >>> t = np.geomspace(0.1, 1e4, 30)
    >>> fit = fit_allan(t, np.sqrt(4.0 / t + FLICKER_FLOOR**2 * 0.09 + 1e-6 * t / 3.0))
    >>> [round(x, 6) for x in (fit.random_walk, fit.bias_instability, fit.rate_random_walk)]
    [2.0, 0.3, 0.001]
    """
    from scipy.optimize import nnls

    t = np.asarray(taus, dtype=float)
    v = np.asarray(adev, dtype=float) ** 2
    w = np.ones_like(t) if weights is None else np.sqrt(np.asarray(weights, dtype=float))
    X = np.stack([1.0 / t, np.full_like(t, FLICKER_FLOOR**2), t / 3.0], axis=1) / v[:, None] * w[:, None]
    c, _ = nnls(X, w)
    return AllanFit(*(float(math.sqrt(x)) for x in c))
