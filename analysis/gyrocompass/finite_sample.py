"""Finite-sample statistics of the estimates (16) under correlated rocking.

Hrechka & Koroliov estimate the stable tilt by the sample mean of n tilt
samples and the rocking variance by ``σ̂²_n = (1/n) Σ (x_k − x̄)²`` (16).  For
samples of a stationary process with autocorrelation ρ taken every h:

* ``Var x̄ = v σ²`` with ``v = (1/n) [1 + 2 Σ_{k<n} (1 − k/n) ρ(k h)]``
  (:func:`strapdown.analysis.gyrocompass.rocking.mean_variance_factor`): the
  mean of n correlated samples is worth ``n_eff = 1/v`` independent ones;
* ``E σ̂²_n = σ² (1 − v)`` exactly (``Σ (x_k − x̄)² = Σ x_k² − n x̄²``): the
  variance estimate of (16) is biased low by the fraction v, which is ``1/n``
  for independent samples and much more for slowly correlated rocking;
* a confidence interval for the stable tilt that holds for correlated samples
  is ``x̄ ± t_ν σ̂ √(v/(1 − v))``: the bias of σ̂² corrected, and Student's t
  with the effective degrees of freedom of σ̂² for a Gaussian process,
  ``ν = n (1 − v)² / [1 + 2 Σ_{k<n} (1 − k/n) ρ(kh)²]`` (Bartlett's
  approximation of ``2 (E σ̂²)² / Var σ̂²``), which is small when the record holds
  few correlation times; the interval of independent samples, ``x̄ ± z σ̂/√n``,
  is too narrow by ``√(n v/(1 − v))``;
  without a model of ρ, batch means (b batches much longer than the
  correlation time, ``x̄ ± t_{b−1} s_b/√b``) hold asymptotically;
* the averaging needed for an azimuth budget: the smallest n from which the
  first-order alignment rms ``√(Σ g_i² σ_i² v_i(n))`` stays within it.

References
----------
Hrechka & Koroliov, eq. (16); Cramér, H., *Mathematical Methods of Statistics*
(their reference [6]) for the independent case; Priestley, M. B., *Spectral
Analysis and Time Series*, Academic Press, 1981, sec. 5.3 (the variance of a
sample mean of a stationary process).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import budget as work
from ..core.validation import as_array, as_int, in_open_interval, positive
from .azimuth import check_latitude, gradient
from .rocking import GaussianRocking, SineRocking, mean_variance_factor

__all__ = ["SampleMeanStatistics", "sample_mean_statistics", "variance_factors", "MeanInterval", "mean_interval", "RequiredAveraging", "required_averaging", "INTERVAL_METHODS"]

INTERVAL_METHODS = ("model", "naive", "batch-means")


@dataclass(frozen=True)
class SampleMeanStatistics:
    """What n correlated samples give the estimates (16).

    Attributes
    ----------
    n_samples : int
        n.
    dt : float or None
        Sample interval [s] (None: independent samples).
    variance_factor : float
        ``v = Var x̄ / σ²``.
    effective_sample_size : float
        ``1/v``.
    variance_bias : float
        ``E σ̂²_n / σ² − 1 = −v``.
    naive_interval_ratio : float
        How much too narrow the independent-sample interval is, ``√(n v/(1 − v))``.
    variance_dof : float
        Effective degrees of freedom ν of σ̂² (``n − 1`` for independent samples, to ``O(1/n)``).
    """

    n_samples: int
    dt: float | None
    variance_factor: float
    effective_sample_size: float
    variance_bias: float
    naive_interval_ratio: float
    variance_dof: float


def sample_mean_statistics(model, n_samples: int, dt, *, axis: str = "xi", limits: work.Limits | None = None) -> SampleMeanStatistics:
    """Effective sample size and bias of the variance estimate of (16).

    Parameters
    ----------
    model : rocking model
        From :mod:`strapdown.analysis.gyrocompass.rocking`.
    n_samples : int
        Samples averaged, at least 2.
    dt : float or None
        Sample interval [s].
    axis : str
        ``"xi"`` or ``"eta"``.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    SampleMeanStatistics

    Raises
    ------
    ValueError
        For ``n_samples`` below 2 or beyond ``limits``.

    Examples
    --------
    Independent samples: the classic ``n_eff = n`` and bias ``−1/n``.

    >>> s = sample_mean_statistics(GaussianRocking(1.0, 1.0), 50, 0.1)
    >>> round(s.effective_sample_size, 9), round(s.variance_bias, 9), s.variance_dof
    (50.0, -0.02, 49.0)
    """
    n = as_int(n_samples, "n_samples", minimum=2)
    work.check(work.autocorrelation_sums(2, n, what=f"`n_samples` = {n:.3g} samples averaged"), limits)
    v = mean_variance_factor(model, n, dt, axis=axis, limits=limits)
    ratio = math.sqrt(n * v / (1.0 - v)) if v < 1.0 else math.inf
    return SampleMeanStatistics(n, dt, v, 1.0 / v if v > 0 else math.inf, -v, ratio, _variance_dof(model, n, dt, v, axis))


def _variance_dof(model, n, dt, v, axis) -> float:
    """Bartlett's effective degrees of freedom of the sample variance of a Gaussian process."""
    if dt is None or isinstance(model, GaussianRocking):
        return float(n - 1)
    k = np.arange(1, n, dtype=float)
    rho = model.autocorrelation(k * dt, axis=axis) if isinstance(model, SineRocking) else model.autocorrelation(k * dt)
    w = 1.0 + 2.0 * float(np.sum((1.0 - k / n) * rho * rho))
    return max(n * (1.0 - v) ** 2 / w, 1.0)


