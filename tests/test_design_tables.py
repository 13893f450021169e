"""Computational load and Tables 4–5 of Budennyi, Kalinovsky, Panov et al.

The operation counts are checked against Table 2 and against a direct count of the
quaternion update; the printed loads (Tables 4–5) come from ``derivations.coning.published``.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest

from strapdown.analysis.cli import main
from strapdown.analysis.coning.computational_load import (
    LoadModel,
    OperationCount,
    design,
    largest_step,
    operation_count,
    quaternion_update,
    quaternion_update_count,
    series_terms,
    step_load,
    truncation_error,
)
from strapdown.analysis.coning.papers.budennyi_loads import explain_misses, per_sample_fit, printed_consistency, reproduce_loads
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.core.units import rad, rad_per_s
from strapdown.derivations.coning import published as P
from strapdown.derivations.coning.algorithms import Algorithm, Term
from strapdown.derivations.coning.registry import get

CONING = RegularPrecession(-1.0, 2 * math.pi * 10.0, rad(1.0))
PRECESSION = RegularPrecession(0.5, 2 * math.pi * 10.0, rad(1.0))


# --------------------------------------------------------------------------- operation counts
@pytest.mark.parametrize("column", P.BUDENNYI_TABLE_2, ids=lambda c: f"algorithm-{c.algorithm}")
def test_operation_count_reproduces_table_2(column):
    """s, u of Table 2, counted from the algorithm's terms (bilinear factoring of (p1+p2)×(p3+p4))."""
    assert operation_count(get(f"panov-4s-{column.algorithm}")) == OperationCount(column.additions, column.multiplications)


def test_operation_count_factors_only_true_products():
    """4/3 (p1×p4 + p2×p3) does not factor (two cross products); 2/3 (p1+p2)×(p3+p4) does (one)."""
    one = Fraction(1)
    pair = Algorithm("pair", 4, (Term(one, (1, 4)), Term(one, (2, 3))))
    product = Algorithm("product", 4, tuple(Term(one, (i, j)) for i in (1, 2) for j in (3, 4)))
    signed = Algorithm("signed", 3, (Term(one, (1, 2)), Term(one, (2, 3))))  # p1×p2 + p2×p3 = (p1 − p3) × p2
    assert operation_count(pair) == OperationCount(9 + 2 * 3 + 3 + 3, 2 * 6 + 3)
    assert operation_count(product) == OperationCount(9 + 3 + 3 + 3 + 3, 6 + 3)
    assert operation_count(signed) == OperationCount(6 + 3 + 3 + 3, 6 + 3)


def _count_by_hand(terms: int) -> OperationCount:
    """One quaternion update counted line by line (independent of ``quaternion_update``)."""
    adds = 2 + 12  # |Δφ|² (3 products summed), Λ ∘ λ (16 products, 4 sums of 4)
    mults = 3 + 3 + 16  # |Δφ|², s·Δφ, Λ ∘ λ
    if terms >= 3:
        mults += terms - 2  # x², …, x^(K−1)
    adds += 2 * (terms - 1)  # one addition per kept term after the first, in each series
    mults += 2 * (terms - 1)  # one constant per kept term after the first, in each series
    return OperationCount(adds, mults)


@pytest.mark.parametrize("terms", [1, 2, 3, 4, 5, 6])
def test_quaternion_update_count(terms):
    assert quaternion_update_count(terms) == _count_by_hand(terms)
    assert sum(op.multiplications for op in quaternion_update(terms)) == _count_by_hand(terms).multiplications
    if terms >= 2:
        assert quaternion_update_count(terms).cost(5) == 102 + 17 * terms


def test_series_coefficients_are_the_half_angle_series():
    text = [op.name for op in quaternion_update(4)]
    assert "c = cos(φ/2) ≈ 1 − x/8 + x²/384 − x³/46080" in text
    assert "s = sin(φ/2)/φ ≈ 1/2 − x/48 + x²/3840 − x³/645120" in text


# --------------------------------------------------------------------------- the series rule
@pytest.mark.parametrize("terms", [1, 2, 3, 4])
@pytest.mark.parametrize("angle", [0.05, 0.3])
def test_truncation_error_matches_the_truncated_quaternion(terms, angle):
    """The stated leading error equals the angle error of the truncated (c, s Δφ) to relative O(φ²)."""
    a = angle / 2
    c = sum((-1) ** k * a ** (2 * k) / math.factorial(2 * k) for k in range(terms))
    s = sum((-1) ** k * a ** (2 * k + 1) / math.factorial(2 * k + 1) for k in range(terms))
    exact = abs(2 * math.atan2(s, c) - angle)
    assert float(truncation_error(angle, terms)) == pytest.approx(exact, rel=0.6 * angle**2 + 1e-9)


