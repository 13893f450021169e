"""Lines that alias with the step rate, one quoted drift, environment-rates on large tables, bad input, noise through the algorithm.

The truth of the aliasing checks is an independent DOP853 simulation of the
kinematics (``simulation.line_drift_check``: the body rate and specific force
integrated into the attitude and velocity, the algorithm run on the
increments), which shares nothing with the closed form of
``vibration.aliasing``.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H
from strapdown.analysis.vibration.drift import environment_drift, theory_warnings
from strapdown.analysis.vibration.environment import Environment, VibrationLine, coning_line
from strapdown.analysis.vibration.examples import QUALIFICATION
from strapdown.analysis.vibration.noise import SensorNoise, noise_monte_carlo, noise_through_algorithm
from strapdown.analysis.vibration.rate_design import rate_design
from strapdown.analysis.vibration.sensor_dynamics import ChannelFilter, Sensor, analog_filter, digital_filter
from strapdown.analysis.vibration.simulation import common_period, line_drift_check
from strapdown.analysis.vibration.tuning import classical_algorithm
from strapdown.derivations.coning.drift import optimal_coning_algorithm
from strapdown.derivations.coning.registry import get, names

K = RAD_PER_S_TO_DEG_PER_H
D5 = math.radians(5.0)


def _cli(*argv, check=True):
    r = subprocess.run([sys.executable, "-m", "strapdown.analysis", *argv], capture_output=True, text=True, timeout=600)
    if check:
        assert r.returncode == 0, r.stderr
    return r


def _json(*argv):
    return json.loads(_cli(*argv, "--json", "--quiet").stdout)


def _vibration_line(freq, rate=(0.0, 0.0, 0.0), rate_phase=(0.0, 0.0, 0.0), accel=(0.0, 0.0, 0.0), accel_phase=(0.0, 0.0, 0.0)):
    return (
        "[[vibration_line]]\n"
        f"freq_hz = {freq!r}\nrate_amplitude_deg_s = {list(rate)!r}\nrate_phase_deg = {list(rate_phase)!r}\n"
        f"accel_amplitude_m_s2 = {list(accel)!r}\naccel_phase_deg = {list(accel_phase)!r}\n"
    )


def _audit_pair(second_hz=140.0):
    """x 60 Hz + y 140 Hz, 5 deg/s each, y 90° ahead (the audit's case)."""
    return Environment((VibrationLine(60.0, [D5, 0, 0, 0, 0, 0], "x"), VibrationLine(second_hz, [0, 1j * D5, 0, 0, 0, 0], "y")))


# --------------------------------------------------------------------------- 1. aliasing pairs
def test_the_audit_pair_agrees_with_dop853_within_two_percent(tmp_path):
    path = tmp_path / "pair.toml"
    path.write_text(_vibration_line(60.0, (5.0, 0, 0)) + _vibration_line(140.0, (0, 5.0, 0), (0, 90.0, 0)), encoding="utf-8")
    data = _json("environment-drift", "--algorithm", "two-sample", "--environment", str(path), "--sample-interval", str(1 / 400))
    closed = np.array(data["total_drift_vector_rad_s"])
    sim = line_drift_check(get("two-sample"), _audit_pair(), 1 / 400, periods=4)
    assert np.linalg.norm(closed - sim.drift) <= 0.02 * np.linalg.norm(sim.drift)
    # the audit's DOP853: −0.150 deg/h about z (the package printed 0 before the cross terms were taken)
    assert sim.drift[2] * K == pytest.approx(-0.150, abs=5e-4)
    assert [p["kind"] for p in data["parts"]] == ["line", "line", "alias"]
    assert data["aliasing_pairs"][0]["kind"] == "sum" and data["aliasing_pairs"][0]["multiple_of_step_rate"] == 1


def test_a_pair_that_does_not_alias_adds_nothing_and_dop853_agrees():
    env = _audit_pair(150.0)  # 60 + 150 = 210 Hz, 10 Hz off the step rate: beat period 0.1 s, not listed at the default 0.1 s
    d = environment_drift(get("two-sample"), env, 1 / 400)
    assert [p.kind for p in d.parts] == ["line", "line"] and d.magnitude == 0.0
    sim = line_drift_check(get("two-sample"), env, 1 / 400, periods=2)
    assert np.linalg.norm(sim.drift) * K < 1e-4  # against 0.150 deg/h when the same lines alias


def test_a_difference_alias_through_filters_and_decimation_depends_on_each_coefficient():
    ch = ChannelFilter(analog_filter("lowpass1", cutoff_hz=300.0), digital_filter("butterworth", cutoff_hz=400.0, order=2))
    gyro = Sensor((ch, ch, ChannelFilter(analog_filter("lowpass1", cutoff_hz=330.0))), 2)
    env = Environment((VibrationLine(50.0, [D5, 0, 0, 0, 0, 0], "x"), VibrationLine(250.0, [0, 0, D5 * np.exp(0.6j), 0, 0, 0], "z")),
                      gyro=gyro, accelerometer=Sensor(decimation=2))  # fmt: skip
    registry, ignagni_form = get("optimal-3"), optimal_coning_algorithm(3)  # the same lag sums, the coefficients on other pairs
    results = []
    for alg in (registry, ignagni_form):
        d = environment_drift(alg, env, 1 / 600)  # step rate 200 Hz: 250 − 50 = 200
        assert d.parts[-1].kind == "alias"
        sim = line_drift_check(alg, env, 1 / 600, periods=4)
        assert np.linalg.norm(d.total_vector - sim.drift) <= 0.02 * np.linalg.norm(sim.drift)
        results.append(d.magnitude)
    assert results[1] > 10 * results[0]  # one line cannot tell them apart; an aliasing pair can


def test_a_sculling_pair_agrees_with_dop853_within_two_percent():
    env = Environment((VibrationLine(80.0, [D5, 0, 0, 0, 0, 0], "roll"), VibrationLine(120.0, [0, 0, 0, 0, 2.0j, 0], "lateral")))
    d = environment_drift(get("two-sample"), env, 1 / 400)  # 80 + 120 = 200 Hz
    sim = line_drift_check(get("two-sample"), env, 1 / 400, periods=4, velocity=True)
    assert np.linalg.norm(sim.sculling) > 0
    assert np.linalg.norm(d.sculling_vector - sim.sculling) <= 0.02 * np.linalg.norm(sim.sculling)


def test_a_pair_one_hertz_off_an_alias_gives_the_mean_and_states_the_beat_period(tmp_path):
    path = tmp_path / "near.toml"
    path.write_text(_vibration_line(60.0, (5.0, 0, 0)) + _vibration_line(141.0, (0, 5.0, 0), (0, 90.0, 0)), encoding="utf-8")
    r = _cli("environment-drift", "--algorithm", "two-sample", "--environment", str(path), "--sample-interval", str(1 / 400))
    assert "beat period 1 s" in r.stdout and "mean 0 over many beats" in r.stdout
    data = _json("environment-drift", "--algorithm", "two-sample", "--environment", str(path), "--sample-interval", str(1 / 400))
    assert data["total_drift_magnitude_rad_s"] == 0.0
    (near,) = data["near_aliases"]
    assert near["beat_period_s"] == pytest.approx(1.0) and near["offset_hz"] == pytest.approx(1.0)
    # over one whole beat DOP853 sees no mean, against a swing of about 0.156 deg/h within it
    sim = line_drift_check(get("two-sample"), _audit_pair(141.0), 1 / 400, periods=1)
    assert sim.period == pytest.approx(1.0)
    assert np.linalg.norm(sim.drift) < 1e-3 * near["drift_amplitude_rad_s"]
    assert near["drift_amplitude_rad_s"] * K == pytest.approx(0.1557, abs=1e-3)


def test_common_period_refuses_incommensurate_rates():
    assert common_period([60.0, 141.0], 1 / 200) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="common period"):
        common_period([math.pi * 10], 1 / 200)


