"""Alignment from a large heading error: filterpy's unscented filter and the closed-loop error-state filter."""

import math

import numpy as np

from strapdown.analysis.alignment.fine import FilterTuning, fine_alignment
from strapdown.analysis.alignment.imu import Scenario, SensorErrors, simulate_imu
from strapdown.analysis.alignment.unscented import UnscentedTuning, unscented_alignment

B = math.radians(0.01) / 3600
ERR = SensorErrors(gyro_bias_sigma=B, accel_bias_sigma=1e-4, gyro_noise=math.radians(0.002) / 60, accel_noise=0.006 / 60)
SC = Scenario(math.radians(45.0), heading=0.5, duration=120.0, sample_rate=5.0)


def test_unscented_filter_has_the_linear_filters_covariance_from_a_small_error():
    rec = simulate_imu(SC, ERR, n_trials=2, rng=3, truth_stride=5)
    kw = dict(gyro_bias=B, accel_bias=1e-4, gyro_noise=ERR.gyro_noise, accel_noise=ERR.accel_noise)
    u = unscented_alignment(rec, UnscentedTuning(prior_heading=math.radians(1.0), prior_tilt=math.radians(0.1), alpha=1e-3, **kw), rng=4)
    f = fine_alignment(rec, FilterTuning(epoch=1.0, prior_heading=math.radians(1.0), **kw), rng=4)
    # the same information: the heading σ of the two filters within 5 % at 10, 30, 60 and 120 s
    idx = [9, 29, 59, 119]
    np.testing.assert_allclose(u.heading_sigma[0, idx], f.heading_sigma[idx], rtol=0.05)
    assert np.all(np.abs(u.estimate.heading_error) < 4 * u.heading_sigma[:, -1])


def test_both_filters_converge_from_tens_of_degrees():
    rec = simulate_imu(SC, ERR, n_trials=4, rng=7, truth_stride=5)
    kw = dict(gyro_bias=B, accel_bias=1e-4, gyro_noise=ERR.gyro_noise, accel_noise=ERR.accel_noise)
    u = unscented_alignment(rec, UnscentedTuning(prior_heading=math.radians(40.0), alpha=1e-3, **kw), rng=8)
    f = fine_alignment(rec, FilterTuning(epoch=1.0, prior_heading=math.radians(40.0), **kw), rng=8)
    start = np.abs(u.initial_heading_error)
    assert start.max() > math.radians(20.0)
    # the unscented filter has shrunk every error at least fivefold; the closed-loop error-state filter is at its floor
    assert np.all(np.abs(u.estimate.heading_error) < start / 5)
    assert np.all(np.abs(f.estimate.heading_error) < math.radians(0.5))
