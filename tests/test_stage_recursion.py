"""The stage recursion: compiled loop against the plain-Python reference, gain switches."""

from dataclasses import replace

import numpy as np
import pytest
from scipy.linalg import expm

from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.multistage.stage_recursion import correction_map
from strapdown.analysis.multistage.stages import Stage, run_stage


def _inputs(n=1500, seed=7):
    rng = np.random.default_rng(seed)
    dq = quat.rotvec_to_quat(rng.normal(0.0, 0.02, (n, 3)))
    force = np.column_stack([rng.normal(0, 2.0, n), 9.81 + rng.normal(0, 0.5, n), rng.normal(0, 2.0, n)])
    ref = quat.normalize(quat.rotvec_to_quat(np.cumsum(rng.normal(0, 0.01, (n + 1, 3)), axis=0)))
    return dq, force, ref


STAGES = [
    Stage(((0.0, 0.3, 0.02), (60.0, 0.0, 1e-3)), "pure"),
    Stage(((0.0, 0.3, 0.02), (60.0, 0.1, 1e-3), (200.0, 0.0, 2e-3)), "pure", switch="rescale"),
    Stage(((0.0, 0.3, 0.02), (60.0, 0.0, 1e-3)), "pure", switch="bumpless", rho=0.0),
    Stage(((0.0, 0.2, 0.01),), "tilt", components=(0, 1, 2, 3)),
    Stage(((0.0, 0.2, 0.01), (100.0, 0.05, 0.002)), "tilt", c=2.0, switch="bumpless"),
    Stage(((0.0, 0.5, 0.05),), "external", rho=0.5),
]


@pytest.mark.parametrize("stage", STAGES, ids=range(len(STAGES)))
def test_compiled_matches_python_reference(stage):
    dq, force, ref = _inputs()
    kw = dict(reference=ref) if stage.reference == "external" else dict(force=force)
    nu_c, y_c = run_stage(stage, 0.2, dq, initial=[0.99, 0.05, -0.1, 0.03], engine="compiled", **kw)
    nu_p, y_p = run_stage(stage, 0.2, dq, initial=[0.99, 0.05, -0.1, 0.03], engine="python", **kw)
    assert np.abs(nu_c).max() > 0.5
    np.testing.assert_allclose(nu_c, nu_p, rtol=0, atol=1e-13)
    np.testing.assert_allclose(y_c, y_p, rtol=0, atol=1e-13 * max(1.0, np.abs(y_p).max()))


def test_correction_map_is_the_exact_flow():
    k, l, c, tau = 0.3, 0.02, 2.0, 0.7
    a = np.array([[-0.5 * k * c, 0.5, 0.5 * k], [-l * c, 0.0, l], [0.0, 0.0, 0.0]])
    e = correction_map(k, l, c, tau)
    two = correction_map(k, l, c, 2 * tau)
    m1 = np.array([[e[0], e[1], e[4]], [e[2], e[3], e[5]], [0, 0, 1]])
    m2 = np.array([[two[0], two[1], two[4]], [two[2], two[3], two[5]], [0, 0, 1]])
    np.testing.assert_allclose(m1 @ m1, m2, atol=1e-15)  # semigroup
    d = 1e-6
    ed = correction_map(k, l, c, tau + d)
    md = np.array([[ed[0], ed[1], ed[4]], [ed[2], ed[3], ed[5]], [0, 0, 1]])
    np.testing.assert_allclose((md - m1) / d, a @ m1, atol=1e-7)  # solves x' = A x
    np.testing.assert_allclose(m1, expm(a * tau), atol=1e-15)


@pytest.mark.parametrize("switch", ["carry", "rescale", "bumpless"])
def test_integral_at_the_switch(switch):
    """carry keeps y, rescale multiplies it by l_new/l_old, bumpless keeps k(m − cν) + y continuous."""
    h, ts, k0, l0, l1 = 0.01, 100.0, 0.05, 1e-3, 2e-4
    n = int(1.5 * ts / h)
    dq = np.broadcast_to(quat.rotvec_to_quat([0.0, 0.0, 1e-3 * h]), (n, 4))
    force = np.broadcast_to([0.3, 9.81, -0.2], (n, 3))
    st = Stage(((0.0, k0, l0), (ts, 0.0, l1)), "pure", rho=0.0, switch=switch)
    nu, y = run_stage(st, h, dq, force)
    i = int(round(ts / h))
    m = np.array([0.0, 0.2 / 9.81, 0.0, 0.3 / 9.81])
    error = (m - st.c * nu[i])[[1, 3]]
    before, after = y[i][[1, 3]], y[i + 1][[1, 3]]  # one step of h later: y moves by O(h l)
    assert np.abs(before).max() > 1e-5 and np.abs(error).max() > 1e-4
    expected = {"carry": before, "rescale": before * l1 / l0, "bumpless": before + k0 * error}[switch]
    np.testing.assert_allclose(after, expected, rtol=1e-3)
    # bumpless: the correction k(m − cν) + y is k0·error + y before and 0·error + y after


