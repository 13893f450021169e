"""The truth model of the section-5 scenario: a body over the rotating Earth (Plotnikov 1999)."""

import numpy as np
import pytest
from scipy.integrate import quad

from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.multistage import earth
from strapdown.analysis.multistage.sensors import SensorErrors, corrupt
from strapdown.analysis.multistage.trajectory import Scenario, eta_azimuth, sample, specific_force_residual, truth


def test_geographic_frame_axes():
    """ζ = (north, up, east) in the Earth frame, from the latitude/longitude formulas."""
    lat, lon = 0.7, -1.9
    q = earth.geographic_to_earth(lat, lon)
    north = [-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)]
    up = [np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)]
    east = [-np.sin(lon), np.cos(lon), 0.0]
    np.testing.assert_allclose(quat.rotate(q, np.eye(3)), [north, up, east], atol=1e-15)


def test_velocity_integrates_specific_force_plus_gravitation():
    """Residual check of the truth model: consistent to round-off; the old model misses Coriolis and V²/R."""
    good = specific_force_residual(Scenario())
    assert good.scale > 100.0 and good.max_residual < 1e-9
    bad = specific_force_residual(Scenario(truth="no-coriolis"))
    # 400 m/s × 2Ω sin φ ≈ 0.041 m/s² over the 100 s intervals after the manoeuvre.
    assert bad.max_residual > 1.0


def test_coriolis_direction():
    """Moving north in the northern hemisphere, the Coriolis specific force points west; moving south, east."""
    t = np.array([1300.0])
    f_north = truth(Scenario(), t).specific_force_geographic[0]
    f_south = truth(Scenario(accel=-20.0), t).specific_force_geographic[0]
    assert f_north[2] < 0 < f_south[2]
    assert specific_force_residual(Scenario(accel=-20.0, duration=1400.0)).max_residual < 1e-9


def test_eta_has_no_vertical_rate_and_zeta_has():
    sc = Scenario()
    t = np.linspace(0.0, 5000.0, 1001)
    dt = 1e-3

    def rate(frame_of):
        a, b = frame_of(t), frame_of(t + dt)
        return quat.quat_to_rotvec(quat.multiply(quat.conjugate(a), b), canonical=True) / dt

    def eta(tt):
        tr = truth(sc, tt)
        return quat.multiply(tr.attitude_inertial, quat.conjugate(tr.attitude))

    def zeta(tt):
        return earth.geographic_to_inertial(tt, sc.latitude_at(tt), 0.0 * tt, sc.earth_rate)

    assert np.abs(rate(eta)[:, 1]).max() < 1e-11
    np.testing.assert_allclose(rate(zeta)[:, 1], sc.earth_rate * np.sin(sc.latitude_at(t + dt / 2)), rtol=1e-6)


def test_eta_azimuth_against_quadrature():
    sc = Scenario()
    for t in (0.0, 700.0, 1205.0, 1220.0, 4321.0):
        ref = quad(lambda s: -sc.earth_rate * np.sin(sc.latitude_at(s)), 0.0, t, points=[p for p in (1200.0, 1220.0) if p < t] or None, epsabs=1e-16, limit=200)[0]
        assert eta_azimuth(sc, t) == pytest.approx(ref, abs=1e-14)


def test_body_fixed_to_the_earth_at_rest():
    """Rotating-Earth truth: at rest the body does not move relative to the Earth; its yaw relative to η grows by Ω sin φ t."""
    sc = Scenario()
    t = np.array([0.0, 400.0, 999.0])
    tr = truth(sc, t)
    in_earth = quat.multiply(quat.conjugate(earth.earth_to_inertial(t, sc.earth_rate)), tr.attitude_inertial)
    np.testing.assert_allclose(in_earth, np.broadcast_to(in_earth[0], in_earth.shape), atol=1e-15)
    np.testing.assert_allclose(tr.angles[:, 0], sc.earth_rate * np.sin(sc.latitude) * t, rtol=1e-12)
    np.testing.assert_allclose(tr.specific_force, [[0.0, 9.81, 0.0]] * 3, atol=1e-14)
    old = truth(Scenario(truth="no-coriolis"), t)
    np.testing.assert_allclose(old.angles, 0.0, atol=0.0)


def test_specific_force_while_moving():
    sc = Scenario()
    t = np.array([1210.0, 2000.0])
    f = truth(sc, t).specific_force_geographic
    v = sc.north_velocity(t)
    lat = sc.latitude_at(t)
    np.testing.assert_allclose(f[:, 0], [20.0, 0.0])
    np.testing.assert_allclose(f[:, 1], 9.81 - v * v / sc.earth_radius)
    np.testing.assert_allclose(f[:, 2], -2 * sc.earth_rate * np.sin(lat) * v)


def test_gyro_increments_compose_to_the_inertial_attitude():
    sc = Scenario(duration=1300.0, sensors=SensorErrors())
    d = sample(sc, 0.5)
    lam = truth(sc, d.time).attitude_inertial
    k = 2000
    prod = lam[0]
    for dq in quat.rotvec_to_quat(d.gyro[:k]):
        prod = quat.multiply(prod, dq)
    angle = np.linalg.norm(quat.quat_to_rotvec(quat.multiply(quat.conjugate(lam[k]), prod / np.linalg.norm(prod)), canonical=True))
    assert angle < 1e-12


def test_corrupt_is_seeded_and_split():
    d = sample(Scenario(duration=20.0, sensors=SensorErrors()), 0.5)
    e = SensorErrors(gyro_noise=1e-4, accel_noise=1e-3)
    a, b = corrupt(d, e, rng=3), corrupt(d, e, rng=3)
    np.testing.assert_array_equal(a.gyro, b.gyro)
    gyro_only = corrupt(d, SensorErrors(gyro_noise=1e-4), rng=3)
    np.testing.assert_array_equal(a.gyro, gyro_only.gyro)  # gyro stream independent of the accelerometer draws
    with pytest.raises(TypeError, match="`errors`"):
        corrupt(d, {"gyro_noise": 1.0})


def test_horizontal_centripetal():
    assert earth.horizontal_centripetal(np.radians(45.0), 7.292115e-5, 6.371e6) == pytest.approx(7.292115e-5**2 * 6.371e6 / 2)


def test_sampled_accelerometers_are_the_mean_body_force_of_the_truth():
    """sample's accelerometer record is the 3-point Gauss–Legendre mean of truth(...).specific_force, to the last bit."""
    from strapdown.analysis.multistage.trajectory import GAUSS3, Scenario, grid, sample, truth

    for sc in (Scenario(duration=1300.0, sensors=SensorErrors()), Scenario(duration=1300.0, truth="no-coriolis", sensors=SensorErrors())):
        data = sample(sc, 0.5)
        t = grid(sc, 0.5)
        x, w = GAUSS3
        force = truth(sc, t[:-1, None] + 0.5 * x).specific_force
        np.testing.assert_array_equal(data.accel, np.einsum("nkj,k->nj", force, w))
