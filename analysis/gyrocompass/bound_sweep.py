"""Cross-check sweep: where bounds (14) and (15) of Hrechka & Koroliov hold, and by how much.

A sweep is a list of :class:`SweepCase` (latitude, rocking amplitude,
distribution, correlation, stable tilts, estimate), all angles in radians.
Case ``i`` runs its Monte Carlo serially from the ``i``-th child of the root
SeedSequence, so a sweep gives bit-identical numbers whether it runs serially,
on a :class:`concurrent.futures.ProcessPoolExecutor` or on a
``dask.distributed`` cluster (pass the ``Client`` as ``executor``).

Two estimates are compared with different yardsticks:

``"known"``
    the error (12) at independent instants, against the bounds (14), (15) at
    the variances of the rocking (what the paper bounds);
``"sample-mean"``
    the alignment error ``σ(β̂0, γ̂0) − σ(β0, γ0)`` of the estimate (16) over
    an averaging time, against (14) and (15) evaluated with the variances of
    the *means* (``Dξ → v Dξ``, :func:`strapdown.analysis.gyrocompass.rocking.mean_variance_factor`):
    the bound that applies to the error of a mean.  The paper's own
    prescription (14) with the sample variances of (16) bounds the
    instantaneous error, not the error of the mean; it is kept as
    ``plugin14`` to show by how much it overstates.

With ``control_degree ≥ 1`` each case is a control-variate Monte Carlo whose
standard errors are at most those of a plain one of ``n_samples`` rocking
samples, from far fewer draws.  The error of (12) takes the monomials of the
rocking as controls (:class:`strapdown.analysis.gyrocompass.azimuth.TaylorControls`).
The alignment error of (16) depends on a record only through its sample means,
whose law is exact (:func:`strapdown.analysis.gyrocompass.rocking.mean_law`):
it is drawn from that law, with the monomials of the means as controls; the
plug-in (14) needs the sample variances as well, so its records are simulated,
with the sample variances (exact mean ``(1 − v) σ²``) as controls, their
coefficients the derivatives of (14)².
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import budget, montecarlo
from ..core.validation import as_array, as_int, nonnegative, positive
from .azimuth import AzimuthErrorKernel, ControlVariateSummary, azimuth_monte_carlo, bound14, bound14_squared, bound15, check_latitude, gradient, second_order_theory
from .rocking import mean_law, mean_variance_factor, rocking_model

__all__ = ["SweepCase", "SweepRow", "ValidityMap", "evaluate_case", "sweep", "grid_cases", "validity_map", "first_order_alignment_rms", "local_cluster"]

_MODELS = ("normal", "sine", "narrowband")
_ESTIMATES = ("known", "sample-mean")


@dataclass(frozen=True)
class SweepCase:
    """One configuration of the sweep (angles in rad, times in s).

    Parameters
    ----------
    latitude : float
        Latitude φ [rad], ``|φ|`` < π/2.
    sigma : float
        Standard deviation of ξ and of η [rad], ≥ 0.
    model : str
        ``"normal"``, ``"sine"`` or ``"narrowband"``.
    beta0, gamma0 : float
        Stable tilts [rad].
    period : float
        Rocking period [s] (sine, narrowband).
    damping : float
        Damping ratio of narrow-band rocking, in (0, 1).
    estimate : str
        ``"known"`` (the error (12) at independent instants) or
        ``"sample-mean"`` (the alignment error of (16)).
    averaging_time : float
        Averaging time of (16) [s] (sample-mean).
    dt : float
        Sample interval [s] (sample-mean).
    """

    latitude: float
    sigma: float
    model: str = "normal"
    beta0: float = 0.0
    gamma0: float = 0.0
    period: float = 8.0
    damping: float = 0.1
    estimate: str = "known"
    averaging_time: float = 30.0
    dt: float = 0.1

    def __post_init__(self):
        object.__setattr__(self, "latitude", check_latitude(self.latitude))
        object.__setattr__(self, "sigma", nonnegative(self.sigma, "sigma"))
        if self.model not in _MODELS:
            raise ValueError(f"Expected `model` in {_MODELS}, got {self.model!r}")
        if self.estimate not in _ESTIMATES:
            raise ValueError(f"Expected `estimate` in {_ESTIMATES}, got {self.estimate!r}")
        positive(self.averaging_time, "averaging_time")
        positive(self.dt, "dt")

    def rocking(self):
        """The rocking model of the case (equal standard deviations on both axes).

        Returns
        -------
        GaussianRocking | SineRocking | NarrowbandRocking
        """
        return rocking_model(self.model, self.sigma, self.sigma, period=self.period, damping=self.damping)

    @property
    def n_steps(self) -> int:
        """Samples averaged by (16) (sample-mean cases)."""
        return max(2, int(round(self.averaging_time / self.dt)))


@dataclass(frozen=True)
class SweepRow:
    """Monte Carlo of one case with its bounds and theory (angles in rad).

    Attributes
    ----------
    case : SweepCase
        The configuration.
    rms, rms_lo, rms_hi : float
        Monte Carlo rms error and its 95 % interval.
    mean : float
        Monte Carlo mean error.
    bound14, bound15 : float
        The bounds that apply to the estimate: at the rocking variances
        (known tilts) or at the variances of the means (sample mean).
    theory_rms, theory_rms_first_order, theory_bias : float
        Second-order theory of the same error.
    plugin14 : float or None
        Sample-mean cases: rms of (14) evaluated as the paper prescribes after
        (16), with the sample means and sample variances; None otherwise.
    controls : ControlVariateSummary or None
        The control variates behind ``rms`` and ``mean`` (None: plain Monte Carlo).
    plugin_controls : ControlVariateSummary or None
        The control variates behind ``plugin14`` (sample-mean cases with control variates).
    """

    case: SweepCase
    rms: float
    rms_lo: float
    rms_hi: float
    mean: float
    bound14: float
    bound15: float
    theory_rms: float
    theory_rms_first_order: float
    theory_bias: float
    plugin14: float | None = None
    controls: ControlVariateSummary | None = None
    plugin_controls: ControlVariateSummary | None = None

    def covers(self, bound: float) -> str:
        """``"holds"``, ``"fails"`` or ``"undecided"``: the 95 % interval of the rms against ``bound``.

        Parameters
        ----------
        bound : float
            Bound on the rms [rad].

        Returns
        -------
        str
        """
        if self.rms_hi <= bound:
            return "holds"
        if self.rms_lo > bound:
            return "fails"
        return "undecided"


def evaluate_case(case: SweepCase, n_samples: int, seed, *, control_degree: int = 0, limits: budget.Limits | None = None) -> SweepRow:
    """Monte Carlo of one case with its bounds and theory (angles in rad).

    Parameters
    ----------
    case : SweepCase
        The configuration.
    n_samples : int
        Rocking samples (known tilt) or trials × steps (sample mean); with
        control variates, those of the plain Monte Carlo whose precision is matched.
    seed : SeedSequence | int
        The case's random stream.
    control_degree : int
        0: plain Monte Carlo; else the degree of the Taylor control variates.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s, on one
        core); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    SweepRow

    Raises
    ------
    ValueError
        For bad arguments, or a run beyond ``limits`` (naming ``n_samples``).
    """
    n_samples = as_int(n_samples, "n_samples", minimum=2)
    budget.check(budget.monte_carlo(n_samples, what=f"`n_samples` = {n_samples:.3g} rocking samples"), limits)
    rocking = case.rocking()
    control_degree = as_int(control_degree, "control_degree", minimum=0)
    if case.estimate == "known":
        # a row keeps the moments only: no quantiles (the same draws and moments either way)
        mc = azimuth_monte_carlo(case.latitude, case.beta0, case.gamma0, rocking, n_samples, rng=seed, steps_per_trial=256, control_degree=control_degree, quantiles=())
        r, th = mc.result, mc.theory
        return SweepRow(case, r.rms, r.rms_ci[0], r.rms_ci[1], r.mean, mc.bound14, mc.bound15, th.rms, th.rms_first_order, th.bias, controls=mc.controls)
    n_steps = case.n_steps
    if control_degree:
        root = montecarlo.root_seed_sequence(seed)
        n_trials = max(2, n_samples // n_steps)
        mc = azimuth_monte_carlo(case.latitude, case.beta0, case.gamma0, mean_law(rocking, n_steps, case.dt), n_trials, rng=montecarlo.block_seed(root, 0), control_degree=control_degree, quantiles=())
        plugin, plugin_controls = _controlled_plugin14(case, n_trials, montecarlo.block_seed(root, 1))
        r, th = mc.result, mc.theory
        return SweepRow(
            case, r.rms, r.rms_ci[0], r.rms_ci[1], r.mean, mc.bound14, mc.bound15, th.rms, th.rms_first_order, th.bias, plugin14=plugin, controls=mc.controls, plugin_controls=plugin_controls
        )
    kernel = AzimuthErrorKernel(case.latitude, case.beta0, case.gamma0, rocking, n_steps=n_steps, dt=case.dt, estimate="sample-mean")
    sx = rocking.sigma_xi * math.sqrt(mean_variance_factor(rocking, n_steps, case.dt, axis="xi"))
    se = rocking.sigma_eta * math.sqrt(mean_variance_factor(rocking, n_steps, case.dt, axis="eta"))
    th = second_order_theory(case.latitude, case.beta0, case.gamma0, sx, se, kappa_xi=rocking.kappa, kappa_eta=rocking.kappa)
    r = montecarlo.run(kernel, max(2, n_samples // n_steps), rng=seed, trials_per_block=max(1, 65536 // n_steps), scale=max(th.rms_first_order, 1e-12), quantiles=())
    b14 = bound14(case.latitude, case.beta0, case.gamma0, sx, se)
    b15 = bound15(case.latitude, sx)
    return SweepRow(case, r.rms, r.rms_ci[0], r.rms_ci[1], r.mean, b14, b15, th.rms, th.rms_first_order, th.bias, plugin14=math.sqrt(r.aux_mean[0]))


#: fewest records of the controlled plug-in (14), and the margin of a larger redraw
_PLUGIN_MIN = 24
_PLUGIN_MARGIN = 1.5


@dataclass(frozen=True)
class _PluginKernel:
    """Per record: (14)² with the sample means and variances of (16), and the sample variances minus their exact means."""

    case: SweepCase
    var_mean_xi: float
    var_mean_eta: float

    def __call__(self, n_trials, rng):
        c = self.case
        xi, eta = c.rocking().sample(rng, n_trials, c.n_steps, c.dt)
        dxi, deta = xi.var(axis=1), eta.var(axis=1)  # 1/n normalisation, as in (16)
        b14sq = np.broadcast_to(bound14_squared(c.latitude, c.beta0 + xi.mean(axis=1), c.gamma0 + eta.mean(axis=1), dxi, deta), dxi.shape)
        return np.stack([b14sq, dxi - self.var_mean_xi, deta - self.var_mean_eta], axis=1)


def _controlled_plugin14(case: SweepCase, n_trials: int, seed):
    """rms of the plug-in (14) with the sample variances as controls: ``(value [rad], ControlVariateSummary)``.

    ``E σ̂² = (1 − v) σ²`` exactly (:mod:`strapdown.analysis.gyrocompass.finite_sample`).
    The coefficients are fixed in advance: the derivatives of (14)² with
    respect to the two variances at the stable tilts and the expected sample
    variances, so the estimate is unbiased without a pilot.  The run starts
    with ``_PLUGIN_MIN`` records and is redrawn larger until its standard
    error is at most that of a plain run of ``n_trials`` records.
    """
    rocking = case.rocking()
    means = [s * s * (1.0 - mean_variance_factor(rocking, case.n_steps, case.dt, axis=a)) for s, a in ((rocking.sigma_xi, "xi"), (rocking.sigma_eta, "eta"))]
    kernel = _PluginKernel(case, *means)

    def plug_in(dxi, deta):
        return float(bound14_squared(case.latitude, case.beta0, case.gamma0, dxi, deta))

    offset = plug_in(*means)
    c = np.zeros(2)
    for k, m in enumerate(means):
        if m > 0.0:
            h = 1e-3 * m
            c[k] = (plug_in(*(m + h if j == k else x for j, x in enumerate(means))) - plug_in(*(m - h if j == k else x for j, x in enumerate(means)))) / (2.0 * h)
    size, root = _PLUGIN_MIN, montecarlo.root_seed_sequence(seed)
    for attempt in range(4):
        rows = montecarlo.collect(kernel, size, rng=root, trials_per_block=64)
        z = rows[:, 0] - montecarlo.combine(rows[:, 1:], c) - offset
        var_z, var_plain = float(z.var(ddof=1)), float(rows[:, 0].var(ddof=1))
        worth = size * var_plain / var_z if var_z > 0.0 else math.inf
        if worth >= n_trials or attempt == 3:
            break
        size = math.ceil(size * _PLUGIN_MARGIN * n_trials / worth)
    value = offset + float(z.mean())
    return math.sqrt(max(value, 0.0)), ControlVariateSummary(1, 0, size, n_trials, worth)


@dataclass(frozen=True)
class _CaseTask:
    case: SweepCase
    n_samples: int
    entropy: object
    spawn_key: tuple
    index: int
    control_degree: int = 0

    def __call__(self):
        root = np.random.SeedSequence(self.entropy, spawn_key=self.spawn_key)
        return evaluate_case(self.case, self.n_samples, montecarlo.block_seed(root, self.index), control_degree=self.control_degree)


def sweep(cases, *, n_samples: int, rng=None, executor=None, progress: bool = False, control_degree: int = 0, limits: budget.Limits | None = None) -> list:
    """Evaluate every case; the rows come back in case order.

    Parameters
    ----------
    cases : sequence of SweepCase
        The configurations.
    n_samples : int
        Rocking samples per case, at least 2.
    rng : Generator | SeedSequence | int | None
        Root of the per-case streams.
    executor : Executor | dask Client | None
        Where cases run (does not change the result).
    progress : bool
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).
    control_degree : int
        0: plain Monte Carlo; else the degree of the control variates (see
        :func:`evaluate_case`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s, on one
        core); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    list of SweepRow

    Raises
    ------
    ValueError
        For bad arguments, no case, or a sweep beyond ``limits`` (naming ``n_samples``).
    """
    n_samples = as_int(n_samples, "n_samples", minimum=2)
    control_degree = as_int(control_degree, "control_degree", minimum=0)
    root = montecarlo.root_seed_sequence(rng)
    cases = list(cases)
    if not cases:
        raise ValueError("Expected at least one case in `cases`, got none")
    budget.check(budget.monte_carlo(len(cases) * n_samples, what=f"`n_samples` = {n_samples:.3g} rocking samples in each of {len(cases)} cases"), limits)
    for c in cases:
        if not isinstance(c, SweepCase):
            raise TypeError(f"Expected `cases` of SweepCase, got {type(c).__name__}")
    tasks = [_CaseTask(c, n_samples, root.entropy, tuple(root.spawn_key), i, control_degree) for i, c in enumerate(cases)]
    return montecarlo.map_tasks(executor, tasks, progress=progress, desc="azimuth sweep")


def grid_cases(latitudes, sigmas, **fields) -> list:
    """Cases on the latitude × amplitude grid (latitude-major order).

    Parameters
    ----------
    latitudes : array_like
        Latitudes [rad].
    sigmas : array_like
        Rocking standard deviations [rad].
    **fields
        The other :class:`SweepCase` fields, fixed for the grid.

    Returns
    -------
    list of SweepCase
    """
    return [SweepCase(float(lat), float(s), **fields) for lat in np.ravel(latitudes) for s in np.ravel(sigmas)]


@dataclass(frozen=True)
class ValidityMap:
    """A sweep on the latitude × amplitude grid, as arrays (latitude rows, amplitude columns).

    Attributes
    ----------
    latitudes : ndarray
        Grid latitudes [rad].
    sigmas : ndarray
        Grid standard deviations [rad].
    rows : tuple of SweepRow
        The cases in latitude-major order.
    ratio14, ratio15 : ndarray
        Monte Carlo rms over bound (14), (15) (NaN where the bound is 0).
    holds14, fails14, holds15, fails15 : ndarray of bool
        The 95 % decisions of :meth:`SweepRow.covers`.
    """

    latitudes: np.ndarray
    sigmas: np.ndarray
    rows: tuple
    ratio14: np.ndarray
    ratio15: np.ndarray
    holds14: np.ndarray
    fails14: np.ndarray
    holds15: np.ndarray
    fails15: np.ndarray

    @property
    def plugin_ratio14(self) -> np.ndarray:
        """Monte Carlo rms over the paper's plug-in (14) (sample-mean maps; NaN otherwise)."""
        return self._grid([r.rms / r.plugin14 if r.plugin14 else math.nan for r in self.rows])

    def _grid(self, values):
        return np.array(values, dtype=float).reshape(len(self.latitudes), len(self.sigmas))


