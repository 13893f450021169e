"""CLI: strapdown derive local-error, strapdown design, drift's asymptotic key."""

from __future__ import annotations

import json

import pytest

from strapdown.analysis.cli import main
from strapdown.derivations.coning import published as P


def _json(capsys, argv):
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_local_error_json_table_2_algorithm_4(capsys):
    data = _json(capsys, ["derive", "local-error", "--algorithm", "panov-4s-4"])
    printed = {c.algorithm: c for c in P.BUDENNYI_TABLE_2}
    four, three = printed[4], printed[3]
    assert data["order"] == 4 and data["delta"] == str(four.delta)
    # Table 2 as printed, except its misprinted k002, k0001 (errata): δ4 k002 and δ4 k0001 are
    # common to every pairwise algorithm, so they are algorithm 3's products over algorithm 4's δ4.
    expected = list(four.k)
    for i in (2, 4):
        expected[i] = three.delta * three.k[i] / four.delta
    assert data["coefficients"] == {name: str(k) for name, k in zip(("x03", "x12", "x002", "x110", "x0001"), expected)}
    assert data["latex"].startswith(f"\\delta\\varphi = \\frac{{{four.delta.numerator}}}{{{four.delta.denominator}}}")


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
    printed = next(r for r in P.BUDENNYI_TABLE_3 if r.algorithm == 1 and r.eps == -1.0)  # the conditions of the run above
    assert data["asymptotic_drift_deg_per_h"] == pytest.approx(printed.u_a_deg_per_h, rel=0.01)


# ------------------------------------------------------------------ derive local-error --max-order
OPTIMAL_6_TOML = """name = "optimal-coning-6"
samples = 6
[cross]
"5,6" = "15797/4620"
"4,6" = "7834/4620"
"3,6" = "7296/4620"
"2,6" = "4558/4620"
"1,6" = "2315/4620"
"""
SAVAGE_TOML = 'name = "savage-1+1"\nsamples = 1\nreference = "Savage (1998)"\n[cross]\n"0,1" = "1/12"\n'


def test_local_error_to_h13_reaches_the_six_sample_coning_term(tmp_path, capsys):
    """--max-order 13: the coning drift the series implies for a 6-sample algorithm equals derive coning-drift."""
    f = tmp_path / "optimal6.toml"
    f.write_text(OPTIMAL_6_TOML, encoding="utf-8")
    data = _json(capsys, ["derive", "local-error", "--algorithm-file", str(f), "--max-order", "13"])
    assert data["max_order"] == 13 and data["order"] == 3 and data["nonzero_weights"] == list(range(4, 14))
    assert data["coning_drift_series"] == {"12": "1/24024"}
    closed = _json(capsys, ["derive", "coning-drift", "--algorithm-file", str(f)])
    assert (closed["order"], closed["coefficient"]) == (12, "1/24024")
    assert closed["step_coefficient"] == "1/52295018840064"  # Yan (PSINS), ρ_6


def test_local_error_default_order_is_seven(capsys):
    data = _json(capsys, ["derive", "local-error", "--algorithm", "two-sample"])
    assert data["max_order"] == 7 and data["coning_drift_series"] == {"4": "1/60", "6": "-1/504"}


@pytest.mark.parametrize("value", ["2", "21"])
def test_local_error_max_order_out_of_range_exit_2(value, capsys):
    assert main(["derive", "local-error", "--algorithm", "two-sample", "--max-order", value]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--max-order" in err and value in err


def test_local_error_cross_step_file(tmp_path, capsys):
    f = tmp_path / "savage.toml"
    f.write_text(SAVAGE_TOML, encoding="utf-8")
    data = _json(capsys, ["derive", "local-error", "--algorithm-file", str(f), "--max-order", "9"])
    assert (data["history"], data["order"], data["delta"], data["coefficients"]["x02"]) == (1, 3, "1/24", "1")
    assert data["coning_drift_series"] == {"4": "1/60", "6": "-1/504", "8": "1/8640"}


# ------------------------------------------------------------------ derive coning-drift
@pytest.mark.parametrize("name", ["two-sample", "optimal-3", "lebedev-panov-2", "lebedev-panov-4", "lebedev-panov-6"] + [f"panov-4s-{k}" for k in range(1, 6)])
def test_coning_drift_json_for_every_registry_algorithm(name, capsys):
    from strapdown.derivations.coning.drift import coning_drift
    from strapdown.derivations.coning.registry import get

    data = _json(capsys, ["derive", "coning-drift", "--algorithm", name])
    d = coning_drift(get(name))
    assert data["order"] == d.order and data["coefficient"] == f"{d.coefficient.numerator}/{d.coefficient.denominator}"
    assert "/" in data["coefficient"] and "exact minus algorithm" in data["quantity"] and "cone axis" in data["quantity"]


@pytest.mark.parametrize(
    "name, order, coefficient, step_coefficient",
    [
        # Ignagni (1990): two- and three-sample optimal algorithms, α² Ω (ΩT)^(2N) / C_N
        ("two-sample", 4, "1/60", "1/960"),
        ("optimal-3", 6, "1/280", "1/204120"),
    ],
)
def test_coning_drift_published_values(name, order, coefficient, step_coefficient, capsys):
    data = _json(capsys, ["derive", "coning-drift", "--algorithm", name])
    assert (data["order"], data["coefficient"], data["step_coefficient"]) == (order, coefficient, step_coefficient)


def test_coning_drift_cross_step_file_and_values(tmp_path, capsys):
    f = tmp_path / "savage.toml"
    f.write_text(SAVAGE_TOML, encoding="utf-8")
    data = _json(capsys, ["derive", "coning-drift", "--algorithm-file", str(f), "--omega-h-rad", "0.01,0.5"])
    assert (data["history"], data["order"], data["coefficient"]) == (1, 4, "1/60")
    small, large = data["values"]
    assert small["D"] == pytest.approx(small["leading"], rel=1e-4) and large["D"] < large["leading"]
    assert main(["derive", "coning-drift", "--algorithm-file", str(f)]) == 0
    text = capsys.readouterr().out
    assert "1/60 · α² ω (ωh)^4" in text and "lags" in text


@pytest.mark.parametrize(
    "argv, needle",
    [(["--algorithm", "nope"], "nope"), (["--algorithm", "two-sample", "--omega-h-rad", "-1"], "--omega-h-rad"), (["--algorithm", "two-sample", "--omega-h-rad", "a"], "--omega-h-rad")],
)
def test_coning_drift_bad_input_exit_2(argv, needle, capsys):
    assert main(["derive", "coning-drift"] + argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err and "Traceback" not in err
