"""CLI: strapdown derive local-error, strapdown design, drift's asymptotic key."""

from __future__ import annotations

import json
import math

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
    assert (data["accuracy_order"], data["local_error_order"]) == (4, 5) and data["delta"] == str(four.delta)
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
    assert data["algorithm"] == "mine" and data["accuracy_order"] == 4 and data["delta"] == "1/90"


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


@pytest.mark.parametrize("name, dominates", [("panov-4s-3", True), ("two-sample", True), ("savage-1+1", True), ("ignagni-1996-2", False)])
def test_drift_series_follows_the_simulation_where_the_leading_term_does_not(name, dominates, capsys):
    """The series through h^9 agrees with a 200-period parallel computation to 1e-3; u_a only where it dominates.

    ignagni-1996-2 at ϑ = 1°: its leading term (weight 5) is of fourth order in the nutation angle, the next one
    (weight 7, second order in ϑ) is 40 times larger at νH = 0.31 rad, so u_a understates the drift 40-fold.
    """
    argv = ["drift", "--algorithm", name, "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "20"]
    data = _json(capsys, argv)
    assert data["series_drift_deg_per_h"] == pytest.approx(data["simulated_drift_deg_per_h"], rel=1e-3)
    assert data["leading_term_dominates"] is dominates
    if not dominates:
        assert (data["leading_weight"], data["largest_term_weight"]) == (5, 7)
        assert data["asymptotic_drift_deg_per_h"] < 0.05 * data["series_drift_deg_per_h"]
        assert main(argv) == 0
        assert "the series is the drift to quote" in capsys.readouterr().out
    else:
        assert data["asymptotic_drift_deg_per_h"] == pytest.approx(data["series_drift_deg_per_h"], rel=0.1)


@pytest.mark.parametrize("name", ["savage-1+1", "ignagni-1996-1", "ignagni-1996-2", "ignagni-1996-3", "ignagni-1996-4", "ignagni-1996-5", "ignagni-1996-6", "ignagni-1996-7"])
def test_drift_series_of_cross_step_and_compressed_algorithms_equals_the_long_simulation(name, capsys):
    """Over 200 s (2000 spin periods) the slope has averaged out the periodic error: it equals the series through h^11 to 0.1 %."""
    argv = ["drift", "--algorithm", name, "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--max-order", "11"]
    data = _json(capsys, argv + ["--duration", "200"])
    assert data["series_drift_deg_per_h"] == pytest.approx(data["simulated_drift_deg_per_h"], rel=1e-3)
    assert data["simulation_matches_series"] is True


def test_a_run_too_short_to_resolve_the_drift_is_flagged(capsys):
    """ignagni-1996-4 over 2 s: a periodic error of 5e-9 rad against 3.5e-11 rad of drift biases the slope sevenfold."""
    argv = ["drift", "--algorithm", "ignagni-1996-4", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025"]
    short = _json(capsys, argv + ["--duration", "2"])
    assert short["simulation_matches_series"] is False and short["simulated_drift_deg_per_h"] > 5 * short["series_drift_deg_per_h"]
    assert short["periodic_error_rad"] > 50 * short["series_drift_deg_per_h"] / 3600 * math.pi / 180 * 2
    assert main(argv + ["--duration", "2"]) == 0
    assert "a longer --duration brings the two together" in capsys.readouterr().out


def test_drift_max_order_bounds_the_series(capsys):
    argv = ["drift", "--algorithm", "panov-4s-3", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1"]
    low = _json(capsys, argv + ["--max-order", "6"])
    # drift order 6 under coning: nothing through h^6 (the composition of the steps starts at weight 9)
    assert low["asymptotic_drift_deg_per_h"] is None and low["series_drift_deg_per_h"] == 0.0 and low["composition_drift_deg_per_h"] == 0.0
    assert low["series_weight"] == 6 and low["series_converged"] is None and low["exact_drift_deg_per_h"] > 0
    assert main(argv + ["--max-order", "2"]) == 2
    assert capsys.readouterr().err == "strapdown drift: error: Expected --max-order in 3..20, got 2\n"


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
    assert data["max_order"] == 13 and data["accuracy_order"] == 3 and data["nonzero_weights"] == list(range(4, 14))
    # every weight computed is printed, not only the leading one; letters of two digits are comma-separated
    assert [t["weight"] for t in data["series"]] == list(range(4, 14)) and data["series"][0]["coefficients"] == {k: v for k, v in data["coefficients"].items() if v != "0"}
    assert "x0,11" in data["series"][-1]["coefficients"] and all("," not in k for k in data["series"][5]["coefficients"])
    assert data["coning_drift_series"] == {"12": "1/24024"}
    closed = _json(capsys, ["derive", "coning-drift", "--algorithm-file", str(f)])
    assert (closed["coning_drift_order"], closed["coefficient"]) == (12, "1/24024")
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
    assert (data["history"], data["accuracy_order"], data["delta"], data["coefficients"]["x02"]) == (1, 3, "1/24", "1")
    assert data["coning_drift_series"] == {"4": "1/60", "6": "-1/504", "8": "1/8640"}


# ------------------------------------------------------------------ derive coning-drift
@pytest.mark.parametrize("name", ["two-sample", "optimal-3", "lebedev-panov-2", "lebedev-panov-4", "lebedev-panov-6"] + [f"panov-4s-{k}" for k in range(1, 6)])
def test_coning_drift_json_for_every_registry_algorithm(name, capsys):
    from strapdown.derivations.coning.drift import coning_drift
    from strapdown.derivations.coning.registry import get

    data = _json(capsys, ["derive", "coning-drift", "--algorithm", name])
    d = coning_drift(get(name))
    assert data["coning_drift_order"] == d.order and data["coefficient"] == f"{d.coefficient.numerator}/{d.coefficient.denominator}"
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
    assert (data["coning_drift_order"], data["coefficient"], data["step_coefficient"]) == (order, coefficient, step_coefficient)


def test_coning_drift_cross_step_file_and_values(tmp_path, capsys):
    f = tmp_path / "savage.toml"
    f.write_text(SAVAGE_TOML, encoding="utf-8")
    data = _json(capsys, ["derive", "coning-drift", "--algorithm-file", str(f), "--omega-h-rad", "0.01,0.5"])
    assert (data["history"], data["coning_drift_order"], data["coefficient"]) == (1, 4, "1/60")
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
