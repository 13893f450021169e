"""Coning and sculling in a vibration environment: files, closed form, DOP853 and Monte Carlo checks, tuning, rate design."""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest
import sympy as sp
from scipy import integrate

from strapdown.analysis.coning.drift_theory import coning_drift_rate
from strapdown.analysis.coning.sculling_motion import ScullingMotion, rectification_error
from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H
from strapdown.analysis.vibration.drift import coning_vector, environment_drift
from strapdown.analysis.vibration.environment import Environment, Spectrum, VibrationLine, coning_line, load_environment, sculling_line
from strapdown.analysis.vibration.rate_design import rate_design
from strapdown.analysis.vibration.sensor_dynamics import ChannelFilter, Sensor, analog_filter, digital_filter
from strapdown.analysis.vibration.simulation import filtered_coning_check
from strapdown.analysis.vibration.tuning import drift_across_band, tune, tuned_drift
from strapdown.derivations.coning.drift import X
from strapdown.derivations.coning.registry import get
from strapdown.derivations.coning.tuned import CUTOFF, RHO, lowpass_null_coefficient, two_sample_null_coefficient

DEG = math.pi / 180.0


def _write(tmp_path, text, name="env.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text), encoding="utf-8")
    return p


def _lowpass(fc):
    return ChannelFilter(analog_filter("lowpass1", cutoff_hz=fc))


# --------------------------------------------------------------------------- files
def test_the_keys_of_the_issue_work_as_written(tmp_path):
    p = _write(tmp_path, """
        [[line]]                 # classical coning line
        freq_hz = 10.0
        half_angle_deg = 1.0
        [gyro]
        filter = "lowpass1"      # first-order analog low-pass on every gyro axis, before integration
        cutoff_hz = 100.0
    """)
    env = load_environment(p)
    d = environment_drift(get("two-sample"), env, 1e-3)
    # (1 − |H|²) α²ω/2 with |H|² = 1/(1 + 0.01): about 20 deg/h of pseudo-coning
    expected = (1 - 1 / 1.01) * math.sin(DEG) ** 2 * 2 * math.pi * 10 / 2
    assert d.sensor == pytest.approx(expected, rel=1e-12)
    assert 19 < d.sensor * RAD_PER_S_TO_DEG_PER_H < 21
    assert np.allclose(d.coning_axis, [0, 0, 1])


def test_lines_without_axis_cone_about_one_axis_in_one_sense(tmp_path):
    p = _write(tmp_path, """
        [[line]]
        freq_hz = 10.0
        half_angle_deg = 1.0
        [[line]]
        freq_hz = 23.0
        half_angle_deg = 0.5
        phase_deg = 40.0
    """)
    env = load_environment(p)
    q = coning_vector(np.stack([ln.power for ln in env.lines]))
    assert np.all(q[:, 2] > 0) and np.allclose(q[:, :2], 0)


def test_per_axis_filters_digital_filters_decimation_and_spectra(tmp_path):
    p = _write(tmp_path, """
        name = "imu"
        [[sculling_line]]
        freq_hz = 30.0
        angle_amplitude_deg = 0.2
        accel_amplitude_m_s2 = 3.0
        [[spectrum]]
        rate_unit = "deg/s"
        accel_unit = "g"
        freq_hz = [20.0, 200.0]
        wx = [0.1, 0.1]
        wy = [0.1, 0.1]
        ay = [0.01, 0.01]
        wx_wy = [[0.0, -0.05], [0.0, -0.05]]
        wx_ay = [[0.01, 0.0], [0.01, 0.0]]
        [gyro]
        filter = "butterworth"
        order = 3
        cutoff_hz = 250.0
        digital = "coefficients"
        digital_b = [0.5, 0.5]
        [gyro.z]
        filter = "transfer_function"
        num = [1.0]
        den = [0.001, 1.0]
        [accelerometer]
        filter = "bessel"
        cutoff_hz = 200.0
        digital = "butterworth"
        digital_cutoff_hz = 300.0
        [sampling]
        decimation = 4
    """)
    env = load_environment(p)
    assert env.decimation == 4 and env.name == "imu"
    assert env.gyro.axes[0] == env.gyro.axes[1] != env.gyro.axes[2]
    assert env.gyro.axes[2].digital.kind == "coefficients"  # inherited: [gyro.z] sets only the analog filter
    g = env.spectra[0].at(np.array([50.0]))[0]
    assert g[0, 1] == pytest.approx(-0.05j * DEG**2)
    assert g[0, 4] == pytest.approx(0.01 * DEG * 9.80665)
    d = environment_drift(get("optimal-3"), env, 1e-3)
    assert len(d.parts) == 2 and np.isfinite(d.sculling) and d.total != 0.0


@pytest.mark.parametrize(
    "text, message",
    [
        ('[[line]]\nfreq_hz = 10.0\n', "missing key 'half_angle_deg'"),
        ('[[line]]\nfreq_hz = 10.0\nhalf_angle_deg = 1.0\nspeed = 3\n', "unknown key 'speed'"),
        ('[[line]]\nfreq_hz = -1.0\nhalf_angle_deg = 1.0\n', "key 'freq_hz': expected a number > 0"),
        ('[gyro]\nfilter = "lowpass2"\n', "key 'filter': expected one of"),
        ('[gyro]\nfilter = "lowpass1"\n', "missing key 'cutoff_hz'"),
        ('[gyro]\nfilter = "lowpass1"\ncutoff_hz = 100.0\norder = 2\n', "key 'order' does not apply to filter = 'lowpass1'"),
        ('[gyro]\nfilter = "transfer_function"\nnum = [1.0]\nden = [1.0, -1.0]\n', "stable analog filter"),
        ('[gyro]\nfilter = "transfer_function"\nnum = [2.0]\nden = [1.0, 1.0]\n', "unit gain at zero frequency"),
        ('[gyro]\ndigital = "coefficients"\ndigital_b = [0.5, 0.4]\n', "unit gain at zero frequency"),
        ('[gyro.x]\nfilter = "lowpass1"\ncutoff_hz = "fast"\n', "[gyro.x] key 'cutoff_hz'"),
        ('[[spectrum]]\nfreq_hz = [10.0, 20.0]\nwx = [1.0, 1.0]\nwy = [1.0, 1.0]\nwx_wy = [[2.0, 0.0], [0.0, 0.0]]\n', "positive semidefinite"),
        ('[[spectrum]]\nfreq_hz = [20.0, 10.0]\nwx = [1.0, 1.0]\n', "key 'freq_hz'"),
        ('[[spectrum]]\nfreq_hz = [10.0, 20.0]\nwx_wy = [[0.0, 1.0], [0.0, 1.0]]\n', "no auto-spectrum"),
        ('[sampling]\ndecimation = 0\n', "key 'decimation'"),
        ('surprise = 1\n', "top level unknown key 'surprise'"),
        ('[[line]\n', "not valid TOML"),
    ],
)
def test_bad_files_are_refused_naming_file_table_and_key(tmp_path, text, message):
    p = _write(tmp_path, text)
    with pytest.raises(ValueError) as err:
        load_environment(p)
    assert message in str(err.value)
    assert str(p) in str(err.value)


def test_a_digital_cutoff_above_the_sensor_nyquist_frequency_is_refused():
    env = Environment((coning_line(10.0, DEG),), gyro=Sensor((ChannelFilter(digital=digital_filter("butterworth", cutoff_hz=400.0)),) * 3))
    with pytest.raises(ValueError, match="Nyquist"):
        environment_drift(get("two-sample"), env, 1e-3 * 2)


# --------------------------------------------------------------------------- closed form
@pytest.mark.parametrize("name", ["one-sample", "two-sample", "optimal-3", "ignagni-1996-5", "lebedev-panov-6"])
def test_ideal_sensors_give_the_classical_coning_drift(name):
    """Ideal sensors: the closed form in ωh of derivations.coning.drift (first-order rate amplitude ω sin α)."""
    alpha, f, h = 1.0 * DEG, 10.0, 2e-3
    d = environment_drift(get(name), Environment((coning_line(f, alpha),)), h)
    expected = float(coning_drift_rate(get(name), cone_angle=alpha, nu=2 * math.pi * f, sample_interval=h)) * (math.sin(alpha) / alpha) ** 2
    assert d.sensor == 0.0
    assert d.total == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("name", ["one-sample", "two-sample", "optimal-3"])
def test_ideal_sensors_give_the_classical_sculling_rectification(name):
    m = ScullingMotion(2e-3, 1.5, 2 * np.pi * 10, angle_phase=0.3, accel_phase=0.9)
    line = sculling_line(10.0, 2e-3, 1.5, angle_phase=0.3, accel_phase=0.9)
    d = environment_drift(get(name), Environment((line,)), 0.005)
    ref = rectification_error(get(name), m, 0.005)
    assert d.sculling == pytest.approx(ref.rate, rel=1e-10)
    assert d.parts[0].true_rectification[2] == pytest.approx(ref.exact_rate, rel=1e-12)


def test_mismatched_filters_turn_in_phase_vibration_into_pseudo_coning():
    """In-phase angular vibration on x and y has no coning; different filters on x and y make it cone."""
    line = VibrationLine(20.0, np.array([1.0, 1.0, 0, 0, 0, 0]) * 0.01)
    same = Environment((line,), gyro=Sensor((_lowpass(50.0),) * 3))
    mixed = Environment((line,), gyro=Sensor((_lowpass(50.0), _lowpass(80.0), _lowpass(50.0))))
    assert np.allclose(environment_drift(get("two-sample"), same, 1e-3).total_vector, 0.0)
    d = environment_drift(get("two-sample"), mixed, 1e-3)
    w = 2 * math.pi * 20.0
    hx, hy = 1 / (1 + 1j * w / (2 * math.pi * 50.0)), 1 / (1 + 1j * w / (2 * math.pi * 80.0))
    q_sensed = np.imag(hx * np.conj(hy)) * 0.01**2  # Im(Ã_x conj Ã_y) for real A_x = A_y
    assert d.sensor_vector[2] == pytest.approx(-q_sensed / (2 * w), rel=1e-12)


def test_spectrum_integral_agrees_with_scipy_quad():
    f = np.array([20.0, 60.0, 300.0])
    g = np.zeros((3, 6, 6), dtype=complex)
    g[:, 0, 0] = g[:, 1, 1] = [1e-4, 4e-4, 2e-5]
    g[:, 0, 1] = [-0.5e-4j, -3e-4j, -1e-5j]
    g[:, 1, 0] = np.conj(g[:, 0, 1])
    spectrum = Spectrum(f, g)
    env = Environment((), (spectrum,), gyro=Sensor((_lowpass(150.0),) * 3))
    alg, h = get("two-sample"), 1e-3
    d = environment_drift(alg, env, h)

    def integrand(freq):
        single = Environment((VibrationLine(freq, np.zeros(6)),), (), env.gyro)  # sensors only
        w = 2 * math.pi * freq
        gf = spectrum.at(np.array([freq]))[0]
        hh = single.gyro.response(np.array([w]), h)[0]
        q = -2 * np.imag(gf[0, 1])
        qt = -2 * np.imag(np.conj(hh[0]) * hh[1] * gf[0, 1])
        from strapdown.analysis.coning.drift_theory import coning_drift_function

        return (q - qt) / (2 * w) + qt * float(coning_drift_function(alg)(w * h)) / w

    ref = sum(integrate.quad(integrand, a, b, epsabs=0, epsrel=1e-12)[0] for a, b in zip(f[:-1], f[1:]))
    assert d.total_vector[2] == pytest.approx(ref, rel=1e-8)


# --------------------------------------------------------------------------- DOP853
@pytest.mark.parametrize("cutoff", [30.0, 100.0, 300.0])
@pytest.mark.parametrize("mismatch", [1.0, 1.3])
def test_pseudo_coning_agrees_with_dop853_within_one_percent(cutoff, mismatch):
    """Classical coning (1°, 10 Hz) through first-order filters: closed form against DOP853 with the filters in continuous time."""
    gyro = Sensor((_lowpass(cutoff), _lowpass(cutoff * mismatch), _lowpass(cutoff)))
    alg, h = get("two-sample"), 1e-3
    d = environment_drift(alg, Environment((coning_line(10.0, DEG),), gyro=gyro), h)
    sim = filtered_coning_check(alg, gyro, h, freq_hz=10.0, half_angle=DEG, periods=2)
    assert sim.sensor_drift == pytest.approx(d.sensor, rel=1e-2)
    assert sim.total_drift == pytest.approx(d.total, rel=1e-2)
    assert abs(sim.sensor_drift / d.sensor - 1) < 1e-4  # the α² neglected: (1°)² ≈ 3e-4


# --------------------------------------------------------------------------- Monte Carlo
SPECTRUM_FILE = """
    name = "two lines and a band"
    [[line]]
    freq_hz = 15.0
    half_angle_deg = 0.5
    [[line]]
    freq_hz = 37.0
    half_angle_deg = 0.2
    axis = [0.0, 0.0, -1.0]
    [[spectrum]]
    label = "coning band"
    rate_unit = "deg/s"
    freq_hz = [40.0, 80.0, 160.0]
    wx = [0.2, 0.4, 0.1]
    wy = [0.2, 0.4, 0.1]
    wz = [0.1, 0.1, 0.1]
    wx_wy = [[0.0, -0.15], [0.1, -0.3], [0.0, -0.08]]
    [gyro]
    filter = "butterworth"
    order = 2
    cutoff_hz = 150.0
    digital = "moving_average"
    digital_taps = 2
    [gyro.y]
    filter = "lowpass1"
    cutoff_hz = 180.0
    [sampling]
    decimation = 2
"""


@pytest.mark.parametrize("name", ["two-sample", "optimal-3", "ignagni-1996-5"])
def test_monte_carlo_interval_covers_the_closed_form(tmp_path, name):
    """Two lines and a continuous band, mismatched analog filters, a digital filter and decimation."""
    pytest.importorskip("numba")
    from strapdown.analysis.vibration.monte_carlo import monte_carlo_drift

    env = load_environment(_write(tmp_path, SPECTRUM_FILE))
    alg, h = get(name), 2e-3
    d = environment_drift(alg, env, h)
    assert abs(d.parts[2].total @ d.coning_axis) > 0.05 * abs(d.total)  # the band matters
    mc = monte_carlo_drift(alg, env, h, pairs=80, duration=2.0, rng=20261203)
    low, high = mc.interval(d.coning_axis, level=0.997)
    assert low <= d.total <= high
    mean, se = mc.along(d.coning_axis)
    assert se < 0.02 * abs(d.total)
    assert not low <= d.total - d.sensor <= high  # it resolves the pseudo-coning of the filters
    if name == "two-sample":  # and the algorithm's own residual
        other = environment_drift(get("optimal-3"), env, h).total
        assert not low <= other <= high


def test_monte_carlo_rectification_of_a_sculling_line_through_filters():
    pytest.importorskip("numba")
    from strapdown.analysis.vibration.monte_carlo import monte_carlo_drift

    env = Environment((sculling_line(25.0, 0.5 * DEG, 5.0),), gyro=Sensor((_lowpass(100.0),) * 3), accelerometer=Sensor((_lowpass(60.0),) * 3))
    d = environment_drift(get("two-sample"), env, 1e-3)
    assert abs(d.sensor_sculling) > 0.05 * abs(d.sculling)  # gyro and accelerometer filters differ: pseudo-sculling
    mc = monte_carlo_drift(get("two-sample"), env, 1e-3, pairs=8, duration=0.4, rng=5, velocity=True)
    m, se = mc.along(d.sculling_axis, sculling=True)
    assert m == pytest.approx(d.sculling, rel=1e-3)


def test_monte_carlo_does_not_depend_on_chunking():
    pytest.importorskip("numba")
    from strapdown.analysis.vibration.monte_carlo import monte_carlo_drift

    env = Environment((coning_line(12.0, DEG),), gyro=Sensor((_lowpass(80.0),) * 3))
    a = monte_carlo_drift(get("two-sample"), env, 2e-3, pairs=6, duration=0.2, rng=3, chunk=6)
    b = monte_carlo_drift(get("two-sample"), env, 2e-3, pairs=6, duration=0.2, rng=3, chunk=4)
    assert np.array_equal(a.pairs, b.pairs)


def test_draws_with_one_stream_per_realisation_are_the_single_draws(tmp_path):
    from strapdown.analysis.vibration.monte_carlo import draw_components

    env = load_environment(_write(tmp_path, SPECTRUM_FILE))
    seeds = np.random.SeedSequence(3).spawn(4)
    freq, amp = draw_components(env, 4, [np.random.default_rng(s) for s in seeds])
    for i, s in enumerate(seeds):
        f, z = draw_components(env, 1, np.random.default_rng(s))
        assert np.array_equal(freq[i], f[0]) and np.array_equal(amp[i], z[0])
    with pytest.raises(ValueError, match="`rng`"):
        draw_components(env, 3, [np.random.default_rng(s) for s in seeds])


def test_monte_carlo_phases_advanced_between_anchors_agree_with_direct_evaluation():
    """Phases advanced by e^{iω h_s} between direct evaluations every REANCHOR samples, against sines and cosines at every node."""
    pytest.importorskip("numba")
    from strapdown.analysis.vibration.examples import QUALIFICATION
    from strapdown.analysis.vibration.monte_carlo import REANCHOR, monte_carlo_drift

    env = load_environment(QUALIFICATION)  # lines, a spectrum, second-order analog and digital filters, decimation by 4
    run = dict(pairs=3, duration=0.5, rng=11, velocity=True)
    direct = monte_carlo_drift(get("two-sample"), env, 1e-3, reanchor=1, **run)
    advanced = monte_carlo_drift(get("two-sample"), env, 1e-3, **run)
    assert direct.sensor_samples > 8 * REANCHOR * direct.realisations  # many anchors per realisation
    gap = np.abs(advanced.pairs - direct.pairs)
    # slope gaps times the run: attitude [rad] and velocity [m/s] error gaps at round-off, and relative to the slopes
    assert gap[:, :3].max() * direct.duration < 1e-14
    assert gap[:, 3:].max() * direct.duration < 1e-13
    assert np.all(gap.max(axis=0) < 1e-8 * np.abs(direct.pairs).max(axis=0))


def test_the_pair_kernel_runs_the_negative_member_as_its_own_realisation(tmp_path):
    """The kernel computes the second member of a pair from the first one's motion; run alone, −Z gives the same numbers bit for bit.

    The template is run as plain Python (two-sample placeholder, attitude), so the test needs no numba.
    """
    from strapdown.analysis.vibration import _kernel as template
    from strapdown.analysis.vibration.monte_carlo import draw_components, sensor_matrices

    env = load_environment(_write(tmp_path, SPECTRUM_FILE))  # mismatched analog filters, a digital filter, decimation
    h, rng = 2e-3, np.random.default_rng(4)
    freq, amp = draw_components(env, 1, rng, band_components=2)
    mats = sensor_matrices(env, h, velocity=False)
    om = 2.0 * math.pi * freq
    theta = amp[..., :3] / (1j * om[..., None])
    coef = np.concatenate([theta, amp], axis=-1)
    vel = amp[..., 3:] / (1j * om[..., None])
    out = {}
    for sign in (1.0, -1.0):
        out[sign] = np.empty((2, 6))
        c, v = sign * coef, sign * vel
        template.run(om, c.real.copy(), c.imag.copy(), v.real.copy(), v.imag.copy(), mats["hs"], env.decimation, 40, 6, mats["nodes"],
                     mats["gmat"], mats["db"], mats["da"], 7, out[sign])  # fmt: skip
    assert np.all(out[1.0][:, :3] != 0.0)
    assert np.array_equal(out[1.0][1], out[-1.0][0]) and np.array_equal(out[1.0][0], out[-1.0][1])


@pytest.mark.parametrize("angle", [1e-9, 1e-4, 0.0199, 0.0201, 0.0999, 0.1001, 0.7, 3.0])
def test_monte_carlo_rotation_series_agree_with_the_closed_forms(angle):
    """The kernel's exp(θ) and rotation vector switch to Taylor series below 0.1 and 0.02 rad; both sides agree with scipy."""
    from scipy.spatial.transform import Rotation

    from strapdown.analysis.vibration import _kernel as template

    for axis in np.random.default_rng(1).normal(size=(8, 3)):
        v = angle * axis / np.linalg.norm(axis)
        q = Rotation.from_rotvec(v).as_quat(scalar_first=True)
        np.testing.assert_allclose(template.quat_of(*v), q, rtol=0, atol=4e-17)
        np.testing.assert_allclose(template.error_rotvec(*q), Rotation.from_quat(q, scalar_first=True).as_rotvec(), rtol=0, atol=1e-15 * angle)


# --------------------------------------------------------------------------- tuning
def test_two_sample_tuned_to_one_line_nulls_its_drift_exactly():
    f, h = 40.0, 1e-3
    env = Environment((coning_line(f, DEG),))
    t = tune(env, 2, h)
    x = 2 * math.pi * f * h
    symbolic = float(two_sample_null_coefficient().subs(RHO, 1).evalf(40, subs={X: sp.Rational(repr(x))}))
    assert t.lag_sums[0] == pytest.approx(symbolic, rel=1e-12)
    assert t.nulled and t.taylor_conditions == 0
    exact = environment_drift(t.algorithm, env, h)  # D(x) of the tuned algorithm, derived symbolically
    classical = environment_drift(get("two-sample"), env, h)
    assert abs(exact.total) < 1e-9 * abs(classical.total)


def test_two_sample_tuned_coefficient_tends_to_two_thirds():
    ks = [tune(Environment((coning_line(f, DEG),)), 2, 1e-3).lag_sums[0] for f in (100.0, 10.0, 1.0)]
    gaps = [k - 2 / 3 for k in ks]
    assert gaps[0] > gaps[1] > gaps[2] > 0
    assert gaps[1] / gaps[2] == pytest.approx(100.0, rel=1e-3)  # k − 2/3 ∝ (ωh)²
    assert sp.limit(two_sample_null_coefficient().subs(RHO, 1), X, 0) == sp.Rational(2, 3)


def test_two_sample_tuned_behind_a_lowpass_matches_its_closed_form():
    fc, f, h = 100.0, 10.0, 1e-3
    env = Environment((coning_line(f, DEG),), gyro=Sensor((_lowpass(fc),) * 3))
    t = tune(env, 2, h)
    ref = lowpass_null_coefficient().evalf(40, subs={X: sp.Rational(repr(2 * math.pi * f * h)), CUTOFF: sp.Rational(repr(2 * math.pi * fc * h))})
    assert t.lag_sums[0] == pytest.approx(float(ref), rel=1e-10)
    assert abs(environment_drift(t.algorithm, env, h).total) < 1e-9 * abs(environment_drift(get("two-sample"), env, h).total)


def test_tuned_to_two_lines_nulls_the_drift_of_their_sum():
    h = 1e-3
    lines = (coning_line(10.0, DEG), coning_line(45.0, 0.3 * DEG))
    env = Environment(lines, gyro=Sensor((_lowpass(150.0),) * 3))
    t = tune(env, 2, h)
    d = environment_drift(t.algorithm, env, h)
    alone = [p.total @ d.coning_axis for p in d.parts]
    assert abs(d.total) < 1e-9 * max(abs(v) for v in alone)
    assert min(abs(v) for v in alone) > 1e-3 * max(abs(v) for v in alone)  # each line alone is not nulled
    assert np.allclose(tuned_drift(env, 2, h, t.lag_sums), t.drift, atol=1e-20)


def test_three_sample_tuning_keeps_the_second_order_condition():
    env = Environment((coning_line(10.0, DEG), coning_line(45.0, 0.3 * DEG)))
    t = tune(env, 3, 1e-3)
    assert t.taylor_conditions == 1
    assert sum(lag * k for lag, k in enumerate(t.lag_sums, start=1)) == pytest.approx(27 / 12, rel=1e-12)
    assert abs(environment_drift(t.algorithm, env, 1e-3).total) < 1e-8 * abs(t.classical_drift[2])


def test_sculling_tuning_nulls_the_rectification_error():
    env = Environment((sculling_line(25.0, 0.5 * DEG, 5.0),), gyro=Sensor((_lowpass(100.0),) * 3), accelerometer=Sensor((_lowpass(60.0),) * 3))
    t = tune(env, 2, 1e-3, quantity="sculling")
    d = environment_drift(t.algorithm, env, 1e-3)
    assert abs(d.sculling) < 1e-9 * abs(t.classical_drift @ d.sculling_axis)
    with pytest.raises(ValueError, match="coning to tune to"):
        tune(env, 2, 1e-3)


def test_tuned_algorithm_file_round_trips(tmp_path):
    from strapdown.derivations.coning.algorithms import load_toml

    t = tune(Environment((coning_line(30.0, DEG),)), 2, 1e-3)
    p = tmp_path / "tuned.toml"
    p.write_text(t.toml(), encoding="utf-8")
    alg = load_toml(p, allow_inconsistent=True)
    assert alg.pairwise == t.algorithm.pairwise


def test_drift_across_band_puts_the_tuned_zero_at_the_design_frequency():
    env = Environment((coning_line(40.0, DEG),), gyro=Sensor((_lowpass(200.0),) * 3))
    t = tune(env, 2, 1e-3)
    band = drift_across_band([t.algorithm, get("two-sample")], env, 1e-3, [20.0, 40.0, 80.0], half_angle=DEG)
    assert abs(band.total[0, 1]) < 1e-9 * abs(band.total[1, 1])
    assert np.all(np.abs(band.total[1]) > 0)


# --------------------------------------------------------------------------- rate design
def test_rate_design_finds_the_lowest_admissible_rate():
    env = Environment((coning_line(20.0, DEG), coning_line(55.0, 0.2 * DEG)), gyro=Sensor((_lowpass(2000.0),) * 3))
    budget = 10.0 / RAD_PER_S_TO_DEG_PER_H
    design = rate_design(env, budget, algorithms=[get("two-sample")], tuned=((2, 0),), rates=np.geomspace(100.0, 10000.0, 25), margin=0.05)
    for row in design.rows:
        assert row.sample_rate is not None and row.drift <= budget and row.load > 0
        below = row.sample_rate * 0.98
        worst = max(abs(environment_drift(get("two-sample"), e, 1 / below).total) for e in (env,)) if not row.tuned else None
        if worst is not None:
            assert worst > budget * 0.9
    unreachable = rate_design(Environment((coning_line(20.0, DEG),), gyro=Sensor((_lowpass(50.0),) * 3)), budget, algorithms=[get("two-sample")], tuned=())
    assert unreachable.rows[0].sample_rate is None  # the filter's pseudo-coning alone exceeds the budget


def test_monte_carlo_quadrature_of_the_sensor_samples_has_converged():
    """The Gauss–Legendre rule over each sensor sample (ωh_s ≈ 0.94 here): three nodes agree with six, two do not (fixed draws)."""
    pytest.importorskip("numba")
    from strapdown.analysis.vibration.monte_carlo import monte_carlo_drift

    env = Environment((coning_line(150.0, 0.2 * DEG),), gyro=Sensor((_lowpass(200.0), _lowpass(260.0), _lowpass(200.0))))
    three = monte_carlo_drift(get("two-sample"), env, 1e-3, pairs=2, duration=0.3, rng=9, quadrature_points=3)
    six = monte_carlo_drift(get("two-sample"), env, 1e-3, pairs=2, duration=0.3, rng=9, quadrature_points=6)
    two = monte_carlo_drift(get("two-sample"), env, 1e-3, pairs=2, duration=0.3, rng=9, quadrature_points=2)
    assert np.allclose(three.mean, six.mean, rtol=2e-5, atol=0)
    assert not np.allclose(two.mean, six.mean, rtol=1e-3, atol=0)
