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
