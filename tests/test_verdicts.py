"""Verdicts that can fail: each says "no" or "not resolved" on a case built to fail it and "yes" on one that meets it."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import stats

from strapdown.analysis.core import verdicts as vd
from strapdown.analysis.core.verdicts import Verdict

# ---------------------------------------------------------------- the module


def _tost_p(est, se, low, high):
    """The two one-sided p-values of TOST, from the normal law (Schuirmann 1987), written apart from the module."""
    p_low = stats.norm.sf((est - low) / se)  # H0: true ≤ low
    p_high = stats.norm.cdf((est - high) / se)  # H0: true ≥ high
    return p_low, p_high


@pytest.mark.parametrize("est", np.linspace(-1.5, 1.5, 61))
@pytest.mark.parametrize("se", [0.05, 0.2, 0.6])
def test_yes_is_tost_and_no_is_the_one_sided_test_beyond_the_margin(est, se):
    v = vd.equivalence(est, se, 30, reference=0.0, margin=1.0, criterion="within ±1 of 0")
    alpha = 0.025  # each one-sided test of the two-sided 95 % interval
    p_low, p_high = _tost_p(est, se, -1.0, 1.0)
    assert v.yes == (max(p_low, p_high) < alpha)
    # "no": the true value is beyond the margin on one side, one-sided at the same α
    beyond = stats.norm.sf((est - 1.0) / se) < alpha or stats.norm.cdf((est + 1.0) / se) < alpha
    assert v.no == beyond
    assert v.outcome in vd.OUTCOMES


def test_three_outcomes_and_their_words():
    yes = vd.within(0.2, 0.05, 40, high=0.5, criterion="at most 0.5")
    no = vd.within(0.9, 0.05, 40, high=0.5, criterion="at most 0.5")
    open_ = vd.within(0.45, 0.05, 40, high=0.5, criterion="at most 0.5")
    assert (yes.outcome, no.outcome, open_.outcome) == ("yes", "no", "not resolved")
    assert str(yes) == "yes" and no.label() == "**no**"
    assert str(open_) == f"not resolved: {open_.more_trials} more trials needed"
    assert open_.criterion == "at most 0.5" and yes.region == (-math.inf, 0.5)


def test_trials_needed_is_the_sample_size_whose_interval_reaches_the_margin():
    # s = se·√n = 0.05·√40; the distance to the bound 0.05: N = (z s / d)²
    v = vd.within(0.45, 0.05, 40, high=0.5, criterion="at most 0.5")
    s, d, z = 0.05 * math.sqrt(40), 0.05, stats.norm.ppf(0.975)
    N = math.ceil((z * s / d) ** 2)
    assert v.more_trials == N - 40
    # at N trials with the same spread the interval no longer straddles the bound
    w = vd.within(0.45, s / math.sqrt(N), N, high=0.5, criterion="at most 0.5")
    assert w.outcome == "yes"
    w = vd.within(0.45, s / math.sqrt(N - 1), N - 1, high=0.5, criterion="at most 0.5")
    assert w.outcome == "not resolved"


def test_an_estimate_on_the_margin_cannot_be_resolved():
    v = vd.within(0.5, 0.05, 40, high=0.5, criterion="at most 0.5")
    assert v.outcome == "not resolved" and v.more_trials is None
    assert "sits on the margin" in str(v)


def test_a_verdict_is_not_a_bool():
    v = vd.within(0.2, 0.05, 40, high=0.5, criterion="at most 0.5")
    with pytest.raises(TypeError, match="three outcomes"):
        bool(v)


def test_as_dict_is_json_without_nan_or_infinity():
    v = vd.within(0.45, 0.05, 40, high=0.5, criterion="at most 0.5")
    d = v.as_dict(scale=2.0)
    json.dumps(d, allow_nan=False)
    assert d["region"] == [None, 1.0] and d["outcome"] == "not resolved" and d["more_trials_needed"] == v.more_trials
    c = vd.all_of([v], criterion="all")
    json.dumps(c.as_dict(), allow_nan=False)


def test_rms_within_tests_the_mean_square():
    rng = np.random.default_rng(1)
    x = rng.standard_normal(4000)
    assert vd.rms_within(x, low=0.9, high=1.1, criterion="rms 1 ± 10 %").outcome == "yes"
    assert vd.rms_within(x, high=0.8, criterion="rms ≤ 0.8").outcome == "no"
    few = vd.rms_within(x[:5], low=0.9, high=1.1, criterion="rms 1 ± 10 %")
    assert few.outcome == "not resolved" and few.more_trials > 20
    assert few.estimate == pytest.approx(math.sqrt(np.mean(x[:5] ** 2)))


def test_in_band_and_all_of():
    assert vd.in_band([2.9, 3.1], (2.5, 3.5), n=100, criterion="c").outcome == "yes"
    assert vd.in_band([2.9, 3.6], (2.5, 3.5), n=100, criterion="c").outcome == "no"
    y = vd.within(0.2, 0.05, 40, high=0.5, criterion="a")
    n = vd.within(0.9, 0.05, 40, high=0.5, criterion="a")
    u = vd.within(0.45, 0.05, 40, high=0.5, criterion="a")
    assert vd.all_of([y, y], criterion="c").outcome == "yes"
    assert vd.all_of([y, u, n], criterion="c").outcome == "no"
    assert vd.all_of([y, u], criterion="c").more_trials == u.more_trials
    with pytest.raises(ValueError, match="`verdicts`"):
        vd.all_of([], criterion="c")
    with pytest.raises(TypeError, match="`verdicts`"):
        vd.all_of([True], criterion="c")


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: vd.within(0.0, -1.0, 3, criterion="c"), "`standard_error`"),
        (lambda: vd.within(0.0, 1.0, 0, criterion="c"), "`n`"),
        (lambda: vd.within(0.0, 1.0, 3, low=1.0, high=0.0, criterion="c"), "`low` < `high`"),
        (lambda: vd.within(0.0, 1.0, 3, criterion="c", level=1.0), "`level`"),
        (lambda: vd.equivalence(0.0, 1.0, 3, reference=0.0, margin=0.0), "`margin`"),
        (lambda: vd.rms_within([1.0], criterion="c"), "`values`"),
        (lambda: vd.rms_within([1.0, 2.0], low=-1.0, criterion="c"), "`low`"),
        (lambda: Verdict("maybe", "c", 0.0, (0, 0), (0, 1), 0.0, 0.95, 1, 0), "`outcome`"),
    ],
)
def test_bad_input_names_the_argument(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# ---------------------------------------------------------------- floor reached, on the alignment cases


def test_floor_reached_synthetic():
    from strapdown.analysis.alignment.comparison import floor_reached

    rng = np.random.default_rng(3)
    f = rng.standard_normal(200)
    assert floor_reached(f + 0.3 * rng.standard_normal(200), f).outcome == "yes"
    assert floor_reached(f + 2.0 * rng.standard_normal(200), f).outcome == "no"
    # a residual whose mean is zero but whose rms dwarfs the floor (what the old verdict called "reached")
    assert floor_reached(1e-3 * f + 3.0 * rng.standard_normal(200), 1e-3 * f).outcome == "no"
    with pytest.raises(ValueError, match="`error` and `floor`"):
        floor_reached(f[:10], f)


@pytest.fixture(scope="module")
def aided():
    from strapdown.analysis.alignment import design_studies as ds
    from strapdown.analysis.core.units import rad

    short = ds.aided_checks(rad(np.array([20.0])), n_trials=16, rng=7, duration=5.0)[0]
    straight = ds.aided_checks(rad(np.array([0.0])), n_trials=32, rng=8, duration=180.0)[0]
    return short, straight


def test_at_a_5_s_horizon_the_floor_is_not_reached(aided):
    # before any alignment the error is the 3° prior, the floor a few hundredths of a degree: the residual's
    # mean interval covers zero (the old verdict said "reached"), the rms test says no
    mc, _ = aided
    D = 180.0 / math.pi
    assert mc.error.rms * D > 1.0 and mc.floor.rms * D < 0.2
    assert mc.residual.mean_ci[0] <= 0.0 <= mc.residual.mean_ci[1]
    assert mc.floor_reached.outcome == "no"


def test_the_straight_drive_does_not_reach_its_floor(aided):
    # a straight drive leaves the azimuth as unobservable as at rest: the error is well above the aided floor
    _, mc = aided
    assert mc.residual.rms > 1.3 * mc.floor.rms
    assert mc.floor_reached.outcome != "yes"
    assert mc.floor_reached.outcome == "no"


def test_the_floor_verdict_at_rest_from_too_few_trials_and_from_enough():
    from strapdown.analysis.alignment import design_studies as ds
    from strapdown.analysis.alignment.comparison import compare_methods

    sc = ds.design_scenario(duration=300.0, sample_rate=2.0)
    few = compare_methods(sc, ds.DESIGN_SENSORS, n_trials=8, rng=1, methods=("analytic",)).row("analytic").floor_reached
    many = compare_methods(sc, ds.DESIGN_SENSORS, n_trials=48, rng=1, methods=("analytic",)).row("analytic").floor_reached
    assert few.outcome == "not resolved" and few.more_trials >= 1
    assert str(few).startswith("not resolved:") and "more trials needed" in str(few)
    assert many.outcome == "yes"


# ---------------------------------------------------------------- narrow-band rocking: matched rocking states


@pytest.fixture(scope="module")
def rocking_filters():
    from strapdown.analysis.alignment import studies as st
    from strapdown.analysis.alignment.base_motion import NarrowbandMotion
    from strapdown.analysis.alignment.fine import assumed_disturbance
    from strapdown.analysis.alignment.imu import Scenario
    from strapdown.analysis.alignment.monte_carlo import alignment_monte_carlo

    e = st.NAVIGATION_GRADE
    sc = Scenario(math.radians(60.0), heading=math.radians(30.0), motion=NarrowbandMotion(np.radians([0.5, 1.0, 1.0]), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=120.0)
    out = {}
    for kind in ("shaping", "matched"):
        opts = st.kalman_options(sc, e, disturbance=assumed_disturbance(sc.motion, sc, kind=kind))
        out[kind] = alignment_monte_carlo(sc, e, method="kalman", n_trials=128, rng=11, options=opts)  # the same trials for both
    return out


def test_white_driven_shaping_states_leave_the_nis_below_its_band(rocking_filters):
    k = rocking_filters["shaping"].kalman
    assert k.nis_all < k.nis_band[0]
    assert np.all(k.nis < k.nis_band[1]) and np.sum(k.nis < k.nis_band[0]) >= 4
    assert rocking_filters["shaping"].consistency().outcome == "no"


def test_matched_rocking_states_bring_the_nis_into_its_band(rocking_filters):
    mc = rocking_filters["matched"]
    k = mc.kalman
    assert k.nis_band[0] <= k.nis_all <= k.nis_band[1], k.nis_all
    late = k.times >= 2.5  # both models dip at the second epoch (t = 1 s), a start-up transient of the filter
    assert np.all((k.nis[late] >= k.nis_band[0]) & (k.nis[late] <= k.nis_band[1])), k.nis
    assert rocking_filters["shaping"].kalman.nis[1] < k.nis_band[0]
    # and it is not overconfident: no mean NEES above its band at the family level (16 checks, Bonferroni)
    from strapdown.analysis.core.kalman import chi2_band

    assert np.all(k.nees <= chi2_band(k.dim, mc.result.n_trials, 1.0 - 0.05 / 16)[1]), k.nees
    # the matched model costs nothing in accuracy: the same trials, an rms azimuth error within 10 %
    assert mc.result.rms == pytest.approx(rocking_filters["shaping"].result.rms, rel=0.1)


def test_matched_block_keeps_the_rocking_variances_and_predicts_its_rate():
    """Against the autocovariance of the narrow-band process written apart: quadrature of the density, no package code."""
    from scipy.integrate import quad

    from strapdown.analysis.alignment.base_motion import NarrowbandMotion
    from strapdown.analysis.alignment.fine import matched_rocking_block

    sigma, period, zeta, cut, T = 0.01, 8.0, 0.1, 4.0, 0.5
    motion = NarrowbandMotion(sigma * math.sqrt(2.0), period, zeta, cut)
    w0 = 2 * math.pi / period
    g = lambda w: 1.0 / ((1 - (w / w0) ** 2) ** 2 + 4 * zeta**2 * (w / w0) ** 2)  # noqa: E731
    pts = [w0 * (1 - 4 * zeta), w0, w0 * (1 + 4 * zeta)]
    norm_ = sigma**2 / quad(g, 0, cut * w0, points=pts, limit=400)[0]
    R = lambda f: norm_ * quad(lambda w: g(w) * f(w), 0, cut * w0, points=pts, limit=400, epsabs=0)[0]  # noqa: E731
    C0 = np.array([[R(lambda w: 1.0), 0.0], [0.0, R(lambda w: w * w)]])
    C1 = np.array([[R(lambda w: math.cos(w * T)), R(lambda w: w * math.sin(w * T))], [-R(lambda w: w * math.sin(w * T)), R(lambda w: w * w * math.cos(w * T))]])
    F, Q, C = matched_rocking_block(motion, T, period=period, damping=zeta)
    np.testing.assert_allclose(C[1], C0, rtol=1e-6, atol=1e-12 * sigma**2)
    np.testing.assert_allclose(F[1, 1], (C1 @ np.linalg.inv(C0))[1], rtol=1e-6)
    # stationary: the model keeps the rocking's own covariance
    np.testing.assert_allclose(F[1] @ C0 @ F[1].T + Q[1], C0, rtol=1e-9, atol=1e-15)
    assert np.all(np.linalg.eigvalsh(Q[1]) > 0)
