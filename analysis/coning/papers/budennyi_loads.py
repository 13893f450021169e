"""Tables 4–5 of Budennyi, Kalinovsky, Panov et al.: the computational load for a drift budget.

Every printed load is recomputed from first principles with one model for
both motions and both budgets (:class:`strapdown.analysis.coning.computational_load.LoadModel`):
the operation count of the increment algorithm
(:func:`~strapdown.analysis.coning.computational_load.operation_count`, which
reproduces the counts of Table 2), one quaternion update whose half-angle
series are cut by the accuracy rule
(:func:`~strapdown.analysis.coning.computational_load.series_terms`), and the
time base.  No constant is fitted to the printed loads.  The step of a cell is
the largest step for its budget: from the asymptotic drift u_a for β_a, from the
simulated drift u* at the Table 3 step, scaled with the order ρ, for β*.

:func:`reproduce_loads` gives the per-cell table and the hits;
:func:`printed_consistency` tests the printed loads against each other and
against Table 3, whatever the cost model; :func:`per_sample_fit` keeps the
earlier reading, a quaternion cost fitted per motion, as a comparison.  The
printed tables (:mod:`strapdown.derivations.coning.published`) are compared,
never used as inputs.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eqs. (3), (6), Tables 2–5.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import NamedTuple

import numpy as np

from ....derivations.coning import published as P
from ....derivations.coning.registry import get
from ...core.units import RAD_PER_S_TO_DEG_PER_H
from ...core.validation import positive
from ..computational_load import TIME_BASES, DesignRow, LoadModel, design, largest_step, operation_count, quaternion_update_count, step_load
from ..precession import RegularPrecession
from .budennyi_table3 import Table3Conditions, drift_estimates, table3_conditions

__all__ = [
    "required_drifts",
    "CountCheck",
    "operation_count_checks",
    "LoadCell",
    "LoadReproduction",
    "reproduce_loads",
    "SensitivityCell",
    "load_model_sensitivity",
    "CheapestAlgorithms",
    "cheapest_algorithms",
    "ConsistencyCheck",
    "printed_consistency",
    "MissExplanation",
    "explain_misses",
    "FittedLoad",
    "PerSampleFit",
    "per_sample_fit",
    "FitComparison",
    "compare_per_sample_fit",
    "LoadCurve",
    "load_curves",
    "DesignPoint",
    "design_points",
    "DesignSummary",
    "summarize_designs",
]

#: Column names of the printed loads: β_a and β* of Table 4, β* of Table 5.
COLUMNS = ("β_a (T4)", "β* (T4)", "β* (T5)")


def required_drifts() -> tuple:
    """The drift budgets [u] of Tables 4 and 5 [rad/s].

    Returns
    -------
    tuple of float
        (Table 4, Table 5).
    """
    return tuple(u / RAD_PER_S_TO_DEG_PER_H for u in P.BUDENNYI_CONDITIONS.required_drift_deg_per_h)


class CountCheck(NamedTuple):
    """The operation count of one algorithm beside Table 2.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5.
    printed : tuple of int
        (s, u) as printed: additions and multiplications of one step.
    counted : tuple of int
        (s, u) from :func:`~strapdown.analysis.coning.computational_load.operation_count`.
    """

    algorithm: int
    printed: tuple
    counted: tuple

    @property
    def equal(self) -> bool:
        """True when the count equals the print."""
        return self.printed == self.counted


def operation_count_checks() -> tuple:
    """The operation counts of the five algorithms against the s, u of Table 2.

    Returns
    -------
    tuple of CountCheck
        In the order of Table 2.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), Table 2.

    Examples
    --------
    >>> all(c.equal for c in operation_count_checks())
    True
    """
    out = []
    for c in P.BUDENNYI_TABLE_2:
        n = operation_count(get(f"panov-4s-{c.algorithm}"))
        out.append(CountCheck(c.algorithm, (c.additions, c.multiplications), (n.additions, n.multiplications)))
    return tuple(out)


class _Cell(NamedTuple):
    row: P.BudennyiLoadRow
    column: str
    printed: int
    required_drift: float
    step: float
    order: int


def _cells(conditions: Table3Conditions, simulation_duration: float) -> tuple:
    """Every printed load with its budget, its step and its order."""
    u4, u5 = required_drifts()
    simulated = {(r.printed.algorithm, r.printed.eps): r.simulated for r in drift_estimates(conditions=conditions, simulation_duration=simulation_duration)}
    out = []
    for row in P.BUDENNYI_TABLES_4_5:
        alg = get(f"panov-4s-{row.algorithm}")
        step_a, rho = largest_step(alg, u4, conditions.motion(row.eps))
        u_star = simulated[(row.algorithm, row.eps)]
        if row.beta_a_4 is not None:
            out.append(_Cell(row, COLUMNS[0], row.beta_a_4, u4, step_a, rho))
        out.append(_Cell(row, COLUMNS[1], row.beta_star_4, u4, conditions.step * (u4 / u_star) ** (1.0 / rho), rho))
        out.append(_Cell(row, COLUMNS[2], row.beta_star_5, u5, conditions.step * (u5 / u_star) ** (1.0 / rho), rho))
    return tuple(out)


class LoadCell(NamedTuple):
    """One printed load beside the model.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5.
    eps : float
        ε of the motion.
    column : str
        One of :data:`COLUMNS`.
    printed : int
        The printed load [thousand operations/s].
    required_drift : float
        The budget [u] of the table [rad/s].
    row : strapdown.analysis.coning.computational_load.DesignRow
        The model at the cell's step: angle per step, series terms, costs and load [operations/s].
    """

    algorithm: int
    eps: float
    column: str
    printed: int
    required_drift: float
    row: DesignRow

    @property
    def relative_difference(self) -> float:
        """``model / printed − 1``."""
        return self.row.load / (1e3 * self.printed) - 1


@dataclass(frozen=True)
class LoadReproduction:
    """Every printed load of Tables 4–5 beside one load model.

    Attributes
    ----------
    model : LoadModel
        The rules used.
    cells : tuple of LoadCell
        In the order of the printed tables, column by column.
    tolerance : float
        Relative difference counted as reproduced.
    """

    model: LoadModel
    cells: tuple
    tolerance: float

    @property
    def hits(self) -> tuple:
        """Cells within the tolerance."""
        return tuple(c for c in self.cells if abs(c.relative_difference) <= self.tolerance)

    @property
    def misses(self) -> tuple:
        """Cells beyond the tolerance."""
        return tuple(c for c in self.cells if abs(c.relative_difference) > self.tolerance)

    def series_terms(self, eps: float) -> tuple:
        """The series lengths K the model's rule picks for the cells of one motion, in increasing order.

        Parameters
        ----------
        eps : float
            ε of the motion.

        Returns
        -------
        tuple of int
        """
        return tuple(sorted({c.row.series_terms for c in self.cells if c.eps == eps}))


@cache
def _reproduce_loads(model: LoadModel, tolerance: float, conditions: Table3Conditions, simulation_duration: float) -> LoadReproduction:
    out = []
    for c in _cells(conditions, simulation_duration):
        alg = get(f"panov-4s-{c.row.algorithm}")
        row = step_load(alg, c.step, c.required_drift, conditions.motion(c.row.eps), order=c.order, model=model, count=operation_count(alg))
        out.append(LoadCell(c.row.algorithm, c.row.eps, c.column, c.printed, c.required_drift, row))
    return LoadReproduction(model, tuple(out), tolerance)


def reproduce_loads(*, model: LoadModel | None = None, tolerance: float = 0.02, conditions: Table3Conditions | None = None,
                    simulation_duration: float = 20.0) -> LoadReproduction:  # fmt: skip
    """Recompute every printed load of Tables 4–5 with one load model and no fitted constant.

    Parameters
    ----------
    model : LoadModel, keyword-only, optional
        Default ``LoadModel()`` (time base h, series rule f = 0.1, m = 5).
    tolerance : float, keyword-only
        Relative difference counted as reproduced.
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`strapdown.analysis.coning.papers.budennyi_table3.table3_conditions`.
    simulation_duration : float, keyword-only
        Length of the runs that give u* [s].

    Returns
    -------
    LoadReproduction

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (6), Tables 2–5.

    Examples
    --------
    >>> r = reproduce_loads()
    >>> len(r.cells), len(r.hits)
    (29, 24)
    """
    return _reproduce_loads(model or LoadModel(), positive(tolerance, "tolerance"), conditions or table3_conditions(), positive(simulation_duration, "simulation_duration"))


class SensitivityCell(NamedTuple):
    """How many printed loads one variant of the load model reproduces.

    Attributes
    ----------
    time_base : str
        ``"sample"`` or ``"step"`` (:class:`~strapdown.analysis.coning.computational_load.LoadModel`).
    truncation_fraction : float
        f of the series rule.
    hits : int
        Cells within the tolerance.
    cells : int
        All printed cells.
    """

    time_base: str
    truncation_fraction: float
    hits: int
    cells: int


def load_model_sensitivity(truncation_fractions=(1.0, 0.1, 0.01), *, time_bases=TIME_BASES, m: float | None = None, tolerance: float = 0.02) -> tuple:
    """Cells of Tables 4–5 reproduced by each combination of the two rules of the load model.

    Parameters
    ----------
    truncation_fractions : sequence of float
        Values of f of the series rule, > 0.
    time_bases : sequence of str, keyword-only
        Time bases (default both).
    m : float, keyword-only, optional
        Cost of a multiplication in additions (default: the printed m of eq. (6)).
    tolerance : float, keyword-only
        Relative difference counted as reproduced.

    Returns
    -------
    tuple of SensitivityCell
        Time base by time base, f by f.
    """
    m = P.BUDENNYI_CONDITIONS.multiplication_cost if m is None else m
    out = []
    for tb in time_bases:
        for f in truncation_fractions:
            r = reproduce_loads(model=LoadModel(m, tb, f), tolerance=tolerance)
            out.append(SensitivityCell(tb, float(f), len(r.hits), len(r.cells)))
    return tuple(out)


class CheapestAlgorithms(NamedTuple):
    """The cheapest algorithm of both load tables under one motion, by the model and as printed.

    Attributes
    ----------
    eps : float
        ε of the motion.
    model : tuple of int
        The algorithms that are cheapest by the model in the β* columns of Tables 4 and 5.
    printed : tuple of int
        The same from the printed loads.
    """

    eps: float
    model: tuple
    printed: tuple

    @property
    def as_printed(self) -> bool:
        """True when the model ranks as the paper does."""
        return self.model == self.printed


def cheapest_algorithms(reproduction: LoadReproduction | None = None) -> tuple:
    """The ranking of the paper: which algorithm is cheapest in both β* columns, per motion.

    Parameters
    ----------
    reproduction : LoadReproduction, optional
        Default :func:`reproduce_loads` ``()``.

    Returns
    -------
    tuple of CheapestAlgorithms
        By increasing ε.
    """
    reproduction = reproduction or reproduce_loads()
    out = []
    for eps in sorted({c.eps for c in reproduction.cells}):
        model, printed = set(), set()
        for column in COLUMNS[1:]:
            cells = [c for c in reproduction.cells if c.eps == eps and c.column == column]
            model.add(min(cells, key=lambda c: c.row.load).algorithm)
            printed.add(min(cells, key=lambda c: c.printed).algorithm)
        out.append(CheapestAlgorithms(eps, tuple(sorted(model)), tuple(sorted(printed))))
    return tuple(out)


class ConsistencyCheck(NamedTuple):
    """A ratio of two printed loads against the ratio any load ``σ / H_max`` with one cost must give.

    Attributes
    ----------
    cells : tuple of str
        The two cells, e.g. ``("alg. 3 ε=-1 β* (T4)", "alg. 3 ε=-1 β_a (T4)")``.
    printed_ratio : float
        First printed load over the second.
    expected_ratio : float
        The same ratio from the printed drift rates of Table 3 and the budgets:
        the ratio of the two largest steps, inverted.
    reason : str
        What the expectation rests on.
    """

    cells: tuple
    printed_ratio: float
    expected_ratio: float
    reason: str

    @property
    def deviation(self) -> float:
        """``printed_ratio / expected_ratio − 1``."""
        return self.printed_ratio / self.expected_ratio - 1


def _label(row, column) -> str:
    return f"alg. {row.algorithm} ε={row.eps:g} {column}"


def printed_consistency() -> tuple:
    """Test the printed loads against each other and against the printed Table 3.

    For a load ``β = σ / H_max`` with the same cost σ in both cells, and
    ``H_max ∝ u^(−1/ρ)``:

    * β* / β_a of one row (Table 4) equals ``(u*/u_a)^(1/ρ)`` of Table 3;
    * β* of Table 5 over β* of Table 4 equals ``([u]_4/[u]_5)^(1/ρ)``;
    * two algorithms with the same operation counts (Table 2) and order under
      one motion have β ratios ``(u*_1/u*_2)^(1/ρ)``.

    The series length of the quaternion update can change the cost between two
    cells by one series term, a few per cent at most.

    Returns
    -------
    tuple of ConsistencyCheck

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), Tables 2–5.
    """
    u4, u5 = P.BUDENNYI_CONDITIONS.required_drift_deg_per_h
    t3 = {(r.algorithm, r.eps): r for r in P.BUDENNYI_TABLE_3}
    counts = {c.algorithm: (c.additions, c.multiplications) for c in P.BUDENNYI_TABLE_2}
    rows = P.BUDENNYI_TABLES_4_5
    out = []
    for row in rows:
        rho = row.order
        r3 = t3[(row.algorithm, row.eps)]
        if row.beta_a_4 is not None and r3.u_a_deg_per_h is not None:
            out.append(ConsistencyCheck((_label(row, COLUMNS[1]), _label(row, COLUMNS[0])), row.beta_star_4 / row.beta_a_4, (r3.u_star_deg_per_h / r3.u_a_deg_per_h) ** (1 / rho),
                                        "printed u*/u_a of Table 3"))  # fmt: skip
        out.append(ConsistencyCheck((_label(row, COLUMNS[2]), _label(row, COLUMNS[1])), row.beta_star_5 / row.beta_star_4, (u4 / u5) ** (1 / rho),
                                    "the two budgets [u]"))  # fmt: skip
    for a in rows:
        for b in rows:
            same = a.eps == b.eps and a.order == b.order and counts[a.algorithm] == counts[b.algorithm]
            if same and a.algorithm > b.algorithm:
                expected = (t3[(a.algorithm, a.eps)].u_star_deg_per_h / t3[(b.algorithm, b.eps)].u_star_deg_per_h) ** (1 / a.order)
                for col, ba, bb in ((COLUMNS[1], a.beta_star_4, b.beta_star_4), (COLUMNS[2], a.beta_star_5, b.beta_star_5)):
                    out.append(ConsistencyCheck((_label(a, col), _label(b, col)), ba / bb, expected, "equal operation counts (Table 2) and printed u* of Table 3"))
    return tuple(out)


class FittedLoad(NamedTuple):
    """One printed load beside the fitted per-sample reading.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5.
    column : str
        One of :data:`COLUMNS`.
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
    """The per-sample reading with a quaternion cost fitted to the printed loads of one motion.

    Attributes
    ----------
    eps : float
        ε of the motion.
    sigma_q : float
        Fitted quaternion-update cost per step H [addition-equivalents].
    cells : tuple of FittedLoad
        Every printed load of the motion.
    samples : int
        Samples N per step.
    """

    eps: float
    sigma_q: float
    cells: tuple
    samples: int = 4

    @property
    def sigma_q_per_sample(self) -> float:
        """σ_q / N [addition-equivalents per sample]."""
        return self.sigma_q / self.samples

    def within(self, tolerance: float = 0.02) -> tuple:
        """The cells the fitted reading reproduces within ``tolerance``.

        Parameters
        ----------
        tolerance : float
            Relative difference counted as reproduced.

        Returns
        -------
        tuple of FittedLoad
        """
        return tuple(c for c in self.cells if abs(c.model / c.printed - 1) <= tolerance)


