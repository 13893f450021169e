"""``strapdown align``: keys, the theory it prints, and one-line errors with exit status 2."""

import json
import math

import pytest

from strapdown.analysis.cli import main


def _run(capsys, argv):
    code = main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


BASE = ["align", "--lat-deg", "60", "--duration", "30", "--sample-rate-hz", "10", "--trials", "64", "--seed", "1"]


def test_gyro_bias_floor_at_the_command_line(capsys):
    code, out, _ = _run(capsys, BASE + ["--method", "analytic", "--gyro-bias-deg-per-h", "0,0.01,0", "--arw-deg-per-rt-h", "0.0005", "--json"])
    assert code == 0
    d = json.loads(out)
    floor = -math.degrees(0.01 / (15.041067 * math.cos(math.radians(60.0))))  # b/(Ω cos φ) [rad] in deg, Ω = 15.041067 deg/h
    assert d["theory_gyro_bias_deg"] == pytest.approx(floor, rel=1e-6)
    lo, hi = d["azimuth_error_mean_ci_deg"]
    assert lo < d["theory_gyro_bias_deg"] < hi
    for key in ("azimuth_error_mean_deg", "azimuth_error_rms_deg", "azimuth_error_rms_ci_deg", "theory_rms_deg", "theory_accel_bias_deg", "theory_rocking_rms_deg", "theory_gyro_noise_rms_deg"):
        assert key in d


def test_kalman_prints_nees_and_nis(capsys):
    code, out, _ = _run(capsys, BASE + ["--method", "kalman", "--epoch", "0.5", "--gyro-bias-sigma-deg-per-h", "0.01", "--accel-bias-sigma-m-s2", "0.0005", "--json"])
    assert code == 0
    d = json.loads(out)
    assert len(d["nees"]["mean"]) == len(d["nees"]["times"]) and d["nees"]["dof"] == 12
    assert d["nis"]["dof"] == 3 and "theory_kalman_sigma_deg" in d


def test_rocking_and_tilt_channel_only(capsys):
    argv = BASE + ["--method", "analytic", "--rocking", "sine", "--amplitude-deg", "0,0.5,0.5", "--period", "7", "--tilt-channel-only", "--formula", "paper", "--json"]
    code, out, _ = _run(capsys, argv)
    d = json.loads(out)
    assert code == 0 and d["rocking_in_gyros"] is False
    lo, hi = d["azimuth_error_rms_ci_deg"]
    assert lo < d["theory_rocking_rms_deg"] < hi


@pytest.mark.parametrize(
    "extra, needle",
    [
        (["--method", "analytic", "--period", "5"], "--period does not apply to --rocking none"),
        (["--method", "analytic", "--rocking", "sine"], "--amplitude-deg is required"),
        (["--method", "inertial", "--formula", "paper"], "--formula does not apply to --method inertial"),
        (["--method", "analytic", "--rocking", "sine", "--amplitude-deg", "1", "--damping", "0.2"], "--damping does not apply to --rocking sine"),
        (["--method", "analytic", "--rocking", "sine", "--amplitude-deg", "95"], "amplitude-deg"),
        (["--method", "analytic", "--beta0-deg", "91"], "beta0-deg"),
        (["--method", "analytic", "--gyro-bias-deg-per-h", "1,2"], "gyro-bias-deg-per-h"),
        (["--method", "kalman", "--lever-arm", "x"], "lever-arm"),
        (["--method", "analytic", "--lat-deg", "90"], "lat-deg"),
        (["--method", "analytic", "--rocking", "white", "--amplitude-deg", "1", "--bandwidth-hz", "6"], "bandwidth-hz"),
    ],
)
def test_bad_input_exit_2(capsys, extra, needle):
    code, out, err = _run(capsys, BASE + extra)
    assert code == 2 and out == ""
    assert needle in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
