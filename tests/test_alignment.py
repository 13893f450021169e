"""Self-alignment on a rocking base: kinematics, sensor record, the three methods against theory.

Every Monte Carlo check has a fixed seed and compares a theory with a 95 %
interval built from the batch standard error; where a check is deterministic
(no randomness in the trial) the tolerance is the size of the neglected
second-order term.
"""

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from strapdown.analysis.alignment.analytic import analytic_alignment
from strapdown.analysis.alignment.base_motion import NarrowbandMotion, SineMotion, WhiteMotion, mean_variance
from strapdown.analysis.alignment.earth import EARTH_RATE, earth_rate_ned, gravity_ned, normal_gravity
from strapdown.analysis.alignment.imu import Scenario, SensorErrors, simulate_imu
from strapdown.analysis.alignment.inertial import inertial_alignment, wahba_rotation
from strapdown.analysis.alignment.monte_carlo import AlignmentKernel, AlignmentOptions, alignment_monte_carlo
from strapdown.analysis.alignment.preintegration import chain_rotations, preintegrate
from strapdown.analysis.alignment.theory import analytic_theory
from strapdown.analysis.alignment.tilt_attitude import attitude_matrix, body_acceleration, body_rate, tilts_from_specific_force
from strapdown.analysis.core import montecarlo
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.gyrocompass.azimuth import azimuth_error, second_order_theory

R = np.radians
B_001 = R(0.01) / 3600.0  # 0.01 deg/h [rad/s]


def _inside(ci, value):
    return ci[0] <= value <= ci[1]


# ---------------------------------------------------------------- kinematics
def test_attitude_is_the_composition_of_elementary_rotations():
    a = np.array([0.7, -0.3, 0.4])
    C = Rotation.from_euler("z", a[0]) * Rotation.from_euler("x", -a[1]) * Rotation.from_euler("y", a[2])
    np.testing.assert_allclose(attitude_matrix(a), C.as_matrix(), atol=1e-15)


def test_body_rate_and_acceleration_are_the_derivatives_of_the_attitude():
    f = lambda t: np.array([0.7 + 0.3 * np.sin(t), -0.3 + 0.2 * np.cos(2 * t), 0.4 + 0.1 * t**2])  # noqa: E731
    df = lambda t: np.array([0.3 * np.cos(t), -0.4 * np.sin(2 * t), 0.2 * t])  # noqa: E731
    ddf = lambda t: np.array([-0.3 * np.sin(t), -0.8 * np.cos(2 * t), 0.2])  # noqa: E731
    t, h = 0.3, 1e-6
    C = attitude_matrix(f(t))
    W = C.T @ (attitude_matrix(f(t + h)) - attitude_matrix(f(t - h))) / (2 * h)
    np.testing.assert_allclose(body_rate(f(t), df(t)), [W[2, 1], W[0, 2], W[1, 0]], atol=1e-9)
    wd = (body_rate(f(t + h), df(t + h)) - body_rate(f(t - h), df(t - h))) / (2 * h)
    np.testing.assert_allclose(body_acceleration(f(t), df(t), ddf(t)), wd, atol=1e-8)


def test_two_gyros_read_the_papers_A_and_B_at_zero_heading():
    """At ψ = 0 the horizontal gyros read Ω (A, B) of Hrechka & Koroliov (after eq. (2))."""
    phi, b, g = 1.0, 0.05, -0.03
    w = attitude_matrix([0.0, b, g]).T @ earth_rate_ned(phi)
    A = math.cos(phi) * math.cos(g) + math.sin(phi) * math.cos(b) * math.sin(g)
    assert w[:2] / EARTH_RATE == pytest.approx([A, math.sin(phi) * math.sin(b)], abs=1e-15)
    f = attitude_matrix([0.4, b, g]).T @ -gravity_ned(phi)
    assert tilts_from_specific_force(f) == pytest.approx([b, g], abs=1e-15)


def test_normal_gravity_wgs84():
    assert normal_gravity(0.0) == pytest.approx(9.7803253359, abs=1e-10)
    assert normal_gravity(math.pi / 2) == pytest.approx(9.8321849378, abs=1e-9)  # NIMA TR8350.2, table 3.4


# ---------------------------------------------------------------- base motion
def test_fft_evaluation_equals_the_sum_of_sinusoids():
    m = NarrowbandMotion(0.02, 8.0, 0.1)
    r = m.draw(1, 2, 400, 0.05)
    a, d, _ = r.evaluate(400, 0.013)
    t = 0.013 + np.arange(400) * 0.05
    s = r.spectrum
    direct = np.real(r.coefficients[1, 2, :, None] * np.exp(1j * np.outer(s.omega, t))).sum(axis=0)
    rate = np.real(1j * s.omega[:, None] * r.coefficients[1, 2, :, None] * np.exp(1j * np.outer(s.omega, t))).sum(axis=0)
    np.testing.assert_allclose(a[1, :, 2], direct, atol=1e-15)
    np.testing.assert_allclose(d[1, :, 2], rate, atol=1e-14)


def test_rocking_statistics():
    m = NarrowbandMotion([0.01, 0.02, 0.03], 8.0, 0.1)
    (a,) = m.draw(2, 1000, 3, 0.1).evaluate(1, derivatives=0)
    # Gaussian coefficients: the value at an instant is N(0, σ²); SE of a std from 1000 draws ≈ 2.2 %
    # the trapezoidal sum of the density: σ² up to the band edge between grid points (the density there is 1/225 of its low end)
    np.testing.assert_allclose(m.spectrum(3, 0.1).sigma, m.sigma, rtol=1e-7)
    np.testing.assert_allclose(a[:, 0].std(axis=0), m.sigma, rtol=0.08)
    w = WhiteMotion(0.01)
    x = w.draw(3, 200, 400, 0.01).evaluate(400, derivatives=0)[0][:, :, 1]
    assert abs(np.mean(x[:, :-1] * x[:, 1:]) / np.mean(x * x)) < 0.02  # white at the sample rate
    s = SineMotion([0.01, 0.02, 0.03], 5.0).draw(4, 64, 100, 0.1).evaluate(100)[0]
    np.testing.assert_allclose(np.abs(s).max(axis=(0, 1)), [0.01, 0.02, 0.03], rtol=2e-3)


# ---------------------------------------------------------------- sensor record
@pytest.mark.parametrize("motion", [SineMotion(R(np.array([0.5, 2.0, 3.0])), 6.0), NarrowbandMotion(R(np.array([0.0, 2.0, 1.0])), 8.0, 0.1)], ids=["sine", "narrowband"])
@pytest.mark.parametrize("lever_arm", [[0.5, -0.3, 1.0], [0.0, 0.0, 0.0]], ids=["lever-arm", "at-the-centre"])
@pytest.mark.parametrize("in_gyros", [True, False], ids=["gyros-see-it", "tilt-channel"])
def test_compiled_sensor_loops_equal_the_numpy_reference(motion, lever_arm, in_gyros):
    """The fused increments and the compiled preintegration against their numpy forms, to round-off."""
    from dataclasses import replace

    from strapdown.analysis.alignment.imu import ideal_increments

    sc = Scenario(R(60.0), heading=0.5, beta0=0.02, gamma0=-0.01, motion=motion, lever_arm=lever_arm, sample_rate=10.0, duration=20.0, rocking_in_gyros=in_gyros)
    m = sc.motion.draw(np.random.default_rng(7), 3, sc.n_samples + 1, sc.dt)
    fast, ref = ideal_increments(sc, m), ideal_increments(sc, m, compiled=False)
    for a, b in zip(fast, ref):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-15 * np.max(np.abs(b)))
    for M in (1, 7, 10):  # 7: a partial last epoch is dropped
        e1, e2 = preintegrate(*ref, sc.dt, M), preintegrate(*ref, sc.dt, M, compiled=False)
        assert e1.n_epochs == e2.n_epochs == sc.n_samples // M
        for name in ("rotation", "velocity", "moment"):
            np.testing.assert_allclose(getattr(e1, name), getattr(e2, name), rtol=0, atol=1e-14 * max(np.max(np.abs(getattr(e2, name))), 1e-300))
        np.testing.assert_allclose(chain_rotations(quat.identity((3,)), e2.rotation), chain_rotations(quat.identity((3,)), e2.rotation, compiled=False), rtol=0, atol=1e-15)
    assert replace(sc, motion=motion).n_samples == fast[0].shape[1]


