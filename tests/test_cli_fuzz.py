"""Fuzz the command line: a table of hostile inputs and hypothesis over every command's options.

Each case runs ``strapdown`` in-process and is checked against the contract of
``tests/cli_contract.py`` (one JSON object of finite numbers, or one line on stderr
naming the option with exit status 2; no traceback, no warning, no hang).  The
table mutates one option of a valid baseline command at a time, for every
option that the argparse tree of the command has, so a new option is fuzzed
without editing this file; a new command needs a baseline in ``BASELINES``.
"""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

import pytest
from cli_contract import leaf_parsers, options, run, violations, warm_up
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[1]
#: The environment file of the environment commands' baselines.
ENVIRONMENT = str(ROOT / "analysis" / "vibration" / "environments" / "coning-10hz.toml")

#: The example log of the docs, and a directory for the files the log commands write.
EXAMPLE_LOG = str(ROOT / "docs" / "examples" / "rocking-imu-log.npz")
LOG_OUT = tempfile.mkdtemp(prefix="strapdown-fuzz-")

#: A valid, fast invocation of every command (the fuzz mutates one option at a time).
BASELINES = {
    "algorithms list": [],
    "algorithms show": ["--algorithm", "two-sample"],
    "align": ["--method", "analytic", "--lat-deg", "45", "--duration", "10", "--sample-rate-hz", "10", "--trials", "16"],
    "azimuth": ["--lat-deg", "45", "--sigma-xi-deg", "0.5", "--sigma-eta-deg", "0.5", "--samples", "20000"],
    "azimuth-design": ["--budget-deg", "0.1", "--lat-deg", "45", "--points", "3"],
    "derive coning-drift": ["--algorithm", "two-sample", "--omega-h-rad", "0.1"],
    "derive local-error": ["--algorithm", "two-sample"],
    "derive lyapunov": [],
    "design": ["--required-drift-deg-per-h", "1e-3", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10"],
    "design-coning": ["--samples", "2", "--environment", ENVIRONMENT, "--sample-interval", "1e-3"],
    "design-sculling": None,  # needs an environment with sculling: its errors are fuzzed through design-coning's options
    "environment-drift": ["--algorithm", "two-sample", "--environment", ENVIRONMENT, "--sample-interval", "1e-3"],
    "environment-rates": ["--environment", ENVIRONMENT, "--budget-deg-per-h", "25", "--rates", "5", "--tuned-up-to", "2"],
    "log allan": [EXAMPLE_LOG],
    "log inspect": [EXAMPLE_LOG],
    "log coning": [EXAMPLE_LOG, "--algorithm", "two-sample", "--prediction", "none"],
    "log environment": [EXAMPLE_LOG, "--out", os.path.join(LOG_OUT, "environment.toml")],
    "mount-environment": ["--profile", str(ROOT / "analysis" / "vibration" / "environments" / "airframe-profile.toml"),
                          "--mount", str(ROOT / "analysis" / "vibration" / "environments" / "isolated-imu-mount.toml"), "--tolerance", "0.01"],
    "budget": ["--imu", str(ROOT / "analysis" / "navigation" / "imus" / "tactical.toml"), "--lat-deg", "45", "--duration", "600", "--alignment", "none"],
    "identify": ["--integrator", str(ROOT / "docs" / "integrator_examples.py") + ":two_sample", "--samples-per-step", "2", "--max-previous", "1", "--omega-h-rad", "1"],
    "drift": ["--algorithm", "panov-4s-1", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "0.5"],
    "multistage": ["--duration", "200", "--step", "0.1"],
    "observability": ["--duration", "60", "--epoch", "1"],
    "report": None,  # writes files: fuzzed by test_report_output.py and the table below
    "reproduce tables": [],
    "stability": ["--k", "0.01", "--l", "5e-5"],
    "velocity-error": ["--algorithm", "panov-4s-1", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "0.5", "--nutation-dual-m-s", "0.1"],
}

#: Further valid invocations of a command whose options apply only with some values of another
#: (a rocking model, a method, a motion): the options written in a variant and not in the baseline
#: are fuzzed in it too (in the baseline they are refused as not applying).
VARIANTS = {
    "align": [
        ["--method", "analytic", "--lat-deg", "45", "--duration", "10", "--sample-rate-hz", "10", "--trials", "16", "--formula", "paper",
         "--rocking", "sine", "--amplitude-deg", "0,0.5,0.5", "--period", "7", "--lever-arm", "0.5,0,0",
         "--gyro-bias-deg-per-h", "0,0.01,0", "--accel-bias-m-s2", "1e-4,0,0", "--gyro-scale-ppm", "10", "--accel-scale-ppm", "10,20,30",
         "--gyro-bias-sigma-deg-per-h", "0.01", "--accel-bias-sigma-m-s2", "1e-4", "--arw-deg-per-rt-h", "0.001", "--vrw-m-s-per-rt-h", "0.001",
         "--gyro-quantum-arcsec", "0.1", "--accel-quantum-m-s", "1e-5", "--heading-deg", "10", "--beta0-deg", "1", "--gamma0-deg", "-1"],
        ["--method", "inertial", "--lat-deg", "45", "--duration", "10", "--sample-rate-hz", "10", "--trials", "16", "--observation", "velocity", "--epoch", "1",
         "--rocking", "white", "--amplitude-deg", "0.2", "--bandwidth-hz", "2"],
        ["--method", "kalman", "--lat-deg", "45", "--duration", "10", "--sample-rate-hz", "10", "--trials", "16", "--epoch", "0.5",
         "--rocking", "narrowband", "--amplitude-deg", "0.3", "--period", "6", "--damping", "0.2", "--lever-arm", "0.5,0,0", "--disturbance", "shaping",
         "--prior-heading-deg", "1", "--prior-tilt-deg", "0.1", "--velocity-noise-m-s", "0.001",
         "--assumed-period", "5", "--assumed-damping", "0.3", "--assumed-amplitude-deg", "0.2"],
    ],
    "observability": [
        ["--model", "rocking", "--duration", "60", "--epoch", "1", "--rocking", "sine", "--amplitude-deg", "0,1,1", "--period", "6", "--damping", "0.2",
         "--lever-arm", "0.5,0,1", "--prior-heading-deg", "2", "--prior-tilt-deg", "0.2", "--gyro-bias-sigma-deg-per-h", "0.1",
         "--accel-bias-sigma-m-s2", "1e-4", "--arw-deg-per-rt-h", "0.01", "--vrw-m-s-per-rt-h", "0.01", "--velocity-noise-m-s", "0.01", "--lat-deg", "30"],
        ["--model", "multi-position", "--duration", "60", "--epoch", "1", "--rotation-times", "20,40", "--rotation-axes", "z,x", "--rotation-angles-deg", "90,180",
         "--heading-deg", "10", "--beta0-deg", "1", "--gamma0-deg", "-1"],
    ],
    "azimuth": [
        ["--lat-deg", "45", "--sigma-xi-deg", "0.5", "--sigma-eta-deg", "0.5", "--samples", "20000", "--rocking", "narrowband", "--period", "6", "--damping", "0.2", "--workers", "2"],
    ],
    "azimuth-design": [
        ["--budget-deg", "0.1", "--lat-deg", "45", "--points", "3", "--rocking", "sine", "--averaging-time", "30", "--sample-rate-hz", "5", "--level", "0.9"],
    ],
    "multistage": [
        ["--duration", "200", "--step", "0.1", "--truth", "no-coriolis", "--stage1-reference", "tilt", "--stage1-c", "2", "--stage1-components", "all",
         "--switch", "bumpless", "--rocking-decay-per-s", "0.01", "--rocking-origin", "10", "--accel-m-s2", "5", "--accel-duration", "30", "--lat-deg", "30"],
    ],
    "stability": [
        ["--natural-frequency-rad-s", "0.005", "--damping", "0.7", "--reference", "tilt", "--gravity-m-s2", "9.8", "--earth-radius", "6.4e6",
         "--accel-m-s2", "5", "--accel-duration", "30", "--horizon", "20000"],
    ],
    "velocity-error": [
        ["--algorithm", "panov-4s-1", "--motion", "sculling", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "0.5",
         "--angle-amplitude-deg", "0.1", "--accel-amplitude-m-s2", "1", "--angle-phase-deg", "10", "--accel-phase-deg", "20",
         "--rotation-axis", "x", "--accel-axis", "z", "--w0-m-s", "1,0,0", "--attitude0", "1,0,0,0"],
    ],
}

#: Limits passed to every fuzzed command that has them, so that no accepted case runs long.
FAST = {"--time-limit": "10", "--memory-limit-mb": "512"}

#: Values that must be refused by any numeric option, and values that may be accepted or refused.
NUMBER_REFUSED = ["nan", "inf", "-inf", "1e999", "abc", ""]
NUMBER_EITHER = ["0", "-1", "1e300", "-1e300", "1e-300"]
COUNT_REFUSED = ["nan", "1.5", "abc", ""]
COUNT_EITHER = ["0", "-1", "1e15", "99999999999999999999999"]
_TRIPLE_REFUSED = ["1,2", "a,b,c", "nan,0,0", "1e999,0,0", "", "1,2,3,4"]
_TRIPLE_EITHER = ["1e300,0,0", "-5,0,1e-300", "-1e300"]
TEXT_REFUSED = {
    "--algorithm": ["no-such-algorithm", "", "x" * 5000, "../../etc/passwd"],
    "--integrator": ["", "x" * 5000, "../../etc/passwd", "/etc/passwd:root", str(ROOT / "docs" / "integrator_examples.py"), str(ROOT / "docs") + ":f"],
    "--w0-m-s": _TRIPLE_REFUSED,
    "--attitude0": ["0,0,0,0", "nan,0,0,0", "1,0,0", "inf,0,0,0"],
    "--omega-h-rad": ["", "0", "-1", "a", "nan", "inf", "1,,2", "0.1,-0.1"],
    **{flag: _TRIPLE_REFUSED for flag in ("--lever-arm", "--gyro-bias-deg-per-h", "--accel-bias-m-s2", "--gyro-scale-ppm", "--accel-scale-ppm", "--amplitude-deg", "--assumed-amplitude-deg")},
}
TEXT_EITHER = {
    "--attitude0": ["1e-300,0,0,0", "1e300,1e300,0,0", "-1,0,0,0"],
    "--w0-m-s": _TRIPLE_EITHER,
    "--omega-h-rad": ["1e-300", "1e300", "3.14159", "0.1," * 200 + "0.1"],
    **{flag: _TRIPLE_EITHER for flag in ("--lever-arm", "--gyro-bias-deg-per-h", "--accel-bias-m-s2", "--gyro-scale-ppm", "--accel-scale-ppm", "--amplitude-deg", "--assumed-amplitude-deg")},
}


def _with(argv: list, flag: str, value: str) -> list:
    """``argv`` with ``flag`` set to ``value`` (replaced if present, added otherwise)."""
    out = list(argv)
    if flag in out:
        out[out.index(flag) + 1] = value
    else:
        out += [flag, value]
    return out


def command_argv(name: str, argv: list) -> list:
    parser = leaf_parsers()[name]
    flags = {flag for flag, _ in options(parser)}
    extra = [x for flag, value in FAST.items() if flag in flags and flag not in argv for x in (flag, value)]
    return name.split() + argv + extra + ["--json"]


def _kind(action) -> str:
    if action.choices is not None:
        return "choice"
    typ = getattr(action.type, "__name__", str(action.type))
    if typ in ("int", "count"):
        return "count"
    if typ in ("float", "number"):
        return "number"
    return "text"


def _mutations(name: str, parser, base: list, only=None) -> list:
    """The cases of one valid invocation ``base``: every option (or those in ``only``) mutated in turn."""
    cases = []
    for flag, action in options(parser):
        if flag in FAST or (only is not None and flag not in only):
            continue
        kind = _kind(action)
        if kind == "number":
            cases += [("non-finite or non-numeric number", command_argv(name, _with(base, flag, v)), "refuse", (flag,)) for v in NUMBER_REFUSED]
            cases += [("extreme number", command_argv(name, _with(base, flag, v)), "either", (flag,)) for v in NUMBER_EITHER]
        elif kind == "count":
            cases += [("non-integral count", command_argv(name, _with(base, flag, v)), "refuse", (flag,)) for v in COUNT_REFUSED]
            cases += [("extreme count", command_argv(name, _with(base, flag, v)), "either", (flag,)) for v in COUNT_EITHER]
        elif kind == "choice":
            cases.append(("unknown choice", command_argv(name, _with(base, flag, "no-such-choice")), "refuse", (flag,)))
        else:
            cases += [("malformed text", command_argv(name, _with(base, flag, v)), "refuse", (flag,)) for v in TEXT_REFUSED.get(flag, [])]
            cases += [("extreme text", command_argv(name, _with(base, flag, v)), "either", (flag,)) for v in TEXT_EITHER.get(flag, [])]
        if action.required:
            without = list(base)
            i = without.index(flag)
            del without[i : i + 2]
            cases.append(("missing required option", command_argv(name, without), "refuse", (flag,)))
    return cases


def table() -> list:
    """(class, argv, expect, names) for every command and option, and for the options of every variant."""
    cases = []
    for name, parser in leaf_parsers().items():
        base = BASELINES.get(name)
        if base is None:
            continue
        cases.append(("valid baseline", command_argv(name, base), "accept", ()))
        cases.append(("unknown option", command_argv(name, base + ["--no-such-option", "1"]), "refuse", ("--no-such-option",)))
        cases += _mutations(name, parser, base)
        for variant in VARIANTS.get(name, []):
            cases.append(("valid baseline", command_argv(name, variant), "accept", ()))
            written = {token for token in variant if token.startswith("--")} - set(base)  # the others are fuzzed in the baseline
            cases += [c for c in _mutations(name, parser, variant, only=written) if c[0] != "missing required option"]
    return cases


CASES = table()


def baseline_invocations() -> list:
    """Every baseline as a full command line."""
    return [command_argv(name, base) for name, base in BASELINES.items() if base is not None]


@pytest.fixture(scope="module", autouse=True)
def warm():
    """Run every baseline once first: imports and per-process caches (symbolic theories) are paid here, not in a timed case."""
    warm_up(baseline_invocations())


def test_every_command_has_a_baseline():
    missing = sorted(set(leaf_parsers()) - set(BASELINES))
    assert not missing, f"add a valid, fast baseline invocation to BASELINES for {missing}"


def test_the_table_is_large():
    assert len(CASES) >= 250


@pytest.mark.parametrize("kind, argv, expect, names", CASES, ids=[f"{c[0]}: {' '.join(c[1])[:80]}" for c in CASES])
def test_hostile_option_values(kind, argv, expect, names):
    outcome = run(argv)
    assert not violations(outcome, expect=expect, names=names, argv=argv), (argv, outcome)


# --------------------------------------------------------------------------- hostile files
def _write(path, content) -> str:
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    return str(path)


HOSTILE_TOML = {
    "empty": "",
    "not TOML": "samples = = 2\n",
    "binary": b"\xff\xfe\x00\x01samples",
    "not UTF-8": b'name = "\xe9"\nsamples = 2\n',
    "samples missing": '[cross]\n"1,2" = "2/3"\n',
    "samples huge": "samples = 1000000000000\n",
    "samples float": "samples = 2.0\n",
    "samples negative": "samples = -2\n",
    "coefficient 1e999999999": 'samples = 2\n[cross]\n"1,2" = "1e999999999"\n',
    "coefficient of 100 digits": 'samples = 2\n[cross]\n"1,2" = "' + "7" * 100 + '/3"\n',
    "integer of 4000 digits": 'samples = 2\n[cross]\n"1,2" = ' + "9" * 4000 + "\n",
    "integer of 5000 digits": 'samples = 2\n[cross]\n"1,2" = ' + "9" * 5000 + "\n",
    "division by zero": 'samples = 2\n[cross]\n"1,2" = "1/0"\n',
    "float coefficient": 'samples = 2\n[cross]\n"1,2" = 0.6667\n',
    "nested arrays 100000 deep": "name = " + "[" * 100000 + "]" * 100000 + "\nsamples = 2\n",
    "nested tables": 'samples = 2\n[cross.deeper.still]\n"1,2" = "2/3"\n',
    "inline tables 5000 deep": "x = " + "{a = " * 5000 + "1" + "}" * 5000 + "\n",
    "too many terms": "samples = 64\n[cross]\n" + "".join(f'"{i},{j}" = "1/7"\n' for i in range(1, 65) for j in range(1, 65) if i != j)[: 200_000],
    "file of 2 MB": "# " + "x" * 2_000_000 + "\nsamples = 2\n",
    "key of 100000 digits": 'samples = 2\n[cross]\n"' + "1" * 100000 + ',2" = "2/3"\n',
    "index out of range": 'samples = 2\n[cross]\n"1,3" = "2/3"\n',
    "index far back": 'samples = 2\n[cross]\n"-1000,1" = "2/3"\n',
    "duplicate key": 'samples = 2\nsamples = 3\n',
    "unknown key": 'samples = 2\nbogus = 1\n',
    "name not a string": "samples = 2\nname = 5\n",
    "cross not a table": 'samples = 2\ncross = "x"\n',
    "misses second order": 'samples = 2\n[cross]\n"1,2" = "1/3"\n',
    "long name": 'samples = 2\nname = "' + "n" * 5000 + '"\n[cross]\n"1,2" = "2/3"\n',
}


@pytest.fixture(scope="module")
def toml_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("toml")


def file_cases(root):
    cases = [(label, _write(root / f"case-{i}.toml", text)) for i, (label, text) in enumerate(HOSTILE_TOML.items())]
    (root / "a-directory.toml").mkdir(exist_ok=True)
    cases.append(("a directory", str(root / "a-directory.toml")))
    cases.append(("missing file", str(root / "missing.toml")))
    cases += [("device /dev/zero", "/dev/zero"), ("device /dev/null", "/dev/null")]
    fifo = root / "fifo.toml"
    if not fifo.exists():
        os.mkfifo(fifo)
    cases.append(("a FIFO (would block on open)", str(fifo)))
    loop = root / "loop.toml"
    if not loop.is_symlink():
        loop.symlink_to(loop)
    cases.append(("symbolic link loop", str(loop)))
    return cases


FILE_LABELS = list(HOSTILE_TOML) + ["a directory", "missing file", "device /dev/zero", "device /dev/null", "a FIFO (would block on open)", "symbolic link loop"]


def algorithm_file_commands() -> list:
    """Every command with a baseline that reads ``--algorithm-file``."""
    return [name for name, parser in leaf_parsers().items() if BASELINES.get(name) is not None and "--algorithm-file" in dict(options(parser))]


def with_algorithm_file(command: str, path: str) -> list:
    """The baseline of ``command`` with its ``--algorithm NAME`` replaced by ``--algorithm-file path``."""
    base = list(BASELINES[command])
    if "--algorithm" in base:
        i = base.index("--algorithm")
        del base[i : i + 2]
    return command_argv(command, base + ["--algorithm-file", path])


@pytest.mark.parametrize("command", algorithm_file_commands())
@pytest.mark.parametrize("label", FILE_LABELS)
def test_hostile_algorithm_files_refused_fast(toml_dir, command, label):
    path = dict(file_cases(toml_dir))[label]
    outcome = run(with_algorithm_file(command, path))
    assert not violations(outcome, expect="refuse", names=("--algorithm-file",)), outcome


def test_unreadable_file_is_refused(toml_dir):
    path = toml_dir / "secret.toml"
    path.write_text('samples = 2\n[cross]\n"1,2" = "2/3"\n', encoding="utf-8")
    path.chmod(0)
    try:
        if os.access(path, os.R_OK):
            pytest.skip("running with privileges that read any file")
        outcome = run(command_argv("derive local-error", ["--algorithm-file", str(path)]))
        assert not violations(outcome, expect="refuse", names=("--algorithm-file",)), outcome
    finally:
        path.chmod(stat.S_IRUSR | stat.S_IWUSR)


# --------------------------------------------------------------------------- hypothesis
_NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(min_value=-(10**30), max_value=10**30).map(str),
    st.sampled_from(["0", "-0", "1e-320", "5e-324", "1.7976931348623157e308", "1e6", "2.5e3", " 7", "0x10", "1_0", "−1", "１"]),
    st.text(max_size=12),
)


