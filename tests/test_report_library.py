"""The library results that the report sections format (moved out of the report modules).

Each test checks a result against an independent statement of the same
quantity (a closed form, the definition on the raw arrays, or the printed data).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from strapdown.analysis.coning.computational_load import quaternion_update_count
from strapdown.analysis.coning.drift_theory import coning_drift_function
from strapdown.analysis.coning.frequency_response import coning_frequency_response, finite_angle_check
from strapdown.analysis.coning.papers import budennyi_loads as L45
from strapdown.analysis.coning.papers import budennyi_table3 as T3
from strapdown.analysis.coning.papers.biquaternion_checks import CHECK_MOTION, printed_formula_checks
from strapdown.analysis.coning.papers.formula_one import assignment_scores, best_alternative
from strapdown.analysis.coning.papers.published_check import coning_drift_orders, largest_difference, sculling_error_curve, sculling_simulation_checks
from strapdown.analysis.core import units
from strapdown.analysis.multistage.composition import yaw_study
from strapdown.analysis.multistage.readings import (
    Reading,
    compare_with_paper,
    printed_envelope_at_rocking_start,
    run_readings,
    schuler_detuning,
)
from strapdown.analysis.multistage.sensor_statistics import SensorErrorStatistics, sensor_error_monte_carlo
from strapdown.analysis.multistage.stages import StagePeaks, simulate
from strapdown.analysis.multistage.trajectory import Scenario, coriolis_term, truth
from strapdown.derivations.coning import published as P
from strapdown.derivations.coning.printed_checks import table2_checks
from strapdown.derivations.coning.registry import get
from strapdown.derivations.multistage.published import PAPER, SECTION5


# --------------------------------------------------------------------------- Tables 2-5
def test_operation_counts_are_those_of_table_2():
    checks = L45.operation_count_checks()
    assert [c.printed for c in checks] == [(c.additions, c.multiplications) for c in P.BUDENNYI_TABLE_2]
    assert all(c.equal for c in checks)
    assert not L45.CountCheck(1, (15, 9), (15, 10)).equal


def test_load_model_sensitivity_contains_the_default_model():
    cells = L45.load_model_sensitivity((0.1,), time_bases=("sample",))
    default = L45.reproduce_loads()
    assert [(c.time_base, c.truncation_fraction, c.hits, c.cells) for c in cells] == [("sample", 0.1, len(default.hits), len(default.cells))]


def test_cheapest_algorithms_rank_as_printed():
    rep = L45.reproduce_loads()
    ranking = {c.eps: c for c in L45.cheapest_algorithms(rep)}
    for eps, c in ranking.items():
        printed = {min((r for r in P.BUDENNYI_TABLES_4_5 if r.eps == eps), key=lambda r: getattr(r, col)).algorithm for col in ("beta_star_4", "beta_star_5")}
        assert c.printed == tuple(sorted(printed))
    assert all(c.as_printed for c in ranking.values())


def test_per_sample_fit_comparison():
    rep = L45.reproduce_loads()
    comp = L45.compare_per_sample_fit(rep)
    assert comp.total_cells == len(rep.cells)
    assert comp.total_within == sum(sum(abs(c.model / c.printed - 1) <= 0.02 for c in f.cells) for f in comp.fits)
    assert comp.series_terms == tuple(tuple(sorted({c.row.series_terms for c in rep.cells if c.eps == f.eps})) for f in comp.fits)
    assert comp.per_sample_difference == pytest.approx((comp.fits[-1].sigma_q - comp.fits[0].sigma_q) / P.BUDENNYI_CONDITIONS.samples)
    m = rep.model.m
    assert comp.two_term_cost == 2 * (quaternion_update_count(3).cost(m) - quaternion_update_count(2).cost(m))


def test_design_summary_picks_the_cheapest():
    u4, u5 = L45.required_drifts()
    points = L45.design_points(4000.0, eps_values=(-1.0, 0.5), nutation=math.radians(1.0), budgets=(u4, u5), algorithms=("panov-4s-1", "panov-4s-3"))
    s = L45.summarize_designs(points)
    assert len(s.cheapest) == 4 and s.largest_nu_step == max(p.nu_step for p in points)
    for best in s.cheapest:
        rivals = [p for p in points if p.eps == best.eps and p.required_drift == best.required_drift]
        assert best.row.load == min(p.row.load for p in rivals)
    assert [p.required_drift for p in s.cheapest[:2]] == [u4, u5]  # the larger budget first
    with pytest.raises(ValueError, match="`points`"):
        L45.summarize_designs(())


def test_table_3_agreement_summary():
    rows = T3.drift_estimates()
    agree = T3.table3_agreement(rows)
    assert {r.printed.algorithm for r in agree.order_6} == {3, 5}
    assert [(r.printed.algorithm, r.printed.eps) for r in agree.unprinted] == [(5, 0.5)]
    assert 0 < agree.worst_order_4 < 0.02 and 0 < agree.worst_order_6_vs_simulated < 0.05
    printed_order_4 = [r for r in rows if r.order == 4 and r.printed.u_a_deg_per_h is not None]
    assert agree.worst_order_4 == max(abs(units.deg_per_h(r.asymptotic) / r.printed.u_a_deg_per_h - 1) for r in printed_order_4)


def test_u_star_cells_reproduced():
    cells = T3.reproduce_u_star(duration=20.0)
    assert all(c.reproduced(0.02) for c in cells)
    assert not cells[0]._replace(relative_difference=0.03).reproduced(0.02)


def test_best_alternative_assignment():
    scores = assignment_scores(duration=5.0)
    best = best_alternative(scores)
    registry = next(s for s in scores if s.assignment.is_registry)
    assert not best.assignment.is_registry and best.hits_corrected == max(s.hits_corrected for s in scores if not s.assignment.is_registry)
    assert best.hits_corrected < registry.hits_corrected
    with pytest.raises(ValueError, match="`scores`"):
        best_alternative([registry])


def test_printed_products_of_table_2():
    three = next(c for c in table2_checks() if c.algorithm == 3)
    printed = next(c for c in P.BUDENNYI_TABLE_2 if c.algorithm == 3)
    assert three.printed_products == tuple(printed.delta * k for k in printed.k)


# --------------------------------------------------------------------------- published algorithms, coning drift
def test_design_order_of_the_cross_step_class():
    orders = {d.algorithm: d.design_order for d in coning_drift_orders(("savage-1+1", "ignagni-1996-2"), sample_intervals=(0.004, 0.002), cycles=5)}
    assert orders["savage-1+1"] == 4
    assert orders["ignagni-1996-2"] == 2 * len(set(get("ignagni-1996-2").pairwise.values())) + 2


def test_sculling_point_relative_is_on_the_curve():
    (point,) = sculling_simulation_checks([("two-sample", 0.2)], cycles=10)
    (curve,) = sculling_error_curve(["two-sample"], [0.2])
    assert point.exact_rate == pytest.approx(0.5e-3)  # ½ θ₀ A, in phase
    assert point.simulated_relative == pytest.approx(curve.relative[0], rel=1e-2)
    assert largest_difference([point]) == abs(point.relative_difference) and math.isnan(largest_difference([]))


def test_frequency_response_summaries():
    alg = get("two-sample")
    resp = coning_frequency_response([alg], [0.1, 0.5], check_omega_h=(0.5,))
    r = resp.responses[0]
    assert r.drift_at(0.1) == float(np.asarray(coning_drift_function(alg)(0.1)))
    (check,) = resp.simulated_checks
    assert check.simulated_coefficient == pytest.approx(check.simulated / (check.cone_angle**2 * check.nu))
    assert check.simulated_coefficient == pytest.approx(r.drift_at(0.5), rel=1e-3)
    assert resp.largest_relative_difference == abs(check.relative_difference)
    f = finite_angle_check(alg, 0.1, cone_angle=math.radians(1.0), periods=20)
    assert f.simulated_vs_series == pytest.approx(f.simulated / f.series - 1)


def test_printed_formula_checks_report_their_sizes():
    c = printed_formula_checks(0)
    assert (c.points, c.times, c.time_span) == (200, 50, 100.0) and c.motion == CHECK_MOTION
    assert (c.motion.nu_dual, c.motion.nutation_dual) == (10.0, 100.0)


# --------------------------------------------------------------------------- multistage
def test_stage_peak_ratios():
    a, b = StagePeaks(2.0, 3.0, 4.0, 5.0), StagePeaks(1.0, 2.0, 8.0, 5.0)
    assert a.over(b) == StagePeaks(2.0, 1.5, 0.5, 1.0)
    assert a.relative_to(b) == StagePeaks(1.0, 0.5, -0.5, 0.0)


def test_peak_times_are_the_times_of_the_peaks():
    res = simulate(Scenario(duration=1500.0), step=0.5)
    times, peaks = res.peak_times(), res.peaks()
    for s in range(2):
        for axis, name in enumerate(("yaw", "pitch", "roll")):
            i = int(np.flatnonzero(res.time == getattr(times[s], name))[0])
            assert abs(res.errors[s, i, axis]) == getattr(peaks[s], name)
    late = res.peak_times(since=1000.0)[1]
    assert min(late) >= 1000.0


def test_readings_against_the_paper():
    short = Scenario(duration=2000.0)
    results = run_readings((Reading("default"), Reading("rescale", switch="rescale"), Reading("old truth", truth="no-coriolis")), base=short, step=0.5)
    default, rescale, old = results
    assert default.roll_ratio == default.peaks[0].roll / default.peaks[1].roll
    assert rescale.peak_change(rescale) == 0.0 and default.peak_change(rescale) > 1.0
    cmp = compare_with_paper(results)
    assert cmp.earlier_truth is old and cmp.roll_ratio_range == (default.roll_ratio, default.roll_ratio)  # the only consistent one
    assert set(cmp.above_bound) == {r for r in results if r.peaks[1].pitch > PAPER.two_stage_pitch_bound.value}
    assert set(cmp.stage1_pitch_near) == {r for r in results if abs(r.peaks[0].pitch / PAPER.stage1_pitch_peak.value - 1) < 0.2}


def test_printed_envelope_leaves_no_rocking():
    e = printed_envelope_at_rocking_start()
    assert e == pytest.approx(math.exp(-SECTION5.envelope_decay * (SECTION5.rest_end - SECTION5.envelope_origin)), rel=1e-6)


def test_schuler_detuning():
    rows = schuler_detuning()
    assert rows[0].peak == 0.0 and rows[0].l == pytest.approx(9.81 / 6.371e6)
    assert all(r.peak > 0 for r in rows[1:])
    assert rows[1].l == pytest.approx(1.01 * rows[0].l) and rows[2].k == 1e-3


def test_vertical_earth_rate_and_coriolis_term():
    sc = Scenario()
    assert sc.vertical_earth_rate == pytest.approx(sc.earth_rate * math.sin(sc.latitude))
    c = coriolis_term(sc)
    lat = float(truth(sc, np.array([sc.duration])).latitude[0])
    assert c.time == sc.duration and c.velocity > 0
    assert c.acceleration == pytest.approx(2 * sc.earth_rate * math.sin(lat) * c.velocity, rel=1e-9)


def test_yaw_study_helpers():
    study = yaw_study(Scenario(duration=1200.0), step=0.5, times=(600.0, 1000.0))
    horizontal, all_four = study.readings
    assert horizontal.peak == max(horizontal.stage1_peak, horizontal.two_stage_peak)
    assert all_four.stage1_yaw_at(600.0) == all_four.stage1_yaw[0] and math.isnan(all_four.stage1_yaw_at(601.0))
    assert study.true_yaw(600.0) == study.yaw_rate * 600.0


def test_monte_carlo_spread():
    mc = sensor_error_monte_carlo(SensorErrorStatistics(), 8, scenario=Scenario(duration=600.0), step=1.0, rng=1, trials_per_block=4)
    assert mc.spread() == float(np.abs(mc.percentiles[:, -1, :3] - mc.nominal[-1, :3]).max())
    assert mc.spread(1) == float(np.abs(mc.percentiles[:, 0, :3] - mc.nominal[0, :3]).max())
    with pytest.raises(ValueError, match="`stage`"):
        mc.spread(3)


def test_noise_units():
    assert units.deg_per_sqrt_h(2.9e-7) == pytest.approx(2.9e-7 * 180 / math.pi * 60)
    assert units.micro_g_per_sqrt_hz(1e-4) == pytest.approx(1e-4 / 9.80665 * 1e6)


def test_largest_design_difference():
    from strapdown.analysis.multistage import gain_design as gd

    checks = [gd.check_design(gd.design_gains(1e-2, zeta, reference="tilt"), duration=300.0, step=1.0) for zeta in (0.3, 1.0)]
    assert gd.largest_design_difference(checks) == max(checks[0].max_difference, checks[1].max_difference)
    assert math.isnan(gd.largest_design_difference([]))