@pytest.mark.parametrize(
    "model", [NarrowbandMotion(R(np.array([0.0, 1.0, 2.0])), 10.0, 0.1), WhiteMotion(R(np.array([0.3, 1.0, 2.0]))), SineMotion(R(np.array([0.0, 1.0, 2.0])), 7.0)], ids=["narrowband", "white", "sine"]
)
def test_scaled_draws_share_their_evaluations_and_equal_the_direct_sum(model):
    """The same draw at another amplitude (common random numbers) shares the unit evaluations; the values are a fresh evaluation's and the direct sum's."""
    from dataclasses import replace

    from strapdown.analysis.alignment.base_motion import MotionRealisation

    r1 = model.draw(np.random.default_rng(3), 4, 301, 0.1)
    r2 = r1.rescaled(replace(model, amplitude=3.0 * model.amplitude))
    assert r2.unit is r1.unit  # one draw, passed on: its evaluations are shared
    fresh = replace(model, amplitude=3.0 * model.amplitude).draw(np.random.default_rng(3), 4, 301, 0.1)
    assert np.array_equal(fresh.coefficients, r2.coefficients)  # the same numbers as a draw from the same state
    with pytest.raises(ValueError, match="amplitudes only"):
        r1.rescaled(replace(model, amplitude=model.amplitude, **({"period": 3.0} if hasattr(model, "period") else {"bandwidth": 1.0})))
    t = 0.03 + 0.1 * np.arange(300)
    direct = np.real(np.einsum("nam,km->nka", r2.coefficients, np.exp(1j * np.outer(t, r2.spectrum.omega))))
    for r, scale in ((r1, 1.0), (r2, 3.0)):
        plain = MotionRealisation(r.spectrum, r.coefficients, r.dt)  # no unit: a fresh FFT or sum
        for a, b in zip(r.evaluate(300, 0.03), plain.evaluate(300, 0.03)):
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-15 * np.max(np.abs(b)))
        np.testing.assert_allclose(r.evaluate(300, 0.03, derivatives=0)[0] * (3.0 / scale), direct, rtol=0, atol=1e-13 * np.max(np.abs(direct)))


def test_unit_evaluation_times_its_scale_is_the_evaluation_and_the_compiled_loop_applies_it():
    """A scaled draw hands its shared unit arrays and amplitudes to the compiled loop, which scales them itself:
    the same increments as the loop on the multiplied-out rocking (the same products), to the last bit."""
    from strapdown.analysis.alignment import kernels as k

    sc = Scenario(R(60.0), heading=0.5, lever_arm=[0.5, -0.3, 1.0], sample_rate=10.0, duration=20.0)
    m = NarrowbandMotion(R(np.array([0.3, 2.0, 1.0])), 8.0, 0.1).draw(np.random.default_rng(2), 3, sc.n_samples + 1, sc.dt)
    parts, scale = m.unit_evaluation(sc.n_samples, 0.02)
    assert not parts[0].flags.writeable and np.array_equal(scale, m.scale)  # the kept unit evaluation
    for a, b in zip(m.evaluate(sc.n_samples, 0.02), parts):
        assert np.array_equal(a, scale * b)
    W, g, fixed = earth_rate_ned(sc.latitude), gravity_ned(sc.latitude), np.zeros(3)
    out = [np.zeros((3, sc.n_samples, 3)) for _ in range(4)]
    k.accumulate_ideal_increments(*parts, sc.stable_angles, W, g, sc.lever_arm, fixed, True, 0.05, out[0], out[1], scale=scale)
    k.accumulate_ideal_increments(*(scale * p for p in parts), sc.stable_angles, W, g, sc.lever_arm, fixed, True, 0.05, out[2], out[3])
    assert np.array_equal(out[0], out[2]) and np.array_equal(out[1], out[3])
    with pytest.raises(ValueError, match="`scale`"):
        k.accumulate_ideal_increments(*parts, sc.stable_angles, W, g, sc.lever_arm, fixed, True, 0.05, out[0], out[1], scale=[1.0, 2.0])


def test_sensor_terms_in_one_pass_are_the_numpy_operations():
    """Scale factors, bias and noise applied by the compiled pass: the product and the two sums of the numpy form, to the last bit."""
    from strapdown.analysis.alignment import kernels as k

    rng = np.random.default_rng(4)
    x, b, s, z = rng.normal(size=(3, 50, 3)), rng.normal(size=(3, 3)) * 1e-3, 1.0 + rng.normal(size=3) * 1e-4, rng.normal(size=(3, 50, 3)) * 1e-2
    for scale, noise in ((None, None), (s, None), (None, z), (s, z)):
        ref = x.copy()
        if scale is not None:
            ref *= scale
        ref += b[:, None, :]
        if noise is not None:
            ref += noise
        out = x.copy()
        k.add_sensor_terms(out, b, scale=scale, noise=noise)
        assert np.array_equal(out, ref)
    with pytest.raises(TypeError, match="`increments`"):
        k.add_sensor_terms(x.astype(np.float32), b)
    with pytest.raises(ValueError, match="`noise`"):
        k.add_sensor_terms(x.copy(), b, noise=z[:, :10])
    with pytest.raises(ValueError, match="`bias`"):
        k.add_sensor_terms(x.copy(), b[:2])


