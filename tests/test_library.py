"""The library of published algorithms: data, published figures, cross-step runs, the algorithms CLI."""

from __future__ import annotations

import json
import re
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from strapdown.analysis.cli import main
from strapdown.analysis.coning.algorithm_summary import summarize
from strapdown.analysis.coning.evaluation import increment
from strapdown.analysis.coning.papers.published_check import coefficient_checks, coning_coefficient, coning_coefficient_checks, coning_drift_orders
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import sample_increments, simulate, step_windows, window_index
from strapdown.analysis.core import quaternion as quat
from strapdown.derivations.coning.algorithms import Algorithm, Term, load_toml, second_order_defect
from strapdown.derivations.coning.polynomial_fit import polynomial_fit_coefficients
from strapdown.derivations.coning.published import PSINS_TABLE_10_1_N6, PUBLISHED_ALGORITHM_COEFFICIENTS, PUBLISHED_ALGORITHM_ERRORS
from strapdown.derivations.coning.registry import COMPRESSED_TABLE, get, names

DOCS = Path(__file__).resolve().parents[1] / "docs" / "algorithm-files.md"


# --------------------------------------------------------------------------- registry data
def test_every_entry_is_exact_and_cited():
    for name in names(library=True):
        alg = get(name)
        assert alg.reference, name
        assert all(isinstance(t.coefficient, Fraction) for t in alg.terms), name
        expected = {"one-sample": -Fraction(1, 12), "lebedev-panov-2": -Fraction(16, 3)}.get(name, Fraction(0))
        assert second_order_defect(alg) == expected, name


def test_paper_set_is_unchanged_and_library_is_larger():
    paper = ["two-sample", "optimal-3", "lebedev-panov-2", "lebedev-panov-4", "lebedev-panov-6"] + [f"panov-4s-{k}" for k in range(1, 6)]
    assert names() == paper
    library = names(library=True)
    assert set(paper) < set(library)
    assert {"savage-1+1", "miller-3", "polynomial-3", "polynomial-4", "polynomial-5"} | {f"compressed-{n}" for n in range(2, 7)} | {f"ignagni-1996-{k}" for k in range(1, 8)} <= set(library)
    cross_step = [n for n in library if get(n).history]
    assert len([n for n in cross_step if n.startswith("ignagni-1996")]) == 5


def test_registry_compressed_coefficients_are_the_published_ones():
    for n, (ks, _) in PUBLISHED_ALGORITHM_COEFFICIENTS.items():
        alg = get(f"compressed-{n}")
        assert tuple(Fraction(k) for k in COMPRESSED_TABLE[n]) == ks
        assert alg.pairwise == {(i, n): k for i, k in enumerate(ks, start=1)}


def test_polynomial_fits():
    assert polynomial_fit_coefficients(2) == {(1, 2): Fraction(2, 3)}
    assert get("polynomial-3").pairwise == polynomial_fit_coefficients(3)  # Ignagni's Algorithm D as printed
    # the cubic fit is the four-sample algorithm 5 of Budennyi et al. Table 1
    assert get("polynomial-4").pairwise == get("panov-4s-5").pairwise
    for n in (5, 6, 7, 8):  # exact rationals at every N (from N = 7 on, a numerical reconstruction of them failed)
        coefficients = polynomial_fit_coefficients(n)
        assert coefficients and all(isinstance(c, Fraction) for c in coefficients.values()), n
        assert second_order_defect(Algorithm(f"polynomial-{n}", n, tuple(Term(c, pair) for pair, c in coefficients.items()), "", "")) == 0, n
    with pytest.raises(ValueError, match="samples"):
        polynomial_fit_coefficients(1)


def test_ignagni_1996_1_expands_the_interval_product():
    alg = get("ignagni-1996-1")
    assert alg.history == 2 and alg.window == 4
    assert alg.pairwise == {(-1, 1): Fraction(-1, 180), (-1, 2): Fraction(-1, 180), (0, 1): Fraction(-1, 180), (0, 2): Fraction(-1, 180), (1, 2): Fraction(32, 45)}


# --------------------------------------------------------------------------- published figures
def test_coefficient_table_reproduced_except_the_tab_10_1_misprint():
    checks = coefficient_checks()
    bad = [c for c in checks if not c.reproduced]
    assert [c.key for c in bad] == ["k1-N6-tab-10-1"]
    assert bad[0].published == PSINS_TABLE_10_1_N6[0][0] and bad[0].ours == PUBLISHED_ALGORITHM_COEFFICIENTS[6][0][0]  # the glv.cs value
    assert "second-order condition" in bad[0].note
    assert sum(c.reproduced for c in checks) == len(checks) - 1


