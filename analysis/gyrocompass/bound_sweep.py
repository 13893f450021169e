"""Cross-check sweep: where bounds (14) and (15) of Hrechka & Koroliov hold, and by how much.

A sweep is a list of :class:`SweepCase` (latitude, rocking amplitude,
distribution, correlation, stable tilts, estimate).  Case ``i`` runs its Monte
Carlo serially from the ``i``-th child of the root SeedSequence, so a sweep
gives bit-identical numbers whether it runs serially, on a
:class:`concurrent.futures.ProcessPoolExecutor` or on a ``dask.distributed``
cluster (pass the ``Client`` as ``executor``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import montecarlo
from ..core.validation import as_int
from .azimuth import AzimuthErrorKernel, azimuth_monte_carlo, bound14, bound15, gradient, second_order_theory
from .rocking import mean_variance_factor, rocking_model

__all__ = ["SweepCase", "evaluate_case", "sweep", "grid_cases", "local_cluster"]


@dataclass(frozen=True)
class SweepCase:
    """One configuration of the sweep (angles in degrees, times in seconds).

    ``estimate="known"``: the error (12) at independent instants;
    ``estimate="sample-mean"``: the alignment error of (16) from
    ``averaging_time`` of samples every ``dt``.
    """

    latitude_deg: float
    sigma_deg: float
    model: str = "normal"
    beta0_deg: float = 0.0
    gamma0_deg: float = 0.0
    period: float = 8.0
    damping: float = 0.1
    estimate: str = "known"
    averaging_time: float = 30.0
    dt: float = 0.1

    def rocking(self):
        s = math.radians(self.sigma_deg)
        return rocking_model(self.model, s, s, period=self.period, damping=self.damping)


def evaluate_case(case: SweepCase, n_samples: int, seed) -> dict:
    """Monte Carlo of one case with its bounds and theory (angles in rad).

    Parameters
    ----------
    case : SweepCase
    n_samples : int — rocking samples (known tilt) or trials × steps (sample mean)
    seed : SeedSequence | int — the case's random stream

    Returns
    -------
    dict
        ``rms, rms_lo, rms_hi, mean, bound14, bound15, theory_rms,
        theory_rms_first_order, theory_bias`` and, for the sample-mean case,
        ``plugin14, plugin15`` (the bounds with the estimates of (16)).
    """
    lat, b0, g0 = math.radians(case.latitude_deg), math.radians(case.beta0_deg), math.radians(case.gamma0_deg)
    rocking = case.rocking()
    row = {}
    if case.estimate == "known":
        mc = azimuth_monte_carlo(lat, b0, g0, rocking, n_samples, rng=seed, steps_per_trial=256)
        r, th = mc.result, mc.theory
        b14, b15 = mc.bound14, mc.bound15
    else:
        n_steps = max(2, int(round(case.averaging_time / case.dt)))
        kernel = AzimuthErrorKernel(lat, b0, g0, rocking, n_steps=n_steps, dt=case.dt, estimate="sample-mean")
        vx = mean_variance_factor(rocking, n_steps, case.dt, axis="xi")
        ve = mean_variance_factor(rocking, n_steps, case.dt, axis="eta")
        th = second_order_theory(lat, b0, g0, rocking.sigma_xi * math.sqrt(vx), rocking.sigma_eta * math.sqrt(ve), kappa_xi=rocking.kappa, kappa_eta=rocking.kappa)
        n_trials = max(2, n_samples // n_steps)
        r = montecarlo.run(kernel, n_trials, rng=seed, trials_per_block=max(1, 65536 // n_steps), scale=max(th["rms_first_order"], 1e-12))
        b14 = bound14(lat, b0, g0, rocking.sigma_xi, rocking.sigma_eta)
        b15 = bound15(lat, rocking.sigma_xi)
        row["plugin14"], row["plugin15"] = math.sqrt(r.aux_mean[0]), math.sqrt(r.aux_mean[1])
    row.update(
        rms=r.rms,
        rms_lo=r.rms_ci[0],
        rms_hi=r.rms_ci[1],
        mean=r.mean,
        bound14=b14,
        bound15=b15,
        theory_rms=th["rms"],
        theory_rms_first_order=th["rms_first_order"],
        theory_bias=th["bias"],
    )
    return row


@dataclass(frozen=True)
class _CaseTask:
    case: SweepCase
    n_samples: int
    entropy: object
    spawn_key: tuple
    index: int

    def __call__(self):
        root = np.random.SeedSequence(self.entropy, spawn_key=self.spawn_key)
        return evaluate_case(self.case, self.n_samples, montecarlo.block_seed(root, self.index))


def sweep(cases, *, n_samples: int, rng=None, executor=None, progress: bool = False) -> list:
    """Evaluate every case; the rows come back in case order.

    Parameters
    ----------
    cases : sequence of SweepCase
    n_samples : int — rocking samples per case, at least 2
    rng : Generator | SeedSequence | int | None — root of the per-case streams
    executor : Executor | dask Client | None — where cases run (does not change the result)
    progress : bool — tqdm bar on stderr

    Returns
    -------
    list of dict — :func:`evaluate_case` rows with the case fields added
    """
    n_samples = as_int(n_samples, "n_samples", minimum=2)
    root = montecarlo.root_seed_sequence(rng)
    cases = list(cases)
    tasks = [_CaseTask(c, n_samples, root.entropy, tuple(root.spawn_key), i) for i, c in enumerate(cases)]
    rows = montecarlo.map_tasks(executor, tasks, progress=progress, desc="azimuth sweep")
    return [{**c.__dict__, **row} for c, row in zip(cases, rows)]


def grid_cases(latitudes_deg, sigmas_deg, **fields) -> list:
    """Cases on the latitude × amplitude grid (latitude-major order); ``fields`` fix the rest."""
    return [SweepCase(float(lat), float(s), **fields) for lat in latitudes_deg for s in sigmas_deg]


def local_cluster(n_workers: int = 2):
    """A ``dask.distributed`` Client on a local cluster (the ``distributed`` extra).

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


def first_order_alignment_rms(case: SweepCase) -> float:
    """First-order rms of the alignment error of (16) for a sample-mean case [rad]."""
    rocking = case.rocking()
    n_steps = max(2, int(round(case.averaging_time / case.dt)))
    gb, gg = gradient(math.radians(case.latitude_deg), math.radians(case.beta0_deg), math.radians(case.gamma0_deg))
    vx = mean_variance_factor(rocking, n_steps, case.dt, axis="xi")
    ve = mean_variance_factor(rocking, n_steps, case.dt, axis="eta")
    return math.sqrt(gb**2 * rocking.sigma_xi**2 * vx + gg**2 * rocking.sigma_eta**2 * ve)