def variance_factors(model, max_samples: int, dt: float, *, axis: str = "xi", limits: work.Limits | None = None) -> np.ndarray:
    """``v(n)`` for every n = 1 … max_samples at once (cumulative sums of the autocorrelation).

    ``v(n) = (1/n) [1 + 2 S1(n) − (2/n) S2(n)]``, ``S1 = Σ_{k<n} ρ_k``, ``S2 = Σ_{k<n} k ρ_k``.

    Parameters
    ----------
    model : rocking model
        From :mod:`strapdown.analysis.gyrocompass.rocking`.
    max_samples : int
        Largest n.
    dt : float
        Sample interval [s].
    axis : str
        ``"xi"`` or ``"eta"``.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray
        ``(max_samples,)``, entry ``n − 1`` is v(n).

    Raises
    ------
    ValueError
        For ``max_samples`` below 1 or beyond ``limits``.
    """
    N = as_int(max_samples, "max_samples", minimum=1)
    work.check(work.arrays(N, what=f"`max_samples` = {N:.3g}", copies=10.0), limits)
    n = np.arange(1, N + 1, dtype=float)
    if isinstance(model, GaussianRocking):
        return 1.0 / n
    dt = positive(dt, "dt")
    k = np.arange(0, N, dtype=float)
    rho = model.autocorrelation(k * dt, axis=axis) if isinstance(model, SineRocking) else model.autocorrelation(k * dt)
    s1 = np.concatenate([[0.0], np.cumsum(rho[1:])])  # Σ_{1≤k<n}
    s2 = np.concatenate([[0.0], np.cumsum(k[1:] * rho[1:])])
    return np.maximum((1.0 + 2.0 * s1 - 2.0 * s2 / n) / n, 0.0)


@dataclass(frozen=True)
class MeanInterval:
    """Confidence interval of the stable tilt from samples (vectorised over leading axes).

    Attributes
    ----------
    estimate : ndarray
        Sample mean x̄ (16) [rad].
    low, high : ndarray
        Interval bounds [rad].
    standard_error : ndarray
        Estimated standard error of x̄ [rad].
    method : str
        ``"model"``, ``"naive"`` or ``"batch-means"``.
    level : float
        Coverage aimed at.
    """

    estimate: np.ndarray
    low: np.ndarray
    high: np.ndarray
    standard_error: np.ndarray
    method: str
    level: float

    def covers(self, value) -> np.ndarray:
        """Whether each interval contains ``value``.

        Parameters
        ----------
        value : array_like
            The true stable tilt(s) [rad].

        Returns
        -------
        ndarray of bool
        """
        value = np.asarray(value, dtype=float)
        return (self.low <= value) & (value <= self.high)