def validity_map(latitudes, sigmas, *, n_samples: int, rng=None, executor=None, progress: bool = False, control_degree: int = 0, limits: budget.Limits | None = None, **fields) -> ValidityMap:
    """Sweep the latitude × amplitude grid and classify bounds (14), (15) in every cell.

    Parameters
    ----------
    latitudes : array_like
        Grid latitudes [rad].
    sigmas : array_like
        Grid standard deviations of ξ and η [rad].
    n_samples : int
        Rocking samples per cell.
    rng : Generator | SeedSequence | int | None
        Root of the per-cell streams.
    executor : Executor | dask Client | None
        Where cells run (does not change the result).
    progress : bool
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).
    control_degree : int
        0: plain Monte Carlo; else the degree of the control variates (see
        :func:`evaluate_case`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s, on one
        core); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.
    **fields
        The other :class:`SweepCase` fields.

    Returns
    -------
    ValidityMap

    Raises
    ------
    ValueError
        For an empty grid, bad fields, or a sweep beyond ``limits`` (as :func:`sweep`).
    """
    lats, sig = as_array(latitudes, "latitudes").ravel(), as_array(sigmas, "sigmas").ravel()
    for name, values in (("latitudes", lats), ("sigmas", sig)):
        if values.size == 0:
            raise ValueError(f"Expected at least one value in `{name}`, got an empty array")
    rows = tuple(sweep(grid_cases(lats, sig, **fields), n_samples=n_samples, rng=rng, executor=executor, progress=progress, control_degree=control_degree, limits=limits))
    shape = (len(lats), len(sig))

    def grid(values, dtype=float):
        return np.array(values, dtype=dtype).reshape(shape)

    return ValidityMap(
        latitudes=lats,
        sigmas=sig,
        rows=rows,
        ratio14=grid([r.rms / r.bound14 if r.bound14 > 0 else math.nan for r in rows]),
        ratio15=grid([r.rms / r.bound15 if r.bound15 > 0 else math.nan for r in rows]),
        holds14=grid([r.covers(r.bound14) == "holds" for r in rows], bool),
        fails14=grid([r.covers(r.bound14) == "fails" for r in rows], bool),
        holds15=grid([r.covers(r.bound15) == "holds" for r in rows], bool),
        fails15=grid([r.covers(r.bound15) == "fails" for r in rows], bool),
    )