@cache
def per_sample_fit(*, conditions: Table3Conditions | None = None, simulation_duration: float = 20.0) -> tuple:
    """The earlier reading, kept as a comparison: ``β = (N σ_alg + σ_q)/H_max`` with σ_q fitted per motion.

    The algorithm's operations are spent once per sample (N times per step),
    the quaternion update once per step, and σ_q is fitted per motion by least
    squares on log β (1-unit grid).  This fits constants to the print; the model
    of :func:`reproduce_loads` does not.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`strapdown.analysis.coning.papers.budennyi_table3.table3_conditions`.
    simulation_duration : float, keyword-only
        Length of the runs that give u* [s].

    Returns
    -------
    tuple of PerSampleFit
        One per motion, by increasing ε.
    """
    conditions = conditions or table3_conditions()
    m = P.BUDENNYI_CONDITIONS.multiplication_cost
    cells = _cells(conditions, simulation_duration)
    out = []
    for eps in sorted({c.row.eps for c in cells}):
        data = [(c.row.algorithm, c.column, c.printed, conditions.samples * operation_count(get(f"panov-4s-{c.row.algorithm}")).cost(m), c.step) for c in cells if c.row.eps == eps]
        grid = np.arange(0.0, 3000.0, 1.0)
        err = np.zeros_like(grid)
        for _, _, b, cost, H in data:  # summed cell by cell, in the order of the cells, for every σ_q of the grid at once
            err += (np.log((cost + grid) / H / 1e3) - np.log(b)) ** 2
        q = float(grid[int(np.argmin(err))])
        out.append(PerSampleFit(eps, q, tuple(FittedLoad(k, col, b, (cost + q) / H / 1e3) for k, col, b, cost, H in data), conditions.samples))
    return tuple(out)


