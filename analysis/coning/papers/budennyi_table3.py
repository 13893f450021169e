"""Table 3 of Budennyi, Kalinovsky, Panov et al.: the constant drift of the five algorithms.

At the conditions of the table (ϑ = 1°, f = 10 Hz, H = 4h = 0.01 s; coning
ε = −1 and precession ε = 0.5) the drift u* is computed by parallel
computation (:func:`strapdown.analysis.coning.simulator.simulate`: the
algorithm beside the exact solution), and the asymptotic drift u_a from the
symbolic series (:mod:`strapdown.analysis.coning.drift_theory`).  For u_a two
estimates of the leading term are given
(:func:`strapdown.derivations.coning.leading_drift.leading_drift`): the
projection of the leading local error at the middle of the step, which is the
paper's eq. (3), and the full coefficient, which adds the transport of the
weight-5 error where the weight-5 drift cancels (algorithms 3 and 5 under
coning).  The printed table (:data:`strapdown.derivations.coning.published.BUDENNYI_TABLE_3`)
is compared, never used.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eqs. (3)–(5), Table 3.
Lebedev & Panov (1989), eqs. (4.1), (5.3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import NamedTuple

import numpy as np

from ....derivations.coning import drift as D
from ....derivations.coning import published as P
from ....derivations.coning.algorithms import Algorithm
from ....derivations.coning.leading_drift import leading_drift, small_cone_limit
from ....derivations.coning.registry import get
from ...core.cache import derived
from ...core.units import deg_per_h, rad
from ...core.validation import positive
from ..drift_theory import algorithm_key, asymptotic_drift, asymptotic_order, drift_series
from ..precession import RegularPrecession
from ..simulator import simulate

__all__ = [
    "Table3Conditions",
    "table3_conditions",
    "Table3Drift",
    "simulated_drift",
    "UStarCell",
    "reproduce_u_star",
    "DriftEstimate",
    "drift_estimates",
    "Table3Agreement",
    "table3_agreement",
    "LeadingEstimates",
    "leading_estimates",
    "ErrorHistory",
    "coning_error_histories",
]


@dataclass(frozen=True)
class Table3Conditions:
    """Where Table 3 is computed: the two motions and the step.

    Attributes
    ----------
    nutation : float
        ϑ [rad].
    nu : float
        ν = 2π f [rad/s].
    step : float
        Algorithm step H [s].
    samples : int
        Samples per step N (H = N h).
    coning_eps : float
        ε of the coning motion (−1).
    precession_eps : float
        ε of the precession motion (0.5).
    """

    nutation: float
    nu: float
    step: float
    samples: int = 4
    coning_eps: float = -1.0
    precession_eps: float = 0.5

    @property
    def sample_interval(self) -> float:
        """h = H / N [s]."""
        return self.step / self.samples

    def motion(self, eps: float) -> RegularPrecession:
        """The regular precession (4.1) at ``eps``.

        Parameters
        ----------
        eps : float
            ε = μ/ν [-].

        Returns
        -------
        RegularPrecession
        """
        return RegularPrecession(eps, self.nu, self.nutation)

    @property
    def motions(self) -> tuple:
        """(coning, precession) motions."""
        return self.motion(self.coning_eps), self.motion(self.precession_eps)


def table3_conditions() -> Table3Conditions:
    """The conditions printed with Table 3, in SI units.

    Returns
    -------
    Table3Conditions
        ϑ = 1°, ν = 2π · 10 Hz, H = 0.01 s, N = 4.

    Examples
    --------
    >>> c = table3_conditions()
    >>> c.sample_interval
    0.0025
    """
    c = P.BUDENNYI_CONDITIONS
    return Table3Conditions(rad(c.nutation_deg), 2 * math.pi * c.freq_hz, c.step, c.samples, *c.eps)


def _conditions(conditions) -> Table3Conditions:
    if conditions is None:
        return table3_conditions()
    if not isinstance(conditions, Table3Conditions):
        raise TypeError(f"Expected `conditions` to be Table3Conditions or None, got {type(conditions).__name__}")
    return conditions


class Table3Drift(NamedTuple):
    """Constant drift rates of one algorithm under the two motions of Table 3.

    Attributes
    ----------
    coning : float
        Drift rate under coning [rad/s].
    precession : float
        Drift rate under precession [rad/s].
    """

    coning: float
    precession: float


@cache
def _simulated_drift(algorithm: Algorithm, conditions: Table3Conditions, duration: float) -> Table3Drift:
    r = simulate(algorithm, list(conditions.motions), conditions.sample_interval, duration)
    norm = np.linalg.norm(r.drift, axis=-1)
    return Table3Drift(float(norm[0]), float(norm[1]))


def simulated_drift(algorithm: Algorithm, *, conditions: Table3Conditions | None = None, duration: float = 100.0) -> Table3Drift:
    """Drift u* of ``algorithm`` at the conditions of Table 3, by parallel computation.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm (four-sample for the table's step).
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`table3_conditions`.
    duration : float, keyword-only
        Length of each run [s], > 0.  The paper does not print it; 100 s makes
        the least-squares slope converge (10 s changes no cell by more than 3 %).

    Returns
    -------
    Table3Drift
        [rad/s].

    Raises
    ------
    ValueError
        For a non-positive ``duration``.

    Examples
    --------
    >>> d = simulated_drift(get("panov-4s-1"), duration=1.0)
    >>> round(deg_per_h(d.coning), 2)
    2.47
    """
    return _simulated_drift(algorithm, _conditions(conditions), positive(duration, "duration"))


class UStarCell(NamedTuple):
    """One u* cell of Table 3: printed and simulated.

    Attributes
    ----------
    printed : strapdown.derivations.coning.published.BudennyiTable3Row
        The printed row (deg/h).
    simulated : float
        u* by parallel computation [rad/s].
    relative_difference : float
        ``simulated / printed − 1`` (in the printed unit).
    """

    printed: P.BudennyiTable3Row
    simulated: float
    relative_difference: float

    def reproduced(self, tolerance: float) -> bool:
        """Whether the simulation reproduces the printed u* within ``tolerance``.

        Parameters
        ----------
        tolerance : float
            Largest relative difference counted as reproduced [-].

        Returns
        -------
        bool
        """
        return abs(self.relative_difference) <= tolerance


@cache
def _reproduce_u_star(conditions: Table3Conditions, duration: float) -> tuple:
    drifts = {k: simulated_drift(get(f"panov-4s-{k}"), conditions=conditions, duration=duration) for k in range(1, 6)}
    out = []
    for row in P.BUDENNYI_TABLE_3:
        d = drifts[row.algorithm]
        ours = d.coning if row.eps == conditions.coning_eps else d.precession
        out.append(UStarCell(row, ours, deg_per_h(ours) / row.u_star_deg_per_h - 1.0))
    return tuple(out)


def reproduce_u_star(*, conditions: Table3Conditions | None = None, duration: float = 100.0) -> tuple:
    """Every u* cell of Table 3 next to the simulated drift.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`table3_conditions`.
    duration : float, keyword-only
        Length of each run [s].

    Returns
    -------
    tuple of UStarCell
        In the order of the printed table.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3, column u*.
    """
    return _reproduce_u_star(_conditions(conditions), positive(duration, "duration"))


class DriftEstimate(NamedTuple):
    """One row of Table 3: the printed values and every estimate of the package.

    Attributes
    ----------
    printed : strapdown.derivations.coning.published.BudennyiTable3Row
        The printed row (deg/h).
    order : int
        ρ of the drift at the motion, derived.
    asymptotic : float
        u_a, the full leading term of the drift series [rad/s].
    series : float
        The drift series through weight 7 [rad/s].
    mid_step : float or None
        The paper's estimate (3): the leading local error projected at the middle of
        the step [rad/s]; given where it differs from ``asymptotic`` (ρ = 6), else None.
    simulated : float
        u* by parallel computation [rad/s].
    """

    printed: P.BudennyiTable3Row
    order: int
    asymptotic: float
    series: float
    mid_step: float | None
    simulated: float

    @property
    def asymptotic_vs_printed(self) -> float | None:
        """``u_a / printed u_a − 1`` (in the printed unit); None where u_a is not printed."""
        return None if self.printed.u_a_deg_per_h is None else deg_per_h(self.asymptotic) / self.printed.u_a_deg_per_h - 1

    @property
    def printed_vs_asymptotic(self) -> float | None:
        """``printed u_a / u_a − 1`` (in the printed unit); None where u_a is not printed."""
        return None if self.printed.u_a_deg_per_h is None else self.printed.u_a_deg_per_h / deg_per_h(self.asymptotic) - 1

    @property
    def asymptotic_vs_printed_u_star(self) -> float:
        """``u_a / printed u* − 1`` (in the printed unit)."""
        return deg_per_h(self.asymptotic) / self.printed.u_star_deg_per_h - 1

    @property
    def asymptotic_vs_simulated(self) -> float:
        """``u_a / simulated u* − 1``."""
        return self.asymptotic / self.simulated - 1


def _mid_step(algorithm, motion, step, rho):
    est = leading_drift(algorithm, rho + 1)
    d = float(est.mid_step.subs({D.EPS: motion.eps, D.THETA: motion.nutation}))
    return abs(d) * motion.nu ** (rho + 1) * step**rho


@cache
def _drift_estimates(conditions: Table3Conditions, duration: float) -> tuple:
    out = []
    H = conditions.step
    for row in P.BUDENNYI_TABLE_3:
        alg = get(f"panov-4s-{row.algorithm}")
        m = conditions.motion(row.eps)
        ours = float(asymptotic_drift(alg, eps=m.eps, nu=m.nu, nutation=m.nutation, step=H))
        ser = float(drift_series(alg, eps=m.eps, nu=m.nu, nutation=m.nutation, step=H))
        rho = int(asymptotic_order(alg, m.eps, m.nutation))
        mid = _mid_step(alg, m, H, rho) if rho == 6 else None
        r = simulate(alg, m, conditions.sample_interval, duration)
        out.append(DriftEstimate(row, rho, ours, ser, mid, float(np.linalg.norm(r.drift, axis=-1))))
    return tuple(out)


def drift_estimates(*, conditions: Table3Conditions | None = None, simulation_duration: float = 20.0) -> tuple:
    """Table 3 row by row: derived order, u_a (full and mid-step), the h⁷ series and the simulated u*.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`table3_conditions`.
    simulation_duration : float, keyword-only
        Length of each parallel-computation run [s].

    Returns
    -------
    tuple of DriftEstimate
        In the order of the printed table.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Table 3.
    """
    return _drift_estimates(_conditions(conditions), positive(simulation_duration, "simulation_duration"))


class Table3Agreement(NamedTuple):
    """How the package's estimates of Table 3 agree with the print and the simulation.

    Attributes
    ----------
    worst_order_4 : float
        Largest ``|u_a / printed u_a − 1|`` over the ρ = 4 rows with a printed u_a.
    worst_order_6_vs_simulated : float
        Largest ``|u_a / simulated u* − 1|`` over the ρ = 6 rows.
    order_6 : tuple of DriftEstimate
        The ρ = 6 rows.
    unprinted : tuple of DriftEstimate
        The rows whose u_a is not printed.
    """

    worst_order_4: float
    worst_order_6_vs_simulated: float
    order_6: tuple
    unprinted: tuple


def table3_agreement(estimates=None) -> Table3Agreement:
    """Summary of :func:`drift_estimates`: the worst agreement of u_a with the print and with the simulation.

    Parameters
    ----------
    estimates : sequence of DriftEstimate, optional
        Default :func:`drift_estimates` ``()``.

    Returns
    -------
    Table3Agreement

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3.
    """
    rows = tuple(drift_estimates() if estimates is None else estimates)
    order_4 = [abs(r.asymptotic_vs_printed) for r in rows if r.order == 4 and r.asymptotic_vs_printed is not None]
    order_6 = tuple(r for r in rows if r.order == 6)
    worst_6 = max((abs(r.asymptotic_vs_simulated) for r in order_6), default=float("nan"))
    unprinted = tuple(r for r in rows if r.printed.u_a_deg_per_h is None)
    return Table3Agreement(max(order_4, default=float("nan")), worst_6, order_6, unprinted)


class ErrorHistory(NamedTuple):
    """Attitude error of one algorithm against time.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    time : ndarray
        Step ends [s].
    error : ndarray
        ``|δφ_I|`` [rad], the norm of the error rotation vector in frame I.
    """

    algorithm: str
    time: np.ndarray
    error: np.ndarray


def coning_error_histories(*, conditions: Table3Conditions | None = None, duration: float = 10.0, engine: str = "auto") -> tuple:
    """Attitude error of the five algorithms of Table 3 under its coning motion.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`table3_conditions`.
    duration : float, keyword-only
        Length of each run [s].
    engine : {"auto", "numpy", "compiled"}, keyword-only
        Simulator engine (:func:`strapdown.analysis.coning.simulator.simulate`);
        ``"numpy"`` compiles nothing, the right choice for a few short runs on a
        cold cache.

    Returns
    -------
    tuple of ErrorHistory
        For ``panov-4s-1`` … ``panov-4s-5``.
    """
    c = _conditions(conditions)
    motion = c.motion(c.coning_eps)
    out = []
    for k in range(1, 6):
        r = simulate(get(f"panov-4s-{k}"), motion, c.sample_interval, positive(duration, "duration"), engine=engine)
        out.append(ErrorHistory(r.algorithm.name, r.time, np.linalg.norm(r.attitude_error, axis=-1)))
    return tuple(out)


class LeadingEstimates(NamedTuple):
    """Three estimates of u_a for a cell whose fourth-order drift cancels (ρ = 6), signed.

    Rates are along the precession axis, exact minus algorithm, so that
    ``full = mid_step + transport``; u_a is their magnitude.  ``small_angle``
    is the part of ``full`` that is of second order in the nutation ϑ (the
    classical small-cone-angle coning drift ``c ϑ² ν (ν h)^6``); the rest of
    ``full`` is of order ϑ⁴ and above.

    Attributes
    ----------
    printed : strapdown.derivations.coning.published.BudennyiTable3Row
        The printed row (deg/h).
    mid_step : float
        The paper's estimate (3): the h⁷ error projected at the middle of the step [rad/s].
    full : float
        The full leading term of the drift series [rad/s].
    transport : float
        ``full − mid_step``: the transport of the weight-5 error [rad/s].
    simulated : float
        ``|u*|`` by parallel computation [rad/s].
    small_angle : float
        The ϑ² part of ``full``: ``lim d_7/ϑ² · ϑ² ν⁷ H⁶`` [rad/s].
    """

    printed: P.BudennyiTable3Row
    mid_step: float
    full: float
    transport: float
    simulated: float
    small_angle: float

    @property
    def printed_vs_mid_step(self) -> float:
        """``printed u_a / |mid_step| − 1`` (in the printed unit)."""
        return self.printed.u_a_deg_per_h / deg_per_h(abs(self.mid_step)) - 1

    @property
    def printed_vs_full(self) -> float:
        """``printed u_a / |full| − 1`` (in the printed unit)."""
        return self.printed.u_a_deg_per_h / deg_per_h(abs(self.full)) - 1

    @property
    def printed_vs_small_angle(self) -> float:
        """``printed u_a / |small_angle| − 1`` (in the printed unit)."""
        return self.printed.u_a_deg_per_h / deg_per_h(abs(self.small_angle)) - 1

    @property
    def full_vs_simulated(self) -> float:
        """``|full| / simulated − 1``."""
        return abs(self.full) / self.simulated - 1


def leading_estimates(*, conditions: Table3Conditions | None = None, simulation_duration: float = 20.0) -> tuple:
    """The three estimates of u_a, signed, for the rows of Table 3 whose drift is of order 6.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`table3_conditions`.
    simulation_duration : float, keyword-only
        Length of each parallel-computation run [s].

    Returns
    -------
    tuple of LeadingEstimates
        Algorithms 3 and 5 under coning, in the order of the table.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Table 3.
    """
    c = _conditions(conditions)
    out = []
    for r in drift_estimates(conditions=c, simulation_duration=simulation_duration):
        if r.order != 6:
            continue
        m = c.motion(r.printed.eps)
        alg = get(f"panov-4s-{r.printed.algorithm}")
        est = leading_drift(alg, 7)
        scale = m.nu**7 * c.step**6
        mid, full = (float(e.subs({D.EPS: m.eps, D.THETA: m.nutation})) * scale for e in (est.mid_step, est.full))
        small = float(_small_cone_limit(alg, 7)) * m.nutation**2 * scale if m.eps == -1.0 else math.nan
        out.append(LeadingEstimates(r.printed, mid, full, full - mid, r.simulated, small))
    return tuple(out)


def _small_cone_limit(algorithm: Algorithm, weight: int):
    """:func:`strapdown.derivations.coning.leading_drift.small_cone_limit` (an exact rational), derived once per algorithm content and weight."""
    key = f"{small_cone_limit.__module__}:{small_cone_limit.__qualname__}:v1:{algorithm_key(algorithm)}:{weight!r}"
    return derived(key, lambda: small_cone_limit(algorithm, weight))
