"""CLI: strapdown derive local-error, strapdown design, drift's asymptotic key."""

from __future__ import annotations

import json

import pytest

from strapdown.analysis.cli import main


def _json(capsys, argv):
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_local_error_json_table_2_algorithm_4(capsys):
    data = _json(capsys, ["derive", "local-error", "--algorithm", "panov-4s-4"])
    assert data["order"] == 4 and data["delta"] == "1/315"
    assert data["coefficients"] == {"x03": "52", "x12": "0", "x002": "448", "x110": "1344", "x0001": "-448"}
    assert data["latex"].startswith("\\delta\\varphi = \\frac{1}{315}")


def test_local_error_from_file(tmp_path, capsys):
    f = tmp_path / "alg.toml"
    f.write_text('name = "mine"\nsamples = 2\n[cross]\n"1,2" = "2/3"\n', encoding="utf-8")
    data = _json(capsys, ["derive", "local-error", "--algorithm-file", str(f)])
    assert data["algorithm"] == "mine" and data["order"] == 4 and data["delta"] == "1/90"


def test_local_error_unknown_algorithm_exit_2(capsys):
    assert main(["derive", "local-error", "--algorithm", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "nope" in err and "Traceback" not in err


def test_local_error_without_algorithm_exit_2(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["derive", "local-error"])
    assert exc.value.code == 2


def test_design_json_ranks_by_load(capsys):
    data = _json(capsys, ["design", "--required-drift-deg-per-h", "1e-3", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10"])
    loads = [r["load"] for r in data["ranking"]]
    assert loads == sorted(loads)
    row = {r["algorithm"]: r for r in data["ranking"]}["panov-4s-3"]
    assert row["order"] == 6 and row["step"] == pytest.approx(11.657e-3, rel=1e-3)


@pytest.mark.parametrize("flag, value", [("--required-drift-deg-per-h", "0"), ("--nutation-deg", "190"), ("--freq-hz", "nan")])
def test_design_bad_input(flag, value, capsys):
    argv = {"--required-drift-deg-per-h": "1e-3", "--eps": "-1", "--nutation-deg": "1", "--freq-hz": "10"}
    argv[flag] = value
    assert main(["design"] + [x for kv in argv.items() for x in kv]) == 2
    err = capsys.readouterr().err
    assert flag in err and err.count("\n") == 1  # the option as typed


def test_drift_reports_asymptotic_drift(capsys):
    data = _json(capsys, ["drift", "--algorithm", "panov-4s-1", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "2"])
    assert data["asymptotic_drift_deg_per_h"] == pytest.approx(2.51, rel=0.01)