class FitComparison(NamedTuple):
    """The fitted per-sample reading set against the load model, motion by motion.

    Attributes
    ----------
    fits : tuple of PerSampleFit
        By increasing ε.
    series_terms : tuple of tuple of int
        For each fit, the series lengths K the model picks for that motion.
    model_costs : tuple of tuple of float
        For each fit, the model's quaternion-update cost σ_q at those K.
    within : tuple of int
        For each fit, the cells it reproduces within the tolerance.
    tolerance : float
        Relative difference counted as reproduced.
    per_sample_difference : float
        Difference of the two fitted costs per sample, last motion minus first.
    two_term_cost : float
        The model's cost of two more series terms (K = 2 → 3, times two).
    """

    fits: tuple
    series_terms: tuple
    model_costs: tuple
    within: tuple
    tolerance: float
    per_sample_difference: float
    two_term_cost: float

    @property
    def total_within(self) -> int:
        """Cells of both motions reproduced by the fitted reading."""
        return sum(self.within)

    @property
    def total_cells(self) -> int:
        """All printed cells."""
        return sum(len(f.cells) for f in self.fits)


def compare_per_sample_fit(reproduction: LoadReproduction | None = None, *, tolerance: float = 0.02) -> FitComparison:
    """The earlier, fitted reading (:func:`per_sample_fit`) against the model of :func:`reproduce_loads`.

    Parameters
    ----------
    reproduction : LoadReproduction, optional
        Default :func:`reproduce_loads` ``()``.
    tolerance : float, keyword-only
        Relative difference counted as reproduced.

    Returns
    -------
    FitComparison
    """
    reproduction = reproduction or reproduce_loads()
    tolerance = positive(tolerance, "tolerance")
    m = reproduction.model.m
    fits = per_sample_fit()
    terms = tuple(reproduction.series_terms(f.eps) for f in fits)
    costs = tuple(tuple(quaternion_update_count(k).cost(m) for k in ks) for ks in terms)
    within = tuple(len(f.within(tolerance)) for f in fits)
    difference = fits[-1].sigma_q_per_sample - fits[0].sigma_q_per_sample
    two_terms = 2 * (quaternion_update_count(3).cost(m) - quaternion_update_count(2).cost(m))
    return FitComparison(fits, terms, costs, within, tolerance, float(difference), float(two_terms))


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


