"""ArduPilot's batch sampler (ISBH/ISBD) and raw GYR/ACC messages: read where the two sensors pair, explained where they cannot."""

import numpy as np
import pytest

from strapdown.analysis import cli
from strapdown.analysis.logs.reader import read_imu_log
from strapdown.analysis.logs.synthetic import BATCH_MULTIPLIERS, rocking_truth, write_synthetic


@pytest.fixture(scope="module")
def truth():
    return rocking_truth(duration=30.0, rate=50.0)  # bursts of 64 samples last 1.28 s: long enough for the checks' one-second windows


def _stream(log, topic):
    return next(s for s in log.inventory.streams if s.topic == topic)


def test_alternating_bursts_are_listed_with_the_reason_they_cannot_be_read(tmp_path, truth, capsys):
    path = write_synthetic(tmp_path / "alternating.bin", truth, held="rates", batch="alternating")
    log = read_imu_log(path)
    assert log.topic == "IMU[0]"  # bursts are never the default
    isb = _stream(log, "ISB[0]")
    assert not isb.readable and "in turn" in isb.note and "IMU[0]" in isb.note and "IMT[0]" in isb.note
    with pytest.raises(ValueError, match="no increments can be formed"):
        read_imu_log(path, topic="ISB[0]")
    assert cli.main(["log", "inspect", str(path), "--topic", "ISB[0]"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--topic" in err[0] and "in turn" in err[0]


def test_paired_bursts_give_the_truth_back_to_the_quantum(tmp_path, truth):
    path = write_synthetic(tmp_path / "paired.bin", truth, held="rates", batch="paired")
    log = read_imu_log(path, topic="ISB[0]")
    isb = _stream(log, "ISB[0]")
    assert isb.readable and log.held == "rates" and log.checks.passed
    n_bursts = truth.time.size // 64 // 4 + (1 if (truth.time.size // 64) % 4 else 0)
    assert len(log.segments) == n_bursts and log.n_samples == 64 * n_bursts
    h = truth.interval
    t0 = read_imu_log(path).segments[0].time[0]  # the log's first IMU sample: the truth's first
    for seg in log.segments:
        k = int(round((seg.time[0] - t0) / h))  # the burst's first sample in the truth
        assert np.allclose(seg.time - t0, truth.time[k : k + seg.n_samples] - truth.time[0], atol=1e-9)
        # int16 counts / mul: within half a quantum of the truth, plus the rate × interval round-off
        assert np.max(np.abs(seg.dtheta / seg.dt - truth.gyro[k : k + seg.n_samples])) <= 0.5 / BATCH_MULTIPLIERS["gyro"] + 1e-9
        assert np.max(np.abs(seg.dv / seg.dt - truth.accel[k : k + seg.n_samples])) <= 0.5 / BATCH_MULTIPLIERS["accel"] + 1e-9
        assert np.max(np.abs(seg.dtheta / seg.dt - truth.gyro[k : k + seg.n_samples])) > 1e-6  # really quantised: the test can fail


def test_raw_gyr_and_acc_pair_at_their_sample_times(tmp_path, truth):
    path = write_synthetic(tmp_path / "raw.bin", truth, held="rates", raw=True)
    log = read_imu_log(path, topic="GYRACC[0]")
    assert _stream(log, "GYRACC[0]").readable and len(log.segments) == 1
    np.testing.assert_allclose(log.segments[0].dtheta, truth.dtheta, rtol=1e-6, atol=1e-12)  # float32 in the log
    np.testing.assert_allclose(log.segments[0].dv, truth.dv, rtol=1e-6, atol=1e-12)
    assert {"GYR[0]", "ACC[0]"} <= {s.topic for s in log.inventory.streams}