def test_compiled_preintegration_steps_each_trial_on_its_own():
    """The compiled loop steps trials side by side: each trial's epochs are those of the trial alone, to the
    last bit, whatever its neighbours (a large rotation that takes the exact branch, a NaN, a partial group),
    and the numpy form's to round-off."""
    from strapdown.analysis.alignment import kernels as k

    rng = np.random.default_rng(11)
    n, N, M = 11, 60, 7
    th, v = rng.normal(size=(n, N, 3)) * 2e-3, rng.normal(size=(n, N, 3)) * 0.1
    th[2, 20] = [0.3, -0.2, 0.1]  # beyond the series branch of the rotation
    th[5, 33, 1] = math.nan
    together = k.preintegrate_loop(th, v, 0.1, M, N // M)
    for i in range(n):
        alone = k.preintegrate_loop(th[i : i + 1], v[i : i + 1], 0.1, M, N // M)
        assert all(np.array_equal(a[i : i + 1], b, equal_nan=True) for a, b in zip(together, alone))
    ok = [i for i in range(n) if i != 5]
    ref = preintegrate(th[ok], v[ok], 0.1, M, compiled=False)
    for a, b in zip(together, (ref.rotation, ref.velocity, ref.moment)):
        np.testing.assert_allclose(a[ok], b, rtol=0, atol=1e-14 * np.max(np.abs(b)))
    assert np.all(np.isnan(together[0][5, 33 // M])) and not np.any(np.isnan(together[0][5, 0]))  # the NaN stays in its trial


@pytest.mark.parametrize("lever_arm", [[0.0, 0.0, 0.0], [0.5, -0.3, 1.0]], ids=["no-lever", "lever"])
@pytest.mark.parametrize("yaw", [0.0, 0.3], ids=["no-yaw", "yaw"])
@pytest.mark.parametrize("in_gyros", [True, False], ids=["gyros-see-it", "tilt-channel"])
def test_both_nodes_and_the_sensor_terms_in_one_pass_are_the_separate_passes(lever_arm, yaw, in_gyros):
    """sensor_increments: the two nodes accumulated into zeros, then the sensor terms, to the last bit, for every
    combination of scale factors and noise (and none: the ideal increments); only the gyros' and the
    accelerometers' terms together."""
    from strapdown.analysis.alignment import kernels as k

    sc = Scenario(R(60.0), heading=0.5, beta0=0.02, lever_arm=lever_arm, sample_rate=10.0, duration=20.0, rocking_in_gyros=in_gyros)
    m = NarrowbandMotion(R(np.array([yaw, 2.0, 1.0])), 8.0, 0.1).draw(np.random.default_rng(2), 3, sc.n_samples + 1, sc.dt)
    nodes = [m.unit_evaluation(sc.n_samples, t, derivatives=2) for t in (0.02, 0.08)]
    scale = nodes[0][1]
    W, g = earth_rate_ned(sc.latitude), gravity_ned(sc.latitude)
    fixed = np.array([1e-5, -2e-5, 3e-5])
    rng = np.random.default_rng(4)
    b, z = rng.normal(size=(2, 3, 3)) * 1e-3, rng.normal(size=(2, 3, sc.n_samples, 3)) * 1e-2
    s = 1.0 + rng.normal(size=(2, 3)) * 1e-4
    cases = [None] + [((b[0], s[0] if i & 1 else None, z[0] if i & 2 else None), (b[1], s[1] if i & 4 else None, z[1] if i & 8 else None)) for i in range(16)]
    for terms in cases:
        ref = [np.zeros((3, sc.n_samples, 3)) for _ in range(2)]
        for parts, _ in nodes:
            k.accumulate_ideal_increments(*parts, sc.stable_angles, W, g, sc.lever_arm, fixed, in_gyros, 0.05, *ref, scale=scale)
        if terms is not None:
            for x, (bias, factor, noise) in zip(ref, terms):
                k.add_sensor_terms(x, bias, scale=factor, noise=noise)
        gyro, accel = (None, None) if terms is None else terms
        out = k.sensor_increments(*(parts for parts, _ in nodes), sc.stable_angles, W, g, sc.lever_arm, fixed, in_gyros, 0.05, scale=scale, gyro=gyro, accel=accel)
        assert all(np.array_equal(x, y) for x, y in zip(out, ref))
        assert all(x.flags.c_contiguous and x.flags.writeable and x.shape == (3, sc.n_samples, 3) for x in out)
    with pytest.raises(ValueError, match="`gyro` and `accel` both"):
        k.sensor_increments(*(parts for parts, _ in nodes), sc.stable_angles, W, g, sc.lever_arm, fixed, in_gyros, 0.05, scale=scale, gyro=cases[1][0])
    with pytest.raises(ValueError, match="`noise`"):
        k.sensor_increments(*(parts for parts, _ in nodes), sc.stable_angles, W, g, sc.lever_arm, fixed, in_gyros, 0.05, gyro=(b[0], None, z[0][:, :10]), accel=(b[1], None, None))
    with pytest.raises(ValueError, match="`second` as \\(angles, rates, accels\\)"):
        k.sensor_increments(nodes[0][0], nodes[1][0][:2], sc.stable_angles, W, g, sc.lever_arm, fixed, in_gyros, 0.05)


@pytest.mark.parametrize(
    "model",
    [NarrowbandMotion(R(np.array([0.3, 2.0, 1.0])), 8.0, 0.1), WhiteMotion(R(np.array([0.3, 1.0, 2.0]))), SineMotion(R(np.array([0.0, 2.0, 1.0])), 7.0), None],
    ids=["narrowband", "white", "sine", "still"],
)
def test_one_draw_in_chunks_gives_the_records_of_separate_draws(model):
    """Draws made chunk after chunk into one draw: the numbers of separate draws of the chunks, and records whose
    trials are the chunks' records, to the last bit (each trial is its own)."""
    from dataclasses import replace

    from strapdown.analysis.alignment.base_motion import MotionRealisation
    from strapdown.analysis.alignment.imu import draw_imu

    sc = Scenario(R(60.0), heading=0.5, lever_arm=[0.5, -0.3, 1.0], sample_rate=10.0, duration=20.0)
    sc = sc if model is None else replace(sc, motion=model)
    e = SensorErrors(gyro_bias=[1e-6, 0.0, -2e-6], gyro_bias_sigma=1e-6, accel_scale=[1e-4, 0.0, 0.0], gyro_noise=1e-5, accel_noise=1e-4, gyro_quantum=1e-6, accel_quantum=1e-4)
    whole = draw_imu(sc, e, n_trials=7, rng=np.random.default_rng(6), chunk=3)
    g = np.random.default_rng(6)
    chunks = [draw_imu(sc, e, n_trials=n, rng=g) for n in (3, 3, 1)]
    for name in ("gyro_bias", "accel_bias", "gyro_noise", "accel_noise", "gyro_start", "accel_start"):
        assert np.array_equal(getattr(whole, name), np.concatenate([getattr(c, name) for c in chunks])), name
    assert np.array_equal(whole.rocking.coefficients, np.concatenate([c.rocking.coefficients for c in chunks]))
    for at in (sc, replace(sc, motion=replace(model, amplitude=0.5 * model.amplitude)) if model is not None else sc):  # the drawn amplitudes and others
        rec = simulate_imu(at, e, draws=whole, truth_stride=5)
        parts = [simulate_imu(at, e, draws=c, truth_stride=5) for c in chunks]
        for name in ("dtheta", "dv", "truth_angles", "truth_velocity", "truth_rates", "gyro_bias", "accel_bias"):
            assert np.array_equal(getattr(rec, name), np.concatenate([getattr(p, name) for p in parts])), name
    assert MotionRealisation.concatenate([chunks[0].rocking]) is chunks[0].rocking
    if model is not None:
        other = draw_imu(replace(sc, motion=replace(model, amplitude=2.0 * model.amplitude)), e, n_trials=2, rng=1)
        with pytest.raises(ValueError, match="one model"):
            MotionRealisation.concatenate([chunks[0].rocking, other.rocking])
    with pytest.raises(ValueError, match="`chunk`"):
        draw_imu(sc, e, n_trials=2, rng=1, chunk=0)


@pytest.mark.parametrize("method", ["analytic", "inertial", "kalman"])
def test_kernel_simulates_its_chunks_together_without_changing_a_trial(method, monkeypatch):
    """The Monte Carlo kernel draws in chunks and simulates consecutive chunks at once: the trials of a chunk at a time."""
    from strapdown.analysis.alignment import monte_carlo as mc

    sc = Scenario(R(60.0), heading=0.5, motion=NarrowbandMotion(R(np.array([0.3, 1.0, 1.0])), 8.0, 0.1), lever_arm=[0.5, -0.3, 1.0], sample_rate=10.0, duration=20.0)
    e = SensorErrors(gyro_bias_sigma=1e-6, accel_bias_sigma=1e-4, gyro_noise=1e-5, accel_noise=1e-4)
    kernel = AlignmentKernel(sc, e, method, AlignmentOptions(), (0, 10), chunk=3)
    together = kernel.draw(8, np.random.default_rng(2))
    monkeypatch.setattr(mc, "SIMULATED_AT_ONCE", 0)  # a chunk at a time
    apart = kernel.draw(8, np.random.default_rng(2))
    assert (len(together.imu), len(apart.imu)) == (1, 3)
    for a, b in zip(kernel.evaluate(together), kernel.evaluate(apart)):
        assert np.array_equal(a, b, equal_nan=True)


@pytest.mark.parametrize("compiled", [True, False], ids=["compiled", "numpy"])
def test_increments_without_rocking_are_the_first_trial_for_all(compiled):
    """No rocking (a still base, or a draw at zero amplitude): one trial computed, the same for all, equal to a computation per trial."""
    from strapdown.analysis.alignment.base_motion import MotionRealisation
    from strapdown.analysis.alignment.imu import ideal_increments

    sc = Scenario(R(60.0), heading=0.5, beta0=0.01, lever_arm=[0.5, -0.3, 1.0], sample_rate=10.0, duration=5.0)
    for m in (SineMotion(0.0, 7.0).draw(1, 4, sc.n_samples + 1, sc.dt), sc.motion.draw(1, 4, sc.n_samples + 1, sc.dt)):
        dtheta, dv = ideal_increments(sc, m, compiled=compiled)
        assert dtheta.shape == dv.shape == (4, sc.n_samples, 3) and dtheta.flags.writeable
        for i in range(4):
            single = ideal_increments(sc, MotionRealisation(m.spectrum, m.coefficients[i : i + 1], m.dt), compiled=compiled)
            assert np.array_equal(dtheta[i : i + 1], single[0]) and np.array_equal(dv[i : i + 1], single[1])
    ref = ideal_increments(sc, sc.motion.draw(1, 4, sc.n_samples + 1, sc.dt), compiled=not compiled)
    np.testing.assert_allclose(dtheta, ref[0], rtol=0, atol=1e-15 * np.max(np.abs(ref[0])))
    np.testing.assert_allclose(dv, ref[1], rtol=0, atol=1e-15 * np.max(np.abs(ref[1])))


@pytest.mark.parametrize(
    "model",
    [NarrowbandMotion(R(np.array([0.3, 2.0, 1.0])), 8.0, 0.1), WhiteMotion(R(np.array([0.3, 1.0, 2.0]))), SineMotion(R(np.array([0.3, 2.0, 1.0])), 7.0)],
    ids=["narrowband", "white", "sine"],
)
def test_rocking_at_a_few_instants_is_the_record_there(model):
    """The direct sum at a few sample instants against the evaluation of the whole record: the same sums for
    sinusoids, round-off of the FFT for the Gaussian models."""
    from strapdown.analysis.alignment.base_motion import MotionRealisation

    r = model.draw(np.random.default_rng(5), 3, 301, 0.1)
    idx = np.array([0, 7, 300])
    for realisation in (r, MotionRealisation(r.spectrum, r.coefficients, r.dt)):  # scaled unit draw, and plain
        for whole, points in zip(realisation.evaluate(301, 0.0), realisation.evaluate_points(idx)):
            if model.name == "sine":
                assert np.array_equal(whole[:, idx], points)
            else:
                np.testing.assert_allclose(points, whole[:, idx], rtol=0, atol=1e-13 * np.max(np.abs(whole)))
    with pytest.raises(ValueError, match="`indices`"):
        r.evaluate_points([0.5, 1.0])
    with pytest.raises(ValueError, match="`derivatives` in 0..2"):
        r.evaluate_points([0], derivatives=3)


def test_increments_reproduce_the_true_attitude_and_velocity():
    """An independent navigator (scipy rotations) integrates the record back to the truth."""
    lat = R(50.0)
    sc = Scenario(lat, heading=0.4, beta0=0.01, gamma0=-0.02, motion=SineMotion(R(np.array([1.0, 2.0, 3.0])), 6.0), lever_arm=[0.5, -0.3, 1.0], sample_rate=100.0, duration=20.0)
    rec = simulate_imu(sc, n_trials=2, rng=1)
    ep = preintegrate(rec.dtheta, rec.dv, sc.dt, 10)
    W, g = earth_rate_ned(lat), gravity_ned(lat)
    Wx = np.array([[0, -W[2], W[1]], [W[2], 0, -W[0]], [-W[1], W[0], 0]])
    att = Rotation.from_matrix(attitude_matrix(rec.truth_angles[:, 0]))
    v = rec.truth_velocity[:, 0].copy()
    turn = Rotation.from_rotvec(-W * ep.epoch)
    for j in range(ep.n_epochs):
        C = att.as_matrix()
        v = v + np.einsum("nij,nj->ni", C, ep.velocity[:, j]) - np.einsum("nij,nj->ni", C, ep.moment[:, j]) @ Wx.T + g * ep.epoch - 2 * np.cross(W, v) * ep.epoch
        att = turn * att * Rotation.from_quat(ep.rotation[:, j], scalar_first=True)
    err = (att * Rotation.from_matrix(attitude_matrix(rec.truth_angles[:, -1])).inv()).magnitude()
    assert np.max(err) < 1e-9
    assert np.max(np.abs(v - rec.truth_velocity[:, -1])) < 1e-6  # against 0.05 m/s of lever-arm velocity


def test_quantised_increments_sum_to_within_one_quantum():
    sc = Scenario(R(45.0), duration=10.0, sample_rate=50.0)
    q = R(1.0 / 3600.0)
    ideal = simulate_imu(sc, n_trials=3, rng=5)
    quant = simulate_imu(sc, SensorErrors(gyro_quantum=q), n_trials=3, rng=5)
    assert np.all(np.abs(quant.dtheta.sum(axis=1) - ideal.dtheta.sum(axis=1)) <= q)
    np.testing.assert_allclose(np.round(quant.dtheta / q), quant.dtheta / q, atol=1e-6)


# ---------------------------------------------------------------- the analytic method
@pytest.mark.parametrize("lat_deg", [0.0, 30.0, 60.0, 75.0])
def test_gyro_bias_floor(lat_deg):
    """East gyro bias b alone: mean azimuth error −b/(Ω cos φ) (deterministic: to (b/Ω cos φ)² relative)."""
    lat = R(lat_deg)
    sc = Scenario(lat, duration=60.0, sample_rate=10.0)
    b = B_001
    floor = -b / (EARTH_RATE * math.cos(lat))
    mc = alignment_monte_carlo(sc, SensorErrors(gyro_bias=[0.0, b, 0.0]), method="analytic", n_trials=4, rng=1)
    assert mc.result.mean == pytest.approx(floor, rel=10 * (b / (EARTH_RATE * math.cos(lat))) ** 2 + 1e-12)
    assert mc.theory.gyro_bias == pytest.approx(floor, rel=1e-12)
    # with white gyro noise the interval is real: the floor lies inside it
    noisy = alignment_monte_carlo(sc, SensorErrors(gyro_bias=[0.0, b, 0.0], gyro_noise=R(0.0005) / 60.0), method="analytic", n_trials=256, rng=2)
    assert _inside(noisy.result.mean_ci, floor)
    assert _inside(noisy.result.rms_ci, noisy.theory.rms)


def test_accelerometer_bias_tilt_and_azimuth_terms():
    """East accelerometer bias a: azimuth tan φ · a/g and tilt a/g; north bias: tilt only."""
    lat = R(60.0)
    sc = Scenario(lat, duration=30.0, sample_rate=10.0)
    g = normal_gravity(lat)
    a = 1e-3
    noise = SensorErrors(accel_bias=[0.0, a, 0.0], accel_noise=2e-4, gyro_noise=R(0.0002) / 60.0)
    mc = alignment_monte_carlo(sc, noise, method="analytic", n_trials=256, rng=3)
    assert mc.theory.accel_bias == pytest.approx(math.tan(lat) * a / g, rel=1e-9)
    assert _inside(mc.result.mean_ci, math.tan(lat) * a / g)
    north = alignment_monte_carlo(sc, SensorErrors(accel_bias=[a, 0.0, 0.0]), method="analytic", n_trials=2, rng=3)
    assert abs(north.result.mean) < 1e-9 and north.theory.accel_bias == pytest.approx(0.0, abs=1e-15)
    assert north.tilt_rms[1] == pytest.approx(a / g, rel=1e-6)  # γ̂ − γ = a_N / g


@pytest.mark.parametrize("duration", [20.0, 80.0])
def test_white_noise_against_alignment_time(duration):
    """ARW N and VRW: rms azimuth error √(|G_ω|² N_g² + |G_a|² N_a²)/√T, checked at two T."""
    sc = Scenario(R(45.0), duration=duration, sample_rate=10.0)
    e = SensorErrors(gyro_noise=R(0.003) / 60.0, accel_noise=5e-4)
    mc = alignment_monte_carlo(sc, e, method="analytic", n_trials=400, rng=4)
    assert _inside(mc.result.rms_ci, mc.theory.rms)
    assert mc.theory.rms == pytest.approx(analytic_theory(Scenario(R(45.0), duration=20.0, sample_rate=10.0), e).rms * math.sqrt(20.0 / duration), rel=1e-12)


def test_quantisation_and_scale_factor_terms():
    sc = Scenario(R(40.0), heading=R(30.0), duration=20.0, sample_rate=10.0)
    e = SensorErrors(gyro_quantum=R(2.0 / 3600.0), accel_quantum=1e-3, gyro_noise=R(0.0001) / 60.0)
    mc = alignment_monte_carlo(sc, e, method="analytic", n_trials=400, rng=5)
    assert _inside(mc.result.rms_ci, mc.theory.rms)
    s = SensorErrors(gyro_scale=[300e-6, -200e-6, 0.0])
    mc = alignment_monte_carlo(sc, s, method="analytic", n_trials=2, rng=5)
    # (s_y − s_x) sin 2ψ / 2 for a level block at heading ψ; the simulation to second order in s
    first = (-200e-6 - 300e-6) * math.sin(2 * R(30.0)) / 2
    assert mc.theory.gyro_scale == pytest.approx(first, rel=1e-9)
    assert mc.result.mean == pytest.approx(first, rel=1e-3)


def test_paper_formula_is_exact_at_zero_heading_only():
    for heading, exact in ((0.0, True), (R(90.0), False)):
        sc = Scenario(R(60.0), heading=heading, beta0=R(1.0), gamma0=R(-0.5), duration=5.0, sample_rate=10.0)
        e = analytic_alignment(simulate_imu(sc, n_trials=1, rng=0), formula="paper").heading_error[0]
        assert (abs(e) < 1e-12) == exact
    # at 90° the error is of the order of tan φ · β0 (the correction σ belongs to zero heading)
    assert 0.5 < abs(e) / (math.tan(R(60.0)) * R(1.0)) < 2.0


def test_paper_tilt_channel_is_the_special_case():
    """Gyros at the stable attitude, ideal sensors: the analytic error is σ(β̂, γ̂) − σ(β0, γ0) of (16), and
    its Monte Carlo rms matches the paper's tilt-channel theory with the variance of the mean."""
    lat, b0, g0 = R(70.0), R(2.0), R(-1.0)
    motion = NarrowbandMotion(R(np.array([0.0, 1.0, 1.0])) * math.sqrt(2.0), 8.0, 0.1)
    sc = Scenario(lat, beta0=b0, gamma0=g0, motion=motion, sample_rate=10.0, duration=30.0, rocking_in_gyros=False)
    rec = simulate_imu(sc, n_trials=50, rng=6)
    est = analytic_alignment(rec, formula="paper")
    tilts = np.stack([est.beta - b0, est.gamma - g0])
    np.testing.assert_allclose(est.heading_error, azimuth_error(tilts[0], tilts[1], latitude=lat, beta0=b0, gamma0=g0), atol=1e-12)
    mc = alignment_monte_carlo(sc, method="analytic", n_trials=800, rng=7, options=AlignmentOptions(formula="paper"))
    sd = np.sqrt(mean_variance(motion, sc.n_samples * sc.dt, sc.dt))  # standard deviation of the continuous mean per axis
    th = second_order_theory(lat, b0, g0, sd[1], sd[2])
    assert _inside(mc.result.rms_ci, th.rms)
    assert mc.theory.rocking == pytest.approx(th.rms_first_order, rel=1e-9)


@pytest.mark.parametrize("motion", [SineMotion(R(np.array([0.005, 0.01, 0.01])), 7.0), NarrowbandMotion(R(np.array([0.005, 0.01, 0.01])), 8.0, 0.1)])
def test_rocking_in_the_gyros_against_theory(motion):
    sc = Scenario(R(50.0), heading=0.4, beta0=0.01, gamma0=-0.02, motion=motion, lever_arm=[0.3, 0.2, 1.0], sample_rate=10.0, duration=60.0)
    mc = alignment_monte_carlo(sc, method="analytic", n_trials=600, rng=8)
    assert _inside(mc.result.rms_ci, mc.theory.rocking)
    tilt_only = analytic_theory(Scenario(R(50.0), heading=0.4, beta0=0.01, gamma0=-0.02, motion=motion, lever_arm=[0.3, 0.2, 1.0], sample_rate=10.0, duration=60.0, rocking_in_gyros=False))
    assert mc.theory.rocking > 1e3 * tilt_only.rocking  # orders of magnitude above the tilt channel


# ---------------------------------------------------------------- inertial frame
def test_wahba_rotation_agrees_with_scipy():
    rng = np.random.default_rng(0)
    b = rng.normal(size=(3, 6, 3))
    r = b @ Rotation.from_rotvec([0.2, -0.1, 0.4]).as_matrix().T + 1e-3 * rng.normal(size=(3, 6, 3))
    C = wahba_rotation(r, b)
    for k in range(3):
        ref, _ = Rotation.align_vectors(r[k], b[k])
        np.testing.assert_allclose(C[k], ref.as_matrix(), atol=1e-12)


def test_inertial_alignment_integrates_the_rocking_out():
    sc = Scenario(R(50.0), heading=2.0, motion=SineMotion(R(np.array([0.5, 1.0, 1.5])), 7.0), sample_rate=20.0, duration=60.0)
    est = inertial_alignment(simulate_imu(sc, n_trials=4, rng=9))
    assert np.max(np.abs(est.heading_error)) < 1e-6  # against degrees for the analytic method
    b = B_001
    mc = alignment_monte_carlo(Scenario(R(60.0), duration=60.0, sample_rate=10.0), SensorErrors(gyro_bias=[0.0, b, 0.0]), method="inertial", n_trials=2, rng=1)
    assert mc.result.mean == pytest.approx(mc.bias_floor[0], rel=1e-4)


# ---------------------------------------------------------------- Kalman fine alignment
def _kalman_options(gb, ab, **kw):
    from strapdown.analysis.alignment.fine import FilterTuning

    return AlignmentOptions(tuning=FilterTuning(epoch=0.2, prior_heading=R(0.5), gyro_bias=gb, accel_bias=ab, **kw))


def test_kalman_is_consistent_when_the_truth_follows_its_prior():
    gb, ab = B_001, 5e-4
    sc = Scenario(R(50.0), heading=0.5, duration=60.0, sample_rate=10.0)
    e = SensorErrors(gyro_bias_sigma=gb, accel_bias_sigma=ab, gyro_noise=R(0.002) / 60.0, accel_noise=1e-4)
    mc = alignment_monte_carlo(sc, e, method="kalman", n_trials=128, rng=10, options=_kalman_options(gb, ab, gyro_noise=e.gyro_noise, accel_noise=e.accel_noise))
    k = mc.kalman
    lo, hi = k.nees_band
    # 8 checked epochs at 95 % each, the bands widened by 10 %
    assert np.all((k.nees > 0.9 * lo) & (k.nees < 1.1 * hi)), k.nees
    lo, hi = k.nis_band
    assert np.all((k.nis > 0.9 * lo) & (k.nis < 1.1 * hi)), k.nis
    assert _inside(mc.result.rms_ci, k.heading_sigma)


@pytest.mark.parametrize("shaping", [True, False], ids=["rocking-states", "no-rocking-states"])
@pytest.mark.parametrize("lever_arm_known", [True, False], ids=["lever-arm-known", "lever-arm-as-noise"])
def test_compiled_filter_loop_equals_the_numpy_reference(shaping, lever_arm_known):
    """The compiled epoch loop against the numpy loop: equal to the round-off the closed loop amplifies.

    The filter feeds its estimates back every epoch, and the NEES weighs the
    errors by an inverse covariance with tiny entries: a change of one unit in
    the last place of the velocity increments moves the NEES of the numpy loop
    itself by about 6e-11 relative, so the two loops agree to 1e-9 and not to 1e-15."""
    from dataclasses import replace

    from strapdown.analysis.alignment.fine import Disturbance, fine_alignment, simulate_epoch_record
    from strapdown.analysis.alignment.studies import kalman_options

    sc = Scenario(R(60.0), heading=R(30.0), motion=NarrowbandMotion(R(np.array([0.0, 2.0, 2.0])), 10.0, 0.1), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=40.0)
    e = SensorErrors(gyro_bias_sigma=B_001, accel_bias_sigma=1e-4, gyro_noise=R(0.002) / 60.0, accel_noise=1e-4)
    tuning = kalman_options(sc, e, disturbance=Disturbance("shaping", 0.01) if shaping else Disturbance("none")).tuning
    tuning = replace(tuning, lever_arm_known=lever_arm_known)
    rec = simulate_epoch_record(sc, e, int(round(tuning.epoch * sc.sample_rate)), n_trials=6, rng=4)
    a, b = fine_alignment(rec, tuning, rng=5), fine_alignment(rec, tuning, rng=5, compiled=False)
    assert a.nees.shape == b.nees.shape == (6, rec.increments.n_epochs)
    for name in ("nees", "nis", "heading_error"):
        x, y = getattr(a, name), getattr(b, name)
        np.testing.assert_allclose(x, y, rtol=0, atol=1e-9 * np.max(np.abs(y)), err_msg=name)
    np.testing.assert_allclose(a.estimate.heading_error, b.estimate.heading_error, rtol=0, atol=1e-11)


def test_fine_alignment_with_its_model_given_is_the_same_run():
    from strapdown.analysis.alignment.fine import filter_model, fine_alignment, simulate_epoch_record
    from strapdown.analysis.alignment.studies import kalman_options

    sc = Scenario(R(60.0), heading=R(30.0), sample_rate=10.0, duration=20.0)
    e = SensorErrors(gyro_bias_sigma=B_001, accel_bias_sigma=1e-4, gyro_noise=R(0.002) / 60.0)
    tuning = kalman_options(sc, e).tuning
    model = filter_model(sc, tuning)
    rec = simulate_epoch_record(sc, e, model.samples_per_epoch, n_trials=3, rng=4)
    a, b = fine_alignment(rec, tuning, rng=5), fine_alignment(rec, tuning, rng=5, model=model)
    assert np.array_equal(a.nees, b.nees) and np.array_equal(a.heading_error, b.heading_error)
    with pytest.raises(TypeError, match="`model` to be a FineAlignmentModel"):
        fine_alignment(rec, tuning, model=model.F)


def test_explicit_draws_give_the_trials_of_the_stream_at_any_amplitude():
    """Common random numbers passed explicitly: a run on drawn numbers equals the run from the stream, bit for bit,
    in the drawn scenario and in one that differs by the rocking amplitudes."""
    from dataclasses import replace

    from strapdown.analysis.alignment import fine as fa
    from strapdown.analysis.alignment.monte_carlo import alignment_draws
    from strapdown.analysis.alignment.studies import kalman_options

    sc = Scenario(R(60.0), heading=R(30.0), motion=NarrowbandMotion(R(np.array([0.0, 1.0, 1.0])), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=10.0)
    e = SensorErrors(gyro_bias_sigma=B_001, gyro_noise=R(0.002) / 60.0, accel_quantum=1e-4)
    a = fa.simulate_epoch_record(sc, e, 5, n_trials=5, rng=np.random.default_rng(8), chunk=2)
    b = fa.simulate_epoch_record(sc, e, 5, draws=fa.draw_epoch_record(sc, e, n_trials=5, rng=np.random.default_rng(8), chunk=2))
    for name in ("rotation", "velocity", "moment"):
        assert np.array_equal(getattr(b.increments, name), getattr(a.increments, name))
    assert np.array_equal(b.truth_velocity, a.truth_velocity)
    with pytest.raises(ValueError, match="accel_start"):  # numbers drawn for other errors
        fa.simulate_epoch_record(sc, e, 5, draws=fa.draw_epoch_record(sc, replace(e, accel_quantum=0.0), n_trials=2, rng=1))
    opts = kalman_options(sc, e)
    sc2 = replace(sc, motion=replace(sc.motion, amplitude=3.0 * sc.motion.amplitude))
    for method, options in (("analytic", None), ("kalman", opts)):
        draws = alignment_draws(sc, e, method=method, n_trials=6, rng=3, options=options, trials_per_block=4)
        for scenario in (sc, sc2):
            from_stream = alignment_monte_carlo(scenario, e, method=method, n_trials=6, rng=3, options=options, trials_per_block=4)
            from_draws = alignment_monte_carlo(scenario, e, method=method, n_trials=6, options=options, draws=draws)
            assert from_draws.result.rms == from_stream.result.rms and from_draws.result.aux_mean == from_stream.result.aux_mean
    with pytest.raises(ValueError, match="amplitudes only"):
        alignment_monte_carlo(replace(sc, motion=replace(sc.motion, period=5.0)), e, method="analytic", n_trials=6, draws=alignment_draws(sc, e, method="analytic", n_trials=6, rng=3))


@pytest.mark.parametrize("motion", [NarrowbandMotion(R(np.array([0.0, 1.0, 1.0])), 8.0, 0.1), SineMotion(R(np.array([0.5, 1.0, 1.0])), 8.0)], ids=["narrowband", "sine"])
def test_kept_noise_terms_and_truth_points_equal_the_products_made_again(motion):
    """The noise terms and the truth at the ends kept with the draws give, at every amplitude and at every call,
    the values made from the numbers again, bit for bit; another noise density makes them anew."""
    from dataclasses import replace

    from strapdown.analysis.alignment.base_motion import MotionRealisation
    from strapdown.analysis.alignment.imu import draw_imu

    sc = Scenario(R(60.0), heading=R(30.0), motion=motion, lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=10.0)
    e = SensorErrors(gyro_bias_sigma=B_001, gyro_noise=R(0.002) / 60.0, accel_noise=1e-4)
    draws = draw_imu(sc, e, n_trials=4, rng=5)
    N, dt = sc.n_samples, sc.dt
    for sensor, density, numbers in (("gyro", e.gyro_noise, draws.gyro_noise), ("accel", e.accel_noise, draws.accel_noise)):
        term = draws.noise_term(sensor, density * math.sqrt(dt))
        assert np.array_equal(term, (density * math.sqrt(dt)) * numbers) and not term.flags.writeable
        assert draws.noise_term(sensor, density * math.sqrt(dt)) is term  # kept
        other = draws.noise_term(sensor, 2.0 * density * math.sqrt(dt))
        assert np.array_equal(other, (2.0 * density * math.sqrt(dt)) * numbers)
    idx = np.array([0, N])
    for k in (0.5, 1.0, 3.0):
        sc_k = replace(sc, motion=replace(motion, amplitude=k * motion.amplitude))
        scaled = draws.rocking.rescaled(sc_k.motion)
        # the reference: the unit coefficients evaluated afresh, then scaled per axis
        unit = MotionRealisation(draws.rocking.unit.spectrum, draws.rocking.unit.coefficients, draws.rocking.dt)
        fresh = unit.evaluate_points(idx, derivatives=1)
        for _ in range(2):  # made, then kept
            for got, ref in zip(scaled.evaluate_points(idx, derivatives=1), fresh):
                assert np.array_equal(got, scaled.scale * ref)
        a, b = simulate_imu(sc_k, e, draws=draws), simulate_imu(sc_k, e, draws=draws)
        assert np.array_equal(a.dtheta, b.dtheta) and np.array_equal(a.dv, b.dv) and np.array_equal(a.truth_angles, b.truth_angles)
    ideal = simulate_imu(sc_k, SensorErrors(gyro_bias_sigma=B_001), draws=draw_imu(sc, SensorErrors(gyro_bias_sigma=B_001), n_trials=4, rng=5))
    noise = simulate_imu(sc_k, e, draws=draws).dtheta - ideal.dtheta
    assert np.allclose(noise, (e.gyro_noise * math.sqrt(dt)) * draws.gyro_noise, rtol=0, atol=1e-15)  # the noise is the one added


@pytest.mark.parametrize("compiled", [True, False], ids=["compiled", "numpy"])
def test_unscored_filter_gives_the_same_estimates_without_nees_and_nis(compiled):
    from strapdown.analysis.alignment import kernels as k
    from strapdown.analysis.alignment.fine import fine_alignment, simulate_epoch_record
    from strapdown.analysis.alignment.studies import kalman_options

    sc = Scenario(R(60.0), heading=R(30.0), motion=NarrowbandMotion(R(np.array([0.0, 2.0, 2.0])), 10.0, 0.1), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=20.0)
    e = SensorErrors(gyro_bias_sigma=B_001, accel_bias_sigma=1e-4, gyro_noise=R(0.002) / 60.0, accel_noise=1e-4)
    tuning = kalman_options(sc, e).tuning
    rec = simulate_epoch_record(sc, e, 5, n_trials=4, rng=4)
    ends = simulate_epoch_record(sc, e, 5, n_trials=4, rng=4, truth="ends")  # the same trials, the truth at the ends only
    assert np.isnan(ends.truth_angles[:, 1:-1]).all() and np.array_equal(ends.increments.velocity, rec.increments.velocity)
    np.testing.assert_allclose(ends.truth_angles[:, [0, -1]], rec.truth_angles[:, [0, -1]], rtol=0, atol=1e-15)  # summed, not by FFT
    a = fine_alignment(rec, tuning, rng=5, compiled=compiled)
    for r in (rec, ends):
        b = fine_alignment(r, tuning, rng=5, score=False, compiled=compiled)
        np.testing.assert_allclose(b.estimate.heading_error, a.estimate.heading_error, rtol=0, atol=1e-14)
        np.testing.assert_allclose(b.heading_error[:, -1], a.heading_error[:, -1], rtol=0, atol=1e-14)
        assert np.all(np.isnan(b.heading_error[:, :-1])) and np.all(np.isnan(b.nees)) and np.all(np.isnan(b.nis))
    assert np.all(np.isfinite(a.nees))
    with pytest.raises(ValueError, match="truth at every epoch to score"):
        fine_alignment(ends, tuning, rng=5)
    with pytest.raises(ValueError, match="`truth` in"):
        simulate_epoch_record(sc, e, 5, n_trials=4, rng=4, truth="start")
    from strapdown.analysis.alignment.fine import epoch_record

    with pytest.raises(ValueError, match="truth at its start and at the end of its last epoch"):
        epoch_record(simulate_imu(sc, e, n_trials=2, rng=1, truth_stride=5), 5, truth="ends")
    with pytest.raises(ValueError, match="truth every 5 samples"):
        epoch_record(simulate_imu(sc, e, n_trials=2, rng=1), 5)
    with pytest.raises(ValueError, match="both given"):
        z = np.zeros
        k.fine_alignment_loop(
            z((2, 3, 3)), z((2, 3)), z((2, 4, 3, 3)), z((2, 4, 3)), z((2, 4, 3)), z((2, 4, 3)), z((2, 4, 3)), z((2, 5, 3, 3)), z((2, 5, 3)), z((2, 5, 3)),
            z((2, 5, 3)), z((2, 5, 0)), np.eye(3), z((3, 3)), z(3), 0.5, z(3), False, z((0, 0)), z((3, 12)), z((4, 12, 3)), z((4, 12, 12)), None,
        )  # fmt: skip


def test_kalman_bias_response_matches_its_linear_theory():
    b = B_001
    sc = Scenario(R(60.0), duration=60.0, sample_rate=10.0)
    e = SensorErrors(gyro_bias=[0.0, b, 0.0], gyro_noise=R(0.0005) / 60.0)
    mc = alignment_monte_carlo(sc, e, method="kalman", n_trials=128, rng=11, options=_kalman_options(b, 1e-4, gyro_noise=e.gyro_noise))
    assert _inside(mc.result.mean_ci, mc.kalman_theory.gyro_bias)


def test_alignment_statistics_do_not_depend_on_chunking():
    sc = Scenario(R(45.0), motion=SineMotion(R(0.01), 5.0), duration=10.0, sample_rate=10.0)
    kernel = AlignmentKernel(sc, SensorErrors(gyro_noise=1e-6), "analytic", AlignmentOptions())
    a = montecarlo.run(kernel, 40, rng=3, trials_per_block=8, blocks_per_chunk=1)
    b = montecarlo.run(kernel, 40, rng=3, trials_per_block=8, blocks_per_chunk=5)
    assert (a.mean, a.mse, a.rms_ci) == (b.mean, b.mse, b.rms_ci)


# ---------------------------------------------------------------- the designer's answer
@pytest.mark.parametrize("power", [1.0, 2.0, 3.5, 6.0])
@pytest.mark.parametrize("root", [R(0.02), R(3.0), R(15.0)])
@pytest.mark.parametrize("start", [R(1.0), "near"])
def test_amplitude_search_finds_the_root_in_few_evaluations(power, root, start):
    """The root search of the admissible amplitude on fn² = floor² + (u a)^p: within rtol/2 of the root, in few runs,
    fewer from the previous frequency's root."""
    from strapdown.analysis.alignment.design import _root

    budget, floor, rtol, cap = 1.0, 0.45, 0.1, R(20.0)
    u = math.sqrt(budget**2 - floor**2) ** (2.0 / power) / root
    calls = []

    def fn(a):
        calls.append(a)
        return math.sqrt(floor**2 + (u * a) ** power)

    a, (lo, hi) = _root(fn, budget, 1.3 * root if start == "near" else start, cap, rtol)
    assert abs(math.log(a / root)) <= 0.5 * math.log(1.0 + rtol)
    assert fn(lo) <= budget < fn(hi) and lo <= root <= hi
    assert len(set(calls)) <= (5 if start == "near" else 6), calls  # fn(0), then at most 4 or 5 Monte Carlo runs


@pytest.mark.parametrize("seed", range(6))
def test_amplitude_search_brackets_a_rough_function(seed):
    """On an increasing function with steps and kinks (an order statistic of few trials), where the power-law steps
    mispredict, the bisection safeguard still closes the bracket to log(1 + rtol)/2 about a crossing of the budget."""
    from strapdown.analysis.alignment.design import _root

    rng = np.random.default_rng(seed)
    e0, v = rng.normal(0.0, 0.3, 15), rng.normal(0.0, 1.0, 15)
    budget, rtol, cap = 1.0, 0.1, 50.0

    calls = []

    def fn(a):  # the 90 % order statistic of |e0 + a v| over 15 trials: continuous, piecewise linear, rough
        calls.append(a)
        return float(np.quantile(np.abs(e0 + a * v), 0.9, method="inverted_cdf"))

    a, (lo, hi) = _root(fn, budget, 0.01, cap, rtol)
    assert 0.0 < lo < hi and math.log(hi / lo) <= 0.5 * math.log(1.0 + rtol) + 1e-12
    assert fn(lo) <= budget < fn(hi) and a in (lo, hi)
    assert len(set(calls)) <= 16, calls  # from 0.01 (two decades below the root): halvings at worst every other step


@pytest.mark.parametrize("n_steps", [2, 3, 300])
def test_coverage_study_samples_xi_as_the_model_does(n_steps):
    """The coverage study filters only ξ's rows of the narrow-band model's draws: the model's own ξ, to the bit."""
    from strapdown.analysis.alignment.studies import _xi_sample
    from strapdown.analysis.gyrocompass.rocking import NarrowbandRocking

    m = NarrowbandRocking(0.02, 0.01, 8.0, 0.1)
    xi, _ = m.sample(np.random.default_rng(5), 40, n_steps, 0.1)
    assert np.array_equal(_xi_sample(m, np.random.default_rng(5), 40, n_steps, 0.1), xi)


def test_amplitude_search_ends():
    from strapdown.analysis.alignment.design import _root

    assert _root(lambda a: 2.0, 1.0, 0.1, 1.0, 0.1) == (0.0, (0.0, 0.0))  # the sensors alone exceed the budget
    assert _root(lambda a: 0.5 + 0.1 * a, 1.0, 0.1, 1.0, 0.1) == (1.0, (1.0, 1.0))  # the cap is admissible
    assert _root(lambda a: 0.5 + 1e15 * a, 1.0, 0.1, 1.0, 0.1)[0] < 1e-9  # below any resolution: 0


def test_admissible_rocking_meets_the_budget():
    """Analytic: the first-order rms at the admissible amplitude is the budget; inertial: the root search's own
    Monte Carlo at its root is within the budget and one bracket step above it is not."""
    from dataclasses import replace

    from strapdown.analysis.alignment.design import admissible_rocking

    sc = Scenario(R(60.0), heading=R(30.0), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=60.0)
    e = SensorErrors(gyro_noise=R(0.002) / 60.0)
    budget = R(0.2)
    d = admissible_rocking("analytic", budget, sc, [0.1], e, rocking="narrowband")
    th = analytic_theory(replace(sc, motion=NarrowbandMotion(d.amplitude[0] * d.pattern, 10.0, 0.1)), e)
    assert th.rms == pytest.approx(budget, rel=1e-9)
    assert d.amplitude_percentile[0] < d.amplitude[0]  # 95 % of a Gaussian error needs 1.96 rms
    env = admissible_rocking("analytic", budget, sc, [0.1, 0.15], e, rocking="sine")
    exact = admissible_rocking("analytic", budget, sc, [0.1, 0.15], e, rocking="sine", envelope=False)
    assert np.all(env.amplitude <= exact.amplitude * (1 + 1e-12))  # the envelope is the worst case
    mc = admissible_rocking("inertial", budget, sc, [0.1], e, rocking="sine", n_trials=16, rtol=0.2, rng=5)
    assert 0.0 < mc.amplitude[0] < mc.max_amplitude
    assert mc.amplitude_ci[0, 0] <= mc.amplitude[0] <= mc.amplitude_ci[0, 1]


@pytest.mark.parametrize("sines", [[], [0.7], [1.0, 0.4], [0.5, 0.3, 0.2]], ids=["gaussian", "one-sine", "two-sines", "three-sines"])
@pytest.mark.parametrize("mean", [0.0, 0.2])
def test_abs_error_probability_is_the_phase_grid_mean_and_inverts_the_percentile(sines, mean):
    """The half grid of the phases gives the mean over the whole grid (every sine value twice there); the
    percentile of abs_error_quantile is where the probability reaches the level."""
    from scipy.special import ndtr

    from strapdown.analysis.gyrocompass.error_distribution import _phase_values, abs_error_probability, abs_error_quantile

    s, x = 0.3, 0.8
    m = _phase_values(np.array(sines, dtype=float)) + mean
    full = float(np.mean(ndtr((x - m) / s) - ndtr((-x - m) / s)))
    assert abs_error_probability(sines, s, x, mean=mean) == pytest.approx(full, rel=1e-13, abs=1e-15)
    q = abs_error_quantile(sines, s, 0.95, mean=mean)
    assert abs_error_probability(sines, s, q.value, mean=mean) == pytest.approx(0.95, abs=1e-8)
    assert abs_error_probability(sines, s, 0.0, mean=mean) == 0.0


def test_abs_error_probability_refuses_bad_input():
    from strapdown.analysis.gyrocompass.error_distribution import abs_error_probability

    with pytest.raises(ValueError, match="`gaussian_sigma`"):
        abs_error_probability([1.0], 0.0, 1.0)
    with pytest.raises(ValueError, match="`x`"):
        abs_error_probability([1.0], 0.1, -1.0)
    with pytest.raises(ValueError, match="at most 3 sinusoidal residues"):
        abs_error_probability([1.0, 1.0, 1.0, 1.0], 0.1, 1.0)


@pytest.mark.parametrize("rocking", ["sine", "narrowband"])
def test_analytic_percentile_amplitude_puts_the_percentile_on_the_budget(rocking):
    """The admissible amplitude by the percentile (analytic method, a root search on the probability) against the
    percentile of abs_error_quantile at that amplitude, and the search on the percentile itself."""
    from dataclasses import replace

    from scipy.optimize import brentq

    from strapdown.analysis.alignment.design import _analytic_percentile, _motion
    from strapdown.analysis.alignment.studies import DESIGN_SCENARIO, NAVIGATION_GRADE
    from strapdown.analysis.gyrocompass.error_distribution import abs_error_quantile

    budget, cap = R(0.3), R(20.0)
    th = analytic_theory(replace(DESIGN_SCENARIO, motion=_motion(rocking, np.array([0.0, 1.0, 1.0]), 0.1, 0.1)), NAVIGATION_GRADE, envelope=rocking == "sine")
    sines = th.rocking_sine_amplitudes if rocking == "sine" else np.zeros(0)

    def q(a):
        s = th.sensor_sigma if rocking == "sine" else math.hypot(th.sensor_sigma, a * th.rocking)
        return abs_error_quantile(a * sines, s, 0.95, mean=th.mean).value - budget

    a = _analytic_percentile(th, budget, 0.95, cap, rocking)
    assert 0.0 < a < cap and abs(q(a)) < 1e-7 * budget
    assert a == pytest.approx(brentq(q, 0.0, cap, xtol=1e-12 * cap, rtol=1e-10), rel=1e-7)


def test_compiled_loops_refuse_wrong_shapes_and_outputs():
    """The loops index without bounds checks: every shape is checked first, with the argument named."""
    from strapdown.analysis.alignment import kernels as k
    from strapdown.analysis.alignment.imu import ideal_increments

    a, out = np.zeros((2, 5, 3)), np.zeros((2, 5, 3))
    v = np.zeros(3)
    with pytest.raises(ValueError, match=r"`rates` with shape \(2, 5, 3\)"):
        k.accumulate_ideal_increments(a, np.zeros((2, 4, 3)), None, v, v, v, v, v, True, 0.1, out, out.copy())
    with pytest.raises(TypeError, match="`dv` to be a writable C-contiguous float64"):
        k.accumulate_ideal_increments(a, a, None, v, v, v, v, v, True, 0.1, out, np.zeros((2, 5, 3), dtype=np.float32))
    with pytest.raises(ValueError, match="`gravity`"):
        k.accumulate_ideal_increments(a, a, None, v, v, [0.0, math.nan, 0.0], v, v, True, 0.1, out, out.copy())
    with pytest.raises(ValueError, match="at least samples_per_epoch × n_epochs = 6"):
        k.preintegrate_loop(a, a, 0.1, 3, 2)
    with pytest.raises(ValueError, match="`start` with shape"):
        k.chain_loop(np.ones((3, 4)), np.zeros((2, 4, 4)))
    with pytest.raises(ValueError, match=r"`gains` with shape \(4, 12, 3\)"):
        z = np.zeros
        k.fine_alignment_loop(
            z((2, 3, 3)), z((2, 3)), z((2, 4, 3, 3)), z((2, 4, 3)), z((2, 4, 3)), z((2, 4, 3)), z((2, 4, 3)), z((2, 5, 3, 3)), z((2, 5, 3)), z((2, 5, 3)),
            z((2, 5, 3)), z((2, 5, 0)), np.eye(3), z((3, 3)), z(3), 0.5, z(3), False, z((0, 0)), z((3, 12)), z((4, 12, 2)), z((4, 12, 12)), z((4, 3, 3)),
        )  # fmt: skip
    with pytest.raises(TypeError, match="`motion` to be a MotionRealisation"):
        ideal_increments(Scenario(R(45.0), duration=1.0), np.zeros((1, 10, 3)))


def test_noise_terms_refuse_another_sensor_a_missing_noise_and_a_bad_factor():
    from strapdown.analysis.alignment.imu import draw_imu

    sc = Scenario(R(60.0), sample_rate=10.0, duration=2.0)
    draws = draw_imu(sc, SensorErrors(gyro_noise=R(0.002) / 60.0), n_trials=2, rng=1)
    assert draws.noise_term("gyro", 1e-4).shape == (2, sc.n_samples, 3)
    with pytest.raises(ValueError, match="`sensor` 'gyro' or 'accel', got 'mag'"):
        draws.noise_term("mag", 1e-4)
    with pytest.raises(ValueError, match="accel noise numbers"):
        draws.noise_term("accel", 1e-4)  # drawn without accelerometer noise
    with pytest.raises(ValueError, match="`factor` to be finite"):
        draws.noise_term("gyro", math.nan)