def test_published_coning_coefficients_reproduced():
    checks = coning_coefficient_checks(simulate_up_to=2)
    assert len(checks) == len(PUBLISHED_ALGORITHM_ERRORS)
    for c in checks:
        assert c.reproduced, c
        assert c.ours == c.published
    sims = [c for c in checks if c.simulated is not None]
    assert len(sims) == 2
    for c in sims:
        assert c.simulated == pytest.approx(float(c.ours), rel=0.02)


def test_coning_coefficient_refuses_cross_step():
    with pytest.raises(ValueError, match="within-step pairwise"):
        coning_coefficient(get("savage-1+1"))


# --------------------------------------------------------------------------- cross-step windows
def test_window_index_and_step_windows():
    np.testing.assert_array_equal(window_index(2, 3, 2), [[0, 1, 2, 3, 4], [3, 4, 5, 6, 7]])
    seq = np.arange(8 * 3, dtype=float).reshape(8, 3)
    w = step_windows(seq, 3, 2)
    assert w.shape == (2, 5, 3)
    np.testing.assert_array_equal(w[1, 0], seq[3])
    with pytest.raises(ValueError, match="history"):
        step_windows(seq[:7], 3, 2)


def test_first_window_reaches_before_t0_into_the_exact_motion():
    m = RegularPrecession(-1.0, 2 * np.pi, 0.2)
    w = sample_increments(m, 0.01, 3, 2, history=2)
    t = np.arange(-2, 7) * 0.01
    np.testing.assert_allclose(w[0], m.angle_increments(t[:4], t[1:5]), atol=1e-15)
    np.testing.assert_allclose(w[2, 2:], m.angle_increments(t[6:8], t[7:9]), atol=1e-15)


@pytest.mark.parametrize("name", ["savage-1+1", "ignagni-1996-1", "ignagni-1996-6"])
def test_cross_step_simulation_equals_step_by_step_loop(name):
    """The vectorised run against a plain loop that keeps the last samples by hand."""
    alg = get(name)
    m = RegularPrecession(0.5, 2 * np.pi * 3, 0.3)
    h, steps = 0.004, 37
    r = simulate(alg, m, h, steps * alg.samples * h)
    n, hist = alg.samples, alg.history
    lam = np.array([1.0, 0.0, 0.0, 0.0])
    previous = list(m.angle_increments(np.arange(-hist, 0) * h, np.arange(-hist + 1, 1) * h))
    for k in range(steps):
        t0 = (k * n + np.arange(n)) * h
        current = list(m.angle_increments(t0, t0 + h))
        window = np.array(previous[len(previous) - hist:] + current) if hist else np.array(current)
        lam = quat.multiply(lam, quat.rotvec_to_quat(increment(alg, window)))
        previous = previous + current
    exact = quat.multiply(quat.conjugate(m.attitude(0.0)), m.attitude(steps * n * h))
    err = quat.quat_to_rotvec(quat.multiply(exact, quat.conjugate(lam)), canonical=True)  # exact minus computed
    np.testing.assert_allclose(r.attitude_error[-1], err, atol=1e-13)


#: Orders of the coning drift.  Ignagni (1996) chooses each coefficient to cancel one
#: term of the coning-drift series in (Ωh)²: K coefficients leave a drift of order 2K + 2
#: (2 for the 1 + 1, whose one coefficient is fixed by the second-order condition).
CONING_ORDERS = {
    "savage-1+1": (4, (0.012, 0.006, 0.003)),
    "ignagni-1996-1": (6, (0.012, 0.006, 0.003)),
    "ignagni-1996-2": (6, (0.012, 0.006, 0.003)),
    "ignagni-1996-3": (6, (0.012, 0.006, 0.003)),
    "ignagni-1996-4": (8, (0.012, 0.006, 0.003)),
    "ignagni-1996-5": (8, (0.012, 0.006, 0.003)),
    "ignagni-1996-6": (10, (0.012, 0.006)),
    "ignagni-1996-7": (8, (0.012, 0.006)),
}


@pytest.mark.parametrize("name", list(CONING_ORDERS))
def test_coning_drift_converges_at_the_design_order(name):
    order, hs = CONING_ORDERS[name]
    (d,) = coning_drift_orders([name], nutation=np.radians(0.05), sample_intervals=hs, cycles=100)
    # order 10 leaves the pre-asymptotic range only where the drift reaches the round-off floor
    # (~1e-15 rad/s): 9.7 at h = 0.012 → 0.006 s, which no other even order explains
    assert d.order == pytest.approx(order, abs=0.5 if order == 10 else 0.3), d


