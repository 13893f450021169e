"""The published coning tables and the library functions that reproduce or check them.

Printed numbers are read from ``strapdown.derivations.coning.published`` (Budennyi, Kalinovsky,
Panov et al., Tables 1–5; Lebedev & Panov 1989, section 6 and eqs. (1.12), (2.4), (4.7)).
"""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from strapdown.analysis.cli import main
from strapdown.analysis.coning.drift_crosscheck import drift_ratios
from strapdown.analysis.coning.order_study import drift_orders
from strapdown.analysis.coning.papers import budennyi_table3 as T3
from strapdown.analysis.coning.papers import lebedev_panov_table as LP
from strapdown.analysis.coning.papers.formula_one import assignment_scores, column_2_estimates, column_2_readings, table2_fits
from strapdown.analysis.coning.papers.lebedev_panov_dot_term import dot_term_study
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.core.units import deg_per_h
from strapdown.derivations.coning import drift as D
from strapdown.derivations.coning import published as P
from strapdown.derivations.coning.formula_one import BasisAssignment, algorithm_from_constants, basis_assignments
from strapdown.derivations.coning.leading_drift import leading_drift, small_cone_limit
from strapdown.derivations.coning.printed_checks import eq_2_4_check, structure_function_checks, table2_checks
from strapdown.derivations.coning.registry import PANOV_TABLE_1, get


# --------------------------------------------------------------------------- published data
def test_published_tables_are_complete():
    assert [c.algorithm for c in P.BUDENNYI_TABLE_2] == [1, 2, 3, 4, 5]
    assert len(P.BUDENNYI_TABLE_3) == 10 and len(P.BUDENNYI_TABLES_4_5) == 10
    assert sum(r.u_a_deg_per_h is None for r in P.BUDENNYI_TABLE_3) == 1
    # 29 printed loads: 10 β* of Table 4, 9 β_a, 10 β* of Table 5
    assert sum(1 + (r.beta_a_4 is not None) + 1 for r in P.BUDENNYI_TABLES_4_5) == 29
    assert len(P.LEBEDEV_PANOV_TABLE) == 24 and len(P.EQ_2_4) == 20
    assert {c.quantity for c in P.LEBEDEV_PANOV_TABLE} == set(LP.QUANTITIES)


# --------------------------------------------------------------------------- formula (1)
def test_basis_assignments_and_the_registry_reading():
    found = basis_assignments()
    assert len(found) == 24 and len({a.combinations for a in found}) == 24
    assert found[0].is_registry and not any(a.is_registry for a in found[1:])
    for k, column in PANOV_TABLE_1.items():
        assert algorithm_from_constants(column).pairwise == get(f"panov-4s-{k}").pairwise


@pytest.mark.parametrize("constants", [("1", "2", "3"), ("1", "x", "0", "0")])
def test_algorithm_from_constants_rejects_bad_input(constants):
    with pytest.raises(ValueError, match="`constants`"):
        algorithm_from_constants(constants)
    with pytest.raises(ValueError, match="`combinations`"):
        BasisAssignment(((2, 3),))


def test_only_the_registry_assignment_reproduces_table_3():
    scores = assignment_scores()
    registry = next(s for s in scores if s.assignment.is_registry)
    assert registry.satisfies_sum_rule and registry.hits_corrected == 10 and registry.hits_as_printed == 8
    assert max(s.hits_corrected for s in scores if not s.assignment.is_registry) <= 4
    assert [s.assignment for s in scores if s.satisfies_sum_rule] == [registry.assignment]


def test_table_1_column_2_readings():
    printed = {r.eps: r.u_star_deg_per_h for r in P.BUDENNYI_TABLE_3 if r.algorithm == 2}
    col2 = column_2_readings()
    assert deg_per_h(col2.corrected.coning) == pytest.approx(printed[-1.0], rel=0.02)
    assert deg_per_h(col2.corrected.precession) == pytest.approx(printed[0.5], rel=0.02)
    assert deg_per_h(col2.printed.coning) < 0.2 * printed[-1.0]
    est = column_2_estimates()
    assert est.k12 == Fraction(4)
    assert deg_per_h(est.asymptotic.coning) == pytest.approx(0.160, abs=5e-4)


