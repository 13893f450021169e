"""Evidence for the reconstruction of formula (1) and Table 1 of Budennyi, Kalinovsky, Panov et al.

Two independent checks decide which constant of Table 1 multiplies which
cross product, and how the column of algorithm 2 must be read:

* :func:`assignment_scores` simulates every assignment of a1 … a4 to the
  registry's four combinations (:func:`strapdown.derivations.coning.formula_one.basis_assignments`)
  at the conditions of Table 3, with Table 1 as printed and with column 2
  read as a1 = a2 = 4/3, and counts the printed u* cells each reproduces;
* :func:`table2_fits` fits the local error of each algorithm, on a motion with
  no symmetry (:class:`strapdown.analysis.coning.local_error.TumblingMotion`),
  to the basis of eq. (2) and sets the fitted ``c/δ4`` beside the printed k of
  Table 2, for the registry algorithms and for column 2 as printed.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), formula (1), Tables 1–3.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from typing import NamedTuple

from ....derivations.coning import published as P
from ....derivations.coning import series as S
from ....derivations.coning.algorithms import Algorithm, second_order_defect
from ....derivations.coning.formula_one import BasisAssignment, algorithm_from_constants, basis_assignments
from ....derivations.coning.registry import PANOV_TABLE_1, get
from ...core.units import deg_per_h
from ...core.validation import positive
from ..drift_theory import asymptotic_drift
from ..local_error import error_coefficients
from .budennyi_table3 import Table3Conditions, Table3Drift, simulated_drift, table3_conditions

__all__ = [
    "printed_column_2",
    "Column2Readings",
    "column_2_readings",
    "Column2Estimates",
    "column_2_estimates",
    "AssignmentScore",
    "assignment_scores",
    "best_alternative",
    "Table2Fit",
    "table2_fits",
]


def printed_column_2() -> Algorithm:
    """Algorithm 2 of Table 1 as printed under the registry's formula (1): 4/3 (p1×p3 + p2×p4).

    Returns
    -------
    Algorithm

    Examples
    --------
    >>> sorted(printed_column_2().pairwise)
    [(1, 3), (2, 4)]
    """
    return algorithm_from_constants(P.BUDENNYI_TABLE_1_COLUMN_2, name="Table 1 column 2 as printed")


class Column2Readings(NamedTuple):
    """Simulated Table 3 drift of algorithm 2 under the two readings of its Table 1 column.

    Attributes
    ----------
    printed : Table3Drift
        Column 2 as printed, 4/3 (p1×p3 + p2×p4) [rad/s].
    corrected : Table3Drift
        The registry's reading a1 = a2 = 4/3, i.e. 4/3 (p1×p4 + p2×p3) [rad/s].
    """

    printed: Table3Drift
    corrected: Table3Drift


def column_2_readings(*, conditions: Table3Conditions | None = None, duration: float = 100.0) -> Column2Readings:
    """Drift of algorithm 2 read as printed and as corrected, at the conditions of Table 3.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`strapdown.analysis.coning.papers.budennyi_table3.table3_conditions`.
    duration : float, keyword-only
        Length of each run [s].

    Returns
    -------
    Column2Readings
    """
    return Column2Readings(
        simulated_drift(printed_column_2(), conditions=conditions, duration=duration),
        simulated_drift(get("panov-4s-2"), conditions=conditions, duration=duration),
    )


class Column2Estimates(NamedTuple):
    """What the derivation says about algorithm 2 of Table 1 as printed.

    Attributes
    ----------
    k12 : Fraction
        Its local-error coefficient k12, exact, in units of the printed δ4 of algorithm 2
        (Table 2 prints 124 for algorithm 2).
    asymptotic : Table3Drift
        Its asymptotic drift u_a at the conditions of Table 3 [rad/s].
    """

    k12: Fraction
    asymptotic: Table3Drift


def column_2_estimates(*, conditions: Table3Conditions | None = None) -> Column2Estimates:
    """Exact k12 and asymptotic drift of algorithm 2 of Table 1 as printed.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`strapdown.analysis.coning.papers.budennyi_table3.table3_conditions`.

    Returns
    -------
    Column2Estimates

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), Tables 1–3.
    """
    c = conditions or table3_conditions()
    alg = printed_column_2()
    coef = S.error_coefficients(alg)
    delta = next(col.delta for col in P.BUDENNYI_TABLE_2 if col.algorithm == 2)
    k12 = coef.delta * coef.coefficients[S.ORDER4_BASIS[1]] / delta
    drifts = [float(asymptotic_drift(alg, eps=m.eps, nu=m.nu, nutation=m.nutation, step=c.step)) for m in c.motions]
    return Column2Estimates(k12, Table3Drift(*drifts))


class AssignmentScore(NamedTuple):
    """How well one assignment of a1 … a4 reproduces Table 3.

    Attributes
    ----------
    assignment : BasisAssignment
        Which combination each constant multiplies.
    satisfies_sum_rule : bool
        True if all five algorithms (Table 1, column 2 corrected) meet the
        second-order condition Σ c_ij (j − i) = N³/12.
    hits_as_printed : int
        Printed u* cells reproduced with Table 1 as printed (of 10).
    hits_corrected : int
        Printed u* cells reproduced with column 2 read as a1 = a2 = 4/3 (of 10).
    """

    assignment: BasisAssignment
    satisfies_sum_rule: bool
    hits_as_printed: int
    hits_corrected: int


@cache
def _assignment_scores(conditions, duration: float, tolerance: float) -> tuple:
    printed_table = dict(PANOV_TABLE_1)
    printed_table[2] = P.BUDENNYI_TABLE_1_COLUMN_2
    u_star = {(row.algorithm, row.eps): row.u_star_deg_per_h for row in P.BUDENNYI_TABLE_3}
    runs: dict = {}
    out = []
    for assignment in basis_assignments():
        counts, defects = [], []
        for table in (printed_table, PANOV_TABLE_1):
            hits = 0
            for k in range(1, 6):
                alg = algorithm_from_constants(table[k], assignment)
                key = repr(alg.pairwise.items())
                if key not in runs:
                    runs[key] = (simulated_drift(alg, conditions=conditions, duration=duration), second_order_defect(alg))
                drift, defect = runs[key]
                if table is PANOV_TABLE_1:
                    defects.append(defect)
                for eps, ours in ((-1.0, drift.coning), (0.5, drift.precession)):
                    hits += abs(deg_per_h(ours) / u_star[(k, eps)] - 1.0) <= tolerance
            counts.append(hits)
        out.append(AssignmentScore(assignment, all(d == 0 for d in defects), counts[0], counts[1]))
    return tuple(out)


def assignment_scores(*, conditions: Table3Conditions | None = None, duration: float = 20.0, tolerance: float = 0.02) -> tuple:
    """Score every assignment of a1 … a4 by the Table 3 u* cells it reproduces.

    Parameters
    ----------
    conditions : Table3Conditions, keyword-only, optional
        Default :func:`strapdown.analysis.coning.papers.budennyi_table3.table3_conditions`.
    duration : float, keyword-only
        Length of each run [s].
    tolerance : float, keyword-only
        Relative difference accepted as reproduced.

    Returns
    -------
    tuple of AssignmentScore
        In the order of :func:`strapdown.derivations.coning.formula_one.basis_assignments`.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), formula (1), Tables 1, 3.
    """
    return _assignment_scores(conditions, positive(duration, "duration"), positive(tolerance, "tolerance"))


def best_alternative(scores) -> AssignmentScore:
    """The assignment other than the registry's that reproduces the most cells (column 2 corrected).

    Parameters
    ----------
    scores : sequence of AssignmentScore
        From :func:`assignment_scores`.

    Returns
    -------
    AssignmentScore
        Ties go to the most cells with Table 1 as printed, then to the first in order.

    Raises
    ------
    ValueError
        If ``scores`` holds no assignment other than the registry's.
    """
    others = [s for s in scores if not s.assignment.is_registry]
    if not others:
        raise ValueError("Expected `scores` to hold an assignment other than the registry's, got none")
    return max(others, key=lambda s: (s.hits_corrected, s.hits_as_printed))


class Table2Fit(NamedTuple):
    """Fitted local-error coefficients of one algorithm beside a column of Table 2.

    Attributes
    ----------
    printed : strapdown.derivations.coning.published.BudennyiTable2Column
        The printed column it is compared with.
    label : str
        The algorithm fitted (a registry name, or ``"Table 1 column 2 as printed"``).
    fitted_k : tuple of float
        Fitted ``c/δ4`` for k03, k12, k002, k110, k0001 (δ4 as printed).
    residual : float
        Relative residual of the least-squares fit.
    """

    printed: P.BudennyiTable2Column
    label: str
    fitted_k: tuple
    residual: float


@cache
def table2_fits() -> tuple:
    """The local error of each algorithm fitted on the tumbling motion, beside Table 2.

    Returns
    -------
    tuple of Table2Fit
        ``panov-4s-1``, ``panov-4s-2``, column 2 as printed (against the printed
        column 2), ``panov-4s-3`` … ``panov-4s-5``.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (2), Table 2.
    """
    columns = {c.algorithm: c for c in P.BUDENNYI_TABLE_2}
    candidates = [(k, f"panov-4s-{k}", get(f"panov-4s-{k}")) for k in range(1, 6)]
    candidates.insert(2, (2, "Table 1 column 2 as printed", printed_column_2()))
    out = []
    for k, label, alg in candidates:
        coef, resid = error_coefficients(alg)
        delta = columns[k].delta
        out.append(Table2Fit(columns[k], label, tuple(float(c / delta) for c in coef), resid))
    return tuple(out)