# --------------------------------------------------------------------------- 2. one quoted quantity
def test_three_commands_quote_one_drift_magnitude(tmp_path):
    q = str(QUALIFICATION)
    drift = _json("environment-drift", "--algorithm", "two-sample", "--environment", q, "--sample-interval", "1e-3")
    tuned_file = tmp_path / "tuned.toml"
    design = _json("design-coning", "--samples", "2", "--environment", q, "--sample-interval", "1e-3", "--write-algorithm", str(tuned_file))
    rates = _json("environment-rates", "--environment", q, "--budget-deg-per-h", "1e6", "--min-rate-hz", "1000", "--max-rate-hz", "2000",
                  "--rates", "2", "--margin", "0", "--tuned-up-to", "2", "--algorithms", "two-sample")  # fmt: skip
    tuned_drift = _json("environment-drift", "--algorithm-file", str(tuned_file), "--allow-inconsistent", "--environment", q, "--sample-interval", "1e-3")
    row = {r["algorithm"]: r for r in rates["rows"]}
    assert row["two-sample"]["sample_rate_hz"] == 1000.0 and row["tuned-2"]["sample_rate_hz"] == 1000.0
    classical = drift["total_drift_magnitude_deg_per_h"]
    assert classical == pytest.approx(np.linalg.norm(drift["total_drift_vector_rad_s"]) * K, rel=1e-12)
    assert design["classical_algorithm"] == "two-sample"
    assert design["classical_magnitude_deg_per_h"] == pytest.approx(classical, rel=1e-9)
    assert row["two-sample"]["drift_magnitude_deg_per_h"] == pytest.approx(classical, rel=1e-9)
    tuned = design["tuned_magnitude_deg_per_h"]
    assert row["tuned-2"]["drift_magnitude_deg_per_h"] == pytest.approx(tuned, rel=1e-9)
    assert tuned_drift["total_drift_magnitude_deg_per_h"] == pytest.approx(tuned, rel=1e-6)
    # the audit's numbers: vector (0, 0.0969, 0.0697) deg/h, magnitude 0.1193; tuned 0.0170
    assert np.array(drift["total_drift_vector_deg_per_h"]) == pytest.approx([0.0, 0.0969, 0.0697], abs=5e-5)
    assert classical == pytest.approx(0.1193, abs=5e-5) and tuned == pytest.approx(0.0170, abs=5e-5)
    # the projection is named with its axis, and is not the magnitude
    assert drift["along_coning_axis"]["axis"] == drift["coning_axis"]
    assert drift["along_coning_axis"]["total_deg_per_h"] < 0.9 * classical