def mean_interval(samples, *, method: str = "model", model=None, dt=None, level: float = 0.95, batches: int = 10, axis: str = "xi") -> MeanInterval:
    """Confidence interval of the mean of tilt samples, correlated or not.

    Parameters
    ----------
    samples : array_like
        ``(..., n)`` tilt samples [rad] (time along the last axis).
    method : str
        ``"model"`` (correlation from ``model``; the variance estimate's bias
        corrected, Student's t with its effective degrees of freedom),
        ``"naive"`` (independent samples) or ``"batch-means"``.
    model : rocking model, optional
        Required for ``"model"``.
    dt : float or None
        Sample interval [s] (``"model"``).
    level : float
        Coverage in (0, 1).
    batches : int
        Number of batches (``"batch-means"``), at least 2.
    axis : str
        ``"xi"`` or ``"eta"`` (``"model"``).

    Returns
    -------
    MeanInterval

    Raises
    ------
    ValueError
        For an unknown method, a missing model or too few samples.
    """
    from scipy import stats

    x = as_array(samples, "samples")
    if x.ndim == 0 or x.shape[-1] < 2:
        raise ValueError(f"Expected `samples` with at least 2 samples on the last axis, got shape {x.shape}")
    if method not in INTERVAL_METHODS:
        raise ValueError(f"Expected `method` in {INTERVAL_METHODS}, got {method!r}")
    level = in_open_interval(level, "level", 0.0, 1.0)
    n = x.shape[-1]
    mean = x.mean(axis=-1)
    var = x.var(axis=-1)  # 1/n, as in (16)
    z = stats.norm.ppf(0.5 + level / 2)
    if method == "naive":
        se = np.sqrt(var / n)
    elif method == "model":
        if model is None:
            raise ValueError("Expected a rocking `model` for method 'model', got None")
        st = sample_mean_statistics(model, n, dt, axis=axis)
        v = st.variance_factor
        se = np.sqrt(var * v / (1.0 - v)) if v < 1.0 else np.full_like(mean, np.inf)
        z = stats.t.ppf(0.5 + level / 2, st.variance_dof)
    else:
        b = as_int(batches, "batches", minimum=2)
        m = n // b
        if m < 1:
            raise ValueError(f"Expected at most n = {n} batches, got {b}")
        bm = x[..., : b * m].reshape(x.shape[:-1] + (b, m)).mean(axis=-1)
        se = bm.std(axis=-1, ddof=1) / math.sqrt(b)
        z = stats.t.ppf(0.5 + level / 2, b - 1)
    return MeanInterval(mean, mean - z * se, mean + z * se, se, method, level)


@dataclass(frozen=True)
class RequiredAveraging:
    """Averaging needed by (16) for an azimuth budget (tilt channel, first order).

    Attributes
    ----------
    n_samples : int
        Smallest n from which the rms stays within the budget (0 if none up to the search limit).
    duration : float
        ``n·dt`` [s] (NaN if none).
    rms : float
        The first-order alignment rms at that n [rad].
    budget : float
        The budget [rad].
    """

    n_samples: int
    duration: float
    rms: float
    budget: float


def required_averaging(budget, latitude, model, dt: float, *, beta0: float = 0.0, gamma0: float = 0.0, max_samples: int = 200_000, limits: work.Limits | None = None) -> RequiredAveraging:
    """Smallest averaging of (16) from which the first-order alignment rms stays within a budget.

    Parameters
    ----------
    budget : float
        rms azimuth budget [rad].
    latitude : float
        Latitude φ [rad].
    model : rocking model
        From :mod:`strapdown.analysis.gyrocompass.rocking`.
    dt : float
        Sample interval [s].
    beta0, gamma0 : float
        Stable tilts [rad].
    max_samples : int
        Search limit.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    RequiredAveraging

    Raises
    ------
    ValueError
        For bad arguments, or a search limit beyond ``limits`` (naming ``max_samples``).

    Examples
    --------
    White rocking of σ = 1° at 45°: ``1°·tan 45°/√n ≤ 0.01°`` needs n = 10⁴.

    >>> from strapdown.analysis.gyrocompass.rocking import GaussianRocking
    >>> r = required_averaging(math.radians(0.01), math.radians(45), GaussianRocking(math.radians(1), 0.0), 0.1)
    >>> r.n_samples
    10000
    """
    budget = positive(budget, "budget")
    latitude = check_latitude(latitude)
    dt = positive(dt, "dt")
    g = gradient(latitude, beta0, gamma0)
    vx = variance_factors(model, max_samples, dt, axis="xi", limits=limits)
    ve = variance_factors(model, max_samples, dt, axis="eta", limits=limits)
    rms = np.sqrt(g.d_beta**2 * model.sigma_xi**2 * vx + g.d_gamma**2 * model.sigma_eta**2 * ve)
    worst_after = np.maximum.accumulate(rms[::-1])[::-1]  # max over m ≥ n
    ok = np.flatnonzero(worst_after <= budget * (1 + 1e-12))
    if ok.size == 0:
        return RequiredAveraging(0, math.nan, float(rms[-1]), budget)
    n = int(ok[0]) + 1
    return RequiredAveraging(n, n * dt, float(rms[n - 1]), budget)
