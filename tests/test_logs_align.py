"""Alignment of recorded logs: the filter's histories and its NIS test, the compass loop, the
multi-position alignment and the GNSS-aided in-motion alignment, each on a synthetic log with a known truth."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from strapdown.analysis import cli
from strapdown.analysis.alignment.aided import AidedTuning
from strapdown.analysis.alignment.earth import EARTH_RATE, normal_gravity
from strapdown.analysis.alignment.fine import FilterTuning
from strapdown.analysis.alignment.tilt_attitude import angles_from_matrix, attitude_matrix
from strapdown.analysis.alignment.trajectory import Manoeuvre
from strapdown.analysis.logs.alignment import align_log
from strapdown.analysis.logs.imu_log import ImuLog
from strapdown.analysis.logs.native import write_log
from strapdown.analysis.logs.reader import read_imu_log
from strapdown.analysis.logs.synthetic import still_truth, turntable_truth, vehicle_truth, write_synthetic

LAT = math.radians(45.0)
DEG_H = math.radians(1.0) / 3600.0  # 1 deg/h [rad/s]
ARW = math.radians(0.01) / 60.0  # 0.01 deg/√h [rad/√s]
VRW = 0.01 / 60.0  # 0.01 m/s/√h [m/s/√s]


def _wrap(x):
    return (x + math.pi) % (2.0 * math.pi) - math.pi


def _with_errors(truth, *, gyro_bias=(0.0, 0.0, 0.0), accel_bias=(0.0, 0.0, 0.0), arw=0.0, vrw=0.0, seed=0):
    """The truth's increments with constant biases and white noise (angle and velocity random walk) added."""
    rng = np.random.default_rng(seed)
    h = truth.interval
    dth = truth.dtheta + np.asarray(gyro_bias) * h + arw * math.sqrt(h) * rng.standard_normal(truth.dtheta.shape)
    dv = truth.dv + np.asarray(accel_bias) * h + vrw * math.sqrt(h) * rng.standard_normal(truth.dv.shape)
    return replace(truth, dtheta=dth, dv=dv)


def _still(tmp_path, *, heading=0.4, duration=240.0, rate=20.0, name="still.npz", **errors):
    truth = _with_errors(still_truth(duration, rate, latitude=LAT, heading=heading), **errors)
    meta = {"latitude": LAT, "end_heading": heading, "end_beta": 0.0, "end_gamma": 0.0, "stable_heading": heading, "stable_beta": 0.0, "stable_gamma": 0.0}
    return write_log(tmp_path / name, ImuLog(truth.time, truth.dtheta, truth.dv, meta))


# --------------------------------------------------------------------------- histories and the NIS test
def test_the_nis_test_passes_a_filter_that_knows_the_noise_and_fails_one_that_does_not(tmp_path):
    """Kalman on a still log with ARW and VRW: told the true noise its NIS stays in the band; told a tenth of it, it does not."""
    log = read_imu_log(_still(tmp_path, arw=ARW, vrw=VRW, seed=3)).longest
    right = FilterTuning(gyro_noise=ARW, accel_noise=VRW, measurement_noise=1e-5)
    r = align_log(log, LAT, method="kalman", tuning=right, calibration_trials=16)
    h = r.history
    E = h.times.size
    assert h.sigma.shape == (E, 3) and h.innovation.shape == (E, 3) and h.gyro_bias.shape == (E, 3) and h.bias_frame == "NED"
    assert h.nis_consistent, (h.block_nis, h.band)
    assert abs(h.mean_nis / 3.0 - 1.0) < 0.15  # E(NIS) = m = 3 where the model fits
    np.testing.assert_allclose(h.sigma[-1, 2], r.heading_sigma)
    assert np.all(np.diff(h.sigma[:, 2]) <= 1e-12)  # the azimuth σ only falls at rest
    assert abs(r.heading_error) < 3.0 * r.heading_sigma
    wrong = align_log(log, LAT, method="kalman", tuning=replace(right, gyro_noise=0.1 * ARW, accel_noise=0.1 * VRW), calibration_trials=16)
    assert not wrong.history.nis_consistent and wrong.history.mean_nis > wrong.history.band[1]


