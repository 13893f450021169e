"""Recorded IMU logs: the formats, the example log, ``align --log`` and ``observability --log``."""

import json
import math
import runpy
from pathlib import Path

import numpy as np
import pytest

from strapdown.analysis import cli
from strapdown.analysis.alignment.imu import Scenario, simulate_imu
from strapdown.analysis.alignment.observability import observability
from strapdown.analysis.logs.alignment import align_log, recorded_problem
from strapdown.analysis.logs.examples import example_log
from strapdown.analysis.logs.imu_log import ImuLog
from strapdown.analysis.logs.native import read_log, write_log

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "docs" / "examples" / "rocking-imu-log.npz"


def _still_log(heading=0.4, duration=90.0, rate=20.0, seed=0):
    sc = Scenario(math.radians(45.0), heading=heading, duration=duration, sample_rate=rate)
    rec = simulate_imu(sc, None, n_trials=1, rng=seed)
    meta = {"latitude": sc.latitude, "stable_heading": heading, "stable_beta": 0.0, "stable_gamma": 0.0, "end_heading": heading, "end_beta": 0.0, "end_gamma": 0.0}
    return ImuLog(sc.dt * np.arange(1, sc.n_samples + 1), rec.dtheta[0], rec.dv[0], meta)


@pytest.mark.parametrize("suffix", [".npz", ".csv"])
def test_round_trip(tmp_path, suffix):
    log = _still_log(duration=5.0)
    back = read_log(write_log(tmp_path / f"log{suffix}", log))
    np.testing.assert_array_equal(back.time, log.time)
    np.testing.assert_array_equal(back.dtheta, log.dtheta)  # %.17g: exact
    np.testing.assert_array_equal(back.dv, log.dv)
    assert back.metadata == log.metadata


def test_rates_are_read_as_increments(tmp_path):
    log = _still_log(duration=2.0)
    h = log.dt
    p = tmp_path / "rates.csv"
    rows = np.column_stack([log.time, log.dtheta / h, log.dv / h])
    np.savetxt(p, rows, delimiter=",", header="time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z", comments="")
    back = read_log(p)
    np.testing.assert_allclose(back.dtheta, log.dtheta, rtol=1e-12)
    np.savez(tmp_path / "rates.npz", time=log.time, gyro=log.dtheta / h, accel=log.dv / h)
    np.testing.assert_allclose(read_log(tmp_path / "rates.npz").dv, log.dv, rtol=1e-12)


def test_bad_logs_are_refused(tmp_path):
    with pytest.raises(ValueError, match="constant sample interval"):
        ImuLog([0.1, 0.2, 0.4], np.zeros((3, 3)), np.zeros((3, 3)))
    with pytest.raises(ValueError, match="metadata"):
        ImuLog([0.1, 0.2], np.zeros((2, 3)), np.zeros((2, 3)), {"colour": 1.0})
    (tmp_path / "x.csv").write_text("time,a,b\n0.1,1,2\n0.2,1,2\n")
    with pytest.raises(ValueError, match="dtheta_x"):
        read_log(tmp_path / "x.csv")
    with pytest.raises(ValueError, match=".npz or .csv"):
        read_log(tmp_path / "x.txt")


@pytest.mark.parametrize("method", ["analytic", "inertial", "kalman", "compass"])
def test_every_method_aligns_a_still_log(method):
    log = _still_log(duration=120.0, rate=10.0)
    r = align_log(log, math.radians(45.0), method=method, coarse_duration=30.0, calibration_trials=16)
    # ideal sensors: the error left is the method's own (the filters and the loop have not converged in 90 s: 0.05°)
    assert abs(r.heading_error) < math.radians(0.05), (method, math.degrees(r.heading_error))


def test_the_example_log_is_the_script_output(tmp_path):
    runpy.run_path(str(ROOT / "tools" / "make_example_log.py"))["main"]([str(tmp_path / "log.npz")])
    made = read_log(tmp_path / "log.npz")
    assert made.metadata == example_log().metadata
    log = read_log(EXAMPLE)
    assert EXAMPLE.stat().st_size < 0.5e6
    np.testing.assert_array_equal(log.dtheta, made.dtheta)
    np.testing.assert_array_equal(log.dv, made.dv)
    np.testing.assert_array_equal(log.time, made.time)
    assert log.metadata == made.metadata


def test_align_runs_on_the_example_log(capsys):
    argv = ["align", "--method", "inertial", "--lat-deg", "45", "--log", str(EXAMPLE), "--json"]
    assert cli.main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["samples"] == 12000 and data["reference"] == "attitude at the end"
    assert abs(data["heading_error_deg"]) < 0.2
    assert cli.main(["align", "--method", "inertial", "--lat-deg", "45", "--log", str(EXAMPLE), "--rocking", "sine", "--amplitude-deg", "1"]) == 2
    assert "--rocking does not apply to a recorded log" in capsys.readouterr().err


def test_positions_of_a_recorded_motion():
    a = _still_log(heading=0.2, duration=100.0)
    b = _still_log(heading=0.2 + math.pi / 2, duration=100.0)
    turn = np.array([[0.0, 0.0, math.pi / 2]])  # one sample carrying the turn about the vertical
    dth = np.concatenate([a.dtheta, turn, b.dtheta])
    dv = np.concatenate([a.dv, a.dv[:1], b.dv])
    log = ImuLog(a.dt * np.arange(1, dth.shape[0] + 1), dth, dv)
    p = recorded_problem(log, math.radians(45.0))
    assert len(p.models) == 2 and observability(p).rank == 12
    one = recorded_problem(read_log(EXAMPLE), math.radians(45.0))
    assert len(one.models) == 1 and observability(one).rank == 9


def test_observability_cli(capsys):
    assert cli.main(["observability", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["rank"] == 9 and data["dim"] == 12 and data["lat_deg"] == 45.0
    assert data["pairs"] == [["north tilt", "east accelerometer bias"], ["east tilt", "north accelerometer bias"], ["azimuth", "east gyro bias"]]
    assert cli.main(["observability", "--model", "multi-position", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["rank"] == 12
    assert cli.main(["observability", "--log", str(EXAMPLE), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["rank"] == 9
    assert cli.main(["observability", "--model", "multi-position", "--rotation-times", "100,50"]) == 2