def test_zero_gain_stage_is_pure_gyro_integration():
    dq, force, _ = _inputs(500)
    nu, y = run_stage(Stage.constant(0.0, 0.0, "tilt", rho=0.0, components=(0, 1, 2, 3)), 0.1, dq, force)
    prod = np.array([1.0, 0.0, 0.0, 0.0])
    for q in dq:
        prod = quat.multiply(prod, q)
    np.testing.assert_allclose(nu[-1], prod, atol=1e-13)
    assert not y.any()


def test_engine_is_checked():
    dq, force, _ = _inputs(10)
    with pytest.raises(ValueError, match="`engine`"):
        run_stage(Stage.constant(0.1, 0.01), 0.1, dq, force, engine="fortran")


# ---------------------------------------------------------------------------
# The whole cascade in one compiled pass against the stage-by-stage reference
# ---------------------------------------------------------------------------
def _cascades():
    from strapdown.analysis.multistage.stages import plotnikov_1999_stages

    default = plotnikov_1999_stages(switch_time=150.0)
    return {
        "section5": default,
        "all-four-bumpless": plotnikov_1999_stages(switch_time=150.0, stage1_components=(0, 1, 2, 3), switch="bumpless"),
        "pure-rescale": plotnikov_1999_stages(switch_time=150.0, stage1_reference="pure", switch="rescale"),
        "external-three-stages": (
            Stage.constant(0.05, 1e-4, "external", rho=0.5),
            default[1],
            # an empty segment (two switches on the same step) and a switch after the end
            Stage(((0.0, 0.02, 1e-4), (100.0, 0.0, 2e-4), (100.01, 0.01, 1e-5), (1e6, 0.0, 1e-6)), "tilt", switch="bumpless", components=(0, 1, 2, 3)),
        ),
        "one-stage-no-norm-flow": (Stage.constant(0.02, 1e-4, "tilt", rho=0.0, c=2.0),),
    }


@pytest.mark.parametrize("name", list(_cascades()))
def test_compiled_cascade_matches_the_reference(name):
    """run_multistage: the one-pass compiled cascade equals the stage-by-stage Python/numpy reference to round-off."""
    from strapdown.analysis.multistage.sensors import SensorErrors
    from strapdown.analysis.multistage.stages import multistage_peaks, run_multistage
    from strapdown.analysis.multistage.trajectory import Scenario, sample

    stages = _cascades()[name]
    sc = Scenario(duration=1400.0, rocking_decay=1e-3, sensors=SensorErrors(gyro_drift=(1e-6, -2e-6, 3e-6), accel_bias=(0.01, -0.02, 0.005), gyro_noise=1e-5, accel_noise=1e-3))
    data = sample(sc, 0.2, rng=3)
    got = run_multistage(data, stages, engine="compiled")
    ref = run_multistage(data, stages, engine="python")
    assert np.abs(ref.errors).max() > 1e-3  # the errors are not trivial
    for field in ("stages", "composite", "errors"):
        np.testing.assert_allclose(getattr(got, field), getattr(ref, field), rtol=0, atol=1e-13)
    peaks = np.array([tuple(p) for p in ref.peaks()])
    np.testing.assert_allclose(multistage_peaks(data, stages), peaks, rtol=1e-12, atol=0)
    np.testing.assert_allclose(multistage_peaks(data, stages, engine="python"), peaks, rtol=0, atol=0)


def test_compiled_cascade_refuses_bad_shapes_and_a_non_finite_run():
    from strapdown.analysis.multistage.stage_recursion import cascade_loop
    from strapdown.analysis.multistage.stages import _cascade_inputs, multistage_peaks
    from strapdown.analysis.multistage.trajectory import Scenario, sample

    data = sample(Scenario(duration=20.0), 0.5)
    stages = [Stage.constant(0.1, 0.01, "tilt")]
    inputs = _cascade_inputs(data, stages)
    with pytest.raises(ValueError, match="`accel`"):
        cascade_loop(data.gyro, data.accel[:-1], data.attitude, data.angles, 9.81, 0.5, *inputs)
    with pytest.raises(ValueError, match="`truth`"):
        cascade_loop(data.gyro, data.accel, data.attitude, data.angles[:-1], 9.81, 0.5, *inputs)
    with pytest.raises(ValueError, match="`kinds`"):
        cascade_loop(data.gyro, data.accel, data.attitude, data.angles, 9.81, 0.5, np.array([1, 0]), *inputs[1:])
    with pytest.raises(ValueError, match="`masks`"):
        cascade_loop(data.gyro, data.accel, data.attitude, data.angles, 9.81, 0.5, inputs[0], np.ones((1, 3), bool), *inputs[2:])
    with pytest.raises(ValueError, match="`engine`"):
        multistage_peaks(data, stages, engine="fortran")
    gyro = data.gyro.copy()
    gyro[7, 1] = np.nan
    broken = replace(data, gyro=gyro)
    for engine in ("compiled", "python"):
        with pytest.raises(ValueError, match="finite"):
            multistage_peaks(broken, stages, engine=engine)


