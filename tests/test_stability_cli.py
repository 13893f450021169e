"""CLI: strapdown stability, strapdown multistage, strapdown derive lyapunov."""

import json

import pytest

from strapdown.analysis.cli import main
from strapdown.derivations.multistage.published import PRINTED_GAINS

#: Stage-1 gains of section 5 of Plotnikov (1999).
K1, L1 = PRINTED_GAINS.stage1


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_stability_json(capsys):
    code, out, _ = run(capsys, "stability", "--k", str(K1), "--l", str(L1), "--json")
    data = json.loads(out)
    assert code == 0
    # s² + K1 s + L1 with K1² < 4 L1: poles −K1/2 ± i √(L1 − K1²/4)
    im = (L1 - K1**2 / 4) ** 0.5
    assert data["poles"] == [[pytest.approx(-K1 / 2), pytest.approx(-im)], [pytest.approx(-K1 / 2), pytest.approx(im)]]
    assert data["damping"] == [pytest.approx(K1 / (2 * L1**0.5))] * 2
    assert data["natural_frequency_rad_s"] == [pytest.approx(L1**0.5)] * 2
    assert data["stability"] == "asymptotically stable"
    assert data["peak_tilt_error_rad"] > 0.1
    assert data["g_m_s2"] == 9.81 and data["R_m"] == 6.371e6


def test_stability_schuler(capsys):
    code, out, _ = run(capsys, "stability", "--schuler", "--accel-m-s2", "5", "--accel-duration", "60", "--json")
    data = json.loads(out)
    assert code == 0 and data["peak_tilt_error_rad"] == 0.0 and data["stability"] == "marginal"
    assert data["l_per_s2"] == pytest.approx(9.81 / 6.371e6) and data["k_per_s"] == 0.0


@pytest.mark.parametrize("k,l", [(str(-K1), str(L1)), (str(K1), "-1e-5"), ("0", "0")])
def test_unstable_gains_are_an_error(capsys, k, l):
    code, out, err = run(capsys, "stability", f"--k={k}", f"--l={l}", "--json")
    assert code == 2 and out == "" and "stable loop" in err and "--k" in err and len(err.strip().splitlines()) == 1


def test_stability_design(capsys):
    code, out, _ = run(capsys, "stability", "--natural-frequency-rad-s", "0.005", "--damping", "0.7", "--reference", "tilt", "--json")
    data = json.loads(out)
    assert code == 0 and data["damping"] == [pytest.approx(0.7)] * 2 and data["natural_frequency_rad_s"] == [pytest.approx(0.005)] * 2
    assert data["design"] == {"reference": "tilt", "c": 1.0, "stage_k_per_s": pytest.approx(4 * 0.7 * 0.005), "stage_l_per_s2": pytest.approx(2 * 0.005**2)}


def test_stability_units_in_options(capsys):
    code, out, _ = run(capsys, "stability", "--schuler", "--gravity-m-s2", "9.8", "--earth-radius", "6.4e6", "--json")
    data = json.loads(out)
    assert code == 0 and data["l_per_s2"] == pytest.approx(9.8 / 6.4e6)


@pytest.mark.parametrize(
    "argv,match",
    [
        (["--k", "nan", "--l", "1e-5"], "argument --k: Expected `k` to be finite"),
        (["--k", "0.01", "--l", "inf"], "argument --l: Expected `l` to be finite"),
        (["--k", "fast", "--l", "1e-5"], "invalid float"),
        (["--k", "0.01"], "--l"),
        (["--k", "0.01", "--l", "1e-5", "--accel-duration", "0"], "argument --accel-duration: Expected `accel_duration` > 0"),
        (["--k", "0.01", "--l", "1e-5", "--horizon", "5"], "argument --horizon: Expected `horizon` >="),
        (["--schuler", "--k", "0.1"], "one of"),
        (["--schuler", "--earth-radius", "-1"], "argument --earth-radius: Expected `earth_radius` > 0"),
        (["--natural-frequency-rad-s", "0.01"], "both"),
        (["--natural-frequency-rad-s", "-0.01", "--damping", "0.5"], "argument --natural-frequency-rad-s: Expected `natural_frequency` > 0"),
    ],
)
def test_stability_bad_input(capsys, argv, match):
    try:
        code = main(["stability", *argv])
    except SystemExit as exc:  # argparse errors
        code = exc.code
    _, err = capsys.readouterr()
    assert code == 2 and match in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_derive_lyapunov(capsys):
    code, out, _ = run(capsys, "derive", "lyapunov", "--json")
    data = json.loads(out)
    assert code == 0 and data["Vdot"] == "-k*l*(z0**2 + z1**2 + z2**2 + z3**2)"
    assert data["V"].startswith("l*z0**2") and data["Vdot_equals_minus_l_k_z_zbar"] is True


def test_multistage_short(capsys):
    code, out, _ = run(capsys, "multistage", "--duration", "1300", "--step", "0.1", "--json")
    data = json.loads(out)
    assert code == 0 and len(data["stages"]) == 2
    assert data["stages"][0]["peak_pitch_error_rad"] > 5 * data["stages"][1]["peak_pitch_error_rad"]


def test_multistage_zero_length(capsys):
    code, _, err = run(capsys, "multistage", "--duration", "0")
    assert code == 2 and "argument --duration: Expected `duration` > 0" in err


@pytest.mark.parametrize("argv,match", [(["--lat-deg", "95"], "`--lat-deg` in (-90, 90) degrees"), (["--stage1-c", "0"], "`--stage1-c` > 0"), (["--step", "0.03"], "`step`")])
def test_multistage_bad_input(capsys, argv, match):
    code, _, err = run(capsys, "multistage", "--duration", "1300", *argv)
    assert code == 2 and match in err and len(err.strip().splitlines()) == 1


def test_multistage_readings(capsys):
    code, out, _ = run(capsys, "multistage", "--duration", "1300", "--step", "0.2", "--stage1-components", "all", "--switch", "bumpless", "--truth", "no-coriolis", "--json")
    data = json.loads(out)
    assert code == 0 and data["readings"]["stage1_components"] == [0, 1, 2, 3] and data["readings"]["truth"] == "no-coriolis"
    assert set(data["stages"][0]) == {"stage", "peak_yaw_error_rad", "peak_pitch_error_rad", "peak_roll_error_rad", "peak_tilt_error_rad"}