def test_align_log_prints_the_histories_and_warns_when_nis_leaves_its_band(tmp_path, capsys):
    path = _still(tmp_path, arw=ARW, vrw=VRW, seed=3)
    base = ["align", "--method", "kalman", "--lat-deg", "45", "--log", str(path), "--velocity-noise-m-s", "1e-5"]
    fig = tmp_path / "history.png"
    assert cli.main(base + ["--arw-deg-per-rt-h", "0.01", "--vrw-m-s-per-rt-h", "0.01", "--json", "--figure", str(fig)]) == 0
    out = capsys.readouterr()
    data = json.loads(out.out)
    h = data["history"]
    n = len(h["times"])
    assert n == len(h["sigma_azimuth_deg"]) == len(h["nis"]) == len(h["gyro_bias_deg_per_h"]) == len(h["innovation_m_s"])
    assert h["innovation_names"] == ["v_N", "v_E", "v_D"] and h["bias_frame"] == "NED" and h["nis_dof"] == 3
    assert h["nis_consistent"] is True and "NIS" not in out.err
    assert h["sigma_azimuth_deg"][-1] == pytest.approx(data["heading_sigma_deg"])
    assert fig.stat().st_size > 10_000 and not list(tmp_path.glob(".*.partial"))
    assert cli.main(base + ["--arw-deg-per-rt-h", "0.001", "--vrw-m-s-per-rt-h", "0.001"]) == 0
    out = capsys.readouterr()
    assert "σ azim" in out.out and "outside" in out.out
    warnings = [line for line in out.err.splitlines() if "NIS" in line]
    assert len(warnings) == 1 and "above" in warnings[0], out.err


