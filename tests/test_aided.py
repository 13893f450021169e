"""In-motion alignment with GNSS aiding: the trajectory's kinematics and the aided filter against its own prediction.

The trajectory's sensor rates are checked by integrating the strapdown
equations in continuous time with DOP853 (a different integration of the same
physics); the navigator of the aided alignment by running it with ideal
sensors and exact fixes; the filter by Monte Carlo (NEES, NIS) and by its
floor at rest, which must be the gyro-bias floor of the self-alignment theory.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from strapdown.analysis.alignment.aided import AidedTuning, aided_alignment, aided_floor, aided_inputs, aided_monte_carlo, aided_sequence, time_to_align
from strapdown.analysis.alignment.earth import EARTH_RATE, normal_gravity
from strapdown.analysis.alignment.sensor_models import GRADES, SensorSpec
from strapdown.analysis.alignment.trajectory import Manoeuvre, position_solution, radii, trajectory_increments, trajectory_state

D = 180.0 / math.pi
TACTICAL = GRADES[3]
GYRO = SensorSpec(TACTICAL.gyro.random_walk, turn_on_bias=TACTICAL.gyro.turn_on_bias)
ACCEL = SensorSpec(TACTICAL.accel.random_walk, turn_on_bias=TACTICAL.accel.turn_on_bias)
WEAVE = Manoeuvre(heading=0.3, speed=10.0, start_speed=2.0, run_up=30.0, weave_amplitude=math.radians(20.0), weave_period=40.0)


def _skew(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def test_sensor_rates_reproduce_the_trajectory_through_the_strapdown_equations():
    man = WEAVE
    T = 60.0
    pos = position_solution(man, T)
    sol = trajectory_state(man, [0.0, T], solution=pos)
    h = man.height

    def rhs(t, y):
        C = y[:9].reshape(3, 3)
        v, lat = y[9:12], y[12]
        st = trajectory_state(man, [t], solution=pos)
        RN, RE = radii(lat)
        wie = EARTH_RATE * np.array([math.cos(lat), 0.0, -math.sin(lat)])
        wen = np.array([v[1] / (RE + h), -v[0] / (RN + h), -v[1] * math.tan(lat) / (RE + h)])
        dC = C @ _skew(st.gyro[0]) - _skew(wie + wen) @ C
        dv = C @ st.accel[0] + np.array([0.0, 0.0, normal_gravity(lat)]) - np.cross(2 * wie + wen, v)
        return np.concatenate([dC.ravel(), dv, [v[0] / (RN + h), v[1] / ((RE + h) * math.cos(lat))]])

    y0 = np.concatenate([sol.attitude[0].ravel(), sol.velocity[0], [sol.latitude[0], sol.longitude[0]]])
    out = solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=1e-11, atol=1e-13).y[:, -1]
    np.testing.assert_allclose(out[:9].reshape(3, 3), sol.attitude[1], atol=1e-8)
    np.testing.assert_allclose(out[9:12], sol.velocity[1], atol=1e-6)
    assert out[12] == pytest.approx(sol.latitude[1], abs=1e-12)


def test_increments_are_the_integrals_of_the_rates():
    dth, dv, sol = trajectory_increments(WEAVE, 10.0, 20.0)
    t = np.linspace(0.0, 0.1, 201)
    st = trajectory_state(WEAVE, 5.0 + t, solution=sol)
    np.testing.assert_allclose(dth[50], np.trapezoid(st.gyro, t, axis=0), rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(dv[50], np.trapezoid(st.accel, t, axis=0), rtol=1e-6)


def test_the_navigator_follows_the_truth_with_ideal_sensors_and_exact_fixes():
    inp = aided_inputs(WEAVE, AidedTuning.for_sensors(GYRO, ACCEL), sample_rate=20.0, duration=200.0)
    r = aided_alignment(inp, SensorSpec(), SensorSpec(), n_trials=1, initial_errors=False, gnss_noise=False)
    # the algorithm's own error: first order in the 0.2 s epoch, far below the 0.08° the filter reaches
    assert np.max(np.abs(r.heading_error)) < math.radians(1e-3)
    assert np.max(r.nis) < 1e-4


def test_the_aided_floor_at_rest_is_the_gyro_bias_floor():
    lat = math.radians(45.0)
    b, a = math.radians(0.01) / 3600, 1e-4
    tun = AidedTuning(gyro_bias=b, accel_bias=a, prior_heading=math.radians(1.0), velocity_noise=1e-3, position_noise=0.01)
    seq = aided_sequence(Manoeuvre(latitude=lat, speed=0.0), tun, sample_rate=10.0, duration=900.0)
    f = aided_floor(seq, np.array([[0, b, 0], [0, 0, 0]]), np.array([[0, 0, 0], [0, a, 0]]))
    assert f[0] == pytest.approx(-b / (EARTH_RATE * math.cos(lat)), rel=0.01)  # still converging after 900 s: 0.3 % short
    assert f[1] == pytest.approx(math.tan(lat) * a / normal_gravity(lat), rel=0.01)


def test_weaving_makes_the_heading_observable_and_the_filter_is_consistent():
    tun = AidedTuning.for_sensors(GYRO, ACCEL)
    straight = aided_sequence(Manoeuvre(heading=0.3, speed=10.0), tun, sample_rate=20.0, duration=300.0)
    inp = aided_inputs(WEAVE, tun, sample_rate=20.0, duration=300.0)
    assert straight.heading_sigma[-1] > math.radians(2.0)  # the tactical gyro cannot gyrocompass: 5° floor
    assert inp.sequence.heading_sigma[-1] < math.radians(0.1)
    mc = aided_monte_carlo(inp, GYRO, ACCEL, n_trials=128, rng=5)
    assert mc.residual.mean_ci[0] < 0.0 < mc.residual.mean_ci[1]
    assert mc.error.rms_ci[0] < mc.heading_sigma < mc.error.rms_ci[1]
    for x, (lo, hi) in ((mc.nees, mc.nees_band), (mc.nis, mc.nis_band)):
        assert np.all((x > 0.93 * lo) & (x < 1.07 * hi)), x  # six checks at 95 % each, the bands widened 7 %


def test_time_to_align_and_errors():
    assert time_to_align([2.0, 1.0, 0.5], [1.0, 2.0, 3.0], 0.6) == 3.0
    assert time_to_align([2.0, 1.0], [1.0, 2.0], 0.5) == math.inf
    with pytest.raises(ValueError, match="latitude"):
        Manoeuvre(latitude=math.radians(89.9))
    assert Manoeuvre(speed=10.0, weave_amplitude=0.1, weave_period=2 * math.pi).lateral_acceleration == pytest.approx(1.0)
    R = Rotation.from_euler("z", 0.3).as_matrix()
    np.testing.assert_allclose(trajectory_state(Manoeuvre(heading=0.3), [0.0]).attitude[0], R, atol=1e-15)


def test_the_compiled_navigator_equals_the_numpy_steps_to_the_last_bit(monkeypatch):
    # the compiled loop between fixes against navigator_step epoch by epoch, on a weave with sensor errors and noisy fixes
    from strapdown.analysis.alignment import kernels

    inp = aided_inputs(WEAVE, AidedTuning.for_sensors(GYRO, ACCEL), sample_rate=10.0, duration=60.0)
    runs = {}
    for compiled in (False, True):
        monkeypatch.setattr(kernels, "use_compiled", lambda c, work, _v=compiled: _v)
        runs[compiled] = aided_alignment(inp, GYRO, ACCEL, n_trials=5, rng=11)
    # the loop's libm and numpy's ufuncs agree to the bit on most machines; numpy's own AVX-512 tan and pow
    # are an ulp apart from libm's on some arguments, and then the two forms agree to round-off only
    x = np.linspace(-1.5, 1.5, 4001)
    same_libm = np.array_equal(np.tan(x), [math.tan(t) for t in x]) and np.array_equal(np.power(x + 2.0, 1.5), [(t + 2.0) ** 1.5 for t in x])
    for name in ("heading_error", "nees", "nis"):
        a, b = getattr(runs[True], name), getattr(runs[False], name)
        if same_libm:
            assert np.array_equal(a, b), name
        else:
            np.testing.assert_allclose(a, b, rtol=1e-12, atol=0.0, err_msg=name)
    # and the comparison can tell: another stream gives other errors
    other = aided_alignment(inp, GYRO, ACCEL, n_trials=5, rng=12)
    assert not np.array_equal(other.heading_error, runs[True].heading_error)


def test_the_compiled_navigator_refuses_shapes_that_do_not_fit():
    from strapdown.analysis.alignment import kernels

    n, E = 3, 4
    args = [np.zeros((n, 4)), np.zeros((n, 3)), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros((n, 3)), np.zeros((n, 3))]
    with pytest.raises(ValueError, match="velocity"):
        kernels.navigator_loop(*args, np.zeros((n, E, 4)), np.zeros((n, E + 1, 3)), np.zeros((n, E, 3)), 0.1, np.zeros(7))
    with pytest.raises(ValueError, match="constants"):
        kernels.navigator_loop(*args, np.zeros((n, E, 4)), np.zeros((n, E, 3)), np.zeros((n, E, 3)), 0.1, np.zeros(6))