def test_classical_algorithm_names_registry_algorithms_or_none():
    for n in (2, 3, 4):
        alg, in_registry = classical_algorithm(n)
        assert in_registry and alg.name in names(library=True)
        assert alg.pairwise == optimal_coning_algorithm(n).pairwise  # the tuned algorithm's form
    alg, in_registry = classical_algorithm(7)
    assert not in_registry and alg.name not in names(library=True)


# --------------------------------------------------------------------------- 3. environment-rates and bad input
def _table(path, rows):
    f = np.geomspace(10.0, 2000.0, rows)
    s = 1e-4 * (f / 100.0) ** -0.5 * (1 + 0.3 * np.sin(f / 37.0))
    text = ['name = "large table"', "[[spectrum]]", 'rate_unit = "deg/s"', "freq_hz = [" + ",".join(f"{v:.9g}" for v in f) + "]",
            "wx = [" + ",".join(f"{v:.6g}" for v in s) + "]", "wy = [" + ",".join(f"{v:.6g}" for v in s) + "]",
            "wx_wy = [" + ",".join(f"[0.0,{-0.5 * v:.6g}]" for v in s) + "]",
            "[gyro]", 'filter = "butterworth"', "order = 2", "cutoff_hz = 250.0", 'digital = "butterworth"', "digital_cutoff_hz = 184.0",
            "[sampling]", "decimation = 4"]  # fmt: skip
    path.write_text("\n".join(text) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("rows", [2000, 20000])
def test_environment_rates_answers_large_tables(tmp_path, rows):
    path = _table(tmp_path / f"t{rows}.toml", rows)
    drift = _json("environment-drift", "--algorithm", "two-sample", "--environment", str(path), "--sample-interval", "1e-3")
    rates = _json("environment-rates", "--environment", str(path), "--budget-deg-per-h", "0.05")
    assert drift["total_drift_magnitude_deg_per_h"] < 0.05
    for r in rates["rows"]:
        assert r["sample_rate_hz"] is not None, r
        assert r["drift_magnitude_deg_per_h"] <= 0.05
    assert any("left out" in n for n in rates["notes"])  # the digital cut-off of 184 Hz is undefined at the lowest rates


def test_environment_rates_answers_the_simple_environment_that_crashed(tmp_path):
    # one coning line at 50 Hz, the lowest default rate: there every lag response vanishes (ωh = 2π)
    path = tmp_path / "simple.toml"
    path.write_text("[[line]]\nfreq_hz = 50.0\nhalf_angle_deg = 0.1\n", encoding="utf-8")
    rates = _json("environment-rates", "--environment", str(path), "--budget-deg-per-h", "0.5")
    assert all(r["sample_rate_hz"] is not None for r in rates["rows"]), rates["rows"]


def test_rate_design_names_the_reason_when_no_rate_is_defined():
    ch = ChannelFilter(digital=digital_filter("butterworth", cutoff_hz=184.0))
    env = Environment((coning_line(20.0, 0.01),), gyro=Sensor((ch,) * 3))
    with pytest.raises(ValueError, match="Nyquist"):
        rate_design(env, 1e-6, algorithms=[get("two-sample")], rates=[100.0, 200.0, 300.0])


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("", ("no motion",)),
        ("# only a comment\n", ("no motion",)),
        ("[gyro]\nfilter = 'lowpass1'\ncutoff_hz = 100.0\n", ("no motion",)),
        (_vibration_line(30.0), ("no motion", "zero")),
    ],
)
def test_an_environment_without_motion_is_refused(tmp_path, text, words):
    path = tmp_path / "empty.toml"
    path.write_text(text, encoding="utf-8")
    for argv in (("environment-drift", "--algorithm", "two-sample", "--sample-interval", "1e-3"), ("environment-rates", "--budget-deg-per-h", "0.5")):
        r = _cli(*argv, "--environment", str(path), check=False)
        assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1
        for w in words:
            assert w in r.stderr