def test_series_terms_follows_budget_and_angle():
    u = rad_per_s(1e-3)
    assert series_terms(0.0015, 1.4e-3, u) == 2  # coning at f = 10 Hz
    assert series_terms(0.35, 3.7e-3, u) == 5  # precession at f = 10 Hz
    assert series_terms(0.35, 3.7e-3, u, fraction=1.0) == 4
    k = series_terms(0.35, 3.7e-3, u)
    assert truncation_error(0.35, k) / 3.7e-3 <= 0.1 * u < truncation_error(0.35, k - 1) / 3.7e-3
    with pytest.raises(ValueError, match="`step`"):
        series_terms(0.1, 0.0, u)
    with pytest.raises(ValueError, match="at most 2 terms"):
        series_terms(0.35, 3.7e-3, u, max_terms=2)


def test_load_model_validates():
    with pytest.raises(ValueError, match="`time_base`"):
        LoadModel(time_base="hour")
    with pytest.raises(ValueError, match="`truncation_fraction`"):
        LoadModel(truncation_fraction=0.0)
    with pytest.raises(ValueError, match="`m`"):
        LoadModel(m=-1.0)


def test_step_load_parts_add_up():
    H = largest_step(get("panov-4s-1"), rad_per_s(1e-3), PRECESSION).step
    row = step_load(get("panov-4s-1"), H, rad_per_s(1e-3), PRECESSION)
    assert row.angle == pytest.approx(np.linalg.norm(PRECESSION.omega(0.0)) * H)
    assert row.quaternion_cost == quaternion_update_count(row.series_terms).cost(5)
    assert row.load == pytest.approx((row.algorithm_cost + row.quaternion_cost) / (H / 4))
    step_based = step_load(get("panov-4s-1"), H, rad_per_s(1e-3), PRECESSION, model=LoadModel(time_base="step"))
    assert step_based.load == pytest.approx(row.load / 4)


# --------------------------------------------------------------------------- Tables 4–5
def test_one_model_reproduces_most_printed_loads_without_fitted_constants():
    rep = reproduce_loads()
    assert len(rep.cells) == 29 and len(rep.hits) == 24
    assert {c.row.series_terms for c in rep.cells if c.eps == -1.0} == {2}
    assert {c.row.series_terms for c in rep.cells if c.eps == 0.5} == {4, 5}
    missed = {(c.algorithm, c.eps, c.column) for c in rep.misses}
    assert missed == {(3, -1.0, "β* (T4)"), (5, -1.0, "β* (T4)"), (3, 0.5, "β_a (T4)"), (5, 0.5, "β* (T4)"), (5, 0.5, "β* (T5)")}


def test_each_miss_fails_a_check_of_the_print():
    for m in explain_misses():
        assert m.checks, m.cell
        assert max(abs(k.deviation) for k in m.checks) > 0.03
    # the consistency checks pass where the model hits: one printed row, within 1 %
    row1 = [k for k in printed_consistency() if k.cells[1] == "alg. 1 ε=-1 β_a (T4)"]
    assert len(row1) == 1 and abs(row1[0].deviation) < 0.01


def test_fitted_comparison_matches_the_model_series_lengths():
    """The two fitted quaternion costs are, per sample, the model's update at K = 2 (coning) and K = 4 (precession)."""
    fits = {f.eps: f for f in per_sample_fit()}
    assert fits[-1.0].sigma_q / 4 == pytest.approx(quaternion_update_count(2).cost(5), abs=2)
    assert fits[0.5].sigma_q / 4 == pytest.approx(quaternion_update_count(4).cost(5), abs=2)


def test_design_ranks_and_uses_the_model():
    rows = design(rad_per_s(1e-3), CONING, algorithms=[f"panov-4s-{k}" for k in range(1, 6)])
    assert [r.load for r in rows] == sorted(r.load for r in rows)
    assert rows[0].algorithm == "panov-4s-3" and rows[0].order == 6 and rows[0].series_terms == 2
    fixed = design(rad_per_s(1e-3), CONING, algorithms=["panov-4s-3"], quaternion_cost=0.0)[0]
    assert fixed.series_terms == 0 and fixed.cost == fixed.algorithm_cost
    with pytest.raises(TypeError, match="`motion`"):
        design(rad_per_s(1e-3), "coning")
    with pytest.raises(ValueError, match="`required_drift`"):
        design(0.0, CONING)


def test_design_cli_reports_the_model(capsys):
    argv = ["design", "--required-drift-deg-per-h", "1e-3", "--eps", "0.5", "--nutation-deg", "1", "--freq-hz", "10", "--json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["time_base"] == "sample" and data["truncation_fraction"] == 0.1
    row = {r["algorithm"]: r for r in data["ranking"]}["panov-4s-1"]
    assert row["series_terms"] == 5 and row["load"] == pytest.approx(267e3, rel=0.01)
    assert main(argv[:-1] + ["--time-base", "step", "--json"]) == 0
    step = {r["algorithm"]: r for r in json.loads(capsys.readouterr().out)["ranking"]}["panov-4s-1"]
    assert step["load"] == pytest.approx(row["load"] / 4)