# --------------------------------------------------------------------------- the compass loop
def test_the_compass_loop_on_a_log_settles_at_its_gyro_bias_floor(tmp_path, capsys):
    """A still log with an east gyro bias: the loop settles where φ_D = ε_E/(Ω cos φ) (Titterton & Weston 10.3.2), the closed form.

    The azimuth error is ψ̂ − ψ = −φ_D (``C̃ = (I − [φ×]) C``), so the heading comes out ε_E/(Ω cos φ) short.
    """
    heading = 0.3
    bias_e = 0.2 * DEG_H  # the gyro bias resolved in NED points east
    body = attitude_matrix([heading, 0.0, 0.0]).T @ np.array([0.0, bias_e, 0.0])
    path = _still(tmp_path, heading=heading, duration=900.0, rate=10.0, gyro_bias=body)
    floor = bias_e / (EARTH_RATE * math.cos(LAT))
    assert cli.main(["align", "--method", "compass", "--lat-deg", "45", "--log", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["method"] == "compass" and data["reference"] == "attitude at the end"
    assert math.radians(data["heading_error_deg"]) == pytest.approx(-floor, rel=0.05), (data["heading_error_deg"], math.degrees(floor))
    ideal = align_log(read_imu_log(_still(tmp_path, heading=heading, duration=900.0, rate=10.0, name="ideal.npz")).longest, LAT, method="compass")
    assert abs(ideal.heading_error) < 0.05 * floor  # without the bias the loop settles at the truth: the floor is the bias's
    assert cli.main(["align", "--method", "compass", "--lat-deg", "45"]) == 2
    assert "--log" in capsys.readouterr().err


# --------------------------------------------------------------------------- multi-position
def _turntable(tmp_path, headings, *, seed=1):
    truth, _ = turntable_truth(headings, dwell=120.0, turn=10.0, rate=20.0, latitude=LAT, beta=0.01, gamma=-0.02)
    bg, ba = np.array([1.0, -0.8, 0.3]) * DEG_H, np.array([3e-4, -2e-4, 1e-4])
    noisy = _with_errors(truth, gyro_bias=bg, accel_bias=ba, arw=0.2 * ARW, vrw=0.5 * VRW, seed=seed)
    return write_synthetic(tmp_path / f"table{len(headings)}.npz", noisy), bg, ba


def test_multiposition_separates_the_biases_that_one_position_cannot(tmp_path, capsys):
    headings = [0.5, 0.5 + math.pi]
    path, bg, ba = _turntable(tmp_path, headings)
    log = read_imu_log(path).longest
    r = align_log(log, LAT, method="multiposition", tuning=FilterTuning(gyro_noise=0.2 * ARW, accel_noise=0.5 * VRW))
    mp = r.multiposition
    assert len(mp.positions) == 2 and math.degrees(mp.positions[1].angle) == pytest.approx(180.0, abs=0.01)
    truth = angles_from_matrix(attitude_matrix([headings[0], 0.01, -0.02]))
    sd = np.sqrt(np.diag(mp.covariance))
    assert abs(_wrap(r.heading - float(truth.heading))) < 3.0 * r.heading_sigma
    assert abs(r.beta - 0.01) < 3.0 * r.tilt_sigma[0] + 1e-6 and abs(r.gamma + 0.02) < 3.0 * r.tilt_sigma[1] + 1e-6
    assert np.all(np.abs(mp.gyro_bias - bg) < 3.0 * sd[3:6]) and np.all(np.abs(mp.accel_bias - ba) < 3.0 * sd[6:9] + 1e-9)
    # the analytic alignment of the first position alone carries the bias floor, many σ away
    p0 = mp.positions[0]
    one = align_log(replace(log, time=log.time[p0.start : p0.end], dtheta=log.dtheta[p0.start : p0.end], dv=log.dv[p0.start : p0.end]), LAT, method="analytic")
    assert abs(_wrap(one.heading - headings[0])) > 5.0 * r.heading_sigma
    assert cli.main(["align", "--method", "multiposition", "--lat-deg", "45", "--log", str(path), "--arw-deg-per-rt-h", "0.002", "--vrw-m-s-per-rt-h", "0.005", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["reference"] == "attitude of the first position" and len(data["positions"]) == 2
    assert data["heading_deg"] == pytest.approx(math.degrees(r.heading), abs=1e-9) and len(data["gyro_bias_deg_per_h"]) == 3


def test_multiposition_refuses_a_log_in_one_position(tmp_path, capsys):
    path = _still(tmp_path)
    assert cli.main(["align", "--method", "multiposition", "--lat-deg", "45", "--log", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "at least two positions" in err[0]


# --------------------------------------------------------------------------- GNSS-aided, in motion
_SV, _SP = 0.05, 1.0  # GNSS noise written into the log [m/s, m]


def _drive(tmp_path, suffix, *, seed=4, duration=150.0):
    man = Manoeuvre(latitude=LAT, heading=0.6, speed=10.0, start_speed=5.0, run_up=20.0, weave_amplitude=math.radians(20.0), weave_period=30.0)
    truth, end = vehicle_truth(man, duration=duration, rate=50.0)
    noisy = _with_errors(truth, gyro_bias=np.array([0.5, -0.3, 0.2]) * DEG_H, accel_bias=[1e-3, -2e-3, 5e-4], arw=5 * ARW, vrw=5 * VRW, seed=seed)
    rng = np.random.default_rng(seed + 1)
    g = truth.gnss
    R = 6.378e6
    fixes = replace(
        g, latitude=g.latitude + _SP * rng.standard_normal(g.time.size) / R, longitude=g.longitude + _SP * rng.standard_normal(g.time.size) / (R * math.cos(LAT)),
        altitude=g.altitude + _SP * rng.standard_normal(g.time.size), velocity=g.velocity + _SV * rng.standard_normal(g.velocity.shape),
    )  # fmt: skip
    return write_synthetic(tmp_path / f"drive{suffix}", replace(noisy, gnss=fixes), gnss=True, held="increments"), end


@pytest.mark.parametrize("suffix", [".ulg", ".bin"])
def test_aided_alignment_of_a_drive_lands_within_its_sigma(tmp_path, suffix):
    """A weaving drive with biased, noisy sensors and noisy fixes: the heading at the end within 3σ of the filter's own σ.

    The tolerance is the filter's: a consistent filter leaves 3σ 0.3 % of the time, and the seeds are fixed.
    """
    path, end = _drive(tmp_path, suffix)
    rec = read_imu_log(path)
    assert rec.checks.passed and rec.inventory.gnss is not None and rec.inventory.gnss.velocity is not None
    tuning = AidedTuning(gyro_noise=5 * ARW, accel_noise=5 * VRW, gyro_bias=1.0 * DEG_H, accel_bias=3e-3, velocity_noise=_SV, position_noise=_SP)
    r = align_log(rec.longest, LAT, method="aided", gnss=rec.inventory.gnss, aided=tuning)
    err = _wrap(r.heading - float(end.heading[0]))
    assert r.heading_sigma < math.radians(0.2)
    assert abs(err) < 3.0 * r.heading_sigma, (math.degrees(err), math.degrees(r.heading_sigma))
    assert r.history.nis_consistent and r.history.innovation_names == ("v_N", "v_E", "v_D", "p_N", "p_E", "p_D")
    # a filter that trusts the fixes ten times too much is caught by its NIS
    tight = align_log(rec.longest, LAT, method="aided", gnss=rec.inventory.gnss, aided=replace(tuning, velocity_noise=0.1 * _SV, position_noise=0.1 * _SP))
    assert not tight.history.nis_consistent


def test_aided_on_the_command_line(tmp_path, capsys):
    path, end = _drive(tmp_path, ".ulg", seed=3, duration=90.0)
    argv = ["align", "--method", "aided", "--lat-deg", "45", "--log", str(path), "--arw-deg-per-rt-h", "0.05", "--vrw-m-s-per-rt-h", "0.05", "--gyro-bias-sigma-deg-per-h", "1",
            "--accel-bias-sigma-m-s2", "0.003", "--json"]  # fmt: skip
    assert cli.main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["history"]["innovation_names"][3:] == ["p_N", "p_E", "p_D"] and "innovation_m" in data["history"]
    assert abs(math.degrees(_wrap(math.radians(data["heading_deg"]) - float(end.heading[0])))) < 3.0 * data["heading_sigma_deg"]
    assert cli.main(argv[:-1] + ["--arw-deg-per-rt-h", "0", "--vrw-m-s-per-rt-h", "0"]) == 2  # no noise: refused
    assert "needs the sensor's noise" in capsys.readouterr().err
    still = _still(tmp_path)
    assert cli.main(["align", "--method", "aided", "--lat-deg", "45", "--log", str(still), "--arw-deg-per-rt-h", "0.05", "--vrw-m-s-per-rt-h", "0.05"]) == 2
    assert "GNSS" in capsys.readouterr().err


def test_a_drive_is_not_refused_by_the_gyro_scale_check(tmp_path):
    path, _ = _drive(tmp_path, ".ulg", duration=60.0)
    check = read_imu_log(path).checks.by_name("gyro scale")
    assert check.status == "skip" and "GNSS speed" in check.value
    assert normal_gravity(LAT) > 9.8


def test_aided_alignment_with_positions_only(tmp_path):
    """Fixes without velocity: the filter measures the position alone (three innovations) and still lands within 3σ."""
    path, end = _drive(tmp_path, ".ulg")
    rec = read_imu_log(path)
    fixes = replace(rec.inventory.gnss, velocity=None)
    tuning = AidedTuning(gyro_noise=5 * ARW, accel_noise=5 * VRW, gyro_bias=1.0 * DEG_H, accel_bias=3e-3, velocity_noise=_SV, position_noise=_SP)
    r = align_log(rec.longest, LAT, method="aided", gnss=fixes, aided=tuning)
    assert r.history.innovation_names == ("p_N", "p_E", "p_D") and r.history.dof == 3
    assert abs(_wrap(r.heading - float(end.heading[0]))) < 3.0 * r.heading_sigma
    with_velocity = align_log(rec.longest, LAT, method="aided", gnss=rec.inventory.gnss, aided=tuning)
    assert with_velocity.heading_sigma < r.heading_sigma  # the velocities add information


def test_a_one_position_method_warns_on_a_log_that_turns(tmp_path, capsys):
    path, _, _ = _turntable(tmp_path, [0.5, 0.5 + math.pi])
    assert cli.main(["align", "--method", "analytic", "--lat-deg", "45", "--log", str(path)]) == 0
    warnings = [line for line in capsys.readouterr().err.splitlines() if "positions" in line]
    assert len(warnings) == 1 and "2 positions" in warnings[0] and "180°" in warnings[0] and "multiposition" in warnings[0]
    assert cli.main(["align", "--method", "analytic", "--lat-deg", "45", "--log", str(_still(tmp_path))]) == 0
    assert "positions" not in capsys.readouterr().err