def test_margin_two_is_refused_naming_the_option():
    r = _cli("environment-rates", "--environment", str(QUALIFICATION), "--budget-deg-per-h", "0.5", "--margin", "2", check=False)
    assert r.returncode == 2 and "--margin" in r.stderr and "factor" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_a_digital_cutoff_above_nyquist_is_refused_at_that_interval():
    r = _cli("environment-drift", "--algorithm", "two-sample", "--environment", str(QUALIFICATION), "--sample-interval", "1e-2", check=False)
    assert r.returncode == 2 and "Nyquist" in r.stderr and "Traceback" not in r.stderr


def test_a_violent_spectrum_is_flagged_outside_the_small_angle_range(tmp_path):
    path = tmp_path / "violent.toml"
    path.write_text("[[spectrum]]\nfreq_hz = [10.0, 100.0]\nwx = [1e6, 1e6]\nwy = [1e6, 1e6]\nwx_wy = [[0.0, -1e5], [0.0, -1e5]]\n", encoding="utf-8")
    r = _cli("environment-drift", "--algorithm", "two-sample", "--environment", str(path), "--sample-interval", "1e-3")
    assert "warning: outside the small-angle range" in r.stderr
    quiet = Environment((coning_line(10.0, 0.001),))
    assert theory_warnings(quiet, 1e-3) == ()  # a modest motion is inside: the check can say either


