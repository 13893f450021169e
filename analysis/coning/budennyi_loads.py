"""Tables 4–5 of Budennyi, Kalinovsky, Panov et al.: the computational load for a drift budget.

For each algorithm and motion of Table 3 and each drift budget [u] of Tables
4 (1e-3 deg/h) and 5 (1e-5 deg/h), the largest step ``H_max`` follows from the
asymptotic drift (:func:`strapdown.analysis.coning.computational_load.largest_step`)
and the load is ``β = σ / H_max`` with the operation counts of Table 2,
``σ = s + m u`` (eq. (6)).  The printed tables are compared, never used.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eqs. (3), (6), Tables 2–5.
"""

from __future__ import annotations

from functools import cache
from typing import NamedTuple

import numpy as np

from ...derivations.coning import published as P
from ...derivations.coning.registry import get
from ..core.units import RAD_PER_S_TO_DEG_PER_H
from ..core.validation import nonnegative
from .budennyi_table3 import Table3Conditions, table3_conditions
from .computational_load import DesignRow, OperationCount, design, largest_step
from .precession import RegularPrecession

__all__ = [
    "required_drifts",
    "LoadRow",
    "load_rows",
    "QuaternionCostFit",
    "fit_quaternion_cost",
    "FittedLoad",
    "PerSampleFit",
    "per_sample_fit",
    "table2_counts",
    "LoadCurve",
    "load_curves",
    "DesignPoint",
    "design_points",
]


def required_drifts() -> tuple:
    """The drift budgets [u] of Tables 4 and 5 [rad/s].

    Returns
    -------
    tuple of float
        (Table 4, Table 5).
    """
    return tuple(u / RAD_PER_S_TO_DEG_PER_H for u in P.BUDENNYI_CONDITIONS.required_drift_deg_per_h)


def table2_counts() -> dict:
    """The operation counts s, u of Table 2, ``{"panov-4s-<n>": OperationCount}``.

    Returns
    -------
    dict
    """
    return {f"panov-4s-{c.algorithm}": OperationCount(c.additions, c.multiplications) for c in P.BUDENNYI_TABLE_2}


class LoadRow(NamedTuple):
    """One row of Tables 4–5 with the largest steps and the algorithm's cost.

    Attributes
    ----------
    printed : strapdown.derivations.coning.published.BudennyiLoadRow
        The printed row (thousand operations/s).
    order : int
        ρ of the drift, derived.
    step_4 : float
        H_max for the budget of Table 4 [s], from u_a.
    step_5 : float
        H_max for the budget of Table 5 [s], from u_a.
    algorithm_cost : float
        σ_alg = s + m u of one step [addition-equivalents].
    """

    printed: P.BudennyiLoadRow
    order: int
    step_4: float
    step_5: float
    algorithm_cost: float


@cache
def _load_rows(conditions: Table3Conditions, m: float) -> tuple:
    counts = table2_counts()
    u4, u5 = required_drifts()
    rows = []
    for printed in P.BUDENNYI_TABLES_4_5:
        name = f"panov-4s-{printed.algorithm}"
        motion = conditions.motion(printed.eps)
        h4, rho = largest_step(get(name), u4, motion)
        h5, _ = largest_step(get(name), u5, motion)
        rows.append(LoadRow(printed, rho, h4, h5, counts[name].cost(m)))
    return tuple(rows)


def load_rows(*, conditions: Table3Conditions | None = None, m: float | None = None) -> tuple:
    """Tables 4–5 row by row: derived order, largest steps and the algorithm cost of Table 2.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`strapdown.analysis.coning.budennyi_table3.table3_conditions`.
    m : float, keyword-only, optional
        Cost of a multiplication in additions; default the paper's m = 5.

    Returns
    -------
    tuple of LoadRow
        In the order of the printed tables.
    """
    m = P.BUDENNYI_CONDITIONS.multiplication_cost if m is None else nonnegative(m, "m")
    return _load_rows(conditions or table3_conditions(), m)


class QuaternionCostFit(NamedTuple):
    """The quaternion-update cost that best fits the printed β_a of Table 4 under β = (σ_alg + σ_q)/H_max.

    Attributes
    ----------
    sigma_q : float
        Least-squares σ_q (squared log error, 1-unit grid) [addition-equivalents].
    implied : tuple of float
        σ_q backed out of each printed β_a: ``β_a H_max − σ_alg``.
    """

    sigma_q: float
    implied: tuple


def fit_quaternion_cost(rows) -> QuaternionCostFit:
    """Fit one σ_q to the printed β_a of Table 4 (a comparison with the print, not a model).

    Parameters
    ----------
    rows : sequence of LoadRow
        From :func:`load_rows`.

    Returns
    -------
    QuaternionCostFit
    """
    grid = np.arange(0.0, 3000.0, 1.0)
    data = [(r.algorithm_cost, r.step_4, r.printed.beta_a_4) for r in rows if r.printed.beta_a_4 is not None]
    cost = [sum((np.log((sig + q) / H / 1e3) - np.log(b)) ** 2 for sig, H, b in data) for q in grid]
    q = float(grid[int(np.argmin(cost))])
    return QuaternionCostFit(q, tuple(b * 1e3 * H - sig for sig, H, b in data))


class FittedLoad(NamedTuple):
    """One printed load beside the fitted per-sample reading.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5.
    column : str
        ``"β_a (T4)"``, ``"β* (T4)"`` or ``"β* (T5)"``.
    printed : float
        The printed load [thousand operations/s].
    model : float
        The fitted reading [thousand operations/s].
    """

    algorithm: int
    column: str
    printed: float
    model: float