def load_curves(frequencies, *, eps_values, nutation: float, required_drift: float, algorithms, model: LoadModel | None = None) -> tuple:
    """Load of each algorithm against f for each ε (Tables 4–5 extended in frequency).

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
    model : LoadModel, keyword-only, optional
        Default ``LoadModel()``.

    Returns
    -------
    tuple of LoadCurve
        ε by ε, algorithm by algorithm.
    """
    freqs = np.asarray(frequencies, dtype=float)
    out = []
    for eps in eps_values:
        for name in algorithms:
            loads = [design(required_drift, RegularPrecession(eps, 2 * np.pi * f, nutation), algorithms=[name], model=model)[0].load for f in freqs]
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
        Step, angle per step, series terms, sampling rate and load.
    nu_step : float
        νH [rad]: the spin angle per step, on which the accuracy of the asymptotic drift depends.
    """

    eps: float
    required_drift: float
    row: DesignRow
    nu_step: float


def design_points(freq_hz: float, *, eps_values, nutation: float, budgets: tuple, algorithms, model: LoadModel | None = None) -> tuple:
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
    model : LoadModel, keyword-only, optional
        Default ``LoadModel()``.

    Returns
    -------
    tuple of DesignPoint
    """
    nu = 2 * np.pi * positive(freq_hz, "freq_hz")
    out = []
    for eps in eps_values:
        for u in budgets:
            for r in design(u, RegularPrecession(eps, nu, nutation), algorithms=algorithms, model=model):
                out.append(DesignPoint(eps, u, r, nu * r.step))
    return tuple(out)