@pytest.mark.parametrize("name", list(_cascades()))
def test_bounds_skip_only_steps_that_cannot_raise_a_peak(name):
    """Peaks only: skipping the errors bounded below their running peaks gives the peaks of the full evaluation, bit for bit."""
    from strapdown.analysis.multistage.sensors import SensorErrors
    from strapdown.analysis.multistage.stage_recursion import cascade_loop
    from strapdown.analysis.multistage.stages import _cascade_inputs
    from strapdown.analysis.multistage.trajectory import Scenario, sample

    stages = list(_cascades()[name])
    sc = Scenario(duration=1400.0, rocking_decay=1e-3, sensors=SensorErrors(gyro_drift=(1e-6, -2e-6, 3e-6), accel_bias=(0.01, -0.02, 0.005), gyro_noise=1e-5, accel_noise=1e-3))
    data = sample(sc, 0.2, rng=4)
    args = (data.gyro, data.accel, data.attitude, data.angles, sc.gravity, 0.2, *_cascade_inputs(data, stages))
    bounded = cascade_loop(*args, store=False, bounds=True)[0]
    full = cascade_loop(*args, store=False, bounds=False)[0]
    stored = cascade_loop(*args, store=True)[0]
    np.testing.assert_array_equal(bounded, full)
    np.testing.assert_array_equal(stored, full)


def test_bounds_are_not_used_when_truth_is_not_the_attitude():
    """Angles that are not those of the attitude switch the bounds off (checked at 17 points); the peaks stay right."""
    from strapdown.analysis.multistage.stage_recursion import cascade_loop
    from strapdown.analysis.multistage.stages import _cascade_inputs, multistage_peaks, plotnikov_1999_stages
    from strapdown.analysis.multistage.trajectory import Scenario, sample

    data = sample(Scenario(duration=1400.0), 0.2)
    angles = data.angles.copy()
    angles[:, 0] += 0.3  # a yaw offset: the true attitude and the angles disagree
    shifted = replace(data, angles=angles)
    stages = list(plotnikov_1999_stages(switch_time=150.0))
    args = (shifted.gyro, shifted.accel, shifted.attitude, shifted.angles, 9.81, 0.2, *_cascade_inputs(shifted, stages))
    np.testing.assert_array_equal(cascade_loop(*args, store=False, bounds=True)[0], cascade_loop(*args, store=False, bounds=False)[0])
    np.testing.assert_allclose(multistage_peaks(shifted, stages), multistage_peaks(shifted, stages, engine="python"), rtol=1e-12, atol=0)


def test_bound_terms_formed_once_give_the_same_peaks():
    """Terms of the true attitude formed once (a Monte Carlo on one truth) give the peaks of terms formed at every call, bit for bit."""
    from strapdown.analysis.multistage.sensors import SensorErrors, corrupt
    from strapdown.analysis.multistage.stage_recursion import bound_terms
    from strapdown.analysis.multistage.stages import multistage_peaks, plotnikov_1999_stages
    from strapdown.analysis.multistage.trajectory import Scenario, sample

    ideal = sample(Scenario(duration=1400.0, sensors=SensorErrors()), 0.2)
    stages = plotnikov_1999_stages(switch_time=150.0)
    terms = bound_terms(ideal.attitude, ideal.angles)
    assert terms.shape == (ideal.attitude.shape[0], 8) and not terms.flags.writeable
    for seed in range(3):
        data = corrupt(ideal, SensorErrors(gyro_drift=(1e-6, -2e-6, 3e-6), accel_bias=(0.01, -0.02, 0.005), gyro_noise=1e-5, accel_noise=1e-3), rng=seed)
        np.testing.assert_array_equal(multistage_peaks(data, stages, terms=terms), multistage_peaks(data, stages))
    shifted = ideal.angles.copy()
    shifted[:, 0] += 0.3
    assert bound_terms(ideal.attitude, shifted) is None  # angles that are not those of the attitude: no bounds
    with pytest.raises(ValueError, match="`terms` with shape"):
        multistage_peaks(ideal, stages, terms=terms[:-1])
