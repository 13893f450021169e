"""The command-line contract at the edge: every exception class, work limits, counts, signals, progress, help.

See ``tests/cli_contract.py`` for the contract itself and ``tests/test_cli_fuzz.py``
for the fuzzing over every option.
"""

from __future__ import annotations

import argparse
import fcntl
import json
import os
import pty
import re
import select
import signal
import struct
import subprocess
import sys
import termios
import time
from pathlib import Path

import pytest
from cli_contract import leaf_parsers, run, violations, warm_up

from strapdown.analysis import cli
from strapdown.analysis.cli import _options, derive_local_error
from strapdown.analysis.core import budget

DRIFT = ["drift", "--algorithm", "panov-4s-1", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1"]
VELOCITY = ["velocity-error"] + DRIFT[1:]
LOCAL_ERROR = ["derive", "local-error", "--algorithm", "two-sample"]
AZIMUTH = ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1"]
ALIGN = ["align", "--lat-deg", "45", "--duration", "10", "--sample-rate-hz", "10", "--trials", "16"]
SCULLING = ["velocity-error", "--algorithm", "panov-4s-1", "--motion", "sculling", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "0.5"]
CONING_DRIFT = ["derive", "coning-drift", "--algorithm", "two-sample"]
STABILITY = ["stability", "--k", "0.01", "--l", "5e-5"]
MULTISTAGE = ["multistage", "--duration", "200", "--step", "0.1"]

#: (class, argv, expect, names): cases beyond the one-option mutations of the fuzz table.
EXTRA_CASES = [
    # work beyond the limits, refused before it starts, naming the size options and the limit option
    ("work beyond the limits", DRIFT[:-1] + ["1e12"], "refuse", ("--memory-limit-mb", "--time-limit")),
    ("work beyond the limits", DRIFT[:-3] + ["1e-12", "--duration", "1"], "refuse", ("--memory-limit-mb", "--time-limit")),
    ("work beyond the limits", VELOCITY[:-1] + ["1e9"], "refuse", ("--memory-limit-mb", "--time-limit")),
    ("work beyond the limits", DRIFT + ["--time-limit", "0.001"], "refuse", ("--time-limit",)),
    ("work beyond the limits", DRIFT[:-1] + ["3000", "--memory-limit-mb", "1"], "refuse", ("--memory-limit-mb",)),
    ("work beyond the limits", ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1", "--samples", "1e15"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", AZIMUTH + ["--samples", "1e9", "--workers", "1000"], "refuse", ("--workers", "--memory-limit-mb", "--time-limit")),
    ("work beyond the limits", ["multistage", "--duration", "1e9"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ["multistage", "--duration", "100", "--step", "1e-9"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "45", "--averaging-time", "1e12"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "45", "--sample-rate-hz", "1e12"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "45", "--points", "1e9"], "refuse", ("--time-limit", "--memory-limit-mb", "--points")),
    ("work beyond the limits", ALIGN[:-1] + ["1e12", "--method", "analytic"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ALIGN[:4] + ["1e9", "--method", "inertial"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ALIGN[:4] + ["3000", "--sample-rate-hz", "100", "--trials", "128", "--method", "kalman", "--epoch", "0.01"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ALIGN + ["--method", "analytic", "--workers", "1e4"], "refuse", ("--workers", "--memory-limit-mb")),
    ("work beyond the limits", ALIGN + ["--method", "analytic", "--time-limit", "0.1"], "refuse", ("--time-limit",)),
    ("work beyond the limits", SCULLING[:-1] + ["1e9"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", ["multistage", "--duration", "1e6", "--step", "0.01", "--stage1-components", "all", "--switch", "bumpless"], "refuse", ("--time-limit", "--memory-limit-mb")),
    ("work beyond the limits", DRIFT + ["--time-limit", "-1"], "refuse", ("--time-limit",)),
    ("work beyond the limits", DRIFT + ["--memory-limit-mb", "nan"], "refuse", ("--memory-limit-mb",)),
    # counts in scientific notation are accepted
    ("count in scientific notation", ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1", "--samples", "2e4", "--json"], "accept", ()),
    ("count in scientific notation", ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1", "--samples", "2.5e4", "--seed", "1e3", "--json"], "accept", ()),
    ("count in scientific notation", ["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "45", "--points", "3e0", "--json"], "accept", ()),
    ("count in scientific notation", ["multistage", "--duration", "2e2", "--step", "1e-1", "--seed", "1e1", "--json"], "accept", ()),
    ("count in scientific notation", ALIGN[:-1] + ["1.6e1", "--seed", "1e1", "--method", "analytic", "--json"], "accept", ()),
    ("count in scientific notation", LOCAL_ERROR + ["--max-order", "5e0", "--json"], "accept", ()),
    # physically meaningless inputs
    ("physically meaningless input", ["stability", "--k", "-1", "--l", "1", "--json"], "either", ("--k", "unstable")),
    ("physically meaningless input", ["stability", "--k", "1", "--l", "-1", "--json"], "either", ("--l", "unstable")),
    ("physically meaningless input", ["stability", "--k", "0.01", "--l", "5e-5", "--gravity-m-s2", "-9.81", "--json"], "refuse", ("--gravity-m-s2",)),
    ("physically meaningless input", ["stability", "--k", "0.01", "--l", "5e-5", "--earth-radius", "0", "--json"], "refuse", ("--earth-radius",)),
    ("physically meaningless input", ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1", "--beta0-deg", "95", "--samples", "2e4", "--json"], "refuse", ("--beta0-deg",)),
    ("physically meaningless input", ["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "45", "--gamma0-deg", "-90", "--json"], "refuse", ("--gamma0-deg",)),
    ("physically meaningless input", ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "400", "--sigma-eta-deg", "1", "--samples", "2e4", "--json"], "refuse", ("--sigma-xi-deg",)),
    ("physically meaningless input", ["azimuth", "--lat-deg", "89.9999999", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1", "--samples", "2e4", "--json"], "either", ("--lat-deg",)),
    ("physically meaningless input", DRIFT[:6] + ["179.999999"] + DRIFT[7:] + ["--json"], "either", ("--nutation-deg",)),
    ("physically meaningless input", DRIFT[:4] + ["1e6"] + DRIFT[5:] + ["--json"], "either", ("--eps",)),
    ("physically meaningless input", DRIFT[:8] + ["1e9"] + DRIFT[9:] + ["--json"], "either", ("--freq-hz",)),
    ("physically meaningless input", VELOCITY + ["--attitude0", "0,0,0,0", "--json"], "refuse", ("--attitude0",)),
    ("physically meaningless input", ["design", "--required-drift-deg-per-h", "1e-300", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--json"], "either", ("--required-drift-deg-per-h",)),
    ("physically meaningless input", ["design", "--required-drift-deg-per-h", "1e300", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--json"], "either", ("--required-drift-deg-per-h",)),
    ("physically meaningless input", ["multistage", "--duration", "200", "--step", "300", "--json"], "either", ("--step",)),
    ("physically meaningless input", ["multistage", "--duration", "200", "--step", "0.1", "--lat-deg", "90", "--json"], "refuse", ("--lat-deg",)),
    # the options of the multistage readings, the stability design, the sculling motion, alignment and the coning drift
    ("physically meaningless input", MULTISTAGE + ["--accel-m-s2", "1e300", "--json"], "either", ("--accel-m-s2",)),
    ("physically meaningless input", MULTISTAGE + ["--accel-duration", "1e9", "--json"], "either", ("--accel-duration",)),
    ("physically meaningless input", MULTISTAGE + ["--rocking-decay-per-s", "-1", "--json"], "refuse", ("--rocking-decay-per-s",)),
    ("physically meaningless input", MULTISTAGE + ["--rocking-origin", "-1e300", "--json"], "either", ("--rocking-origin",)),
    ("physically meaningless input", MULTISTAGE + ["--stage1-c", "-2", "--json"], "refuse", ("--stage1-c",)),
    ("physically meaningless input", MULTISTAGE + ["--stage1-reference", "pure", "--stage1-c", "1e300", "--json"], "either", ("--stage1-c",)),
    ("physically meaningless input", ["stability", "--natural-frequency-rad-s", "1e300", "--damping", "0.7", "--json"], "either", ("--natural-frequency-rad-s",)),
    ("physically meaningless input", ["stability", "--natural-frequency-rad-s", "0.005", "--damping", "-0.1", "--json"], "refuse", ("--damping",)),
    ("physically meaningless input", ["stability", "--natural-frequency-rad-s", "0.005", "--damping", "0", "--json"], "either", ("--damping", "unstable")),
    ("physically meaningless input", ["stability", "--natural-frequency-rad-s", "0.005", "--json"], "refuse", ("--damping",)),
    ("physically meaningless input", ["stability", "--k", "0", "--l", "0", "--json"], "refuse", ("--k", "unstable")),
    ("physically meaningless input", STABILITY + ["--accel-m-s2", "1e300", "--json"], "either", ("--accel-m-s2",)),
    ("physically meaningless input", STABILITY + ["--horizon", "1e300", "--json"], "either", ("--horizon",)),
    ("physically meaningless input", STABILITY + ["--horizon", "1", "--json"], "refuse", ("--horizon",)),
    ("physically meaningless input", SCULLING + ["--angle-amplitude-deg", "1e300", "--json"], "either", ("--angle-amplitude-deg",)),
    ("physically meaningless input", SCULLING + ["--angle-amplitude-deg", "170", "--json"], "either", ("--angle-amplitude-deg",)),
    ("physically meaningless input", SCULLING + ["--accel-amplitude-m-s2", "-1e300", "--json"], "either", ("--accel-amplitude-m-s2",)),
    ("physically meaningless input", SCULLING + ["--accel-axis", "x", "--json"], "refuse", ("--accel-axis",)),
    ("physically meaningless input", SCULLING + ["--eps", "-1", "--json"], "refuse", ("--eps",)),
    ("physically meaningless input", VELOCITY + ["--angle-phase-deg", "10", "--json"], "refuse", ("--angle-phase-deg",)),
    ("physically meaningless input", ["velocity-error"] + [x for x in VELOCITY[1:] if x not in ("--eps", "-1")] + ["--json"], "refuse", ("--eps",)),
    ("physically meaningless input", VELOCITY + ["--nutation-dual-m-s", "1e300", "--json"], "either", ("--nutation-dual-m-s",)),
    ("physically meaningless input", ALIGN + ["--method", "analytic", "--rocking", "sine", "--amplitude-deg", "95", "--json"], "refuse", ("--amplitude-deg",)),
    ("physically meaningless input", ALIGN + ["--method", "analytic", "--rocking", "sine", "--amplitude-deg", "1", "--period", "0.1", "--json"], "refuse", ("--period",)),
    ("physically meaningless input", ALIGN + ["--method", "analytic", "--rocking", "white", "--amplitude-deg", "1", "--bandwidth-hz", "6", "--json"], "refuse", ("--bandwidth-hz",)),
    ("physically meaningless input", ALIGN + ["--method", "kalman", "--rocking", "narrowband", "--amplitude-deg", "1", "--assumed-damping", "1.5", "--json"], "refuse", ("--assumed-damping",)),
    ("physically meaningless input", ALIGN + ["--method", "kalman", "--epoch", "100", "--json"], "refuse", ("--epoch", "--duration")),
    ("physically meaningless input", ALIGN + ["--method", "analytic", "--lat-deg", "89.9999", "--json"], "either", ("--lat-deg",)),
    ("physically meaningless input", ALIGN + ["--method", "analytic", "--rocking", "sine", "--json"], "refuse", ("--amplitude-deg",)),
    ("physically meaningless input", ALIGN + ["--method", "inertial", "--assumed-period", "5", "--json"], "refuse", ("--assumed-period",)),
    ("physically meaningless input", CONING_DRIFT + ["--omega-h-rad", "1e300", "--json"], "either", ("--omega-h-rad",)),
    ("physically meaningless input", CONING_DRIFT + ["--omega-h-rad", "1e-300", "--json"], "either", ("--omega-h-rad",)),
    ("physically meaningless input", CONING_DRIFT + ["--omega-h-rad", "3.14159,6.3,100", "--json"], "either", ("--omega-h-rad",)),
    ("physically meaningless input", CONING_DRIFT + ["--omega-h-rad", "0", "--json"], "refuse", ("--omega-h-rad",)),
    ("physically meaningless input", LOCAL_ERROR + ["--max-order", "2", "--json"], "refuse", ("--max-order",)),
    ("physically meaningless input", LOCAL_ERROR + ["--max-order", "1e6", "--json"], "refuse", ("--max-order",)),
    # command-line syntax
    ("command-line syntax", [], "refuse", ("COMMAND", "required")),
    ("command-line syntax", ["no-such-command"], "refuse", ("no-such-command",)),
    ("command-line syntax", ["derive"], "refuse", ("SUBCOMMAND", "required")),
    ("command-line syntax", ["derive", "nothing"], "refuse", ("nothing",)),
    ("command-line syntax", ["drift"], "refuse", ("required",)),
    ("command-line syntax", ["drift", "--algorithm", "two-sample", "--algorithm-file", "x.toml"], "refuse", ("--algorithm-file", "--algorithm")),
    ("command-line syntax", DRIFT + ["--eps"], "refuse", ("--eps",)),
    ("command-line syntax", DRIFT + ["stray-positional"], "refuse", ("stray-positional",)),
    ("command-line syntax", ["stability", "--schuler", "--k", "0.1"], "refuse", ("--schuler", "--k", "either")),
    ("command-line syntax", ["stability"], "refuse", ("--k", "--l")),
    ("command-line syntax", ["report", "--only"], "refuse", ("--only",)),
    ("command-line syntax", ["report", "--only", "nope", "--out", "/nonexistent/x"], "refuse", ("--only",)),
    ("command-line syntax", ["algorithms"], "refuse", ("SUBCOMMAND", "required")),
    ("command-line syntax", ["algorithms", "show"], "refuse", ("NAME", "--algorithm")),
    ("command-line syntax", ["algorithms", "show", "two-sample", "--algorithm", "optimal-3"], "refuse", ("NAME", "--algorithm")),
    ("command-line syntax", ["algorithms", "show", "no-such-algorithm"], "refuse", ("no-such-algorithm",)),
    ("command-line syntax", ["algorithms", "list", "--algorithm", "two-sample"], "refuse", ("--algorithm",)),
    ("command-line syntax", ["align", "--lat-deg", "45"], "refuse", ("--method",)),
    ("command-line syntax", ["align", "--method", "analytic", "--lat-deg", "45", "--formula", "paper", "--observation", "velocity"], "refuse", ("--observation",)),
    ("command-line syntax", ["derive", "coning-drift"], "refuse", ("--algorithm",)),
    ("command-line syntax", ["derive", "coning-drift", "--algorithm", "two-sample", "--omega-h-rad"], "refuse", ("--omega-h-rad",)),
    ("command-line syntax", ["stability", "--k", "0.01", "--l", "5e-5", "--natural-frequency-rad-s", "0.01", "--damping", "0.5"], "refuse", ("--k", "--natural-frequency-rad-s")),
    ("command-line syntax", ["velocity-error", "--algorithm", "panov-4s-1", "--motion", "tumbling"], "refuse", ("--motion",)),
]


@pytest.fixture(scope="module", autouse=True)
def warm():
    """Imports and per-process caches are paid once, untimed (see test_cli_fuzz.baseline_invocations)."""
    from test_cli_fuzz import baseline_invocations

    warm_up(baseline_invocations())


@pytest.mark.parametrize("kind, argv, expect, names", EXTRA_CASES, ids=[f"{c[0]}: {' '.join(c[1])[:70]}" for c in EXTRA_CASES])
def test_extra_cases(kind, argv, expect, names):
    outcome = run(argv)
    assert not violations(outcome, expect=expect, names=names, json_out="--json" in argv, argv=argv), (argv, outcome)


# --------------------------------------------------------------------------- every exception class at the edge
def _raising(exc):
    def command(args):
        raise exc

    return command


EXCEPTIONS = [
    (ValueError("Expected `x` > 0, got -1\nsecond line"), 2, "Expected `x` > 0, got -1"),
    (TypeError("Expected `x` to be a real number, got str 'a'"), 2, "real number"),
    (MemoryError(), 2, "out of memory"),
    (ValueError("Maximum allowed size exceeded"), 2, "out of memory"),
    (OSError(13, "Permission denied", "/data/x.toml"), 2, "Permission denied: '/data/x.toml'"),
    (IsADirectoryError(21, "Is a directory", "/data"), 2, "Is a directory"),
    (PermissionError(13, "Permission denied", "/read-only/reports"), 2, "Permission denied"),
    (RecursionError("maximum recursion depth exceeded"), 2, "nested too deeply"),
    (ZeroDivisionError("float division by zero"), 2, "arithmetic error (float division by zero)"),
    (OverflowError("math range error"), 2, "arithmetic error (math range error)"),
    (FloatingPointError("overflow encountered"), 2, "arithmetic error"),
    (UnicodeDecodeError("utf-8", b"\xff", 0, 1, "invalid start byte"), 2, "UTF-8"),
    (budget.BudgetExceeded(budget.Estimate(4e9, 1e15, "1e14 things (--n)"), budget.Limits(), "memory"), 2, "over the limit of 2 GB; reduce the request or raise the limit with --memory-limit-mb"),
    (RuntimeError("unexpected"), cli.EXIT_SOFTWARE, "internal error (RuntimeError: unexpected); please report it"),
    (KeyError("k"), cli.EXIT_SOFTWARE, "internal error (KeyError"),
    (KeyboardInterrupt(), cli.EXIT_INTERRUPTED, "interrupted"),
]


@pytest.mark.parametrize("exc, code, text", EXCEPTIONS, ids=[type(e[0]).__name__ + ":" + e[2][:20] for e in EXCEPTIONS])
def test_every_exception_class_is_one_line(monkeypatch, capsys, exc, code, text):
    monkeypatch.setattr(derive_local_error, "local_error_command", _raising(exc))
    assert cli.main(LOCAL_ERROR + ["--json"]) == code
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert text in err, err
    if code == 2:
        assert err.startswith("strapdown derive local-error: error: ")


def test_debug_environment_shows_the_traceback(monkeypatch):
    monkeypatch.setattr(derive_local_error, "local_error_command", _raising(RuntimeError("shown")))
    monkeypatch.setenv("STRAPDOWN_DEBUG", "1")
    with pytest.raises(RuntimeError, match="shown"):
        cli.main(LOCAL_ERROR)


def test_os_error_names_the_option_whose_value_it_quotes(monkeypatch, capsys, tmp_path):
    path = str(tmp_path / "alg.toml")
    monkeypatch.setattr(derive_local_error, "local_error_command", _raising(PermissionError(13, "Permission denied", path)))
    assert cli.main(["derive", "local-error", "--algorithm-file", path]) == 2
    assert capsys.readouterr().err == f"strapdown derive local-error: error: argument --algorithm-file: Permission denied: {path!r}\n"


def test_library_names_become_options(capsys):
    assert cli.main(["multistage", "--duration", "0"]) == 2
    assert capsys.readouterr().err.startswith("strapdown multistage: error: argument --duration: Expected `duration` > 0")
    assert cli.main(["stability", "--k", "0.01", "--l", "5e-5", "--earth-radius", "-1"]) == 2  # `earth_radius` → --earth-radius, by its dest
    assert capsys.readouterr().err.startswith("strapdown stability: error: argument --earth-radius: Expected `earth_radius` > 0")
    assert cli.main(["stability", "--natural-frequency-rad-s", "-1", "--damping", "0.7"]) == 2  # by its dest and unit suffix
    assert capsys.readouterr().err.startswith("strapdown stability: error: argument --natural-frequency-rad-s: Expected `natural_frequency` > 0")
    assert cli.main(["multistage", "--accel-m-s2", "nan"]) == 2
    assert capsys.readouterr().err.startswith("strapdown multistage: error: argument --accel-m-s2: Expected `accel` to be finite")


def test_messages_about_several_options_name_those_typed(capsys):
    assert cli.main(["multistage", "--duration", "200", "--step", "0.03"]) == 2
    assert capsys.readouterr().err.startswith("strapdown multistage: error: arguments --step and --duration: Expected `step` to divide the `duration`")
    assert cli.main(["multistage", "--step", "0.03"]) == 2  # --duration left at its default: only --step is named
    assert capsys.readouterr().err.startswith("strapdown multistage: error: argument --step: Expected `step` to divide the `duration`")
    # a gain designed from --natural-frequency-rad-s overflows: not blamed on --l, which was not typed
    assert cli.main(["stability", "--natural-frequency-rad-s", "1e300", "--damping", "0.7"]) == 2
    err = capsys.readouterr().err
    assert "argument --l" not in err and err.rstrip().endswith("(given: --natural-frequency-rad-s 1e300, --damping 0.7)")
    # a choice that happens to be a word of the message is not taken for a quoted value
    assert cli.main(["stability", "--natural-frequency-rad-s", "1e-300", "--damping", "0.7", "--reference", "tilt"]) == 2
    assert "argument --reference" not in capsys.readouterr().err


def test_directory_as_algorithm_file(capsys, tmp_path):
    assert cli.main(["derive", "local-error", "--algorithm-file", str(tmp_path)]) == 2
    assert capsys.readouterr().err == f"strapdown derive local-error: error: argument --algorithm-file: {tmp_path}: is a directory, expected a TOML algorithm file\n"


def test_read_only_output(capsys):
    assert cli.main(["report", "--only", "errata", "--out", "/proc/strapdown-test/reports", "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("strapdown report: error: argument --out: ") and err.count("\n") == 1, err


# --------------------------------------------------------------------------- numbers and JSON
def _returning(data):
    def command(args):
        return cli.Result(data, "text")

    return command


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf"), [1.0, float("nan")], {"deep": {"x": float("inf")}}])
def test_non_finite_results_are_refused(monkeypatch, capsys, value):
    monkeypatch.setattr(derive_local_error, "local_error_command", _returning({"x": value}))
    for extra in (["--json"], []):
        assert cli.main(LOCAL_ERROR + extra) == 2
        out, err = capsys.readouterr()
        assert out == "" and err.count("\n") == 1 and "came out" in err


def test_numpy_values_and_none_are_plain_json(monkeypatch, capsys):
    import numpy as np

    monkeypatch.setattr(derive_local_error, "local_error_command", _returning({"a": np.float64(1.5), "b": np.arange(3), "c": None, "d": (np.int64(2),)}))
    assert cli.main(LOCAL_ERROR + ["--json"]) == 0
    assert json.loads(capsys.readouterr().out) == {"a": 1.5, "b": [0, 1, 2], "c": None, "d": [2]}


def test_runtime_warnings_never_reach_stderr(monkeypatch, capsys):
    import warnings

    import numpy as np

    def noisy(args):
        with np.errstate(all="warn"):
            value = float(np.exp(np.array([1000.0]))[0] * 0.0 + np.log(np.array([2.0]))[0])  # overflow warning, finite result
        warnings.warn("something to know", UserWarning, stacklevel=1)
        return {"x": value}

    monkeypatch.setattr(derive_local_error, "local_error_command", noisy)
    assert cli.main(LOCAL_ERROR + ["--json"]) == 2  # inf * 0 = nan: refused, and still no warning text
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "RuntimeWarning" not in err and "overflow" not in err

    def fine(args):
        with np.errstate(all="warn"):
            np.log(np.array([0.0]))
        warnings.warn("something to know", UserWarning, stacklevel=1)
        return {"x": 1.0}

    monkeypatch.setattr(derive_local_error, "local_error_command", fine)
    assert cli.main(LOCAL_ERROR + ["--json"]) == 0
    assert capsys.readouterr().err == "strapdown derive local-error: warning: something to know\n"


def test_counts_accept_scientific_notation():
    assert [_options.count(t) for t in ("1e6", "2.5e3", "1_000", "7", "+3", "1E2")] == [1_000_000, 2500, 1000, 7, 3, 100]
    for bad in ("1.5", "1e-3", "abc", "", "nan", "inf", "1e999", "0x10", "1" * 50):
        with pytest.raises(argparse.ArgumentTypeError, match="whole number"):
            _options.count(bad)


def test_numbers_must_be_finite():
    assert _options.number("-1e-3") == -1e-3
    for bad in ("nan", "inf", "-inf", "1e999", "x"):
        with pytest.raises(argparse.ArgumentTypeError):
            _options.number(bad)


def test_negative_numbers_in_scientific_notation_are_values(capsys):
    assert cli.main(DRIFT[:4] + ["-1e0"] + DRIFT[5:] + ["--json"]) == 0
    assert json.loads(capsys.readouterr().out)["eps"] == -1.0


def test_budget_refusal_states_estimate_limit_and_option(capsys):
    # drift streams (constant memory): a run of 1e12 s is refused for its time, naming both options and the steps
    assert cli.main(DRIFT[:-1] + ["1e12"]) == 2
    err = capsys.readouterr().err
    assert "4e+14" not in err and "--duration 1e+12 s over --sample-interval 0.0025 s (1e+14 steps of 4 samples)" in err
    assert "would take an estimated" in err and "years, over the limit of 300 s" in err and "--time-limit" in err
    # a command that keeps its series is refused for its memory
    argv = ["velocity-error", "--algorithm", "panov-4s-1", "--eps", "-1", "--freq-hz", "10", "--nutation-deg", "1", "--sample-interval", "0.0025", "--duration", "1e9"]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert "needs an estimated" in err and "of memory, over the limit of 2 GB" in err and "--memory-limit-mb" in err
    assert cli.main(DRIFT + ["--time-limit", "0.01"]) == 2
    err = capsys.readouterr().err
    assert "would take an estimated" in err and "over the limit of 0.01 s" in err and "--time-limit" in err


def test_budget_limits_can_be_raised(capsys):
    argv = DRIFT[:-1] + ["400"]  # 40 000 steps: a few hundredths of a second
    assert cli.main(argv + ["--memory-limit-mb", "0.5", "--json"]) == 2
    capsys.readouterr()
    assert cli.main(argv + ["--memory-limit-mb", "500", "--json"]) == 0


def test_estimates_grow_with_the_request():
    small = budget.coning_simulation(1e3, window=2, degree_sum=2, velocity=False, chunk_steps=65536, what="x")
    large = budget.coning_simulation(1e9, window=2, degree_sum=2, velocity=False, chunk_steps=65536, what="x")
    dual = budget.coning_simulation(1e9, window=2, degree_sum=2, velocity=True, chunk_steps=65536, what="x")
    assert small.seconds < large.seconds < dual.seconds and small.memory < large.memory < dual.memory
    assert budget.check(small) is small
    with pytest.raises(budget.BudgetExceeded, match="memory"):
        budget.check(large)
    nan = budget.CONING_STEP.estimate(float("nan"), what="nan steps")
    with pytest.raises(budget.BudgetExceeded):
        budget.check(nan)
    # every error is kept for the quantiles: the memory grows with the samples too
    assert budget.monte_carlo(1e8, what="x").memory == budget.MONTE_CARLO_SAMPLE.fixed_bytes + 1e8 * budget.MONTE_CARLO_SAMPLE.bytes_per_unit
    with pytest.raises(budget.BudgetExceeded, match="memory"):
        budget.check(budget.monte_carlo(1e9, what="x"))


def test_options_that_do_not_apply_are_refused(capsys):
    assert cli.main(AZIMUTH + ["--rocking", "normal", "--period", "5", "--samples", "2e4"]) == 2
    assert capsys.readouterr().err == "strapdown azimuth: error: --period does not apply to --rocking normal (it applies to --rocking sine or narrowband)\n"
    assert cli.main(AZIMUTH + ["--rocking", "sine", "--damping", "0.2", "--samples", "2e4"]) == 2
    assert "--damping does not apply to --rocking sine (it applies to --rocking narrowband)" in capsys.readouterr().err
    assert cli.main(AZIMUTH + ["--rocking", "sine", "--period", "5", "--samples", "2e4", "--json"]) == 0
    capsys.readouterr()
    assert cli.main(["azimuth-design", "--budget-deg", "0.1", "--lat-deg", "45", "--exact-phase"]) == 2  # a flag
    assert capsys.readouterr().err == "strapdown azimuth-design: error: --exact-phase does not apply to --rocking narrowband (it applies to --rocking sine)\n"
    assert cli.main(["align", "--method", "analytic", "--lat-deg", "45", "--velocity-noise-m-s", "0.01"]) == 2
    assert "--velocity-noise-m-s does not apply to --method analytic (it applies to --method kalman)" in capsys.readouterr().err
    assert cli.main(SCULLING + ["--nutation-dual-m-s", "1"]) == 2
    assert capsys.readouterr().err == "strapdown velocity-error: error: --nutation-dual-m-s does not apply to --motion sculling (it applies to --motion precession)\n"
    assert cli.main(VELOCITY + ["--rotation-axis", "z"]) == 2
    assert capsys.readouterr().err == "strapdown velocity-error: error: --rotation-axis does not apply to --motion precession (it applies to --motion sculling)\n"


def test_ranges_are_stated_in_the_unit_typed(capsys):
    assert cli.main(AZIMUTH + ["--beta0-deg", "95"]) == 2
    assert capsys.readouterr().err == "strapdown azimuth: error: Expected `--beta0-deg` in (-90, 90) degrees, got 95\n"
    assert cli.main(["align", "--method", "analytic", "--lat-deg", "45", "--gamma0-deg", "-90"]) == 2
    assert capsys.readouterr().err == "strapdown align: error: Expected `--gamma0-deg` in (-90, 90) degrees, got -90\n"
    assert cli.main(["multistage", "--lat-deg", "90"]) == 2
    assert capsys.readouterr().err == "strapdown multistage: error: Expected `--lat-deg` in (-90, 90) degrees, got 90\n"
    assert cli.main(DRIFT[:6] + ["200"] + DRIFT[7:]) == 2
    assert capsys.readouterr().err == "strapdown drift: error: Expected `--nutation-deg` in (0, 180) degrees, got 200\n"


def test_unstable_gains_say_so(capsys):
    assert cli.main(["stability", "--k", "-1", "--l", "1"]) == 2
    err = capsys.readouterr().err
    assert "unstable" in err and "without bound" in err and err.count("\n") == 1


def test_motion_faster_than_the_sampling_is_refused(capsys):
    assert cli.main(DRIFT[:8] + ["1e9"] + DRIFT[9:]) == 2
    assert "less than π rad per sample" in capsys.readouterr().err


def test_drift_below_the_roundoff_floor_is_flagged(capsys):
    argv = ["drift", "--algorithm", "panov-4s-3", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--duration", "2"]
    assert cli.main(argv + ["--sample-interval", "1e-4", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    # the truncation drift of a sixth-order algorithm at h = 1e-4 s is 1.6e-12 deg/h: what the run shows is round-off
    assert data["drift_below_roundoff_floor"] is True and data["simulated_drift_deg_per_h"] < data["roundoff_floor_deg_per_h"]
    assert data["asymptotic_drift_deg_per_h"] < 1e-11
    assert cli.main(argv + ["--sample-interval", "1e-4"]) == 0
    assert "below the float64 round-off floor" in capsys.readouterr().out
    assert cli.main(argv + ["--sample-interval", "2.5e-3", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["drift_below_roundoff_floor"] is False and data["simulated_drift_deg_per_h"] > 100 * data["roundoff_floor_deg_per_h"]


# --------------------------------------------------------------------------- help
def test_help_lists_every_command_on_one_line(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    listing = out.split("commands:\n", 1)[1].splitlines()
    names = sorted(leaf_parsers())
    assert [line.split("  ")[1].strip() if line.startswith("  ") else None for line in listing][: len(names)] != []
    for name in names:
        rows = [line for line in listing if line.strip().startswith(name + "  ")]
        assert len(rows) == 1 and len(rows[0].split(name, 1)[1].strip()) > 10, (name, listing)


# --------------------------------------------------------------------------- real processes: signals, pipes, terminals
ROOT = Path(__file__).resolve().parent.parent


def _env(**extra):
    env = dict(os.environ)
    env.pop("STRAPDOWN_DEBUG", None)
    env.update(extra)
    return env


def _spawn_on_terminal(argv):
    """Start ``strapdown argv`` with stderr on a pseudo-terminal; returns (process, terminal fd)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # a terminal of 100 columns
    # SIGINT back to its default in the child: a shell's background job ignores it, and Python keeps an ignored SIGINT ignored
    proc = subprocess.Popen(
        [sys.executable, "-m", "strapdown.analysis", *argv], stdout=subprocess.PIPE, stderr=slave, stdin=subprocess.DEVNULL, env=_env(COLUMNS="100"), cwd=ROOT,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )  # fmt: skip
    os.close(slave)
    return proc, master


def _read_until(fd, needle, timeout: float = 120.0) -> bytes:
    """Read the terminal until ``needle`` (bytes, or a compiled bytes pattern) appears, it closes, or ``timeout``."""
    found = needle.search if hasattr(needle, "search") else (lambda text: needle in text)
    seen = b""
    deadline = time.monotonic() + timeout
    while not found(seen) and time.monotonic() < deadline:
        ready, _, _ = select.select([fd], [], [], 1.0)
        if ready:
            try:
                chunk = os.read(fd, 4096)
            except OSError:  # the terminal closed: the process ended
                break
            if not chunk:
                break
            seen += chunk
    return seen


def _drain(fd) -> bytes:
    return _read_until(fd, b"\x00never\x00", timeout=30.0)


def test_ctrl_c_is_one_line_and_exit_130():
    # 5e8 samples: a minute of work or more, so the run cannot end before the interrupt even on a loaded machine
    # (the limit admits the 8 GB the kept errors would reach at the end; the interrupt comes long before)
    proc, fd = _spawn_on_terminal(AZIMUTH + ["--samples", "5e8", "--time-limit", "600", "--memory-limit-mb", "9000"])
    try:
        seen = _read_until(fd, re.compile(rb"\| [1-9][0-9]*/[0-9]+ "))  # under way: its progress bar has moved
        assert b"Monte Carlo" in seen and proc.poll() is None, seen
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=120)
        rest = _drain(fd)
    finally:
        if proc.poll() is None:
            proc.kill()
        os.close(fd)
    assert proc.returncode == cli.EXIT_INTERRUPTED
    text = (seen + rest).decode("utf-8", "replace")
    assert "Traceback" not in text and "KeyboardInterrupt" not in text
    assert text.rstrip().splitlines()[-1].split("\r")[-1] == "\x1b[Kstrapdown: interrupted"  # the bar's line cleared first
    assert proc.stdout.read() == b""


def test_progress_on_a_terminal_and_nothing_otherwise():
    proc, fd = _spawn_on_terminal(AZIMUTH + ["--samples", "1e6"])
    try:
        seen = _read_until(fd, b"Monte Carlo")
        proc.wait(timeout=300)
        seen += _drain(fd)
    finally:
        os.close(fd)
    assert proc.returncode == 0 and b"Monte Carlo" in seen and b"\r" in seen
    quiet = subprocess.run([sys.executable, "-m", "strapdown.analysis", *AZIMUTH, "--samples", "1e6", "--json"], capture_output=True, env=_env(), cwd=ROOT, timeout=300)
    assert quiet.returncode == 0 and quiet.stderr == b""
    assert b"\r" not in quiet.stdout and b"\x1b" not in quiet.stdout


def test_activity_display_for_long_commands_without_a_bar():
    proc, fd = _spawn_on_terminal(["multistage", "--duration", "12000", "--step", "0.01"])  # 1.2e6 steps: several seconds with the compiled cascade
    try:
        seen = _read_until(fd, b"elapsed")
        proc.wait(timeout=300)
    finally:
        os.close(fd)
    assert proc.returncode == 0
    assert b"strapdown multistage: 00:0" in seen and b"elapsed" in seen


def test_closed_stdout_is_not_a_crash():
    proc = subprocess.Popen([sys.executable, "-m", "strapdown.analysis", "reproduce", "tables"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=_env(), cwd=ROOT)
    proc.stdout.close()  # like `strapdown reproduce tables | head -0`
    err = proc.stderr.read()
    proc.wait(timeout=120)
    assert b"Traceback" not in err and proc.returncode in (0, 1)


def test_ascii_only_stdout_is_not_a_crash():
    out = subprocess.run([sys.executable, "-m", "strapdown.analysis", "stability", "--schuler"], capture_output=True, env=_env(PYTHONIOENCODING="ascii"), cwd=ROOT, timeout=120)
    assert out.returncode == 0 and b"Traceback" not in out.stderr and b"1/s\\xb2" in out.stdout
