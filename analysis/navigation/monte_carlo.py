"""The error budget checked by simulation: the nonlinear navigator with sensor errors drawn from the data sheet.

Each trial runs the navigator of :mod:`~strapdown.analysis.navigation.mechanization`
at rest on the site, its IMU with the errors of the data sheet drawn afresh
(fixed errors as given; turn-on biases, scale factors and misalignments drawn
once per trial; noise, bias instability and rate random walk drawn along the
run; the output quantised), optionally aligned first by the analytic method of
the alignment toolkit on the same sensors over the window before t = 0 (the
method applied to the window's summed increments).  Its errors at the report
times, estimate minus truth in NED (the attitude error against the local level
at the computed position, as the linear model defines it), are compared with
the budget line by line: for a random source the root mean square of the
trials' horizontal position, horizontal velocity and attitude errors against
the line's 1σ, with the interval of the mean square from its own sample spread
(normal approximation, :data:`LEVEL`); for a fixed source one run against the
signed line, within :data:`DETERMINISTIC_RTOL`.  Nothing of the linear model
enters the simulation.

Public API
----------
.. autosummary::

   SOURCE_FIELDS
   single_source
   MonteCarloErrors
   monte_carlo
   Agreement
   compare
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.stats import norm

from ...derivations.coning.algorithms import Algorithm
from ..alignment.analytic import analytic_alignment
from ..alignment.imu import ImuRecord, Scenario, SensorErrors
from ..alignment.tilt_attitude import attitude_matrix
from ..core import budget
from ..core.progress import bar
from ..core.validation import as_array, as_int
from ..gyrocompass.rocking import as_generator
from .error_model import Site
from .imu_file import ImuSpec, TriadErrors
from .initial_alignment import attitude_error
from .mechanization import NavigatorErrors, earth_frames, noise_terms, run_navigator

__all__ = ["SOURCE_FIELDS", "single_source", "MonteCarloErrors", "monte_carlo", "Agreement", "compare", "LEVEL", "DETERMINISTIC_RTOL", "SAMPLE", "BLOCK_SECONDS"]

#: Coverage of the interval of a random line's mean square (two-sided).
LEVEL = 0.999
#: Relative tolerance of a fixed line (the linear model against one nonlinear run).
DETERMINISTIC_RTOL = 0.02
#: Cost of one IMU sample of the compiled navigator [s] and its memory [bytes] (per trial, the records only).
SAMPLE = budget.CostModel(seconds_per_unit=1e-6, bytes_per_unit=0.0, fixed_seconds=2.0, fixed_bytes=5e7)

#: Longest block of steps over which the sensor errors are drawn at once [s] (the shortest correlation time of a data sheet's flicker band is about 1 s).
BLOCK_SECONDS = 0.05

#: Budget line → (triad, fields of :class:`~strapdown.analysis.navigation.imu_file.TriadErrors`).
SOURCE_FIELDS = {
    "gyro bias": ("gyro", ("bias",)),
    "gyro turn-on bias": ("gyro", ("turn_on_bias",)),
    "gyro scale factor": ("gyro", ("scale_factor", "scale_factor_sigma")),
    "gyro misalignment": ("gyro", ("misalignment", "misalignment_sigma")),
    "ARW": ("gyro", ("random_walk",)),
    "gyro bias instability": ("gyro", ("bias_instability", "flicker_band")),
    "gyro rate random walk": ("gyro", ("rate_random_walk",)),
    "gyro quantization": ("gyro", ("quantum",)),
    "accel bias": ("accel", ("bias",)),
    "accel turn-on bias": ("accel", ("turn_on_bias",)),
    "accel scale factor": ("accel", ("scale_factor", "scale_factor_sigma")),
    "accel misalignment": ("accel", ("misalignment", "misalignment_sigma")),
    "VRW": ("accel", ("random_walk",)),
    "accel bias instability": ("accel", ("bias_instability", "flicker_band")),
    "accel rate random walk": ("accel", ("rate_random_walk",)),
    "accel quantization": ("accel", ("quantum",)),
}


def single_source(imu: ImuSpec, name: str) -> ImuSpec:
    """``imu`` with every error removed but those of the budget line ``name``.

    Parameters
    ----------
    imu : ImuSpec
        The data sheet.
    name : str
        A key of :data:`SOURCE_FIELDS`.

    Returns
    -------
    ImuSpec

    Raises
    ------
    ValueError
        For an unknown line.
    """
    if name not in SOURCE_FIELDS:
        raise ValueError(f"Expected `name` among {tuple(SOURCE_FIELDS)}, got {name!r}")
    triad, fields = SOURCE_FIELDS[name]
    kept = {f: getattr(getattr(imu, triad), f) for f in fields}
    if "flicker_band" not in kept:
        kept["flicker_band"] = getattr(imu, triad).flicker_band
    new = TriadErrors(**kept)
    return replace(imu, gyro=new if triad == "gyro" else TriadErrors(), accel=new if triad == "accel" else TriadErrors())


@dataclass(frozen=True)
class MonteCarloErrors:
    """Navigation errors of the trials at the report times.

    Attributes
    ----------
    times : ndarray
        ``(R,)`` [s].
    errors : ndarray
        ``(n, R, 9)`` estimate minus truth, NED: φ [rad], δv [m/s], δp [m].
    """

    times: np.ndarray
    errors: np.ndarray

    @property
    def n_trials(self) -> int:
        """Trials."""
        return self.errors.shape[0]


def _off_diagonal(m6) -> np.ndarray:
    m = np.zeros((3, 3))
    for value, (i, j) in zip(m6, ((0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1))):
        m[i, j] = value
    return m


def _constant(triad: TriadErrors, x: np.ndarray, g) -> np.ndarray:
    """Fixed bias, a turn-on draw, and scale factor and misalignment (fixed plus drawn) acting on x."""
    S = np.diag(triad.scale_factor + triad.scale_factor_sigma * g.standard_normal(3))
    M = _off_diagonal(triad.misalignment + triad.misalignment_sigma * g.standard_normal(6))
    return triad.bias + triad.turn_on_bias * g.standard_normal(3) + (S + M) @ x


def _rz(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _quat_matrix(q) -> np.ndarray:
    q0, q1, q2, q3 = q
    return np.array([
        [q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
        [2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)],
        [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3],
    ])  # fmt: skip


def monte_carlo(
    imu: ImuSpec,
    site: Site,
    times,
    *,
    n_trials: int,
    algorithm: Algorithm,
    alignment: str = "none",
    alignment_time: float = 300.0,
    residuals=None,
    rng=None,
    progress: bool = False,
    limits: budget.Limits | None = None,
) -> MonteCarloErrors:
    """Run the navigator ``n_trials`` times with the errors of ``imu`` (module docstring).

    Parameters
    ----------
    imu : ImuSpec
        The data sheet (its sample rate is the navigator's).
    site : Site
        Latitude and heading.
    times : array_like
        Report times [s]; each is rounded to a whole number of steps.
    n_trials : int, keyword-only
        Trials [count].
    algorithm : Algorithm, keyword-only
        The coning algorithm (pairwise terms).
    alignment : str, keyword-only
        ``"none"`` or ``"analytic"``.
    alignment_time : float, keyword-only
        Window of the analytic alignment [s].
    residuals : tuple of array_like, optional, keyword-only
        ``(gyro (3,), accel (3,), position rate (3,))`` constant body errors added to
        every trial (the algorithms' residuals in an environment) [rad/s, m/s², m/s].
    rng : Generator | SeedSequence | int | None, keyword-only
        Random stream; trial k uses the k-th child of its ``SeedSequence``.
    progress : bool, keyword-only
        Progress on stderr.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s).

    Returns
    -------
    MonteCarloErrors

    Raises
    ------
    ValueError
        Bad sizes, an unknown alignment, or work beyond ``limits`` (naming ``n_trials`` and ``times``).
    """
    n = as_int(n_trials, "n_trials", minimum=1)
    t = np.sort(as_array(times, "times").reshape(-1))
    if t.size == 0 or t[0] <= 0:
        raise ValueError("Expected `times` > 0 [s]")
    if alignment not in ("none", "analytic"):
        raise ValueError(f"Expected `alignment` in ('none', 'analytic'), got {alignment!r}")
    h = imu.sample_interval
    N = algorithm.samples
    H = N * h
    record = np.unique(np.maximum(1, np.round(t / H).astype(np.int64)))
    steps = int(record[-1])
    a_steps = int(round(alignment_time / H)) if alignment == "analytic" else 0
    samples = float(n) * (steps + a_steps) * N
    what = f"`n_trials` = {n:.3g} runs to `times` up to {t[-1]:.3g} s ({samples:.3g} IMU samples)"
    budget.check(SAMPLE.estimate(samples, what=what), limits)
    frames = earth_frames(site.latitude, site.gravity)
    C_bn = site.attitude
    w_b, f_b = site.body_rate, site.specific_force
    block = max(1, int(BLOCK_SECONDS // H))
    gterms, aterms = noise_terms(imu.gyro.noise_spec(), H * block), noise_terms(imu.accel.noise_spec(), H * block)
    extra = [np.zeros(3)] * 3 if residuals is None else [np.asarray(x, float).reshape(3) for x in residuals]
    seq = rng if isinstance(rng, np.random.SeedSequence) else np.random.SeedSequence(as_generator(rng).integers(2**63))
    from_sums = None
    if a_steps:
        T = a_steps * H
        scenario = Scenario(site.latitude, heading=site.heading, sample_rate=2.0 / T, duration=T)
        zero = np.zeros((1, 2, 3))

        def from_sums(sum_dtheta, sum_dv):
            rec = ImuRecord(scenario, SensorErrors(), np.broadcast_to(0.5 * sum_dtheta, (1, 2, 3)).copy(), np.broadcast_to(0.5 * sum_dv, (1, 2, 3)).copy(),
                            np.array([0.0, T]), zero, zero, zero, np.zeros((1, 3)), np.zeros((1, 3)))  # fmt: skip
            est = analytic_alignment(rec)
            return attitude_matrix(np.array([est.heading[0], est.beta[0], est.gamma[0]]))

    out = np.zeros((n, record.size, 9))
    times_used = record * H
    Om = 7.292115e-5
    for k, child in bar(enumerate(seq.spawn(n)), desc="navigator trials", total=n, enabled=progress, unit="trial"):
        g = np.random.default_rng(child)
        errs = NavigatorErrors(
            _constant(imu.gyro, w_b, g) + extra[0], _constant(imu.accel, f_b, g) + extra[1], extra[2],
            imu.gyro.random_walk, imu.accel.random_walk, gterms, aterms, imu.gyro.quantum, imu.accel.quantum,
        )  # fmt: skip
        lam, v, r = run_navigator(algorithm, frames, C_bn, errs, sample_interval=h, steps=steps, record=record, rng=g, alignment_steps=a_steps, attitude_from_sums=from_sums, block=block)
        for i, ti in enumerate(times_used):
            to_e = _rz(-Om * ti)
            r_e = to_e @ r[i]
            v_e = to_e @ (v[i] - np.cross([0.0, 0.0, Om], r[i]))
            lat_c, lon_c = math.asin(r_e[2] / np.linalg.norm(r_e)), math.atan2(r_e[1], r_e[0])
            ned_c = earth_frames(lat_c, site.gravity).ned @ _rz(-lon_c)
            C_est = ned_c @ to_e @ _quat_matrix(lam[i])
            out[k, i, 0:3] = attitude_error(C_est, C_bn)
            out[k, i, 3:6] = frames.ned @ v_e
            out[k, i, 6:9] = frames.ned @ (r_e - frames.position)
    return MonteCarloErrors(times_used, out)


@dataclass(frozen=True)
class Agreement:
    """A budget line against the simulation, per report time and quantity.

    Attributes
    ----------
    name : str
        The line.
    times : ndarray
        ``(R,)`` [s].
    quantities : tuple of str
        ``("position", "velocity", "attitude")``.
    model : ndarray
        ``(R, 3)`` the line's values [m, m/s, rad].
    simulated : ndarray
        ``(R, 3)`` the simulation's root mean square (one run for a fixed line).
    low, high : ndarray
        ``(R, 3)`` the simulation's interval.
    agrees : ndarray
        ``(R, 3)`` bool: the model inside the interval.
    """

    name: str
    times: np.ndarray
    quantities: tuple
    model: np.ndarray
    simulated: np.ndarray
    low: np.ndarray
    high: np.ndarray
    agrees: np.ndarray

    @property
    def all(self) -> bool:
        """Every time and quantity agrees."""
        return bool(np.all(self.agrees))


_SLICES = {"position": (6, 7), "velocity": (3, 4), "attitude": (0, 1, 2)}


def compare(line, mc: MonteCarloErrors, *, deterministic: bool | None = None, level: float = LEVEL) -> Agreement:
    """A budget line (a :class:`~strapdown.analysis.navigation.error_budget.LineSeries` or the total) against the simulation.

    Parameters
    ----------
    line : LineSeries or TotalSeries
        With ``times`` and the magnitudes ``position``, ``velocity``, ``attitude``.
    mc : MonteCarloErrors
        The simulation of that line's sources.
    deterministic : bool, optional, keyword-only
        Compare as a fixed line (default: the line's own flag; False for the total).
    level : float, keyword-only
        Coverage of a random line's interval.

    Returns
    -------
    Agreement
    """
    fixed = bool(getattr(line, "deterministic", False)) if deterministic is None else bool(deterministic)
    z = float(norm.ppf(0.5 + 0.5 * level))
    R, Q = mc.times.size, len(_SLICES)
    model, sim, lo, hi = (np.zeros((R, Q)) for _ in range(4))
    for i, ti in enumerate(mc.times):
        j = int(np.argmin(np.abs(line.times - ti)))
        if not math.isclose(line.times[j], ti, rel_tol=1e-9, abs_tol=1e-6):
            raise ValueError(f"Expected the line to hold the time {ti:g} s of the simulation")
        for q, (name, idx) in enumerate(_SLICES.items()):
            model[i, q] = float(getattr(line, name)[j])
            sq = np.sum(mc.errors[:, i, list(idx)] ** 2, axis=1)
            m = float(np.mean(sq))
            sim[i, q] = math.sqrt(m)
            if fixed:
                tol = DETERMINISTIC_RTOL * max(sim[i, q], model[i, q]) + 1e-9
                lo[i, q], hi[i, q] = sim[i, q] - tol, sim[i, q] + tol
            else:
                half = z * float(np.std(sq, ddof=1)) / math.sqrt(sq.size) if sq.size > 1 else math.inf
                lo[i, q], hi[i, q] = math.sqrt(max(m - half, 0.0)), math.sqrt(m + half)
    agrees = (model >= lo) & (model <= hi)
    return Agreement(getattr(line, "name", "total"), mc.times, tuple(_SLICES), model, sim, lo, hi, agrees)