# --------------------------------------------------------------------------- 4. claims
def _sensor_part(channel, freq):
    env = Environment(tuple(coning_line(f, 1e-4) for f in freq), gyro=Sensor((channel,) * 3))
    d = environment_drift(get("two-sample"), env, 1e-4)
    return np.array([p.sensor @ d.coning_axis for p in d.parts if p.kind == "line"]) / np.array([p.true_coning @ d.coning_axis for p in d.parts if p.kind == "line"])


@pytest.mark.parametrize(
    ("channel", "slope"),
    [
        (ChannelFilter(analog_filter("lowpass1", cutoff_hz=100.0)), 2.0),
        (ChannelFilter(analog_filter("bessel", cutoff_hz=100.0, order=2)), 2.0),
        (ChannelFilter(analog_filter("butterworth", cutoff_hz=100.0, order=2)), 4.0),
        (ChannelFilter(digital=digital_filter("butterworth", cutoff_hz=92.0, order=2)), 4.0),
    ],
)
def test_pseudo_coning_grows_as_the_filter_family_says(channel, slope):
    # identical filters: the sensor part is (1 − |H|²) of the true coning; 1 − |H|² ~ (ω/ω_c)² unless the filter is maximally flat
    f = np.array([1.0, 2.0])
    ratio = _sensor_part(channel, f)
    assert math.log(ratio[1] / ratio[0], 2) == pytest.approx(slope, abs=0.05)


def test_a_resonant_filter_gives_negative_pseudo_coning():
    wn, zeta = 2 * math.pi * 100.0, 0.2
    resonant = ChannelFilter(analog_filter("transfer_function", num=[wn**2], den=[1.0, 2 * zeta * wn, wn**2]))
    assert _sensor_part(resonant, np.array([60.0]))[0] < 0  # |H| > 1 there: the sensed motion cones more than the true one


# --------------------------------------------------------------------------- 5. noise through the algorithm
NOISE_ENV = Environment(
    (coning_line(30.0, math.radians(0.5)), VibrationLine(70.0, [0.1, 0.05j, 0.02, 0, 0, 0])),
    gyro=Sensor((ChannelFilter(analog_filter("lowpass1", cutoff_hz=100.0)),) * 3),
)


@pytest.mark.parametrize("name", ["two-sample", "optimal-3", "savage-1+1"])
def test_noise_through_the_algorithm_agrees_with_the_monte_carlo(name):
    noise = SensorNoise(angle_random_walk=1e-3, quantization=3e-4)
    closed = noise_through_algorithm(get(name), NOISE_ENV, 1e-3, noise)
    mc = noise_monte_carlo(get(name), NOISE_ENV, 1e-3, noise, realisations=400, steps=200, rng=20261203)
    q = float(np.trace(closed.random_walk))
    assert abs(mc.random_walk_trace - q) <= 3.0 * mc.random_walk_trace_standard_error
    assert np.all(np.abs(mc.mean - closed.mean) <= 3.0 * mc.mean_standard_error)
    # the check can fail: twice the variance (a wrong model) lies far outside the interval
    assert abs(mc.random_walk_trace - 2 * q) > 3.0 * mc.random_walk_trace_standard_error


def test_noise_products_dominate_below_the_crossover_time():
    noise = SensorNoise(angle_random_walk=1e-3)
    r = noise_through_algorithm(get("two-sample"), NOISE_ENV, 1e-3, noise)
    t = r.crossover_time
    assert 0 < t < math.inf
    assert r.products_dominate(0.5 * t) and not r.products_dominate(2.0 * t)