class PerSampleFit(NamedTuple):
    """The per-sample reading fitted to every printed load of one motion.

    Attributes
    ----------
    eps : float
        ε of the motion.
    sigma_q : float
        Fitted quaternion-update cost per step [addition-equivalents].
    cells : tuple of FittedLoad
        Every printed load of the motion.
    """

    eps: float
    sigma_q: float
    cells: tuple


def per_sample_fit(rows, simulated: dict, *, step: float | None = None, samples: int = 4) -> tuple:
    """Fit of ``β = (N σ_alg + σ_q)/H_max`` to every printed load, σ_q per motion.

    The algorithm's operations (Table 2) are spent once per sample h (the
    recursive form of a multi-sample algorithm), so N times per step H, and the
    quaternion update once per step.  β_a uses H_max from u_a; β* (Tables 4 and
    5) uses H_max from the simulated u* at the Table 3 step, with the same
    order.  σ_q is fitted per motion by least squares on log β: this is a
    comparison with the print, not a model.

    Parameters
    ----------
    rows : sequence of LoadRow
        From :func:`load_rows`.
    simulated : mapping
        ``{(algorithm number, ε): u*}`` [rad/s] at the step of Table 3.
    step : float, keyword-only, optional
        The step of the simulated u* [s]; default that of Table 3.
    samples : int, keyword-only
        N.

    Returns
    -------
    tuple of PerSampleFit
        One per motion, by increasing ε.
    """
    H3 = P.BUDENNYI_CONDITIONS.step if step is None else step
    u4, u5 = required_drifts()
    out = []
    for eps in sorted({r.printed.eps for r in rows}):
        data = []
        for r in (r for r in rows if r.printed.eps == eps):
            u_star = simulated[(r.printed.algorithm, eps)]
            cost = samples * r.algorithm_cost
            if r.printed.beta_a_4 is not None:
                data.append((r.printed.algorithm, "β_a (T4)", r.printed.beta_a_4, cost, r.step_4))
            data.append((r.printed.algorithm, "β* (T4)", r.printed.beta_star_4, cost, H3 * (u4 / u_star) ** (1.0 / r.order)))
            data.append((r.printed.algorithm, "β* (T5)", r.printed.beta_star_5, cost, H3 * (u5 / u_star) ** (1.0 / r.order)))
        grid = np.arange(0.0, 3000.0, 1.0)
        err = [sum((np.log((c + q) / H / 1e3) - np.log(b)) ** 2 for _, _, b, c, H in data) for q in grid]
        q = float(grid[int(np.argmin(err))])
        out.append(PerSampleFit(eps, q, tuple(FittedLoad(k, col, b, (c + q) / H / 1e3) for k, col, b, c, H in data)))
    return tuple(out)


class LoadCurve(NamedTuple):
    """Load of one algorithm against the motion frequency.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    eps : float
        ε of the motion.
    frequencies : ndarray
        f [Hz].
    loads : ndarray
        β [operations/s].
    """

    algorithm: str
    eps: float
    frequencies: np.ndarray
    loads: np.ndarray


def load_curves(frequencies, *, eps_values, nutation: float, required_drift: float, algorithms, counts=None) -> tuple:
    """Load of each algorithm against f for each ε (the extension of Tables 4–5 in frequency).

    Parameters
    ----------
    frequencies : array_like
        f [Hz], ν = 2π f.
    eps_values : sequence of float, keyword-only
        ε of the motions.
    nutation : float, keyword-only
        ϑ [rad].
    required_drift : float, keyword-only
        [u] [rad/s].
    algorithms : sequence of str, keyword-only
        Registry names.
    counts : mapping, keyword-only, optional
        Operation counts overriding the package's (as in :func:`~strapdown.analysis.coning.computational_load.design`).

    Returns
    -------
    tuple of LoadCurve
        ε by ε, algorithm by algorithm.
    """
    freqs = np.asarray(frequencies, dtype=float)
    out = []
    for eps in eps_values:
        for name in algorithms:
            loads = [design(required_drift, RegularPrecession(eps, 2 * np.pi * f, nutation), algorithms=[name], counts=counts)[0].load for f in freqs]
            out.append(LoadCurve(name, eps, freqs, np.array(loads)))
    return tuple(out)


class DesignPoint(NamedTuple):
    """One algorithm designed for one motion and budget.

    Attributes
    ----------
    eps : float
        ε of the motion.
    required_drift : float
        [u] [rad/s].
    row : strapdown.analysis.coning.computational_load.DesignRow
        Step, sampling rate and load.
    nu_step : float
        νH [rad]: the spin angle per step.
    """

    eps: float
    required_drift: float
    row: DesignRow
    nu_step: float


def design_points(freq_hz: float, *, eps_values, nutation: float, budgets: tuple, algorithms, counts=None) -> tuple:
    """Design every algorithm at one frequency, for each ε and budget (ranked by load).

    Parameters
    ----------
    freq_hz : float
        f [Hz], ν = 2π f.
    eps_values : sequence of float, keyword-only
        ε of the motions.
    nutation : float, keyword-only
        ϑ [rad].
    budgets : sequence of float, keyword-only
        Budgets [u] [rad/s].
    algorithms : sequence of str, keyword-only
        Registry names.
    counts : mapping, keyword-only, optional
        Operation counts overriding the package's.

    Returns
    -------
    tuple of DesignPoint
    """
    nu = 2 * np.pi * freq_hz
    out = []
    for eps in eps_values:
        for u in budgets:
            for r in design(u, RegularPrecession(eps, nu, nutation), algorithms=algorithms, counts=counts):
                out.append(DesignPoint(eps, u, r, nu * r.step))
    return tuple(out)
