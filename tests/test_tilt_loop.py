"""python-control analysis of the stage loop."""

import control
import numpy as np
import pytest

from strapdown.analysis.multistage.tilt_loop import StageLoop, classify_poles, root_locus_k, root_locus_l
from strapdown.derivations.multistage.published import PRINTED_GAINS

#: The gains of section 5 of Plotnikov (1999): stage 1, and stage 2 before the switch.
K1, L1 = PRINTED_GAINS.stage1
K2, L2 = PRINTED_GAINS.stage2_before


def test_poles_damping_natural_frequency():
    loop = StageLoop(K1, L1)
    wn, zeta, p = loop.damp()
    np.testing.assert_allclose(np.sort_complex(p), np.sort_complex(np.roots([1, K1, L1])), rtol=1e-12)
    np.testing.assert_allclose(wn, np.sqrt(L1))
    np.testing.assert_allclose(zeta, K1 / (2 * np.sqrt(L1)))


@pytest.mark.parametrize(
    "k,l,label",
    [(K1, L1, "asymptotically stable"), (0.0, 1.54e-6, "marginal"), (K1, 0.0, "marginal"), (-K1, L1, "unstable"), (K1, -1e-5, "unstable"), (0.0, 0.0, "unstable")],
)
def test_stability_flags(k, l, label):
    assert StageLoop(k, l).stability == label


def test_complementary_filter():
    loop = StageLoop(K2, L2)
    w = np.logspace(-5, 0, 50)
    hg = control.frequency_response(loop.gyro_highpass(), w)
    ha = control.frequency_response(loop.accel_lowpass(), w)
    total = hg.magnitude * np.exp(1j * hg.phase) + ha.magnitude * np.exp(1j * ha.phase)
    np.testing.assert_allclose(total, 1.0, atol=1e-12)
    assert hg.magnitude[0] < 1e-5 and ha.magnitude[-1] < 0.02


def test_root_loci_match_characteristic_roots():
    ks = np.array([0.0, 0.005, 0.02])
    loci = root_locus_k(L1, ks).loci
    for row, k in zip(loci, ks):
        np.testing.assert_allclose(np.sort_complex(row), np.sort_complex(np.roots([1, k, L1])), atol=1e-12)
    loci = root_locus_l(0.01, [1e-5, 1e-4]).loci
    np.testing.assert_allclose(np.sort_complex(loci[1]), np.sort_complex(np.roots([1, 0.01, 1e-4])), atol=1e-12)


def test_peak_scales_linearly_and_matches_small_gain_limit():
    loop = StageLoop(K1, L1)
    p20, p2 = loop.peak_tilt_error(20.0, 20.0), loop.peak_tilt_error(2.0, 20.0)
    assert p20 == pytest.approx(10 * p2, rel=1e-9)
    # A very fast loop follows the accelerometer: peak → a/g.
    assert StageLoop(100.0, 1e4).peak_tilt_error(20.0, 20.0) == pytest.approx(20 / 9.81, rel=1e-3)


def test_classify_repeated_axis_pole():
    assert classify_poles([1j, 1j, -1j, -1j]) == "unstable"
    assert classify_poles([]) == "asymptotically stable"


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_bad_values(bad):
    with pytest.raises(ValueError, match="finite"):
        StageLoop(bad, 1e-5)
    with pytest.raises(ValueError):
        StageLoop(0.01, 1e-5).peak_tilt_error(bad, 20.0)


def test_bad_types_and_durations():
    with pytest.raises(TypeError, match="`k`"):
        StageLoop("fast", 1e-5)
    with pytest.raises(ValueError, match="accel_duration"):
        StageLoop(0.01, 1e-5).peak_tilt_error(20.0, 0.0)
    with pytest.raises(ValueError, match="horizon"):
        StageLoop(0.01, 1e-5).peak_tilt_error(20.0, 20.0, horizon=10.0)


