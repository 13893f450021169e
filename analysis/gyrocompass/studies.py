"""The tilt-channel studies of the azimuth report, as library functions with typed results.

Each study is a list of cases (angles in radians) and a function that runs
their Monte Carlo, one child of the root SeedSequence per case, so a study is
a pure function of its sizes and seed.  The canonical case lists are kept
here once, shared by the report and the tests:

:data:`VIOLATION_CASES`
    where (14) and (15) fail: dropped stable tilts, second order, large amplitude;
:data:`SMALL_ROCKING_CASES`
    small rocking, where the second-order theory must agree with Monte Carlo;
:data:`DISTRIBUTION_CASES`
    the error distribution against the bounds;
:func:`tilt_design_check`
    Monte Carlo at the admissible amplitudes of
    :func:`strapdown.analysis.gyrocompass.admissible_rocking.admissible_amplitude`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import budget as work
from ..core import montecarlo
from ..core.units import rad
from ..core.validation import as_array, as_int, nonnegative, positive
from ..core.verdicts import Verdict
from .admissible_rocking import AdmissibleRocking, admissible_amplitude
from .azimuth import AzimuthErrorKernel, AzimuthMonteCarlo, azimuth_monte_carlo, check_latitude
from .rocking import GaussianRocking, NarrowbandRocking, SineRocking

__all__ = [
    "THEORY_MARGIN",
    "BoundCase",
    "CaseResult",
    "DesignCheck",
    "VIOLATION_CASES",
    "SMALL_ROCKING_CASES",
    "DISTRIBUTION_CASES",
    "run_cases",
    "tilt_design_check",
]

#: The second-order theory agrees with a small-rocking Monte Carlo when the true rms is within this
#: fraction of it, by TOST (:mod:`strapdown.analysis.core.verdicts`); its remainder is of relative order
#: ``(σ tan² φ)²``, far below 1 % in :data:`SMALL_ROCKING_CASES`.
THEORY_MARGIN = 0.01


@dataclass(frozen=True)
class BoundCase:
    """A tilt-channel case at independent instants (equal rocking on both axes).

    Parameters
    ----------
    label : str
        What the case shows.
    model : str
        ``"normal"`` or ``"sine"``.
    latitude : float
        Latitude φ [rad].
    beta0, gamma0 : float
        Stable tilts [rad].
    sigma : float
        Standard deviation of ξ and η [rad].
    """

    label: str
    model: str
    latitude: float
    beta0: float
    gamma0: float
    sigma: float

    def __post_init__(self):
        check_latitude(self.latitude)
        nonnegative(self.sigma, "sigma")
        if self.model not in ("normal", "sine"):
            raise ValueError(f"Expected `model` in ('normal', 'sine'), got {self.model!r}")

    def rocking(self):
        """The rocking model of the case.

        Returns
        -------
        GaussianRocking | SineRocking
        """
        return GaussianRocking(self.sigma, self.sigma) if self.model == "normal" else SineRocking(self.sigma, self.sigma)


def _case(label, model, *angles):
    # (latitude, β0, γ0, σ) as the study tables below write them, in degrees
    return BoundCase(label, model, *(rad(a) for a in angles))


#: Cases where the bounds (14), (15) fail, and why.
VIOLATION_CASES = (
    _case("(15) drops β0, γ0", "normal", 70.0, 3.0, -3.0, 2.0),
    _case("(15) drops β0, γ0", "sine", 70.0, 3.0, -3.0, 2.0),
    _case("second order, zero tilt", "normal", 80.0, 0.0, 0.0, 1.0),
    _case("second order, zero tilt", "sine", 60.0, 0.0, 0.0, 3.0),
    _case("large amplitude", "normal", 80.0, 2.0, 2.0, 5.0),
    _case("large amplitude", "sine", 75.0, 0.0, 0.0, 10.0),
    _case("large amplitude", "normal", 45.0, 0.0, 0.0, 10.0),
)

#: Small rocking: the second-order theory must fall inside the Monte Carlo interval.
SMALL_ROCKING_CASES = (
    _case("small", "normal", 30.0, 0.0, 0.0, 0.05),
    _case("small", "normal", 60.0, 2.0, 1.0, 0.1),
    _case("small", "sine", 75.0, 1.0, -2.0, 0.1),
    _case("small", "normal", 80.0, 0.0, 0.0, 0.3),
    _case("small", "sine", 80.0, 0.0, 0.0, 0.3),
)

#: The distribution figure.
DISTRIBUTION_CASES = (
    _case("distribution", "normal", 80.0, 0.0, 0.0, 3.0),
    _case("distribution", "sine", 80.0, 0.0, 0.0, 3.0),
    _case("distribution", "normal", 70.0, 3.0, -3.0, 2.0),
)


@dataclass(frozen=True)
class CaseResult:
    """A case with its Monte Carlo, bounds and theory.

    Attributes
    ----------
    case : BoundCase
        The configuration.
    mc : AzimuthMonteCarlo
        Monte Carlo of the error (12) with bounds (14), (15) and the second-order theory.
    """

    case: BoundCase
    mc: AzimuthMonteCarlo

    @property
    def theory_inside(self) -> bool:
        """Whether the second-order rms lies inside the 95 % interval of the Monte Carlo rms (the Monte Carlo does not resolve the remainder)."""
        lo, hi = self.mc.result.rms_ci
        return bool(lo <= self.mc.theory.rms <= hi)

    @property
    def theory_agreement(self) -> Verdict:
        """Does the Monte Carlo rms agree with the second-order theory within ±:data:`THEORY_MARGIN`? (TOST on the mean square.)"""
        return self.mc.result.rms_agrees(self.mc.theory.rms, THEORY_MARGIN, what="the second-order theory")


def run_cases(cases, *, n_samples: int, rng=None, control_degree: int = 0, quantiles=montecarlo.QUANTILES, limits: work.Limits | None = None) -> tuple:
    """Monte Carlo of each case from its own child stream of ``rng``.

    Parameters
    ----------
    cases : sequence of BoundCase
        The configurations.
    n_samples : int
        Rocking samples per case, at least 2; with control variates, the plain
        Monte Carlo whose precision each case matches.
    rng : Generator | SeedSequence | int | None
        Root of the per-case streams.
    control_degree : int
        0: plain Monte Carlo; else the degree of the control variates of
        :func:`strapdown.analysis.gyrocompass.azimuth.azimuth_monte_carlo`.
    quantiles : sequence of float
        Levels in (0, 1) of the sample quantiles of each result (default
        :data:`strapdown.analysis.core.montecarlo.QUANTILES`); an empty sequence
        skips them (the draws and every moment stay the same).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s, on one
        core); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    tuple of CaseResult

    Raises
    ------
    ValueError
        For bad arguments, or runs beyond ``limits`` (naming ``n_samples``).
    """
    n_samples = as_int(n_samples, "n_samples", minimum=2)
    cases = list(cases)
    work.check(work.monte_carlo(len(cases) * n_samples, what=f"`n_samples` = {n_samples:.3g} rocking samples in each of {len(cases)} cases"), limits)
    root = montecarlo.root_seed_sequence(rng)
    out = []
    for i, case in enumerate(cases):
        if not isinstance(case, BoundCase):
            raise TypeError(f"Expected `cases` of BoundCase, got {type(case).__name__}")
        mc = azimuth_monte_carlo(case.latitude, case.beta0, case.gamma0, case.rocking(), n_samples, rng=montecarlo.block_seed(root, i), control_degree=control_degree, quantiles=quantiles)
        out.append(CaseResult(case, mc))
    return tuple(out)


@dataclass(frozen=True)
class DesignCheck:
    """Monte Carlo of the alignment error (16) at admissible amplitudes.

    Attributes
    ----------
    design : AdmissibleRocking
        The chart that was checked.
    budget : float
        Its budget [rad].
    indices : tuple of int
        Frequencies checked (indices into ``design.frequency``).
    results : tuple of MonteCarloResult
        The alignment error Δ at each checked amplitude [rad].
    """

    design: AdmissibleRocking
    budget: float
    indices: tuple
    results: tuple

    @property
    def frequencies(self) -> np.ndarray:
        """Checked frequencies [Hz]."""
        return self.design.frequency[list(self.indices)]

    @property
    def amplitudes(self) -> np.ndarray:
        """Checked admissible amplitudes (rms criterion) [rad]."""
        return self.design.amplitude[list(self.indices)]


def tilt_design_check(
    budget, latitude, averaging_time, frequencies, *, damping: float = 0.1, sample_rate: float = 10.0, n_trials: int = 1000, check=(0, -1), rng=None, limits: work.Limits | None = None
) -> DesignCheck:
    """Admissible narrow-band amplitudes (tilt channel) with a Monte Carlo check at some of them.

    At the admissible amplitude the rms alignment error of the estimate (16)
    should equal the budget.

    Parameters
    ----------
    budget : float
        rms azimuth budget [rad].
    latitude : float
        Latitude φ [rad].
    averaging_time : float
        Averaging time of (16) [s].
    frequencies : array_like
        Rocking frequencies [Hz].
    damping : float
        Damping ratio of the narrow-band rocking.
    sample_rate : float
        Accelerometer sample rate [Hz].
    n_trials : int
        Monte Carlo trials per checked frequency.
    check : sequence of int
        Indices of the frequencies to check.
    rng : Generator | SeedSequence | int | None
        Root of the per-frequency streams.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s, on one
        core); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    DesignCheck

    Raises
    ------
    ValueError
        For bad arguments, or a check beyond ``limits`` (naming ``n_trials``).
    """
    design = admissible_amplitude(budget, latitude, averaging_time, frequencies, rocking="narrowband", damping=damping, sample_rate=sample_rate)
    dt = 1.0 / positive(sample_rate, "sample_rate")
    n_trials = as_int(n_trials, "n_trials", minimum=2)
    f = as_array(frequencies, "frequencies").ravel()
    indices = tuple(int(i) % f.size for i in check)
    draws = float(n_trials) * len(indices) * design.samples
    work.check(work.monte_carlo(draws, what=f"`n_trials` = {n_trials:.3g} trials of {design.samples:.3g} samples at {len(indices)} frequencies"), limits)
    root = montecarlo.root_seed_sequence(rng)
    results = []
    for k, i in enumerate(indices):
        s = float(design.amplitude[i]) / math.sqrt(2.0)
        kernel = AzimuthErrorKernel(latitude, 0.0, 0.0, NarrowbandRocking(s, s, 1.0 / f[i], damping), n_steps=design.samples, dt=dt, estimate="sample-mean")
        results.append(montecarlo.run(kernel, n_trials, rng=montecarlo.block_seed(root, k), trials_per_block=50, scale=budget))
    return DesignCheck(design, float(budget), indices, tuple(results))
