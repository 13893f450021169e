"""The error budget of a strapdown system at rest over its mission: one run of the linear model per source, and the total.

Each source of :mod:`~strapdown.analysis.navigation.error_model` (the data
sheet's errors; with an environment, the algorithms' residuals) is propagated
alone through the navigation error model with its own states, from the
initial condition its alignment leaves
(:mod:`~strapdown.analysis.navigation.initial_alignment`); the alignment's own
noise is one more line.  The model is linear and the sources independent, so
the runs superpose: the mean (fixed errors, signed) and the covariance
(random errors, 1σ) of each line are exact for the model.

Propagation is exact at the times of the series
(:mod:`~strapdown.analysis.navigation.covariance`).  The free-inertial modes appear in the
model's eigenvalues: the Schuler frequency ``√(g/R)`` (84.4 min), split by the
Foucault rate ``Ω sin φ``, and the Earth rate (the 24-hour mode).

Each line reports, at every time, the magnitudes

* ``attitude``: ``√(|m_φ|² + tr P_φφ)`` (the rotation angle of the attitude
  error; its ``tilt`` and ``heading`` parts too),
* ``velocity``: the horizontal velocity error, ``√(m_N² + m_E² + P_NN + P_EE)``,
* ``position``: the horizontal position error, likewise,

which are the norm of the signed error for a fixed source and the radial RMS
(1σ) for a random one; the total is their root sum square.  The signed NED
components of every line are kept too.

Public API
----------
.. autosummary::

   LineSeries
   TotalSeries
   ErrorBudget
   error_budget
   DEFAULT_REPORT_TIMES
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core import budget
from ..core.progress import bar
from ..core.validation import as_array, as_int, positive
from .covariance import propagate
from .error_model import HELD, Site, augmented_model, environment_sources, navigation_dynamics, sensor_sources
from .imu_file import ImuSpec
from .initial_alignment import ALIGNMENTS, AlignmentGains, GivenAlignment, analytic_gains, given_residual, initial_condition

__all__ = ["LineSeries", "TotalSeries", "ErrorBudget", "error_budget", "DEFAULT_REPORT_TIMES", "MAX_POINTS", "MAX_DURATION"]

#: Times of the budget's table [s]: one minute, ten minutes, one hour.
DEFAULT_REPORT_TIMES = (60.0, 600.0, 3600.0)
#: Most times of a series [count].
MAX_POINTS = 100_000
#: Longest mission the linear model is run over [s] (30 days; the model is a small-error model).
MAX_DURATION = 30 * 86400.0
#: Cost of one source at one time of the series (small matrix products) [s]; measured 6.3e-5 on one core.
SECONDS_PER_SOURCE_POINT = 7e-5
#: Memory of one source at one time of the series (its state and covariance rows kept) [bytes]; measured 2.6e3.
BYTES_PER_SOURCE_POINT = 2.6e3


@dataclass(frozen=True)
class LineSeries:
    """One line of the budget against time.

    Attributes
    ----------
    name : str
        The source (``"gyro turn-on bias"``, ``"alignment"``, ``"total"``, ...).
    deterministic : bool
        Fixed errors (signed) rather than random ones (1σ).
    times : ndarray
        ``(T,)`` [s].
    mean : ndarray
        ``(T, 9)`` mean navigation errors (estimate minus truth), NED [rad, m/s, m].
    cov : ndarray
        ``(T, 9, 9)`` their covariance, quantization readings included.
    """

    name: str
    deterministic: bool
    times: np.ndarray
    mean: np.ndarray
    cov: np.ndarray

    def _rms(self, idx) -> np.ndarray:
        idx = list(idx)
        return np.sqrt(np.sum(self.mean[:, idx] ** 2, axis=1) + np.trace(self.cov[:, idx][:, :, idx], axis1=1, axis2=2))

    @property
    def attitude(self) -> np.ndarray:
        """``(T,)`` attitude error [rad]."""
        return self._rms((0, 1, 2))

    @property
    def tilt(self) -> np.ndarray:
        """``(T,)`` tilt error [rad]."""
        return self._rms((0, 1))

    @property
    def heading(self) -> np.ndarray:
        """``(T,)`` heading error [rad]."""
        return self._rms((2,))

    @property
    def velocity(self) -> np.ndarray:
        """``(T,)`` horizontal velocity error [m/s]."""
        return self._rms((3, 4))

    @property
    def position(self) -> np.ndarray:
        """``(T,)`` horizontal position error [m]."""
        return self._rms((6, 7))

    def sigma(self) -> np.ndarray:
        """``(T, 9)`` standard deviations of the components.

        Returns
        -------
        ndarray
        """
        return np.sqrt(np.maximum(np.diagonal(self.cov, axis1=1, axis2=2), 0.0))


@dataclass(frozen=True)
class TotalSeries:
    """The root sum square of the lines' magnitudes.

    Attributes
    ----------
    times : ndarray
        ``(T,)`` [s].
    attitude, tilt, heading : ndarray
        ``(T,)`` [rad].
    velocity : ndarray
        ``(T,)`` [m/s].
    position : ndarray
        ``(T,)`` [m].
    name : str
        ``"total"``.
    """

    times: np.ndarray
    attitude: np.ndarray
    tilt: np.ndarray
    heading: np.ndarray
    velocity: np.ndarray
    position: np.ndarray
    name: str = "total"


@dataclass(frozen=True)
class ErrorBudget:
    """The budget: every line, the total, and what produced them.

    Attributes
    ----------
    imu : str
        The IMU's name.
    site : Site
        Latitude and heading.
    duration : float
        Mission length [s].
    alignment : str
        ``"none"``, ``"analytic"`` or ``"given"``.
    alignment_time : float
        Its window [s] (0 without alignment).
    algorithm : str or None
        The algorithm of the environment lines.
    environment : str or None
        The environment's name.
    lines : tuple of LineSeries
        One per source, then ``"alignment"`` when there is one.
    total : TotalSeries
        Root sum square.
    report_times : ndarray
        Times of the table [s] (all on the series).
    """

    imu: str
    site: Site
    duration: float
    alignment: str
    alignment_time: float
    algorithm: str | None
    environment: str | None
    lines: tuple
    total: TotalSeries
    report_times: np.ndarray

    @property
    def times(self) -> np.ndarray:
        """``(T,)`` times of the series [s]."""
        return self.total.times

    def index(self, time: float) -> int:
        """Position of ``time`` in the series.

        Parameters
        ----------
        time : float
            A time of the series [s].

        Returns
        -------
        int

        Raises
        ------
        ValueError
            For a time not in the series.
        """
        i = int(np.argmin(np.abs(self.times - float(time))))
        if not math.isclose(self.times[i], float(time), rel_tol=1e-12, abs_tol=1e-9):
            raise ValueError(f"Expected `time` among the budget's times, got {time:g}")
        return i

    def line(self, name: str) -> LineSeries:
        """The line of source ``name``.

        Parameters
        ----------
        name : str
            A source.

        Returns
        -------
        LineSeries

        Raises
        ------
        ValueError
            For a name that is not a line.
        """
        for ln in self.lines:
            if ln.name == name:
                return ln
        raise ValueError(f"Expected `name` among {[ln.name for ln in self.lines]}, got {name!r}")

    def dominant(self, quantity: str = "position", time: float | None = None) -> str:
        """The source with the largest ``quantity`` at ``time`` (default the end).

        Parameters
        ----------
        quantity : str
            ``"attitude"``, ``"velocity"`` or ``"position"``.
        time : float, optional
            A time of the series [s].

        Returns
        -------
        str
        """
        if quantity not in ("attitude", "velocity", "position"):
            raise ValueError(f"Expected `quantity` in ('attitude', 'velocity', 'position'), got {quantity!r}")
        i = len(self.times) - 1 if time is None else self.index(time)
        return max(self.lines, key=lambda ln: float(getattr(ln, quantity)[i])).name


def _times(duration: float, points: int, report) -> tuple:
    grid = np.linspace(0.0, duration, points)
    rep = np.array([x for x in report if 0.0 < x <= duration] + [duration])
    t = np.unique(np.concatenate([grid, rep]))
    # merge report times that fall within round-off of a grid time
    keep = np.concatenate([[True], np.diff(t) > 1e-9 * max(duration, 1.0)])
    t = t[keep]
    rep = np.unique(np.array([t[np.argmin(np.abs(t - r))] for r in rep]))
    return t, rep


def error_budget(
    imu: ImuSpec,
    site: Site,
    duration: float,
    *,
    environment=None,
    algorithm: Algorithm | None = None,
    alignment="none",
    alignment_time: float = 300.0,
    report_times=DEFAULT_REPORT_TIMES,
    points: int = 241,
    progress: bool = False,
    limits: budget.Limits | None = None,
) -> ErrorBudget:
    """The error budget of ``imu`` at rest at ``site`` over ``duration`` (module docstring).

    Parameters
    ----------
    imu : ImuSpec
        The data sheet (:func:`strapdown.analysis.navigation.imu_file.load_imu`).
    site : Site
        Latitude and heading (level, at rest).
    duration : float
        Mission length [s], up to 30 days.
    environment : Environment, optional, keyword-only
        A vibration environment (:func:`strapdown.analysis.vibration.environment.load_environment`):
        adds the coning, pseudo-coning, sculling, pseudo-sculling and scrolling lines.
    algorithm : Algorithm, optional, keyword-only
        The coning algorithm (its dual extension for velocity, the position
        algorithm of its N) at the IMU's sample interval; required with an environment.
    alignment : str or GivenAlignment, keyword-only
        ``"none"`` (no initial attitude error), ``"analytic"`` (the analytic
        alignment over ``alignment_time`` at the same place, on the same sensors),
        or a :class:`~strapdown.analysis.navigation.initial_alignment.GivenAlignment`.
    alignment_time : float, keyword-only
        Window of the analytic alignment [s].
    report_times : sequence of float, keyword-only
        Times of the table [s] (those beyond ``duration`` are dropped; the end is added).
    points : int, keyword-only
        Evenly spaced times of the series, ends included [count].
    progress : bool, keyword-only
        Show progress over the sources on stderr.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s).

    Returns
    -------
    ErrorBudget

    Raises
    ------
    TypeError
        Arguments of the wrong type.
    ValueError
        A duration outside (0, 30 days], an unknown alignment, an environment
        without an algorithm, or work beyond ``limits`` (naming ``points``).

    References
    ----------
    Titterton & Weston (2004), ch. 12; Savage (2007), ch. 12; Groves (2013), sec. 14.2.

    Examples
    --------
    A 100 µg north accelerometer bias at rest, without alignment: the Schuler
    response ``(b/ω_s²)(1 − cos ω_s t)`` of the north position.

    >>> from strapdown.analysis.navigation.imu_file import ImuSpec, TriadErrors
    >>> b = 100e-6 * 9.80665
    >>> imu = ImuSpec("x", 100.0, accel=TriadErrors(bias=[b, 0.0, 0.0]))
    >>> site = Site(math.radians(45.0))
    >>> ws = math.sqrt(site.gravity / 6371000.0)
    >>> t = 0.5 * math.pi / ws
    >>> r = error_budget(imu, site, t, report_times=[t])
    >>> north = r.line("accel bias").mean[-1, 6]
    >>> round(float(north / (b / ws**2 * (1.0 - math.cos(ws * t)))), 2)
    1.0
    """
    if not isinstance(imu, ImuSpec):
        raise TypeError(f"Expected `imu` to be an ImuSpec, got {type(imu).__name__}")
    if not isinstance(site, Site):
        raise TypeError(f"Expected `site` to be a Site, got {type(site).__name__}")
    T = positive(duration, "duration")
    if T > MAX_DURATION:
        raise ValueError(f"Expected `duration` up to {MAX_DURATION:g} s (30 days: the error model is linear in small errors), got {T:g}")
    n_points = as_int(points, "points", minimum=2)
    rep = as_array(report_times, "report_times").reshape(-1)
    sources = sensor_sources(site, imu)
    env_name = alg_name = None
    if environment is not None:
        if algorithm is None:
            raise ValueError("Expected `algorithm` with an `environment` (the algorithm whose residuals the environment sets)")
        from ..vibration.drift import environment_drift
        from .scrolling import environment_scrolling

        h = imu.sample_interval
        sources += environment_sources(environment_drift(algorithm, environment, h), environment_scrolling(algorithm, environment, h))
        env_name, alg_name = environment.name, algorithm.name
    elif algorithm is not None:
        alg_name = algorithm.name
    what = f"`points` = {n_points:.3g} times for {len(sources) + 1} sources"
    budget.check(budget.Estimate(SECONDS_PER_SOURCE_POINT * n_points * (len(sources) + 1) + 0.5, BYTES_PER_SOURCE_POINT * n_points * (len(sources) + 2) + 5e6, what), limits)
    if n_points > MAX_POINTS:
        raise ValueError(f"Expected `points` up to {MAX_POINTS}, got {n_points}")
    gains = None
    residual = np.zeros((3, 3))
    if isinstance(alignment, GivenAlignment):
        kind, residual, atime = "given", given_residual(alignment), 0.0
    elif alignment == "none":
        kind, atime = "none", 0.0
    elif alignment == "analytic":
        kind, atime = "analytic", positive(alignment_time, "alignment_time")
        gains: AlignmentGains = analytic_gains(site, atime)
    else:
        raise ValueError(f"Expected `alignment` in {ALIGNMENTS} or a GivenAlignment, got {alignment!r}")
    times, rep_t = _times(T, n_points, rep)
    lines = []
    for src in bar(sources, desc="budget sources", total=len(sources), enabled=progress, unit="source"):
        A, Q = augmented_model(site, src)
        ic = initial_condition(src, gains)
        residual = residual + ic.residual
        m, P = propagate(A, Q, ic.mean, ic.cov, times)
        P = P[:, :9, :9] + np.diag(src.reading)[None]
        lines.append(LineSeries(src.name, src.deterministic, times, m[:, :9], P))
    if kind != "none":
        P0 = np.zeros((9, 9))
        P0[:3, :3] = residual
        A = navigation_dynamics(site)
        m, P = propagate(A, np.zeros((9, 9)), np.zeros(9), P0, times)
        lines.append(LineSeries("alignment", False, times, m, P))
    for ln in lines:
        for i in HELD:
            ln.mean[:, i] = 0.0
    total = TotalSeries(times, *(np.sqrt(sum(getattr(ln, q) ** 2 for ln in lines)) if lines else np.zeros_like(times) for q in ("attitude", "tilt", "heading", "velocity", "position")))
    return ErrorBudget(imu.name, site, T, kind, atime, alg_name, env_name, tuple(lines), total, rep_t)
