"""The environment commands: options checked before the vibration library is imported, and the tuning's conditioning stated."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from strapdown.analysis.cli import environment as cli_environment
from strapdown.analysis.cli import main

ROOT = Path(__file__).resolve().parent.parent
ENVIRONMENT = str(ROOT / "analysis" / "vibration" / "environments" / "coning-10hz.toml")

#: Each command with one bad option, and the option its refusal must name.
BAD = [
    (["environment-drift", "--environment", ENVIRONMENT, "--algorithm", "panov-4s-3", "--sample-interval", "-1"], "--sample-interval"),
    (["design-coning", "--environment", ENVIRONMENT, "--samples", "9", "--sample-interval", "0.001"], "--samples"),
    (["design-sculling", "--environment", ENVIRONMENT, "--samples", "2", "--previous", "12", "--sample-interval", "0.001"], "--previous"),
    (["environment-rates", "--environment", ENVIRONMENT, "--budget-deg-per-h", "1", "--rates", "1"], "--rates"),
    (["environment-drift", "--environment", ENVIRONMENT, "--algorithm", "no-such-algorithm", "--sample-interval", "0.001"], "--algorithm"),
]

_PROBE = """
import json, sys
from strapdown.analysis.cli import main
code = main(json.loads(sys.argv[1]))
heavy = sorted(m for m in sys.modules if m.startswith(("strapdown.analysis.vibration", "scipy.signal", "numba")))
print(json.dumps({"code": code, "heavy": heavy}))
"""


@pytest.mark.parametrize("argv, flag", BAD, ids=[f"{a[0]} {f}" for a, f in BAD])
def test_a_bad_option_is_refused_before_the_library_is_imported(argv, flag):
    """In a fresh process: exit 2, one line naming the option, and no vibration module, scipy.signal or numba loaded."""
    out = subprocess.run([sys.executable, "-c", _PROBE, json.dumps(argv + ["--quiet"])], capture_output=True, text=True, cwd=ROOT, timeout=300)
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result["code"] == 2 and out.stderr.count("\n") == 1 and flag in out.stderr, out.stderr
    assert result["heavy"] == [], result["heavy"]


def test_the_probe_can_see_the_library():
    """The same probe on a valid call finds the library loaded (the check above can fail)."""
    argv = ["environment-drift", "--environment", ENVIRONMENT, "--algorithm", "panov-4s-3", "--sample-interval", "0.001", "--json", "--quiet"]
    out = subprocess.run([sys.executable, "-c", _PROBE, json.dumps(argv)], capture_output=True, text=True, cwd=ROOT, timeout=300)
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result["code"] == 0 and "strapdown.analysis.vibration.drift" in result["heavy"]


def test_the_restated_defaults_are_the_library_s():
    from strapdown.analysis.vibration.rate_design import DEFAULT_RATES, FREQUENCY_MARGIN
    from strapdown.analysis.vibration.tuning import MAX_SAMPLES

    lo, hi, n = cli_environment.DEFAULT_RATE_GRID
    np.testing.assert_array_equal(np.geomspace(lo, hi, n), DEFAULT_RATES)
    assert cli_environment.FREQUENCY_MARGIN == FREQUENCY_MARGIN and cli_environment.MAX_DESIGN_SAMPLES == MAX_SAMPLES


def test_an_ill_conditioned_design_says_so(capsys):
    """Eight samples and eight previous: coefficients of 10¹³ from a system of condition number about 10¹⁵; two samples: 1."""
    argv = ["design-coning", "--environment", ENVIRONMENT, "--sample-interval", "0.001", "--json", "--quiet"]
    assert main(argv + ["--samples", "8", "--previous", "8"]) == 0
    captured = capsys.readouterr()
    bad = json.loads(captured.out)
    assert bad["condition_number"] > 1e12 and bad["well_conditioned"] is False
    assert max(abs(v) for v in bad["coefficients"].values()) > 1e10
    assert captured.err.count("\n") == 1 and "warning: the tuning system is ill-conditioned" in captured.err
    assert main(argv + ["--samples", "2"]) == 0
    captured = capsys.readouterr()
    good = json.loads(captured.out)
    assert good["condition_number"] < 10 and good["well_conditioned"] is True and captured.err == ""


def test_unit_conversions_and_the_environment_reader_refuse_wrong_types_in_the_package_s_words():
    from strapdown.analysis.core.units import deg, deg_per_h, rad_per_s
    from strapdown.analysis.vibration.environment import load_environment

    for convert in (deg, deg_per_h, rad_per_s):
        with pytest.raises(TypeError, match=r"Expected `x` to be a number or an array of numbers, got str 'abc'"):
            convert("abc")
    assert deg_per_h([1.0, 2.0]).shape == (2,) and deg(np.pi) == pytest.approx(180.0)
    with pytest.raises(TypeError, match=r"Expected `path` to be a file path \(str or os.PathLike\), got NoneType None"):
        load_environment(None)
