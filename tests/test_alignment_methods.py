"""The compass loop and coarse-to-fine alignment against their theories, and every method against its trial's bias floor.

Monte Carlo checks use fixed seeds and 95 % intervals from the batch standard
error; the floor of a trial, ``−ε_E/(Ω cos φ) + tan φ ∇_E/g`` of its own
biases, is computed from the derived gains, independently of the methods.
"""

import math

import control
import numpy as np
import pytest

from strapdown.analysis.alignment.coarse_to_fine import attitude_error, coarse_model, coarse_to_fine, split_record
from strapdown.analysis.alignment.comparison import compare_methods, summarise, trial_floors
from strapdown.analysis.alignment.compass_loop import CompassLoopDesign, compass_loop_alignment, compass_loop_system, compass_loop_theory, loop_gains
from strapdown.analysis.alignment.earth import EARTH_RATE, normal_gravity
from strapdown.analysis.alignment.fine import FilterTuning
from strapdown.analysis.alignment.imu import Scenario, SensorErrors, simulate_imu
from strapdown.analysis.alignment.inertial import inertial_alignment
from strapdown.analysis.alignment.tilt_attitude import attitude_matrix
from strapdown.analysis.core import kalman

R = np.radians
B = R(0.01) / 3600.0  # 0.01 deg/h
NAV = SensorErrors(gyro_bias_sigma=B, accel_bias_sigma=1e-4, gyro_noise=R(0.002) / 60.0, accel_noise=0.006 / 60.0)


@pytest.mark.parametrize("bandwidth,damping", [(0.02, 0.7), (0.05, 1.0), (0.1, 0.3)])
def test_loop_gains_place_the_poles(bandwidth, damping):
    k1, k2, k3 = loop_gains(bandwidth, damping)
    w, z = bandwidth, damping
    poles = [-w, -z * w + 1j * w * math.sqrt(1 - z * z), -z * w - 1j * w * math.sqrt(1 - z * z)]
    np.testing.assert_allclose(np.real(np.poly(poles)), [1.0, k1, k2, k3], rtol=1e-12)


def test_closed_loop_poles_are_the_two_designs():
    d = CompassLoopDesign(levelling_bandwidth=0.1, levelling_damping=0.7, compass_bandwidth=0.02, compass_damping=0.7)
    wn, zeta, _ = control.damp(compass_loop_system(R(45.0), d), doprint=False)
    # the Earth rate moves the poles by O(Ω/ω) relative
    np.testing.assert_allclose(np.sort(wn), [0.02, 0.02, 0.02, 0.1, 0.1, 0.1, 0.24], rtol=1e-3)


def test_linear_loop_settles_on_the_bias_floor():
    lat = R(45.0)
    e = SensorErrors(gyro_bias=[0.0, B, 0.0], accel_bias=[0.0, 1e-4, 0.0])
    th = compass_loop_theory(Scenario(lat, duration=1500.0), e, CompassLoopDesign())
    floor = -B / (EARTH_RATE * math.cos(lat)) + math.tan(lat) * 1e-4 / normal_gravity(lat)
    assert th.floor == pytest.approx(floor, rel=1e-12)
    assert th.mean[-1] == pytest.approx(floor, rel=2e-3)  # the loop's steady state (Ω²/ω² terms neglected in the floor)
    assert th.settling_time < 1500.0


def test_compass_loop_monte_carlo_against_its_linear_theory():
    lat = R(45.0)
    e = SensorErrors(gyro_bias=[0.0, B, 0.0], gyro_noise=NAV.gyro_noise, accel_noise=NAV.accel_noise)
    sc = Scenario(lat, heading=0.5, duration=600.0, sample_rate=10.0)
    d = CompassLoopDesign(epoch=0.2)
    rec = simulate_imu(sc, e, n_trials=96, rng=1, truth_stride=2)
    res = compass_loop_alignment(rec, d, rng=2)
    th = compass_loop_theory(sc, e, d)
    s = summarise(res.estimate.heading_error)
    assert s.mean_ci[0] < th.mean[-1] < s.mean_ci[1]
    # the sample standard deviation of 96 normal draws lies within ±15 % of σ with probability 0.97
    assert s.std == pytest.approx(th.std[-1], rel=0.15)
    # the record of the error over time ends on the estimate
    np.testing.assert_allclose(res.heading_error[:, -1], res.estimate.heading_error, atol=1e-12)


def test_split_record_keeps_the_increments_and_the_truth():
    sc = Scenario(R(45.0), heading=0.3, duration=20.0, sample_rate=10.0)
    rec = simulate_imu(sc, NAV, n_trials=3, rng=4, truth_stride=5)
    head, tail = split_record(rec, 100)
    np.testing.assert_array_equal(np.concatenate([head.dtheta, tail.dtheta], axis=1), rec.dtheta)
    np.testing.assert_array_equal(head.truth_angles[:, -1], tail.truth_angles[:, 0])
    assert head.scenario.duration == pytest.approx(10.0) and tail.truth_times[0] == 0.0
    with pytest.raises(ValueError, match="truth"):
        split_record(rec, 102)