def test_table_2_fit_and_derivation_agree_on_the_algorithm_4_misprint():
    fits = {f.label: f for f in table2_fits()}
    assert fits["panov-4s-2"].fitted_k[1] == pytest.approx(next(c for c in P.BUDENNYI_TABLE_2 if c.algorithm == 2).k[1], abs=0.02)
    assert fits["Table 1 column 2 as printed"].fitted_k[1] == pytest.approx(4, abs=0.02)
    assert fits["panov-4s-4"].fitted_k[2] == pytest.approx(448, abs=0.05)
    checks = {c.algorithm: c for c in table2_checks()}
    assert [k for k, c in checks.items() if any(c.differs)] == [4]
    assert checks[4].differs == (False, False, True, False, True) and checks[4].derived[2] == 448


# --------------------------------------------------------------------------- printed formulas
def test_eq_2_4_check_can_fail():
    assert eq_2_4_check() == (True, ())
    changed = dict(P.EQ_2_4, **{"1101": 245})
    assert not eq_2_4_check(tuple(changed.items())).identical


def test_structure_functions_as_printed():
    checks = structure_function_checks()
    assert len(checks) == 8 and all(c.equal for c in checks)


# --------------------------------------------------------------------------- Table 3, ρ = 6
def test_leading_drift_transport_is_common_to_algorithms_3_and_5():
    three, five = leading_drift(get("panov-4s-3"), 7), leading_drift(get("panov-4s-5"), 7)
    assert sp.expand(three.transport - five.transport) == 0
    residual = sp.expand(three.mid_step + three.transport - three.full)
    assert sp.expand(residual.subs(D.SIN**2, 1 - D.COS**2)) == 0  # equal once sin²ϑ = 1 − cos²ϑ
    # along the precession axis: minus the printed ρ_2 of the optimal two-sample algorithm
    rho_2 = next(f.value for f in P.PUBLISHED_ALGORITHM_ERRORS if f.algorithm == "compressed-2")
    assert small_cone_limit(get("two-sample"), 5) == -sp.Rational(rho_2.numerator, rho_2.denominator)
    with pytest.raises(ValueError, match="`weight`"):
        leading_drift(get("panov-4s-3"), 8)


def test_table_3_order_6_estimates():
    """Algorithm 5's printed u_a is the mid-step estimate; algorithm 3's is neither of these two."""
    rows = {r.printed.algorithm: r for r in T3.drift_estimates() if r.order == 6}
    assert sorted(rows) == [3, 5]
    five, three = rows[5], rows[3]
    assert deg_per_h(five.mid_step) == pytest.approx(five.printed.u_a_deg_per_h, rel=0.003)
    for r in (three, five):
        assert r.asymptotic == pytest.approx(r.simulated, rel=0.015)
    assert abs(deg_per_h(three.mid_step) / three.printed.u_a_deg_per_h - 1) > 0.04
    assert abs(three.asymptotic_vs_printed) > 0.04
    # the same transport term moves the two estimates apart, in opposite directions
    assert (three.asymptotic - three.mid_step) == pytest.approx(-(five.asymptotic - five.mid_step), rel=0.01)


def test_table_3_u_star_is_reproduced():
    cells = T3.reproduce_u_star(duration=20.0)
    assert len(cells) == 10 and max(abs(c.relative_difference) for c in cells) < 0.02


def test_conditions_types_are_checked():
    with pytest.raises(TypeError, match="`conditions`"):
        T3.simulated_drift(get("panov-4s-1"), conditions="table 3")
    with pytest.raises(ValueError, match="`duration`"):
        T3.simulated_drift(get("panov-4s-1"), duration=0.0)


# --------------------------------------------------------------------------- Lebedev & Panov (1989)
def test_lebedev_panov_table_and_its_evidence():
    table = LP.reproduce_table()
    assert len(table.reproduced) == 14 and table.worst_reproduced < 0.01
    assert {c.printed.order for c in table.not_reproduced} == {6}
    evidence = LP.cell_evidence(table)
    assert len(evidence) == 12
    for e in evidence:
        assert e.convergence.orders == pytest.approx((6.0, 6.0), abs=0.05)
        assert e.theory_over_ours == pytest.approx(1.0, abs=5e-3)
        assert abs(e.printed_over_theory - 1) > 0.1
    assert LP.theory_agreement(4) < 2e-4


