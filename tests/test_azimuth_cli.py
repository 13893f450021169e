"""``strapdown azimuth`` and ``strapdown azimuth-design``."""

import json
import math

import pytest

from strapdown.analysis.cli import main
from strapdown.analysis.gyrocompass.admissible_rocking import admissible_amplitude


def _run(capsys, argv):
    code = main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_azimuth_json_keys_and_values(capsys):
    code, out, err = _run(capsys, ["azimuth", "--lat-deg", "60", "--sigma-xi-deg", "0.5", "--sigma-eta-deg", "0.5", "--samples", "200000", "--seed", "1", "--json"])
    assert code == 0
    d = json.loads(out)
    for key in ("rms_error_deg", "rms_ci_deg", "mean_error_deg", "bound14_deg", "bound15_deg"):
        assert key in d
    lo, hi = d["rms_ci_deg"]
    assert lo < d["rms_error_deg"] < hi
    assert d["bound15_deg"] == pytest.approx(math.sqrt(3) * 0.5)
    assert lo < d["theory_rms_second_order_deg"] < hi


def test_sine_sigma_is_standard_deviation(capsys):
    """For sine rocking SX is the standard deviation (amplitude SX·√2): rms ≈ tan φ · SX at small SX."""
    code, out, _ = _run(capsys, ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "0.01", "--sigma-eta-deg", "0", "--rocking", "sine", "--samples", "100000", "--json"])
    d = json.loads(out)
    lo, hi = d["rms_ci_deg"]
    assert lo < 0.01 < hi  # with amplitude SX the rms would be 0.01/√2
    assert hi < 0.0105


@pytest.mark.parametrize(
    "extra, needle",
    [
        (["--lat-deg", "90"], "lat-deg"),
        (["--lat-deg", "-95"], "lat-deg"),
        (["--lat-deg", "nan"], "lat-deg"),
        (["--lat-deg", "45", "--sigma-xi-deg", "-0.1"], "sigma-xi-deg"),
        (["--lat-deg", "45", "--sigma-eta-deg", "nan"], "sigma-eta-deg"),
        (["--lat-deg", "45", "--samples", "1"], "samples"),
    ],
)
def test_bad_input_exit_2(capsys, extra, needle):
    argv = ["azimuth", "--sigma-xi-deg", "0.1", "--sigma-eta-deg", "0.1"] + extra
    code, out, err = _run(capsys, argv)
    assert code == 2
    assert needle in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_design_json(capsys):
    code, out, _ = _run(capsys, ["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "60", "--points", "5", "--json"])
    assert code == 0
    d = json.loads(out)
    assert len(d["amplitude_deg"]) == 5
    # narrow-band rocking: faster rocking averages out better
    assert all(b > a for a, b in zip(d["amplitude_deg"], d["amplitude_deg"][1:]))


@pytest.mark.parametrize("extra", [["--budget-deg", "0"], ["--budget-deg", "0.1", "--lat-deg", "90"], ["--budget-deg", "0.1", "--freq-min-hz", "1", "--freq-max-hz", "0.5"]])
def test_design_bad_input(capsys, extra):
    argv = ["azimuth-design", "--lat-deg", "45"] + extra if "--lat-deg" not in extra else ["azimuth-design"] + extra
    code, _, err = _run(capsys, argv)
    assert code == 2 and err.count("\n") == 1


def test_design_amplitude_meets_budget_at_first_order():
    """At the first-order admissible amplitude the first-order alignment rms equals the budget."""
    budget, lat, T = math.radians(0.05), math.radians(50), 30.0
    d = admissible_amplitude(budget, lat, T, [0.1], rocking="narrowband")
    a = d.amplitude_first_order[0]
    assert math.tan(lat) * a / math.sqrt(2) * math.sqrt(d.variance_factor[0]) == pytest.approx(budget, rel=1e-12)


@pytest.mark.parametrize(
    "extra, needle",
    [
        (["--period", "5"], "--period does not apply to --rocking normal"),
        (["--rocking", "sine", "--damping", "0.2"], "--damping does not apply to --rocking sine"),
        (["--rocking", "sine", "--sigma-xi-deg", "70"], "--sigma-xi-deg <= 63.64 deg"),
        (["--beta0-deg", "30", "--sigma-eta-deg", "20"], "--sigma-eta-deg <= 15 deg"),
    ],
)
def test_options_outside_the_model_exit_2(capsys, extra, needle):
    argv = ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "0.1", "--sigma-eta-deg", "0.1", "--samples", "1000"] + extra
    code, out, err = _run(capsys, argv)
    assert code == 2 and out == ""
    assert needle in err and len(err.strip().splitlines()) == 1


def test_design_percentile_and_exact_phase(capsys):
    base = ["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "60", "--points", "6", "--rocking", "sine", "--json"]
    _, out, _ = _run(capsys, base)
    env = json.loads(out)
    _, out, _ = _run(capsys, base + ["--exact-phase"])
    exact = json.loads(out)
    assert env["envelope_over_phase"] and not exact["envelope_over_phase"]
    assert all(a <= b * (1 + 1e-12) for a, b in zip(env["amplitude_deg"], exact["amplitude_deg"]))  # the envelope is the worst case
    assert all(p <= a for p, a in zip(env["amplitude_percentile_deg"], env["amplitude_first_order_deg"]))