def test_attitude_error_is_the_small_rotation():
    C = attitude_matrix([0.3, 0.01, -0.02])
    phi = np.array([1e-4, -2e-4, 3e-4])
    K = np.array([[0, -phi[2], phi[1]], [phi[2], 0, -phi[0]], [-phi[1], phi[0], 0]])
    np.testing.assert_allclose(attitude_error((np.eye(3) - K) @ C, C), phi, rtol=1e-7)


def test_coarse_covariance_describes_the_coarse_errors():
    """The coarse errors of fresh trials against the model: φ − G b has the calibrated covariance (χ² with 3 dof)."""
    lat = R(45.0)
    sc = Scenario(lat, heading=0.5, duration=60.0, sample_rate=10.0)
    cm = coarse_model(sc, NAV, coarse_duration=60.0, n_trials=256, rng=5)
    assert cm.sensitivity[2, 1] == pytest.approx(1.0 / (EARTH_RATE * math.cos(lat)), rel=1e-4)  # φ_D per ε_E: the floor
    rec = simulate_imu(sc, NAV, n_trials=512, rng=9)
    est = inertial_alignment(rec)
    phi = attitude_error(attitude_matrix(np.stack([est.heading, est.beta, est.gamma], -1)), attitude_matrix(rec.truth_angles[:, -1]))
    C0 = attitude_matrix(sc.stable_angles)
    r = phi - np.concatenate([rec.gyro_bias @ C0.T, rec.accel_bias @ C0.T], axis=1) @ cm.sensitivity.T
    q = np.einsum("ni,ij,nj->n", r, np.linalg.inv(cm.noise_covariance), r)
    # mean of 512 χ²(3) draws: 3 ± 0.22 (95 %); the calibration's own error (256 trials) adds about ±0.15
    assert abs(q.mean() - 3.0) < 0.45


def test_coarse_to_fine_reaches_the_floor_consistently():
    lat = R(45.0)
    sc = Scenario(lat, heading=0.5, duration=240.0, sample_rate=10.0)
    tuning = FilterTuning(epoch=0.5, gyro_bias=B, accel_bias=1e-4, gyro_noise=NAV.gyro_noise, accel_noise=NAV.accel_noise)
    cm = coarse_model(sc, NAV, coarse_duration=60.0, n_trials=256, rng=5)
    rec = simulate_imu(sc, NAV, n_trials=256, rng=7, truth_stride=5)
    res = coarse_to_fine(rec, tuning, cm, rng=8)
    resid = summarise(res.fine.estimate.heading_error - trial_floors(sc, rec.gyro_bias, rec.accel_bias))
    assert resid.mean_ci[0] < 0.0 < resid.mean_ci[1]
    idx = [0, 9, 99, 359]
    lo, hi = kalman.chi2_band(12, 256)
    nees = res.fine.nees.mean(axis=0)[idx]
    assert np.all((nees > 0.95 * lo) & (nees < 1.05 * hi)), nees  # four checks at 95 % each, bands widened 5 %
    lo, hi = kalman.chi2_band(3, 256)
    nis = res.fine.nis.mean(axis=0)[idx]
    assert np.all((nis > 0.95 * lo) & (nis < 1.05 * hi)), nis
    # the filter starts from the coarse result: its first azimuth error is the coarse one, corrected by one epoch
    assert np.corrcoef(-res.coarse_error[:, 2], res.fine.heading_error[:, 0])[0, 1] > 0.99


def test_every_method_reaches_its_trials_floor_on_the_same_trials():
    sc = Scenario(R(45.0), heading=0.5, duration=300.0, sample_rate=10.0)
    c = compare_methods(sc, NAV, n_trials=64, rng=3)
    assert c.floor.rms > 0.03 * math.pi / 180  # the floor dominates: σ_ε/(Ω cos φ) ≈ 0.054°
    for row in c.rows:
        assert row.residual.mean_ci[0] < 0.0 < row.residual.mean_ci[1], row.method
        assert row.residual.rms < row.error.rms, row.method
    for m in ("kalman", "coarse-to-fine"):
        r = c.row(m)
        lo, hi = r.nees_band
        assert np.all((r.nees > 0.9 * lo) & (r.nees < 1.1 * hi)), (m, r.nees)
        lo, hi = r.nis_band
        assert np.all((r.nis > 0.9 * lo) & (r.nis < 1.1 * hi)), (m, r.nis)


def test_comparison_does_not_depend_on_the_executor():
    from concurrent.futures import ThreadPoolExecutor

    sc = Scenario(R(45.0), heading=0.5, duration=80.0, sample_rate=5.0)
    kw = dict(n_trials=8, rng=1, methods=["analytic", "coarse-to-fine"], coarse_duration=20.0, trials_per_block=4, calibration_trials=16)
    a = compare_methods(sc, NAV, **kw)
    with ThreadPoolExecutor(2) as pool:
        b = compare_methods(sc, NAV, executor=pool, **kw)
    for ra, rb in zip(a.rows, b.rows):
        assert ra.error == rb.error and ra.residual == rb.residual
    assert np.array_equal(a.row("coarse-to-fine").nees, b.row("coarse-to-fine").nees)
    with pytest.raises(ValueError, match="methods"):
        compare_methods(sc, NAV, n_trials=4, methods=["magnetic"])
