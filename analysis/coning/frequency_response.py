"""Error against frequency: the coning drift of each algorithm as a function of ωh.

Under classical coning (half-cone angle α, coning rate ω, sample interval h)
the constant drift rate of an algorithm along the cone axis is
``u = α² ω D(ωh) + O(α⁴)`` with ``D`` known exactly in ``x = ωh``
(:func:`strapdown.derivations.coning.drift.coning_drift`; exact minus
algorithm, positive when the computed attitude lags the coning rotation).
``|D(x)|`` against x on log–log axes is the algorithm's error-versus-frequency
response: a straight line of slope ``order`` at low frequency, bending where
the higher harmonics of the closed form take over.  Plotted against the
sample interval (ωh, not ωH), algorithms with different N are compared at the
same gyro data rate.

:func:`simulator_check` runs the parallel computation
(:func:`strapdown.analysis.coning.simulator.simulate`) on the same coning and
projects its drift on the cone axis, for every algorithm the simulator
accepts, where the drift is well above the round-off of the run.

References
----------
Lebedev & Panov (1989), eq. (4.1) (ε = −1 is coning).
Ignagni (1990); Savage (1998), for the classical coning drift.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ...derivations.coning.drift import coning_drift, coning_drift_series
from ..core import budget
from ..core.cache import derived
from ..core.validation import as_array, in_open_interval, positive
from .drift_theory import algorithm_key, coning_drift_function, coning_drift_rate, drift_series_terms
from .precession import RegularPrecession
from .simulator import CHUNK_STEPS, simulate

__all__ = [
    "CHECK_CONE_ANGLE",
    "ROUND_OFF_MARGIN",
    "QUARTIC_WEIGHT",
    "SimulatorCheck",
    "ConingResponse",
    "FrequencyResponse",
    "FiniteAngleCheck",
    "simulator_check",
    "coning_response",
    "coning_frequency_response",
    "finite_angle_check",
]

#: Weight of the series searched for the α⁴ term of the coning drift (powers of ωh up to 8).
QUARTIC_WEIGHT = 9

#: Half-cone angle of the simulator checks [rad]: small enough that the O(α⁴)
#: remainder, which for the high-order algorithms starts at a lower power of ωh
#: than their α² term, stays below 1e-3 of the drift at the check points.
CHECK_CONE_ANGLE = 2e-4

#: A simulated drift is compared only where the drift accumulated over the run
#: exceeds ``ROUND_OFF_MARGIN × steps × ε`` (ε the machine epsilon): the
#: worst-case round-off of the attitude product is then below 1/ROUND_OFF_MARGIN of it.
ROUND_OFF_MARGIN = 1e4


@dataclass(frozen=True)
class SimulatorCheck:
    """One point of the closed form against the parallel computation.

    Attributes
    ----------
    omega_h : float
        x = ωh [rad].
    cone_angle : float
        Half-cone angle α [rad].
    nu : float
        Coning rate ω [rad/s].
    sample_interval : float
        h [s].
    duration : float
        Length of the simulated run [s].
    steps : int
        Algorithm steps in the run.
    theory : float
        ``α² ω D(ωh)`` [rad/s].
    round_off_floor : float
        Drift rate below which the run's round-off could matter [rad/s].
    simulated : float or None
        Simulated drift along the cone axis [rad/s], exact minus algorithm;
        None where the point was not simulated (see ``note``).
    note : str
        Why the point was not simulated ("" if it was).
    """

    omega_h: float
    cone_angle: float
    nu: float
    sample_interval: float
    duration: float
    steps: int
    theory: float
    round_off_floor: float
    simulated: float | None
    note: str = ""

    @property
    def relative_difference(self) -> float | None:
        """``simulated / theory − 1`` (None if not simulated)."""
        if self.simulated is None:
            return None
        return self.simulated / self.theory - 1.0

    @property
    def simulated_coefficient(self) -> float | None:
        """The simulated drift as a value of D: ``simulated / (α² ω)`` [-] (None if not simulated)."""
        if self.simulated is None:
            return None
        return self.simulated / (self.cone_angle**2 * self.nu)


def _check_run(algorithm: Algorithm, steps: float, periods, x: float, limits) -> None:
    """Refuse a simulated run beyond ``limits``, naming ``periods`` (before the simulator would name its own arguments)."""
    what = f"`periods` = {periods:.3g} coning periods at `omega_h` = {x:g} ({steps:.3g} steps of {algorithm.samples} samples)"
    degree_sum = sum(t.degree for t in algorithm.terms)
    budget.check(budget.coning_simulation(steps, window=algorithm.window, degree_sum=degree_sum, velocity=False, chunk_steps=CHUNK_STEPS, what=what), limits)


def simulator_check(
    algorithm: Algorithm, omega_h: float, *, cone_angle: float = CHECK_CONE_ANGLE, nu: float = 2 * math.pi * 10.0, periods: int = 50, engine: str = "auto", limits: budget.Limits | None = None
) -> SimulatorCheck:
    """Simulate classical coning and compare the drift along the cone axis with ``α² ω D(ωh)``.

    The motion is (4.1) with ε = −1, ϑ = α, ν = ω, the initial attitude the
    identity (so the precession axis in I is ``n = (0, sin α, cos α)`` and the
    cone axis ``a = −n``); the simulator's drift (exact minus algorithm, frame
    I) projected on ``a`` is the drift ``u`` of the closed form, with its sign.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    omega_h : float
        x = ωh [rad], > 0; the sample interval is ``h = x / ω``.
    cone_angle : float, keyword-only
        Half-cone angle α [rad], in (0, π/2); small, so that the O(α⁴)
        remainder does not blur the comparison (default :data:`CHECK_CONE_ANGLE`).
    nu : float, keyword-only
        Coning rate ω [rad/s], > 0.
    periods : int, keyword-only
        Length of the run in coning periods 2π/ω (≥ 1).
    engine : {"auto", "numpy", "compiled"}, keyword-only
        Simulator engine (:func:`strapdown.analysis.coning.simulator.simulate`);
        ``"numpy"`` compiles nothing, the right choice for a few short runs on a
        cold cache.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the simulation (default 2 GB,
        300 s); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    SimulatorCheck
        With ``simulated = None`` where the simulator rejects the algorithm (e.g.
        samples of earlier steps, where it does not support them) or the drift
        is below the round-off floor.

    Raises
    ------
    ValueError
        For bad parameters, or a run beyond ``limits`` (naming ``periods``).
    """
    x = positive(omega_h, "omega_h")
    alpha = in_open_interval(cone_angle, "cone_angle", 0.0, math.pi / 2, text="(0, π/2)")
    nu = positive(nu, "nu")
    if isinstance(periods, bool) or not isinstance(periods, int) or periods < 1:
        raise ValueError(f"Expected `periods` to be a positive integer, got {periods!r}")
    h = x / nu
    duration = periods * 2 * math.pi / nu
    steps = math.floor(duration / (algorithm.samples * h) * (1.0 + 1e-12))
    _check_run(algorithm, steps, periods, x, limits)
    theory = float(coning_drift_rate(algorithm, cone_angle=alpha, nu=nu, sample_interval=h))
    floor = ROUND_OFF_MARGIN * max(steps, 1) * np.finfo(float).eps / duration
    common = dict(omega_h=x, cone_angle=alpha, nu=nu, sample_interval=h, duration=duration, steps=steps, theory=theory, round_off_floor=floor)
    if steps < 8:
        return SimulatorCheck(**common, simulated=None, note="fewer than 8 steps in the run")
    if abs(theory) < floor:
        return SimulatorCheck(**common, simulated=None, note="drift below the round-off floor of the run")
    motion = RegularPrecession(-1.0, nu, alpha)
    try:
        run = simulate(algorithm, motion, h, duration, engine=engine, limits=limits)
    except budget.BudgetExceeded:
        raise
    except ValueError as exc:
        return SimulatorCheck(**common, simulated=None, note=f"not run by the simulator: {exc}")
    return SimulatorCheck(**common, simulated=float(run.drift @ -motion.precession_axis()))


@dataclass(frozen=True)
class ConingResponse:
    """Coning drift of one algorithm against ωh.

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm.
    order : int
        Power of ωh of the leading term.
    coefficient : Fraction
        Its exact coefficient: ``u ≈ coefficient · α² ω (ωh)^order``.
    omega_h : ndarray
        x = ωh [rad].
    drift : ndarray
        ``D(x) = u / (α² ω)`` [-], signed (exact minus algorithm).
    checks : tuple of SimulatorCheck
        Parallel computation at a few points.
    quartic_order : int or None
        Power of ωh of the leading α⁴ term of the drift (None if it vanishes
        through :data:`QUARTIC_WEIGHT`).
    quartic_coefficient : Fraction or None
        Its coefficient: ``u ≈ α² ω D(ωh) + quartic_coefficient · α⁴ ω (ωh)^quartic_order``.
    """

    algorithm: Algorithm
    order: int
    coefficient: Fraction
    omega_h: np.ndarray
    drift: np.ndarray
    checks: tuple
    quartic_order: int | None = None
    quartic_coefficient: Fraction | None = None

    def crossover_angle(self, omega_h: float) -> float | None:
        """Half-cone angle [rad] at which the leading α⁴ term equals the α² drift at ``omega_h``.

        Above it the α² closed form no longer describes the drift.

        Parameters
        ----------
        omega_h : float
            x = ωh [rad], > 0.

        Returns
        -------
        float or None
            ``sqrt(|D(x)| / |c₄ x^m₄|)``; None without an α⁴ term.
        """
        x = positive(omega_h, "omega_h")
        if self.quartic_order is None:
            return None
        return math.sqrt(abs(self.drift_at(x)) / abs(float(self.quartic_coefficient) * x**self.quartic_order))

    def drift_at(self, omega_h: float) -> float:
        """``D(x)`` at one x = ωh, from the closed form [-], signed (exact minus algorithm).

        Parameters
        ----------
        omega_h : float
            x = ωh [rad], > 0.

        Returns
        -------
        float
        """
        x = positive(omega_h, "omega_h")
        return float(np.asarray(coning_drift_function(self.algorithm)(x)))

    @property
    def leading(self) -> np.ndarray:
        """The leading term ``coefficient · x^order`` on :attr:`omega_h`."""
        return float(self.coefficient) * self.omega_h**self.order

    @property
    def simulated_checks(self) -> tuple:
        """The checks that were simulated."""
        return tuple(c for c in self.checks if c.simulated is not None)


@dataclass(frozen=True)
class FrequencyResponse:
    """Coning drift of several algorithms against ωh.

    Attributes
    ----------
    omega_h : ndarray
        x = ωh [rad].
    responses : tuple of ConingResponse
        One per algorithm, in the order given.
    """

    omega_h: np.ndarray
    responses: tuple

    @property
    def simulated_checks(self) -> tuple:
        """Every simulated check of every algorithm."""
        return tuple(c for r in self.responses for c in r.simulated_checks)

    @property
    def largest_relative_difference(self) -> float:
        """Largest ``|simulated / theory − 1|`` over :attr:`simulated_checks` (NaN if none)."""
        return max((abs(c.relative_difference) for c in self.simulated_checks), default=float("nan"))


def coning_response(
    algorithm: Algorithm, omega_h, *, check_omega_h=(0.25, 0.5, 1.0), cone_angle: float = CHECK_CONE_ANGLE, nu: float = 2 * math.pi * 10.0, periods: int = 50, engine: str = "auto"
) -> ConingResponse:
    """The coning drift ``D(ωh)`` of one algorithm, with simulator checks.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    omega_h : array_like
        x = ωh [rad], > 0.
    check_omega_h : sequence of float, keyword-only
        Points x [rad] of the parallel computation.
    cone_angle, nu, periods, engine : keyword-only
        As in :func:`simulator_check`.

    Returns
    -------
    ConingResponse

    Raises
    ------
    ValueError
        For x not positive or bad check parameters.
    """
    x = as_array(omega_h, "omega_h")
    if np.any(x <= 0):
        raise ValueError(f"Expected `omega_h` > 0, got {x[x <= 0].ravel()[0]:g}")
    order, coefficient, q_order, q_coeff = derived(f"coning:leading-coning-terms:v1:{algorithm_key(algorithm)}", lambda: _leading_terms(algorithm))
    values = np.asarray(coning_drift_function(algorithm)(x), dtype=float)
    checks = tuple(simulator_check(algorithm, float(c), cone_angle=cone_angle, nu=nu, periods=periods, engine=engine) for c in check_omega_h)
    return ConingResponse(algorithm, order, coefficient, x, values, checks, q_order, q_coeff)


def _leading_terms(algorithm: Algorithm) -> tuple:
    """(order, coefficient) of the α² coning drift and (order, coefficient) of its α⁴ term, per (ωh)^order."""
    d = coning_drift(algorithm)
    N = algorithm.samples
    quartic = [(w - 1, c * Fraction(N) ** (w - 1)) for w, c in enumerate(coning_drift_series(algorithm, QUARTIC_WEIGHT, alpha_power=4)) if c]
    q_order, q_coeff = quartic[0] if quartic else (None, None)
    return d.order, d.coefficient, q_order, q_coeff


def coning_frequency_response(
    algorithms, omega_h=None, *, check_omega_h=(0.25, 0.5, 1.0), cone_angle: float = CHECK_CONE_ANGLE, nu: float = 2 * math.pi * 10.0, periods: int = 50, engine: str = "auto"
) -> FrequencyResponse:
    """Coning drift against ωh for several algorithms (see :func:`coning_response`).

    Parameters
    ----------
    algorithms : sequence of Algorithm
        The algorithms.
    omega_h : array_like, optional
        x = ωh [rad]; default 200 points from 10⁻² to π/2, log-spaced.
    check_omega_h : sequence of float, keyword-only
        Points x [rad] of the parallel computation.
    cone_angle, nu, periods, engine : keyword-only
        As in :func:`simulator_check`.

    Returns
    -------
    FrequencyResponse

    Raises
    ------
    TypeError
        If an element of ``algorithms`` is not an Algorithm.
    ValueError
        For bad values (as :func:`coning_response`).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> r = coning_frequency_response([get("two-sample")], [0.1, 0.2], check_omega_h=())
    >>> r.responses[0].order, str(r.responses[0].coefficient)
    (4, '1/60')
    """
    algorithms = list(algorithms)
    for a in algorithms:
        if not isinstance(a, Algorithm):
            raise TypeError(f"Expected `algorithms` to hold Algorithm objects, got {type(a).__name__}")
    x = np.geomspace(1e-2, math.pi / 2, 200) if omega_h is None else as_array(omega_h, "omega_h")
    responses = tuple(coning_response(a, x, check_omega_h=check_omega_h, cone_angle=cone_angle, nu=nu, periods=periods, engine=engine) for a in algorithms)
    return FrequencyResponse(x, responses)


@dataclass(frozen=True)
class FiniteAngleCheck:
    """The coning drift at a finite cone angle: α² closed form, the series exact in α, the simulator.

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm.
    omega_h : float
        x = ωh [rad].
    cone_angle : float
        α [rad].
    nu : float
        ω [rad/s].
    max_weight : int
        Weight of the series (powers of ωh below it are exact, at every order in α).
    closed_form : float
        ``α² ω D(ωh)`` [rad/s], signed as ``series``.
    series : float
        The drift series at ε = −1, ϑ = α through ``max_weight``, all orders in
        α, with the composition of the steps, along the cone axis, exact minus
        algorithm [rad/s].
    simulated : float or None
        Parallel computation: the simulator's drift along the cone axis, exact
        minus algorithm [rad/s] (None if not run, see ``note``).
    note : str
        Why not simulated ("" if it was).
    """

    algorithm: Algorithm
    omega_h: float
    cone_angle: float
    nu: float
    max_weight: int
    closed_form: float
    series: float
    simulated: float | None
    note: str = ""

    @property
    def simulated_vs_series(self) -> float | None:
        """``simulated / series − 1`` (None if not simulated)."""
        return None if self.simulated is None else self.simulated / self.series - 1.0


def finite_angle_check(
    algorithm: Algorithm, omega_h: float, *, cone_angle: float, nu: float = 2 * math.pi * 10.0, max_weight: int = 11, periods: int = 200, limits: budget.Limits | None = None
) -> FiniteAngleCheck:
    """Coning drift at a finite half-cone angle: where the α² closed form stops describing it.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    omega_h : float
        x = ωh [rad], > 0.
    cone_angle : float, keyword-only
        α [rad], in (0, π/2).
    nu : float, keyword-only
        ω [rad/s], > 0.
    max_weight : int, keyword-only
        Weight of the drift series (:func:`strapdown.analysis.coning.drift_theory.drift_series_terms`, with the composition of the steps).
    periods : int, keyword-only
        Length of the simulated run in coning periods.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the simulation (default 2 GB,
        300 s); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    FiniteAngleCheck

    Raises
    ------
    ValueError
        For bad parameters, or a run or a series beyond ``limits`` (naming
        ``periods`` or ``max_weight``).
    """
    x = positive(omega_h, "omega_h")
    alpha = in_open_interval(cone_angle, "cone_angle", 0.0, math.pi / 2, text="(0, π/2)")
    nu = positive(nu, "nu")
    h = x / nu
    H = algorithm.samples * h
    _check_run(algorithm, periods * 2 * math.pi / nu / H, periods, x, limits)
    # the series (with the composition of the steps) is along the precession axis n; the cone axis is a = −n
    series = -drift_series_terms(algorithm, eps=-1.0, nu=nu, nutation=alpha, step=H, max_weight=max_weight, limits=limits).signed_total
    closed = float(coning_drift_rate(algorithm, cone_angle=alpha, nu=nu, sample_interval=h))
    motion = RegularPrecession(-1.0, nu, alpha)
    try:
        run = simulate(algorithm, motion, h, periods * 2 * math.pi / nu, limits=limits)
    except budget.BudgetExceeded:
        raise
    except ValueError as exc:
        return FiniteAngleCheck(algorithm, x, alpha, nu, max_weight, closed, series, None, f"not run by the simulator: {exc}")
    return FiniteAngleCheck(algorithm, x, alpha, nu, max_weight, closed, series, float(run.drift @ -motion.precession_axis()))
