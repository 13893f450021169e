"""Multistage corrected attitude system, Plotnikov (1999), sections 1, 2 and 5."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.multistage.sensors import SensorErrors
from strapdown.analysis.multistage.ship_angles import angles_to_quat, quat_to_angles
from strapdown.analysis.multistage.stages import Stage, accelerometer_quaternion, plotnikov_1999_stages, run_stage, simulate, tilt_quaternion
from strapdown.analysis.multistage.trajectory import Scenario, sample
from strapdown.derivations.multistage.published import PRINTED_GAINS


@given(st.floats(-3, 3), st.floats(-1.5, 1.5), st.floats(-3, 3))
@settings(max_examples=60, deadline=None)
def test_krylov_round_trip(psi, theta, gamma):
    q = angles_to_quat(psi, theta, gamma)
    np.testing.assert_allclose(quat_to_angles(q), [psi, theta, gamma], atol=1e-7)


def test_krylov_is_yaw_pitch_roll_product():
    """(3.6) equals q2(ψ)∘q3(θ)∘q1(γ) built with the package product."""
    psi, th, ga = 0.3, -0.2, 0.7
    q = quat.multiply(quat.multiply(quat.rotvec_to_quat([0, psi, 0]), quat.rotvec_to_quat([0, 0, th])), quat.rotvec_to_quat([ga, 0, 0]))
    np.testing.assert_allclose(angles_to_quat(psi, th, ga), q, atol=1e-15)


@pytest.mark.parametrize("shape", [(6000, 3), (3000, 3, 3), (5000,)])
def test_krylov_quaternion_of_large_arrays_in_blocks_is_the_one_pass_value(monkeypatch, shape):
    """Large arrays form the products of (3.6) block by block: the same bits as in one pass."""
    from strapdown.analysis.core import blocks

    rng = np.random.default_rng(3)
    angles = [3.0 * rng.standard_normal(shape) for _ in range(3)]
    blocked = angles_to_quat(*angles)
    monkeypatch.setattr(blocks, "BLOCK", 10**9)  # one pass
    assert blocked.tobytes() == angles_to_quat(*angles).tobytes()


def test_accelerometer_quaternions_small_tilt():
    mu = angles_to_quat(0.0, 0.01, -0.02)
    f = quat.rotate(quat.conjugate(mu), [0.0, 9.81, 0.0])
    m = accelerometer_quaternion(f, 9.81)
    np.testing.assert_allclose(m[[1, 3]], [-0.02, 0.01], atol=1e-5)  # whole angles: c = 2
    np.testing.assert_allclose(tilt_quaternion(f), mu, atol=1e-14)  # exact for ψ = 0


def test_sensor_model():
    sc = Scenario(duration=20.0, sensors=SensorErrors(gyro_drift=(1e-3, 0, 0)))
    d = sample(sc, 0.5)
    # Body fixed to the Earth with x1 north: Earth rate Ω cos φ + drift on x1.
    np.testing.assert_allclose(d.gyro[:, 0] / 0.5, sc.earth_rate * np.cos(sc.latitude) + 1e-3, rtol=1e-6)
    noisy = Scenario(duration=20.0, sensors=SensorErrors(gyro_noise=1e-4, accel_noise=1e-3))
    a, b = sample(noisy, 0.5, rng=3), sample(noisy, 0.5, rng=3)
    np.testing.assert_array_equal(a.gyro, b.gyro)
    assert not np.array_equal(a.gyro, sample(noisy, 0.5, rng=4).gyro)


def test_external_reference_converges():
    """First variant (c = 1): ν → μ from a perturbed start while the body turns."""
    h, n = 0.5, 8000
    w = np.array([0.0, 0.02, 0.01])
    t = np.arange(n + 1) * h
    mu = quat.rotvec_to_quat(t[:, None] * w)
    dq = np.broadcast_to(quat.rotvec_to_quat(w * h), (n, 4))
    nu, _ = run_stage(Stage.constant(0.05, 1e-4, "external", rho=0.5), h, dq, reference=mu, initial=[0.95, 0.1, -0.05, 0.2])
    assert np.abs(nu[0] - mu[0]).max() > 0.1
    # 4000 s at the slowest rate 1.69e-3 1/s (exact_rate): a factor e^-6.8 ≈ 1e-3.
    assert np.abs(nu[-1] - mu[-1]).max() < 1e-4


def test_static_tilt_levels():
    sc = Scenario(
        duration=3000.0,
        rocking_start=1e-9,
        rocking_frequency=0.0,
        rocking_phase=(0, np.pi / 2, 0),
        rocking_amplitude=(0, 0.1, 0),
        rocking_decay=0,
        rocking_onset=0,
        accel=0,
        earth_rate=0,
        sensors=SensorErrors(),
    )
    def est(stage):
        return simulate(sc, (stage,), step=0.5)

    good = est(Stage.constant(*PRINTED_GAINS.stage1, "tilt"))
    assert abs(good.errors[0, -1, 1]) < 1e-6
    half = est(Stage.constant(*PRINTED_GAINS.stage1, "tilt", c=2.0))
    assert half.errors[0, -1, 1] + 0.1 == pytest.approx(0.05, abs=1e-4)  # c = 2 with half angles: half the tilt
    pure = est(Stage.constant(*PRINTED_GAINS.stage1, "pure"))
    assert pure.errors[0, -1, 1] + 0.1 == pytest.approx(2 * np.arcsin(np.sin(0.1) / 2), abs=1e-6)


@pytest.fixture(scope="module")
def paper_run():
    return simulate(Scenario(), step=0.1)


def test_two_stages_cut_tilt_error_under_acceleration(paper_run):
    """Done-when: with Schuler tuning the two-stage tilt error is >= 5x smaller than stage 1's."""
    tilt = paper_run.tilt()
    assert tilt[0].max() > 0.05  # the 20 m/s² manoeuvre tilts stage 1 by ~0.1 rad
    assert tilt[0].max() >= 5 * tilt[1].max()
    sel = (paper_run.time >= 1200) & (paper_run.time <= 1800)
    assert tilt[0, sel].max() >= 20 * tilt[1, sel].max()