class DesignSummary(NamedTuple):
    """The cheapest design for each motion and budget, and the largest spin angle per step.

    Attributes
    ----------
    cheapest : tuple of DesignPoint
        One per (ε, budget): motions in the order given, budgets from the largest.
    largest_nu_step : float
        Largest νH [rad] of all designs.
    """

    cheapest: tuple
    largest_nu_step: float


def summarize_designs(points) -> DesignSummary:
    """The cheapest algorithm of each motion and budget among :func:`design_points`.

    Parameters
    ----------
    points : sequence of DesignPoint
        From :func:`design_points`.

    Returns
    -------
    DesignSummary

    Raises
    ------
    ValueError
        If ``points`` is empty.
    """
    points = tuple(points)
    if not points:
        raise ValueError("Expected `points` to hold at least one DesignPoint, got none")
    eps_values = list(dict.fromkeys(p.eps for p in points))
    budgets = sorted({p.required_drift for p in points}, reverse=True)
    cheapest = []
    for eps in eps_values:
        for u in budgets:
            group = [p for p in points if p.eps == eps and p.required_drift == u]
            if group:
                cheapest.append(min(group, key=lambda p: p.row.load))
    return DesignSummary(tuple(cheapest), float(max(p.nu_step for p in points)))


class MissExplanation(NamedTuple):
    """A printed load the model misses, with the checks of the print that the same cell fails.

    Attributes
    ----------
    cell : LoadCell
        The missed cell.
    checks : tuple of ConsistencyCheck
        The consistency checks involving the cell that deviate by more than the tolerance.
    """

    cell: LoadCell
    checks: tuple


def explain_misses(reproduction: LoadReproduction | None = None) -> tuple:
    """For every cell the model misses, the printed-consistency checks it fails.

    A miss whose cell also fails a check of the print against itself
    (:func:`printed_consistency`), by about the size of the miss, points at the
    printed value rather than at the model.

    Parameters
    ----------
    reproduction : LoadReproduction, optional
        Default :func:`reproduce_loads` ``()``.

    Returns
    -------
    tuple of MissExplanation
        In the order of the misses.
    """
    reproduction = reproduction or reproduce_loads()
    checks = printed_consistency()
    out = []
    for cell in reproduction.misses:
        label = f"alg. {cell.algorithm} ε={cell.eps:g} {cell.column}"
        failed = tuple(c for c in checks if label in c.cells and abs(c.deviation) > reproduction.tolerance)
        out.append(MissExplanation(cell, failed))
    return tuple(out)