def first_order_alignment_rms(case: SweepCase) -> float:
    """First-order rms of the alignment error of (16) for a sample-mean case [rad].

    Parameters
    ----------
    case : SweepCase
        A case (its averaging time and sample interval are used).

    Returns
    -------
    float
    """
    rocking = case.rocking()
    g = gradient(case.latitude, case.beta0, case.gamma0)
    vx = mean_variance_factor(rocking, case.n_steps, case.dt, axis="xi")
    ve = mean_variance_factor(rocking, case.n_steps, case.dt, axis="eta")
    return math.sqrt(g.d_beta**2 * rocking.sigma_xi**2 * vx + g.d_gamma**2 * rocking.sigma_eta**2 * ve)


def local_cluster(n_workers: int = 2):
    """A ``dask.distributed`` Client on a local cluster (the ``distributed`` extra).

    Parameters
    ----------
    n_workers : int
        Worker processes.

    Returns
    -------
    distributed.Client

    Raises
    ------
    ImportError
        If ``dask.distributed`` is not installed (``pip install 'strapdown-analysis[distributed]'``).
    """
    try:
        from distributed import Client, LocalCluster
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("the dask sweep needs the `distributed` extra: pip install 'strapdown-analysis[distributed]'") from exc
    cluster = LocalCluster(n_workers=as_int(n_workers, "n_workers", minimum=1), threads_per_worker=1, dashboard_address=None, processes=True)
    return Client(cluster)