# --------------------------------------------------------------------------- summaries and CLI
def test_summary_orders():
    s = summarize(get("lebedev-panov-6"))
    assert (s.accuracy_order, s.local_error_order, s.coning_drift_order) == (6, 7, 6)
    s = summarize(get("ignagni-1996-5"))
    assert (s.history, s.window, s.accuracy_order, s.second_order_defect) == (1, 4, 3, 0)
    # tuned to coning: accuracy order 3 in a general motion, coning-drift order 8
    assert (s.local_error_order, s.coning_drift_order) == (4, 8)
    assert (summarize(get("compressed-4")).accuracy_order, summarize(get("compressed-4")).coning_drift_order) == (3, 8)
    with pytest.raises(TypeError, match="Algorithm"):
        summarize("savage-1+1")


def test_algorithms_list_json(capsys):
    assert main(["algorithms", "list", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["algorithms"]
    by = {r["name"]: r for r in rows}
    assert by["savage-1+1"]["history"] == 1 and by["savage-1+1"]["samples"] == 1
    assert by["ignagni-1996-6"]["history"] == 2
    assert by["panov-4s-3"]["paper"] and not by["compressed-5"]["paper"]
    assert all(r["reference"] for r in rows)


def test_algorithms_show_json(capsys, tmp_path):
    assert main(["algorithms", "show", "ignagni-1996-2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["terms"] == [{"coefficient": "-1/30", "product": "p0×p2"}, {"coefficient": "11/15", "product": "p1×p2"}]
    assert (data["samples"], data["history"], data["second_order_defect"]) == (2, 1, "0")
    f = tmp_path / "a.toml"
    f.write_text('samples = 2\n[cross]\n"0,2" = "-1/30"\n"1,2" = "11/15"\n')
    assert main(["algorithms", "show", "--algorithm-file", str(f), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["terms"] == data["terms"]


@pytest.mark.parametrize("argv, fragment", [
    (["algorithms", "show", "nope"], "one of"),
    (["algorithms", "show"], "neither"),
    (["algorithms", "show", "savage-1+1", "--algorithm", "two-sample"], "both"),
])
def test_algorithms_show_bad_input(argv, fragment, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err and err.count("\n") == 1


def _doc_examples():
    return re.findall(r"```toml\n(.*?)```", DOCS.read_text(encoding="utf-8"), re.S)


def test_docs_examples_are_the_registry_algorithms(tmp_path):
    examples = _doc_examples()
    assert len(examples) == 4
    for i, text in enumerate(examples[:3]):
        f = tmp_path / f"ex{i}.toml"
        f.write_text(text)
        alg = load_toml(f)
        assert alg.pairwise == get(alg.name).pairwise and alg.samples == get(alg.name).samples
    f = tmp_path / "nested.toml"
    f.write_text(examples[3])
    with pytest.raises(ValueError, match="second-order"):
        load_toml(f)
    assert isinstance(load_toml(f, allow_inconsistent=True), Algorithm)


@pytest.mark.parametrize("name", ["savage-1+1", "ignagni-1996-1", "ignagni-1996-2", "ignagni-1996-4", "ignagni-1996-5", "ignagni-1996-6", "ignagni-1996-3", "ignagni-1996-7"])
def test_drift_and_velocity_error_run_cross_step_registry_algorithms(name, capsys):
    base = ["--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "2", "--json"]
    assert main(["drift", "--algorithm", name] + base) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["history"] == get(name).history and d["simulated_drift_deg_per_h"] > 0
    assert d["asymptotic_drift_deg_per_h"] > 0  # the drift theory covers cross-step algorithms too
    assert main(["velocity-error", "--algorithm", name, "--nu-dual-m-s2", "1"] + base) == 0
    v = json.loads(capsys.readouterr().out)
    assert v["dW_I"] > 0 and v["motion"] == "precession"


def test_drift_from_toml_with_earlier_indices_equals_registry(tmp_path, capsys):
    f = tmp_path / "ig5.toml"
    f.write_text(_doc_examples()[1])
    base = ["--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "2", "--json"]
    assert main(["drift", "--algorithm-file", str(f)] + base) == 0
    from_file = json.loads(capsys.readouterr().out)
    assert main(["drift", "--algorithm", "ignagni-1996-5"] + base) == 0
    from_registry = json.loads(capsys.readouterr().out)
    assert from_file["simulated_drift_deg_per_h"] == from_registry["simulated_drift_deg_per_h"]
    assert main(["velocity-error", "--algorithm-file", str(f), "--motion", "sculling", "--freq-hz", "10", "--sample-interval", "0.002", "--duration", "2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["history"] == 1


@pytest.mark.parametrize("name", [n for n in names(library=True) if get(n).history])
def test_cross_step_series_order_is_the_measured_one(name):
    """The symbolic order of a cross-step algorithm equals the exponent measured on a tumbling motion (an independent oracle)."""
    from strapdown.analysis.coning.algorithm_summary import cross_step_local_exponent

    assert cross_step_local_exponent(get(name)) == pytest.approx(summarize(get(name)).local_error_order, abs=0.3)
