"""The reader of recorded IMU logs: every format with a known truth, the inventory, the checks, the refusals.

The truths are written by :mod:`strapdown.analysis.logs.synthetic`; the ULog and
DataFlash files are also read by pyulog and pymavlink, which share no code with
the writer or the reader.  Real PX4 logs are read where ``STRAPDOWN_REAL_LOGS``
names a folder holding them (``benchmarks/bench_logs.py`` reports on them).
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np
import pytest

from strapdown.analysis import cli
from strapdown.analysis.logs.imu_log import ImuLog
from strapdown.analysis.logs.inventory import StreamInfo
from strapdown.analysis.logs.native import read_log, write_log
from strapdown.analysis.logs.reader import read_imu_log
from strapdown.analysis.logs.streams import choose_topic
from strapdown.analysis.logs.synthetic import rocking_truth, still_truth, write_synthetic

LAT = math.radians(45.0)


@pytest.fixture(scope="module")
def rocking():
    return rocking_truth(duration=60.0, rate=200.0)


def _joined(log):
    return np.concatenate([s.dtheta for s in log.segments]), np.concatenate([s.dv for s in log.segments]), np.concatenate([s.time for s in log.segments])


FORMATS = [
    ("new.ulg", {}, 2e-7, "ulog"),
    ("old.ulg", {"layout": "old"}, 2e-7, "ulog"),
    ("rates.bin", {"held": "rates"}, 2e-7, "dataflash"),
    ("increments.bin", {}, 2e-7, "dataflash"),
    ("imu.bag", {}, 1e-8, "rosbag1"),
    ("ros2", {}, 1e-8, "rosbag2"),
    ("mav0/imu0/data.csv", {}, 1e-12, "euroc"),
    ("log.npz", {}, 0.0, "npz"),
    ("log.csv", {}, 0.0, "csv"),
    ("rates.npz", {"held": "rates"}, 1e-12, "npz"),
]


@pytest.mark.parametrize(("name", "options", "tol", "fmt"), FORMATS, ids=[f[0] for f in FORMATS])
def test_every_format_gives_the_truth_back(tmp_path, rocking, name, options, tol, fmt):
    path = write_synthetic(tmp_path / name, rocking, **options)
    log = read_imu_log(path, latitude=LAT)
    assert log.format == fmt and len(log.segments) == 1
    dth, dv, t = _joined(log)
    assert dth.shape == rocking.dtheta.shape
    # same increments, units and frame (FRD: at rest gravity reads -g on z), within the storage's round-off
    np.testing.assert_allclose(dth, rocking.dtheta, rtol=0, atol=tol * np.abs(rocking.dtheta).max() + 1e-300)
    np.testing.assert_allclose(dv, rocking.dv, rtol=0, atol=tol * np.abs(rocking.dv).max() + 1e-300)
    np.testing.assert_allclose(t - t[0], rocking.time - rocking.time[0], atol=1e-6)
    assert log.checks.passed, [c.line() for c in log.checks.failures]
    assert log.checks.by_name("gravity direction").status == "pass"
    assert log.checks.by_name("gyro scale").status == "pass"


def test_ulog_integration_interval_units_are_told_apart(tmp_path, rocking):
    new = read_imu_log(write_synthetic(tmp_path / "new.ulg", rocking, layout="new"))
    old = read_imu_log(write_synthetic(tmp_path / "old.ulg", rocking, layout="old"))
    assert new.inventory.timing.integration_interval_unit == "us" and old.inventory.timing.integration_interval_unit == "s"
    assert new.inventory.timing.integration_interval == pytest.approx(0.005) and old.inventory.timing.integration_interval == pytest.approx(0.005)
    np.testing.assert_allclose(_joined(new)[0], _joined(old)[0], rtol=1e-7)  # the old layout holds 5 ms as a float32


def test_the_synthetic_ulog_reads_the_same_in_pyulog(tmp_path, rocking):
    from pyulog import ULog

    path = write_synthetic(tmp_path / "a.ulg", rocking, gnss=True)
    u = ULog(str(path))
    d = u.get_dataset("sensor_combined").data
    gyro = np.stack([d[f"gyro_rad[{i}]"] for i in range(3)], axis=1).astype(float) * (d["gyro_integral_dt"] * 1e-6)[:, None]
    np.testing.assert_allclose(gyro, rocking.dtheta, rtol=0, atol=2e-7 * np.abs(rocking.dtheta).max())
    gps = u.get_dataset("vehicle_gps_position").data
    assert np.allclose(gps["latitude_deg"], 45.0)
    # pyulog's own writer, from what pyulog read: the package reads it to the same increments
    again = tmp_path / "again.ulg"
    u.write_ulog(str(again))
    np.testing.assert_array_equal(_joined(read_imu_log(again))[0], _joined(read_imu_log(path))[0])


def test_the_synthetic_dataflash_reads_the_same_in_pymavlink(tmp_path, rocking):
    from pymavlink import DFReader

    path = write_synthetic(tmp_path / "a.bin", rocking, held="rates", gnss=True)
    df = DFReader.DFReader_binary(str(path))
    rows = []
    while (m := df.recv_match(type="IMU")) is not None:
        rows.append((m.GyrX, m.GyrY, m.GyrZ, m.AccZ))
    rows = np.array(rows)
    assert rows.shape[0] == rocking.time.size
    np.testing.assert_allclose(rows[:, :3], rocking.gyro, rtol=0, atol=2e-7 * np.abs(rocking.gyro).max())
    log = read_imu_log(path, latitude=LAT)
    assert log.inventory.gnss is not None and math.degrees(log.inventory.gnss.mean_latitude) == pytest.approx(45.0, abs=1e-6)
    filters = {f.parameter: f for f in log.inventory.filters}
    assert filters["INS_GYRO_FILTER"].acts_on_samples is True  # the IMU message holds the filtered rates
    incr = read_imu_log(write_synthetic(tmp_path / "b.bin", rocking))
    assert {f.parameter: f for f in incr.inventory.filters}["INS_GYRO_FILTER"].acts_on_samples is False


def test_px4_filters_are_reported_as_not_acting_on_the_increments(tmp_path, rocking):
    log = read_imu_log(write_synthetic(tmp_path / "a.ulg", rocking))
    f = {x.parameter: x for x in log.inventory.filters}
    assert f["IMU_GYRO_CUTOFF"].value == 40.0 and f["IMU_GYRO_CUTOFF"].acts_on_samples is False
    assert "VehicleIMU" in f["IMU_GYRO_CUTOFF"].evidence


def test_rosbag_frame_is_turned_from_flu_to_frd(tmp_path, rocking):
    from rosbags.highlevel import AnyReader

    path = write_synthetic(tmp_path / "imu.bag", rocking)
    with AnyReader([path]) as reader:
        conn = reader.connections[0]
        first = reader.deserialize(next(reader.messages(connections=[conn]))[2], conn.msgtype)
    assert first.linear_acceleration.z > 9.0  # ROS: +g on z up at rest
    log = read_imu_log(path)
    assert log.segments[0].dv[0, 2] < 0 and "FLU" in log.inventory.frame


def test_a_gap_starts_a_new_segment_and_segment_selects(tmp_path):
    tr = still_truth(duration=40.0, rate=50.0)
    keep = (tr.time < 10.0) | (tr.time > 12.0)
    p = tmp_path / "gap.npz"
    np.savez(p, time=tr.time[keep], dtheta=tr.dtheta[keep], dv=tr.dv[keep])
    log = read_imu_log(p)
    assert len(log.segments) == 2 and len(log.inventory.timing.gaps) == 1
    gap = log.inventory.timing.gaps[0]
    assert gap.duration == pytest.approx(2.04, abs=1e-9) and gap.missing == 101  # from 9.98 s to 12.02 s
    assert log.checks.by_name("gaps").status == "warn"
    part = read_imu_log(p, segment=(20.0, 30.0))
    assert len(part.segments) == 1 and part.n_samples == 500
    with pytest.raises(ValueError, match="`segment`"):
        read_imu_log(p, segment=(5.0, 4.0))


def test_the_default_topic_is_the_fastest_that_covers_the_log():
    s = [
        StreamInfo("fast_but_short", 100, 1000.0, 0.0, 0.1, "increments", True),
        StreamInfo("sensor_combined", 25000, 250.0, 0.0, 100.0, "increments", True),
        StreamInfo("vehicle_imu", 200, 2.0, 0.0, 100.0, "increments", True),
        StreamInfo("vehicle_angular_velocity", 80000, 800.0, 0.0, 100.0, "rates", False, "filtered"),
    ]
    assert choose_topic(s, None, 100.0, "x").topic == "sensor_combined"
    assert choose_topic(s, "vehicle_imu", 100.0, "x").topic == "vehicle_imu"
    with pytest.raises(ValueError, match="IMU samples"):
        choose_topic(s, "vehicle_angular_velocity", 100.0, "x")
    with pytest.raises(ValueError, match="among the IMU streams"):
        choose_topic(s, "nope", 100.0, "x")


def test_a_truncated_npz_is_a_value_error_in_the_api(tmp_path):
    p = write_log(tmp_path / "log.npz", ImuLog(*_still_arrays()))
    cut = tmp_path / "cut.npz"
    cut.write_bytes(p.read_bytes()[: p.stat().st_size // 2])
    with pytest.raises(ValueError, match="truncated or corrupt"):
        read_log(cut)
    with pytest.raises(ValueError, match="truncated or corrupt"):
        read_imu_log(cut)


def _still_arrays():
    tr = still_truth(duration=5.0, rate=20.0)
    return tr.time, tr.dtheta, tr.dv


def test_a_truncated_ulog_reads_up_to_the_cut_and_says_so(tmp_path, rocking):
    p = write_synthetic(tmp_path / "a.ulg", rocking)
    cut = tmp_path / "cut.ulg"
    cut.write_bytes(p.read_bytes()[: p.stat().st_size - 17])
    log = read_imu_log(cut)
    assert log.n_samples == rocking.time.size - 1
    assert any("incomplete record" in n for n in log.inventory.notes)


def test_the_checks_pass_on_a_still_navigation_grade_log_and_find_the_latitude(tmp_path):
    tr = still_truth(duration=60.0, rate=50.0, heading=0.3, latitude=math.radians(52.0))
    log = read_imu_log(write_synthetic(tmp_path / "still.npz", tr), latitude=math.radians(52.0))
    assert log.checks.passed
    earth = log.checks.by_name("Earth rate")
    assert earth.status == "pass" and "+52" in earth.value
    wrong = log.recheck(latitude=math.radians(-52.0))  # metadata says +52
    assert wrong.checks.by_name("latitude").status == "fail"


def test_the_latitude_check_uses_the_gnss_fixes(tmp_path, rocking):
    p = write_synthetic(tmp_path / "a.ulg", rocking, gnss=True)
    assert read_imu_log(p, latitude=math.radians(45.01)).checks.by_name("latitude").status == "pass"
    assert read_imu_log(p, latitude=math.radians(47.0)).checks.by_name("latitude").status == "fail"


# --------------------------------------------------------------------------- bad logs at the command line
def _bad_logs(tmp_path):
    tr = rocking_truth(duration=120.0, rate=100.0)
    h = tr.interval
    good = write_synthetic(tmp_path / "good.npz", tr)
    bad = {}
    cut = tmp_path / "truncated.npz"
    cut.write_bytes(good.read_bytes()[: good.stat().st_size * 2 // 3])
    bad["truncated"] = (cut, "truncated or corrupt")
    p = tmp_path / "degrees.npz"
    np.savez(p, time=tr.time, dtheta=np.degrees(tr.dtheta), dv=tr.dv)
    bad["degrees for radians"] = (p, "'gyro scale' failed")
    p = tmp_path / "milliseconds.npz"
    np.savez(p, time=tr.time * 1e3, dtheta=tr.dtheta, dv=tr.dv)
    bad["milliseconds for seconds"] = (p, "'time base' failed")
    p = tmp_path / "zup.npz"
    flip = np.array([1.0, -1.0, -1.0])
    np.savez(p, time=tr.time, dtheta=tr.dtheta * flip, dv=tr.dv * flip)
    bad["z up"] = (p, "'gravity direction' failed")
    p = tmp_path / "rates.npz"
    np.savez(p, time=tr.time, dtheta=tr.dtheta / h, dv=tr.dv / h)
    bad["rates for increments"] = (p, "'increments or rates' failed")
    long = still_truth(duration=400.0, rate=20.0)
    keep = (long.time < 100.0) | (long.time > 280.0)
    p = tmp_path / "gap.npz"
    np.savez(p, time=long.time[keep], dtheta=long.dtheta[keep], dv=long.dv[keep])
    bad["a gap of minutes"] = (p, "'gaps' failed")
    return good, bad


def test_bad_logs_are_refused_with_one_line_naming_the_check(tmp_path, capsys):
    good, bad = _bad_logs(tmp_path)
    assert cli.main(["align", "--method", "analytic", "--lat-deg", "45", "--log", str(good), "--json"]) == 0
    capsys.readouterr()
    for what, (path, words) in bad.items():
        before = sorted(tmp_path.iterdir())
        figure = tmp_path / f"{path.stem}.png"
        status = cli.main(["align", "--method", "analytic", "--lat-deg", "45", "--log", str(path)])
        err = capsys.readouterr().err.strip()
        assert status == 2, (what, err)
        assert len(err.splitlines()) == 1 and words in err and "Traceback" not in err, (what, err)
        if what == "truncated":  # log inspect refuses a corrupt file too, and writes no figure
            assert cli.main(["log", "inspect", str(path), "--figure", str(figure)]) == 2
            capsys.readouterr()
        assert sorted(tmp_path.iterdir()) == before, what


def test_log_inspect_reports_the_inventory_and_draws(tmp_path, capsys, rocking):
    path = write_synthetic(tmp_path / "a.ulg", rocking, gnss=True)
    figure = tmp_path / "a.png"
    assert cli.main(["log", "inspect", str(path), "--json", "--figure", str(figure), "--lat-deg", "45"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["format"] == "ulog" and data["topic"] == "sensor_combined" and data["held"] == "increments"
    assert data["timing"]["integration_interval_unit_in_log"] == "us"
    assert data["samples"] == rocking.time.size and data["gnss"]["fixes"] > 0
    assert {c["name"]: c["status"] for c in data["checks"]}["latitude"] == "pass"
    assert figure.stat().st_size > 10_000
    assert cli.main(["log", "inspect", str(path), "--topic", "nope"]) == 2
    assert "--topic" in capsys.readouterr().err


def test_load_log_prints_warnings_and_still_reads(tmp_path, capsys):
    tr = still_truth(duration=40.0, rate=50.0)
    keep = (tr.time < 10.0) | (tr.time > 12.0)
    p = tmp_path / "gap.npz"
    np.savez(p, time=tr.time[keep], dtheta=tr.dtheta[keep], dv=tr.dv[keep])
    assert cli.main(["align", "--method", "analytic", "--lat-deg", "45", "--log", str(p), "--json"]) == 0
    out = capsys.readouterr()
    assert json.loads(out.out)["segments"] == 2
    assert "warning" in out.err and "'gaps' warns" in out.err


# --------------------------------------------------------------------------- the defects of the earlier log path
def test_observability_of_a_level_still_log_of_half_an_hour_is_rank_9(tmp_path, capsys):
    tr = still_truth(duration=1900.0, rate=10.0, heading=0.6)
    p = write_synthetic(tmp_path / "still.npz", tr)
    assert cli.main(["observability", "--log", str(p), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["segments"] == 1 and data["rank"] == 9


def test_kalman_on_a_log_refuses_zero_noise_and_takes_a_spec_file(tmp_path, capsys):
    tr = still_truth(duration=200.0, rate=10.0, heading=0.4)
    p = write_synthetic(tmp_path / "still.npz", tr)
    base = ["align", "--method", "kalman", "--lat-deg", "45", "--log", str(p), "--json"]
    assert cli.main(base) == 2
    assert "noise" in capsys.readouterr().err
    spec = tmp_path / "imu.toml"
    spec.write_text("[gyro]\narw_deg_per_rt_h = 0.002\nbias_instability_deg_per_h = 0.01\n\n[accel]\nvrw_m_s_per_rt_h = 0.006\nbias_instability_ug = 10\n")
    assert cli.main(base + ["--imu", str(spec)]) == 0
    first = json.loads(capsys.readouterr().out)
    assert cli.main(base + ["--imu", str(spec)]) == 0
    assert json.loads(capsys.readouterr().out)["heading_deg"] == first["heading_deg"]
    assert math.isclose(first["heading_deg"], math.degrees(0.4), abs_tol=0.05)
    zero = tmp_path / "zero.toml"
    zero.write_text("[gyro]\narw_deg_per_rt_h = 0\n[accel]\nvrw_m_s_per_rt_h = 0.006\n")
    assert cli.main(base + ["--imu", str(zero)]) == 2
    assert "arw" in capsys.readouterr().err


def test_align_on_a_log_does_not_depend_on_a_seed(tmp_path, capsys):
    from strapdown.analysis.logs.alignment import align_log

    tr = still_truth(duration=120.0, rate=10.0, heading=0.4)
    log = ImuLog(tr.time, tr.dtheta, tr.dv, {"end_heading": 0.4, "end_beta": 0.0, "end_gamma": 0.0})
    from strapdown.analysis.alignment.fine import FilterTuning

    tuning = FilterTuning(gyro_noise=1e-6, accel_noise=1e-4)
    a = align_log(log, LAT, method="kalman", tuning=tuning, coarse_duration=30.0, calibration_trials=16)
    b = align_log(log, LAT, method="kalman", tuning=tuning, coarse_duration=30.0, calibration_trials=16)
    assert a == b
    p = write_synthetic(tmp_path / "still.npz", tr)
    assert cli.main(["align", "--method", "kalman", "--lat-deg", "45", "--log", str(p), "--arw-deg-per-rt-h", "0.002", "--vrw-m-s-per-rt-h", "0.006", "--seed", "3"]) == 2
    assert "--seed does not apply to a recorded log" in capsys.readouterr().err


# --------------------------------------------------------------------------- real logs, where given
REAL = os.environ.get("STRAPDOWN_REAL_LOGS")


@pytest.mark.skipif(not REAL or not Path(REAL).is_dir(), reason="STRAPDOWN_REAL_LOGS names no folder of real logs")
def test_real_px4_logs_read_and_their_interval_units_differ():
    units = {}
    for path in sorted(Path(REAL).glob("*.ulg")):
        log = read_imu_log(path)
        assert log.n_samples > 100 and log.topic == "sensor_combined"
        units[path.name] = log.inventory.timing.integration_interval_unit
    assert {"s", "us"} <= set(units.values()), units
