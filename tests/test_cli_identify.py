"""``strapdown identify``: the JSON keys of its contract, the algorithm file, bad integrators at the edge."""

from __future__ import annotations

import json
from pathlib import Path

from cli_contract import run, violations

from strapdown.derivations.coning.algorithms import load_toml
from strapdown.derivations.coning.registry import get
from strapdown.derivations.coning.series import error_coefficients

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "docs" / "integrator_examples.py"
BASE = ["identify", "--integrator", f"{EXAMPLES}:two_sample", "--samples-per-step", "2", "--max-previous", "1"]


def _json(argv):
    out = run(argv + ["--json"], timeout=120.0)
    assert not violations(out, expect="accept", names=(), limit=120.0, json_out=True, argv=argv), out
    return json.loads(out.out)


def test_json_keys_of_the_contract():
    data = _json(BASE)
    assert data["terms"] == {"1,2": "2/3"}
    assert (data["coning_drift_order"], data["coefficient"]) == (4, "1/60")  # as `derive coning-drift --algorithm two-sample`
    assert data["consistent"] is True and (data["accuracy_order"], data["local_error_order"]) == (4, 5)
    series = error_coefficients(get("two-sample"))  # the registry's own algorithm: the same series
    assert data["local_error"]["delta"] == str(series.delta)
    assert data["local_error"]["coefficients"] == {"x" + "".join(map(str, w)): str(c) for w, c in series.coefficients.items() if c}
    assert data["remainder"]["above_roundoff"] is False and data["remainder"]["degree"] is None
    check = data["verification"]
    assert check["holds"] is True and check["largest_difference"] <= 1e-6
    assert {p["x"] for p in check["points"]} == {0.25, 0.5, 1.0, 2.0}
    assert data["sculling"] is None


def test_stateful_example_and_its_algorithm_file(tmp_path):
    out = tmp_path / "per_sample.toml"
    argv = ["identify", "--integrator", f"{EXAMPLES}:PerSample", "--samples-per-step", "3", "--max-previous", "2", "--skip-verification"]
    data = _json(argv + ["--write-algorithm", str(out), "--name", "per-sample-3"])
    assert data["terms"] == {"0,1": "1/12", "1,2": "7/12", "1,3": "1/2", "2,3": "7/12"}
    assert data["verification"] is None and data["algorithm_file"] == str(out)
    alg = load_toml(out)
    assert alg.name == "per-sample-3" and {f"{i},{j}": f"{c.numerator}/{c.denominator}" for (i, j), c in alg.pairwise.items()} == data["terms"]


def test_sculling_example():
    data = _json(["identify", "--integrator", f"{EXAMPLES}:savage_with_sculling", "--samples-per-step", "1", "--max-previous", "1", "--omega-h-rad", "1,2"])
    assert data["terms"] == {"0,1": "1/12"}
    assert data["sculling"]["dual_extension"] is True
    assert data["sculling"]["terms"] == {"0,1": "1/12", "1,0": "-1/12", "1,1": "1/2"}
    assert data["sculling"]["verification"]["holds"] is True


def test_an_inconsistent_integrator_is_reported_not_refused():
    data = _json(["identify", "--integrator", f"{EXAMPLES}:per_sample_quaternion", "--samples-per-step", "3", "--max-previous", "0", "--omega-h-rad", "1"])
    assert data["consistent"] is False and data["conditions"]["second_order_defect"] == "-1/4"
    assert data["coning_drift_order"] == 2 and data["remainder"]["degree"] == 3


def _refused(argv, *names):
    out = run(argv, timeout=60.0)
    assert not violations(out, expect="refuse", names=names, limit=60.0, argv=argv), out
    return out.err


def test_bad_integrators_one_line_exit_2(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text(
        "import numpy as np\n"
        "def wrong_shape(g, n):\n    return g\n"
        "def nan(g, n):\n    return np.full((len(g) // n, 3), np.nan)\n"
        "def raises(g, n):\n    raise RuntimeError('sensor offline')\n"
        "calls = [0]\n"
        "def drifting(g, n):\n    calls[0] += 1\n    return g.reshape(-1, n, 3).sum(axis=1) * (1 + 1e-9 * calls[0])\n"
    )
    assert "one row per sample" in _refused(["identify", "--integrator", f"{bad}:wrong_shape", "--samples-per-step", "2"], "wrong_shape")
    assert "NaN" in _refused(["identify", "--integrator", f"{bad}:nan", "--samples-per-step", "2"], "nan")
    assert "raised RuntimeError: sensor offline" in _refused(["identify", "--integrator", f"{bad}:raises", "--samples-per-step", "2"], "raises")
    drifting = _json(["identify", "--integrator", f"{bad}:drifting", "--samples-per-step", "2", "--max-previous", "1", "--skip-verification"])
    assert drifting["assumptions"]["time_invariance"]["holds"] is False and drifting["trusted"] is False  # reported, not refused
    assert "the file defines" in _refused(["identify", "--integrator", f"{bad}:nothing", "--samples-per-step", "2"], "--integrator")
    _refused(["identify", "--integrator", f"{tmp_path / 'missing.py'}:f", "--samples-per-step", "2"], "--integrator")


def test_the_assumption_verdicts_are_in_the_json():
    data = _json(BASE + ["--skip-verification"])
    verdicts = data["assumptions"]
    assert set(verdicts) == {"time_invariance", "memory", "isotropy", "linearity", "precision", "drift_order"}
    assert all(v["holds"] is True and v["summary"] for v in verdicts.values())
    assert verdicts["memory"]["needed"] == 0 and verdicts["linearity"]["probe_amplitude"] == 0.02 and data["trusted"] is True
    assert verdicts["precision"]["measured_relative_noise"] < 1e-13


def test_bad_options_one_line_exit_2():
    _refused(BASE[:-4] + ["--samples-per-step", "65"], "--samples-per-step")
    _refused(BASE + ["--omega-h-rad", "4"], "--omega-h-rad")
    _refused(BASE + ["--tolerance", "0.1"], "--tolerance")
    _refused(BASE + ["--write-algorithm", "x.txt"], "--write-algorithm")
    _refused(BASE + ["--skip-verification", "--omega-h-rad", "1"], "--omega-h-rad", "--skip-verification")
    _refused(BASE + ["--time-limit", "0.001"], "--time-limit")
    _refused(BASE + ["--probe-amplitude-rad", "1"], "--probe-amplitude-rad")
    _refused(BASE + ["--max-previous-limit", "65"], "--max-previous-limit")