def test_schuler_cancellation_without_earth_rotation():
    r = simulate(Scenario(earth_rate=0.0, sensors=SensorErrors()), step=0.2)
    assert r.tilt()[1].max() < 2e-4 < 0.05 < r.tilt()[0].max()


def test_printed_stages():
    s1, s2 = plotnikov_1999_stages()
    assert s2.schedule[0][1:] == PRINTED_GAINS.stage2_before
    assert s2.schedule[1] == (PRINTED_GAINS.switch_time, 0.0, 9.81 / 6.371e6)
    assert s1.schedule[0][1:] == PRINTED_GAINS.stage1
    assert s1.effective_gains[0][1:] == tuple(g / 2 for g in PRINTED_GAINS.stage1)  # c = 1 on half angles
    assert s1.components == (1, 3) and s2.switch == "carry"


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(schedule=((0.0, np.nan, 1e-4),)), "finite"),
        (dict(schedule=((0.0, 0.01, np.inf),)), "finite"),
        (dict(schedule=((0.0, "k", 1e-4),)), "real number"),
        (dict(schedule=((5.0, 0.01, 1e-4),)), "t_start"),
        (dict(schedule=()), "at least one"),
        (dict(schedule=((0.0, 0.01, 1e-4),), reference="gps"), "reference"),
        (dict(schedule=((0.0, 0.01, 1e-4),), rho=-1.0), "rho"),
        (dict(schedule=((0.0, 0.01, 1e-4),), reference="pure", components=(0, 1, 3)), "no components 0 and 2"),
        (dict(schedule=((0.0, 0.01, 1e-4),), reference="tilt", components=(4,)), "components"),
        (dict(schedule=((0.0, 0.01, 1e-4),), reference="tilt", components="all"), "components"),
        (dict(schedule=((0.0, 0.01, 1e-4),), switch="hold"), "switch"),
        (dict(schedule=((0.0, 0.01, 0.0), (5.0, 0.0, 1e-6)), switch="rescale"), "nonzero integral gain"),
    ],
)
def test_bad_stage(kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        Stage(**kwargs)


def test_unstable_gains_are_simulated_not_refused():
    r = simulate(Scenario(duration=200.0, sensors=SensorErrors()), (Stage.constant(-0.05, 1e-4, "pure"),), step=0.5)
    assert np.all(np.isfinite(r.errors)) and np.abs(r.errors).max() > 1e-3


@pytest.mark.parametrize(
    "kwargs", [dict(duration=0.0), dict(duration=np.nan), dict(latitude=2.0), dict(accel=np.inf), dict(rocking_amplitude=(1, 2)), dict(truth="flat"), dict(rocking_decay_origin=np.nan)]
)
def test_bad_scenario(kwargs):
    with pytest.raises((ValueError, TypeError)):
        Scenario(**kwargs)


def test_bad_step():
    with pytest.raises(ValueError, match="step"):
        sample(Scenario(duration=100.0), 0.03)
    with pytest.raises(ValueError, match="event"):
        sample(Scenario(duration=2100.0), 0.3)
