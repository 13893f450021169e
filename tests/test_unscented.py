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


def _filterpy_reference(record, t, x0_err, noise):
    """The filter as filterpy runs it unmodified: ``fx`` once per sigma point, its own unscented transform and cross variance."""
    from filterpy.kalman import MerweScaledSigmaPoints, UnscentedKalmanFilter
    from scipy.spatial.transform import Rotation

    from strapdown.analysis.alignment.earth import earth_rate_ned, gravity_ned
    from strapdown.analysis.alignment.error_model import skew
    from strapdown.analysis.alignment.preintegration import preintegrate
    from strapdown.analysis.alignment.tilt_attitude import angles_from_matrix, attitude_matrix
    from strapdown.analysis.alignment.unscented import _mean, _residual

    sc = record.scenario
    ep = preintegrate(record.dtheta, record.dv, sc.dt, int(round(t.epoch / sc.dt)))
    n, E, D = record.n_trials, ep.n_epochs, ep.epoch
    dR = Rotation.from_quat(ep.rotation.reshape(-1, 4), scalar_first=True).as_matrix().reshape(n, E, 3, 3)
    W, gn = earth_rate_ned(sc.latitude), gravity_ned(sc.latitude)
    Wx, E_earth = skew(W), Rotation.from_rotvec(-W * D).as_matrix()

    def fx(x, dt, R, dV, S):
        C = attitude_matrix(x[0:3])
        bg, ba = x[6:9] * t.gyro_bias, x[9:12] * t.accel_bias
        v = x[3:6] + C @ (dV - ba * D) - Wx @ (C @ S) + gn * D - 2.0 * D * (Wx @ x[3:6])
        C = E_earth @ C @ R @ Rotation.from_rotvec(-bg * D).as_matrix()
        a = angles_from_matrix(C)
        out = x.copy()
        out[0:3] = (a.heading, a.beta, a.gamma)
        out[3:6] = v
        return out

    points = MerweScaledSigmaPoints(12, alpha=t.alpha, beta=t.beta, kappa=t.kappa, subtract=_residual)
    P0 = np.diag(np.square([t.prior_heading, t.prior_tilt, t.prior_tilt] + [t.prior_velocity] * 3 + [1.0] * 6))
    Q = np.diag(np.square([t.gyro_noise] * 3 + [t.accel_noise] * 3 + [0.0] * 6) * D + 1e-14)
    sig = np.empty((n, E))
    final = np.empty((n, 3))
    for i in range(n):
        ukf = UnscentedKalmanFilter(12, 3, D, lambda x: x[3:6], fx, points, x_mean_fn=_mean, residual_x=_residual)
        ukf.x = np.zeros(12)
        ukf.x[0:3] = record.truth_angles[i, 0] + x0_err[i]
        ukf.P, ukf.Q, ukf.R = P0.copy(), Q.copy(), t.measurement_noise**2 * np.eye(3)
        for j in range(E):
            ukf.predict(R=dR[i, j], dV=ep.velocity[i, j], S=ep.moment[i, j])
            ukf.update(noise[i, j])
            sig[i, j] = math.sqrt(ukf.P[0, 0])
        final[i] = ukf.x[0:3]
    return final, sig


def test_the_batched_filter_equals_filterpys_own_to_the_last_bit():
    # all sigma points propagated at once and the vectorised transform against filterpy's loops, from a large heading error
    sc = Scenario(math.radians(45.0), heading=0.5, duration=30.0, sample_rate=5.0)
    rec = simulate_imu(sc, ERR, n_trials=2, rng=5, truth_stride=5)
    t = UnscentedTuning(prior_heading=math.radians(40.0), alpha=1e-3, gyro_bias=B, accel_bias=1e-4, gyro_noise=ERR.gyro_noise, accel_noise=ERR.accel_noise)
    x0 = np.random.default_rng(6).standard_normal((2, 3)) * np.array([t.prior_heading, t.prior_tilt, t.prior_tilt])
    u = unscented_alignment(rec, t, rng=9, initial_errors=x0)
    g = np.random.default_rng(9)
    g.standard_normal((2, 3))  # the initial errors' draw, replaced by x0
    final, sig = _filterpy_reference(rec, t, x0, t.measurement_noise * g.standard_normal((2, u.times.size, 3)))
    assert np.array_equal(u.heading_sigma, sig)
    assert np.array_equal(np.stack([u.estimate.heading, u.estimate.beta, u.estimate.gamma], axis=-1), final)
    # and the comparison can tell: other measurement noise gives other estimates
    other, _ = _filterpy_reference(rec, t, x0, np.zeros((2, u.times.size, 3)))
    assert not np.array_equal(other, final)
