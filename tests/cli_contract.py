"""The command-line contract, as a checker shared by the contract and fuzz tests.

Every command, given any input:

* succeeds (exit 0) and, with ``--json``, prints exactly one JSON object with
  only finite numbers (no NaN, no infinity, no ``"inf"`` strings), or
* refuses (exit 2) with exactly one line on stderr, ``strapdown <command>: error:
  ...``, naming the option at fault, and nothing on stdout;

never prints a traceback or a ``RuntimeWarning``, and never hangs.  :func:`run`
calls ``strapdown.analysis.cli.main`` in-process (with a generous limit that
only a hang reaches) and :func:`violations` lists what an outcome breaks.  How
fast a refusal comes is a speed target, measured by
``benchmarks/bench_refusals.py`` (no unit test times anything: a loaded machine
would fail it).
"""

from __future__ import annotations

import contextlib
import functools
import io
import json
import math
import re
import signal
import time
from dataclasses import dataclass

from strapdown.analysis.cli import build_parser, main


class Hung(BaseException):
    """Raised by the alarm when a command runs past its time limit (not an Exception: nothing catches it)."""


@dataclass
class Outcome:
    code: int
    out: str
    err: str
    seconds: float


def run(argv, timeout: float = 300.0) -> Outcome:
    """Run ``strapdown argv`` in-process; ``code`` is -1 if it ran past ``timeout`` seconds (a hang, not a speed limit)."""
    out, err = io.StringIO(), io.StringIO()

    def alarm(signum, frame):
        raise Hung()

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    start = time.perf_counter()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = main(list(argv))
            except SystemExit as exc:  # argparse: --help, or a parse error
                code = exc.code if isinstance(exc.code, int) else 2
    except Hung:
        code = -1
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    return Outcome(code, out.getvalue(), err.getvalue(), time.perf_counter() - start)


def _strict_json(text: str):
    def reject(token):
        raise ValueError(f"non-finite JSON constant {token}")

    return json.loads(text, parse_constant=reject)


def _non_finite_strings(obj) -> bool:
    if isinstance(obj, str):
        return obj.strip().lower() in ("inf", "-inf", "+inf", "infinity", "-infinity", "nan")
    if isinstance(obj, dict):
        return any(_non_finite_strings(v) for v in obj.values())
    if isinstance(obj, list):
        return any(_non_finite_strings(v) for v in obj)
    return False


def _non_finite_numbers(obj) -> bool:
    if isinstance(obj, float):
        return not math.isfinite(obj)
    if isinstance(obj, dict):
        return any(_non_finite_numbers(v) for v in obj.values())
    if isinstance(obj, list):
        return any(_non_finite_numbers(v) for v in obj)
    return False


def _mentions(line: str, names, argv) -> bool:
    """Whether ``line`` names one of ``names``, or quotes the value one of them was given in ``argv``."""
    if any(n in line for n in names):
        return True
    argv = list(argv or ())
    numbers = set()
    for token in re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?inf|nan", line):
        try:
            numbers.add(float(token))
        except ValueError:
            pass
    for flag in names:
        if flag in argv and argv.index(flag) + 1 < len(argv):
            value = argv[argv.index(flag) + 1]
            if value and value in line:
                return True
            try:
                if float(value) in numbers:
                    return True
            except ValueError:
                pass
    return False


def violations(outcome: Outcome, *, expect: str = "either", names=(), json_out: bool = True, limit: float | None = None, argv=None) -> list:
    """What ``outcome`` breaks of the contract (empty if nothing).

    ``expect`` is ``"refuse"``, ``"accept"`` or ``"either"``; ``names`` are
    strings of which one must appear in the error line (the option at fault;
    quoting the value the option was given in ``argv`` counts too, for a
    message about two options at once); ``limit`` is the largest time a
    refusal may take [s].
    """
    problems = []
    if outcome.code == -1:
        return [f"hung (no answer within {outcome.seconds:.1f} s)"]
    if "Traceback" in outcome.err or "Traceback" in outcome.out:
        problems.append("traceback")
    if "Warning" in outcome.err and not outcome.err.startswith("strapdown"):
        problems.append("warning text on stderr")
    if outcome.code == 0:
        if expect == "refuse":
            problems.append("silently accepted")
        if json_out:
            lines = outcome.out.splitlines()
            try:
                data = _strict_json(outcome.out)
            except ValueError as exc:
                problems.append(f"stdout is not one strict JSON object ({exc})")
            else:
                if not isinstance(data, dict) or len(lines) != 1:
                    problems.append("stdout is not exactly one JSON object on one line")
                elif _non_finite_numbers(data) or _non_finite_strings(data):
                    problems.append("JSON carries NaN or infinity")
        if any(line and not line.startswith("strapdown") for line in outcome.err.splitlines()):
            problems.append(f"unexpected stderr: {outcome.err[:120]!r}")
    elif outcome.code == 2:
        if expect == "accept":
            problems.append(f"refused a valid input: {outcome.err.strip()[:160]}")
        lines = outcome.err.splitlines()
        if len(lines) != 1:
            problems.append(f"{len(lines)} lines on stderr instead of one: {outcome.err[:200]!r}")
        elif not (lines[0].startswith("strapdown") and ": error: " in lines[0]):
            problems.append(f"error line not of the form 'strapdown CMD: error: ...': {lines[0][:120]!r}")
        elif names and not _mentions(lines[0], names, argv):
            problems.append(f"error does not name {' or '.join(names)}: {lines[0][:200]!r}")
        if outcome.out:
            problems.append("stdout not empty on error")
        if limit is not None and outcome.seconds > limit:
            problems.append(f"refusal took {outcome.seconds:.2f} s (limit {limit} s)")
    else:
        problems.append(f"exit status {outcome.code}: {outcome.err.strip()[:200]}")
    return problems


_WARMED: set = set()


def warm_up(invocations) -> None:
    """Run each invocation once, untimed, in this process (imports and per-process caches are then paid)."""
    for argv in invocations:
        key = " ".join(argv)
        if key not in _WARMED:
            run(argv, timeout=600.0)
            _WARMED.add(key)


# --------------------------------------------------------------------------- the argparse tree
def leaf_parsers():
    """``{"derive local-error": parser, ...}`` for every command of ``strapdown``.

    The tree is built once per process (building it imports every command and
    takes a fraction of a second; the fuzz table asks for it hundreds of times
    while it is collected).
    """
    return dict(_leaf_parsers())


@functools.lru_cache(maxsize=1)
def _leaf_parsers():
    out = {}
    stack = [((), build_parser())]
    while stack:
        path, parser = stack.pop()
        subs = [a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction"]
        if subs:
            for name, child in subs[0].choices.items():
                stack.append((path + (name,), child))
        else:
            out[" ".join(path)] = parser
    return dict(sorted(out.items()))


def options(parser):
    """The long options of ``parser`` that take a value (flags and --help excluded)."""
    for action in parser._actions:
        longs = [s for s in action.option_strings if s.startswith("--")]
        if longs and action.nargs != 0:
            yield longs[0], action