def _numeric_options():
    out = []
    for name, parser in leaf_parsers().items():
        if BASELINES.get(name) is None:
            continue
        for flag, action in options(parser):
            if flag not in FAST and _kind(action) in ("number", "count"):
                out.append((name, flag))
    return out


NUMERIC = _numeric_options()


@settings(max_examples=150, suppress_health_check=[HealthCheck.too_slow])
@given(target=st.sampled_from(NUMERIC), value=_NUMBERS)
def test_any_value_of_any_numeric_option_meets_the_contract(target, value):
    name, flag = target
    outcome_argv = command_argv(name, _with(BASELINES[name], flag, value))
    outcome = run(outcome_argv)
    assert not violations(outcome, names=(flag,), argv=outcome_argv), (name, flag, value, outcome)


@settings(max_examples=40, suppress_health_check=[HealthCheck.too_slow])
@given(argv=st.lists(st.sampled_from(["--json", "--eps", "-1", "nan", "--algorithm", "panov-4s-1", "--duration", "1e12", "drift", "report", "--out", "--", "-", "--only", "x"]), max_size=8))
def test_random_token_soup_meets_the_contract(argv):
    if "--help" in argv or "-h" in argv or "report" in argv:
        return
    outcome = run(argv)
    assert not violations(outcome, json_out="--json" in argv and outcome.code == 0), (argv, outcome)
