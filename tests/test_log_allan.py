"""``strapdown log allan``: ARW, bias instability and RRW of a static log, with intervals, and the sensor file.

The static logs are drawn by the package's sensor-error simulation
(:func:`~strapdown.analysis.alignment.sensor_models.simulate_sensor_errors`) from a
known data sheet, whose flicker band reaches well below the sample interval and
above the record, so that the Allan deviation of the model is that of the data
sheet's three terms over the whole curve.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from strapdown.analysis import cli
from strapdown.analysis.alignment.sensor_models import SensorSpec, simulate_sensor_errors
from strapdown.analysis.core.units import DEG, DEG_PER_H_TO_RAD_PER_S, MICRO_G
from strapdown.analysis.logs.imu_log import ImuLog
from strapdown.analysis.logs.native import write_log
from strapdown.analysis.logs.sensor_file import read_sensor_file, write_sensor_file
from strapdown.analysis.logs.static_noise import static_noise

H = 0.5
N = 80_000  # 11 h at 2 Hz: the white, flicker and rate-random-walk regions all on the curve
GYRO = SensorSpec(0.05 * DEG / 60.0, 0.5 * DEG_PER_H_TO_RAD_PER_S, 0.77 * DEG_PER_H_TO_RAD_PER_S / 60.0, turn_on_bias=10 * DEG_PER_H_TO_RAD_PER_S, flicker_band=(0.05, 2e4))
ACCEL = SensorSpec(0.05 / 60.0, 10 * MICRO_G, 0.0, turn_on_bias=1e-3, flicker_band=(0.05, 2e4))
TRUTH = {("gyro", "random_walk"): GYRO.random_walk, ("gyro", "bias_instability"): GYRO.bias_instability, ("gyro", "rate_random_walk"): GYRO.rate_random_walk,
         ("accel", "random_walk"): ACCEL.random_walk, ("accel", "bias_instability"): ACCEL.bias_instability}  # fmt: skip


def _logs(trials: int, seed: int) -> list:
    g = simulate_sensor_errors(GYRO, n_trials=trials, n_samples=N, dt=H, rng=seed)
    a = simulate_sensor_errors(ACCEL, n_trials=trials, n_samples=N, dt=H, rng=seed + 1000)
    t = H * np.arange(1, N + 1)
    return [ImuLog(t, g.increments[k], a.increments[k] + np.array([0.0, 0.0, -9.80665 * H])) for k in range(trials)]


@pytest.fixture(scope="module")
def static_log():
    return _logs(1, 0)[0]


def test_each_coefficient_lies_in_its_interval(tmp_path, capsys, static_log):
    """Seeded static log with a known ARW, bias instability and RRW: each inside its 95 % interval (the coverage is checked below)."""
    log = static_log
    write_log(tmp_path / "static.npz", log)
    out = tmp_path / "imu.toml"
    assert cli.main(["log", "allan", str(tmp_path / "static.npz"), "--out", str(out), "--json", "--quiet"]) == 0
    data = json.loads(capsys.readouterr().out)
    sheet = read_sensor_file(out)
    for (table, attr), true in TRUTH.items():
        lo, hi = sheet.intervals[f"{table}.{attr}"]
        value = getattr(getattr(sheet.sheet, table), attr)
        assert lo <= true <= hi, (table, attr, lo / true, value / true, hi / true)
        assert lo > 0  # seen, not merely bounded
    g = data["gyro"]
    assert g["arw_deg_per_rt_h_ci95"][0] <= 0.05 <= g["arw_deg_per_rt_h_ci95"][1]
    assert g["bias_instability_deg_per_h_ci95"][0] <= 0.5 <= g["bias_instability_deg_per_h_ci95"][1]
    assert g["rrw_deg_per_h_per_rt_h_ci95"][0] <= 0.77 <= g["rrw_deg_per_h_per_rt_h_ci95"][1]
    assert data["accel"]["bias_instability_ug_ci95"][0] <= 10.0 <= data["accel"]["bias_instability_ug_ci95"][1]


def test_the_intervals_cover():
    """Eight independent logs: each coefficient's 95 % interval holds it in at least 6 of 8.

    With a true coverage of 95 % the chance of 5 or fewer in 8 is 0.6 %; the count is
    deterministic (seeded) and at 7 or 8 for every coefficient.
    """
    hits = dict.fromkeys(TRUTH, 0)
    for log in _logs(8, 1):
        r = static_noise(log)
        for (table, attr), true in TRUTH.items():
            c = getattr(getattr(r, table), attr)
            hits[(table, attr)] += c.low <= true <= c.high
    assert all(v >= 6 for v in hits.values()), hits


def test_a_term_the_record_does_not_show_is_bounded_from_zero():
    """White noise only: ARW read at the shortest τ; no bias instability or RRW seen, only bounds above zero."""
    rng = np.random.default_rng(4)
    n = 20_000
    log = ImuLog(0.01 * np.arange(1, n + 1), 1e-4 * math.sqrt(0.01) * rng.standard_normal((n, 3)), 1e-3 * math.sqrt(0.01) * rng.standard_normal((n, 3)))
    r = static_noise(log)
    assert r.gyro.random_walk.tau == pytest.approx(0.01)
    assert r.gyro.random_walk.low <= 1e-4 <= r.gyro.random_walk.high
    assert r.gyro.rate_random_walk.low == 0.0 and r.gyro.rate_random_walk.high > 0


def test_sensor_files_round_trip_and_refuse_bad_ones(tmp_path, static_log):
    r = static_noise(static_log)
    p = write_sensor_file(tmp_path / "imu.toml", r, name="bench")
    back = read_sensor_file(p)
    assert back.sheet.name == "bench"
    assert back.sheet.gyro.random_walk == pytest.approx(r.gyro.random_walk.value, rel=1e-12)
    assert back.sheet.accel.bias_instability == pytest.approx(r.accel.bias_instability.value, rel=1e-12)
    bad = {
        "unknown key": "[gyro]\narw_deg_per_rt_h = 0.1\nbogus = 1\n[accel]\nvrw_m_s_per_rt_h = 0.1\n",
        "missing arw": "[gyro]\n[accel]\nvrw_m_s_per_rt_h = 0.1\n",
        "negative": "[gyro]\narw_deg_per_rt_h = -0.1\n[accel]\nvrw_m_s_per_rt_h = 0.1\n",
        "interval without its value": "[gyro]\narw_deg_per_rt_h = 0.1\nrrw_deg_per_h_per_rt_h_ci95 = [0, 1]\n[accel]\nvrw_m_s_per_rt_h = 0.1\n",
        "interval not holding the value": "[gyro]\narw_deg_per_rt_h = 0.1\narw_deg_per_rt_h_ci95 = [0.2, 0.3]\n[accel]\nvrw_m_s_per_rt_h = 0.1\n",
        "no accel table": "[gyro]\narw_deg_per_rt_h = 0.1\n",
        "not TOML": "[gyro\n",
    }
    for label, text in bad.items():
        f = tmp_path / "bad.toml"
        f.write_text(text)
        with pytest.raises(ValueError, match="bad.toml"):
            read_sensor_file(f)
        assert label
    ok = tmp_path / "sheet.toml"
    ok.write_text("[gyro]\narw_deg_per_rt_h = 0.1\n[accel]\nvrw_m_s_per_rt_h = 0.06\nbias_instability_ug = 20\n")
    s = read_sensor_file(ok).sheet
    assert s.gyro.random_walk == pytest.approx(0.1 * DEG / 60.0)
    assert s.accel.bias_instability == pytest.approx(20 * MICRO_G)
    assert s.gyro.rate_random_walk == 0.0


def test_several_segments_are_refused(static_log):
    with pytest.raises(ValueError, match="one gap-free segment"):
        static_noise([static_log, static_log])