@pytest.mark.parametrize("k,l", [(-K1, L1), (K1, -1e-5), (0.0, 0.0)])
def test_unstable_loop_has_no_peak(k, l):
    loop = StageLoop(k, l)
    assert loop.stability == "unstable"
    with pytest.raises(ValueError, match="stable tilt loop"):
        loop.peak_tilt_error(20.0, 20.0)
    with pytest.raises(ValueError, match="stable tilt loop"):
        loop.drift_response(1e-5, 100.0)


def test_drift_response_peak_is_the_earth_rate_transient():
    """A stage started with an empty integral takes up a constant rate: peak d·max|s/(s² + ks + l)| step response."""
    loop = StageLoop(K2, L2)
    t, e = loop.drift_response(1e-4, 600.0)
    wd = np.sqrt(L2 - (K2 / 2) ** 2)
    closed = 1e-4 / wd * np.exp(-K2 / 2 * t) * np.sin(wd * t)  # inverse Laplace of d/(s² + ks + l)
    np.testing.assert_allclose(e, closed, atol=1e-12)


def test_typed_responses():
    from strapdown.analysis.multistage.tilt_loop import complementary_filter, responses

    loop = StageLoop(K2, L2)
    r = responses(loop, np.linspace(0.0, 500.0, 101))
    assert r.accel_step.shape == r.drift_step.shape == (101,) and r.accel_step[0] == 0.0
    f = complementary_filter(loop, np.logspace(-5, 0, 40))
    assert f.max_sum_error < 1e-12 and f.gyro_magnitude[0] < 1e-5 and f.accel_magnitude[-1] < 0.02


@pytest.mark.parametrize("k,l", [(K1 / 2, L1 / 2), (K2, L2), (0.0, 9.81 / 6.371e6), (0.0, 1.24e-3), (0.02, 1e-4)])
def test_step_response_on_grid_matches_control_step_response(k, l):
    """The zero-order-hold recursion run by lfilter gives the samples of control.step_response (its per-step loop)."""
    from strapdown.analysis.multistage.tilt_loop import step_response_on_grid

    loop = StageLoop(k, l)
    t = np.arange(10149) * 1.0
    for system in (loop.error_from_accel(), loop.error_from_drift(), loop.gyro_highpass(), loop.accel_lowpass()):
        ref = np.asarray(control.step_response(system, T=t).outputs, dtype=float).ravel()
        got = step_response_on_grid(system, t)
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-9 * max(np.abs(ref).max(), 1e-12))


def test_pulse_response_is_the_superposition_of_control_step_responses():
    loop = StageLoop(K2, L2)
    t, e = loop.pulse_response(20.0, 20.0)
    step = np.asarray(control.step_response(loop.error_from_accel(), T=t).outputs, dtype=float).ravel()
    m = int(round(20.0 / (t[1] - t[0])))
    ref = 20.0 * (step - np.concatenate([np.zeros(m), step[:-m]]))
    np.testing.assert_allclose(e, ref, rtol=0, atol=1e-9 * np.abs(ref).max())
    assert loop.peak_tilt_error(20.0, 20.0) == pytest.approx(np.abs(ref).max(), rel=1e-9)


def test_step_response_on_grid_refuses_bad_input():
    from strapdown.analysis.multistage.tilt_loop import step_response_on_grid

    sys = StageLoop(K2, L2).error_from_drift()
    with pytest.raises(TypeError, match="`system`"):
        step_response_on_grid([1.0, 2.0], [0.0, 1.0])
    with pytest.raises(ValueError, match="`system`"):
        step_response_on_grid(control.tf([1.0], [1.0, 0.5], 1.0), [0.0, 1.0])
    with pytest.raises(ValueError, match="`system`"):
        step_response_on_grid(StageLoop(K2, L2).state_space(), [0.0, 1.0])
    with pytest.raises(ValueError, match="uniform"):
        step_response_on_grid(sys, [0.0, 1.0, 3.0])
    with pytest.raises(ValueError, match="from 0"):
        step_response_on_grid(sys, [1.0, 2.0, 3.0])
