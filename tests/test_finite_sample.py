"""Finite-sample statistics of (16) under correlated rocking, checked by Monte Carlo."""

import math

import numpy as np
import pytest

from strapdown.analysis.gyrocompass.finite_sample import mean_interval, required_averaging, sample_mean_statistics, variance_factors
from strapdown.analysis.gyrocompass.rocking import NarrowbandRocking, SineRocking, mean_variance_factor

NB = NarrowbandRocking(1.0, 1.0, 8.0, 0.1)


def test_variance_factors_match_the_direct_sum():
    v = variance_factors(NB, 500, 0.1)
    for n in (1, 2, 37, 500):
        assert v[n - 1] == pytest.approx(mean_variance_factor(NB, n, 0.1), rel=1e-12, abs=1e-15)
    s = SineRocking(1.0, 1.0, 7.0, 7.0)
    assert variance_factors(s, 80, 0.1)[-1] == pytest.approx(mean_variance_factor(s, 80, 0.1), rel=1e-12, abs=1e-15)


def test_variance_estimate_bias_and_interval_coverage():
    """E σ̂² = σ²(1 − v) and the model interval covers 95 %; the independent-sample one does not."""
    n, dt, trials = 100, 0.1, 6000
    xi, _ = NB.sample(11, trials, n, dt)
    st = sample_mean_statistics(NB, n, dt)
    ratio = xi.var(axis=1)
    se = ratio.std(ddof=1) / math.sqrt(trials)
    assert abs(ratio.mean() - (1.0 + st.variance_bias)) < 3 * se  # the bias, about −v
    assert abs(ratio.mean() - 1.0) > 5 * se  # and it is not negligible here
    assert np.var(xi.mean(axis=1)) == pytest.approx(1.0 / st.effective_sample_size, rel=0.06)  # SE of a variance: 1.8 %
    model = mean_interval(xi, method="model", model=NB, dt=dt).covers(0.0).mean()
    naive = mean_interval(xi, method="naive").covers(0.0).mean()
    # binomial SE of a 95 % coverage from 6000 trials: 0.3 %
    assert 0.935 < model < 0.985  # t with Bartlett's degrees of freedom: at least 95 %, a little conservative
    assert naive < 0.6 and st.naive_interval_ratio > 2.5
    long, _ = NB.sample(12, 1000, 6000, dt)
    batch = mean_interval(long, method="batch-means", batches=10).covers(0.0).mean()
    assert 0.92 < batch < 0.98  # batches of 60 s, five envelope correlation times


def test_required_averaging_is_the_first_n_that_stays_within_the_budget():
    lat = math.radians(60.0)
    s = math.radians(0.5)
    r = required_averaging(math.radians(0.02), lat, NarrowbandRocking(s, s, 8.0, 0.1), 0.1, max_samples=20_000)
    assert r.rms <= math.radians(0.02) * (1 + 1e-12)
    assert r.n_samples > 1 and r.duration == pytest.approx(r.n_samples * 0.1)
    g = math.tan(lat)  # ∂σ/∂β at zero tilt; the γ channel does not enter to first order
    v = variance_factors(NarrowbandRocking(s, s, 8.0, 0.1), r.n_samples - 1, 0.1)
    assert g * s * math.sqrt(v[-1]) > math.radians(0.02)  # one sample less is not enough (or it rises again)