def test_lebedev_panov_bad_input():
    with pytest.raises(ValueError, match="`variant`"):
        LP.run_values(4, -1.0, 7)
    with pytest.raises(ValueError, match="`order`"):
        LP.run_values(5, -1.0, 1)
    with pytest.raises(ValueError, match="`quantity`"):
        LP.convergence_study("dW", 6, -1.0, 1)


# --------------------------------------------------------------------------- orders
def test_dot_term_study_and_drift_orders():
    study = dot_term_study()
    assert [r.local_error_order for r in study.rows] == [3, 5, 7, 5]
    assert study.printed_is_sixth_order and study.without_dot.accuracy_order == 4
    study = drift_orders(RegularPrecession(0.5, 2 * np.pi, np.radians(10.0)), steps=(0.08, 0.04, 0.02), algorithms=["lebedev-panov-4"])
    assert study[0].slope == pytest.approx(4.0, abs=0.1)
    with pytest.raises(TypeError, match="`motion`"):
        drift_orders("coning")


def test_drift_ratios_tend_to_one():
    (r,) = drift_ratios([RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(10.0))], steps=(0.02, 0.01), algorithms=["two-sample"])
    assert r.deviations[1] < r.deviations[0] < 0.05


# --------------------------------------------------------------------------- CLI
def test_reproduce_tables_json(capsys):
    assert main(["reproduce", "tables", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["budennyi_table3_u_star"]) == 10
    assert len(data["lebedev_panov_1989"]) == sum(len(c.variants) for c in P.LEBEDEV_PANOV_TABLE)
    assert all(abs(r["rel_diff"]) < 0.02 for r in data["budennyi_table3_u_star"])


# --------------------------------------------------------------------------- errata classes
def test_erratum_kind_is_validated():
    from strapdown.analysis.report import Erratum

    assert Erratum("s", "p", "c", "e", kind="ambiguous", alternatives="a").kind == "ambiguous"
    with pytest.raises(ValueError, match="`kind`"):
        Erratum("s", "p", "c", "e", kind="correct")


def test_coning_and_core_errata_are_classified(tmp_path):
    from strapdown.analysis.report import Context, algorithms, derivations, errata

    ctx = Context(out_dir=tmp_path, quick=True, show_progress=False)
    entries = [e for module in (algorithms, derivations, errata) for e in module.errata(ctx)]
    assert all(e.kind in ("misprint", "ambiguous") for e in entries)
    ambiguous = [e for e in entries if e.kind == "ambiguous"]
    assert [e.source for e in ambiguous] == [f"Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3, u_a of algorithm {k} under coning (drift order 6)" for k in (3, 5)]
    assert all(e.alternatives and "Correct" not in e.correct for e in ambiguous)


def test_table_3_algorithm_3_is_the_small_cone_angle_term():
    """Algorithm 3's printed u_a is the ϑ² part of the leading drift, c ϑ² ν (ν h)⁶ with c = 2/315; algorithm 5's is not."""
    est = {e.printed.algorithm: e for e in T3.leading_estimates()}
    three, five = est[3], est[5]
    assert deg_per_h(abs(three.small_angle)) == pytest.approx(three.printed.u_a_deg_per_h, rel=0.002)
    assert abs(five.printed_vs_small_angle) > 0.02
    # the ϑ² part is the classical coning drift of `derive coning-drift`: c α² ω (ω h)^6
    from strapdown.derivations.coning.drift import coning_drift

    m = P.BUDENNYI_CONDITIONS
    c = coning_drift(get("panov-4s-3"))
    omega, alpha, h = 2 * math.pi * m.freq_hz, math.radians(m.nutation_deg), m.step / m.samples
    assert abs(three.small_angle) == pytest.approx(float(c.coefficient) * alpha**2 * omega * (omega * h) ** c.order, rel=1e-9)
