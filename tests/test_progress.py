"""Progress where nobody watches a terminal: plain lines in a log, at a steady pace, and nothing with --quiet."""

from __future__ import annotations

import io
import os
import re
import subprocess
import sys
import time
from pathlib import Path

from strapdown.analysis.core import progress

ROOT = Path(__file__).resolve().parent.parent
LINE = re.compile(r"^(?P<label>strapdown [\w -]+): (?:(?P<pct>\d+)% done, )?(?:(?P<steps>.+), )?(?P<elapsed>\d+) s elapsed$")


def test_mode_follows_the_stream_and_quiet():
    assert progress.mode(False, io.StringIO()) == "lines"
    assert progress.mode(True, io.StringIO()) == "off"

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    assert progress.mode(False, Terminal()) == "bar"


def test_lines_report_the_task_the_fraction_and_the_time():
    log = io.StringIO()
    with progress.lines("strapdown demo", stream=log, interval=0.05):
        outer = progress.bar(["a", "b"], desc="section", enabled=True)
        for name in outer:
            outer.set_description(f"section {name}")
            with progress.bar(total=4, desc="chunks", enabled=True) as inner:
                for _ in range(4):
                    time.sleep(0.04)
                    inner.update(1)
    text = log.getvalue()
    assert "\r" not in text and "\x1b" not in text
    rows = [LINE.match(line) for line in text.splitlines()]
    assert rows and all(rows), text
    assert any(r["steps"] and "section b 1/2" in r["steps"] and "chunks" in r["steps"] for r in rows), text
    fractions = [int(r["pct"]) for r in rows if r["pct"] is not None]
    assert fractions == sorted(fractions) and fractions[-1] >= 50 and fractions[0] < 50, text


def test_short_work_writes_no_line():
    log = io.StringIO()
    with progress.lines("strapdown demo", stream=log, interval=5.0):
        for _ in progress.bar(range(3), desc="quick", enabled=True):
            pass
    assert log.getvalue() == ""


def test_a_bar_outside_a_lines_block_is_tqdm_and_silent_when_disabled():
    shown = progress.bar(range(2), desc="x", enabled=False)
    assert type(shown).__name__ == "tqdm" and list(shown) == [0, 1]


def _cli(*argv, interval="0.25"):
    env = dict(os.environ, STRAPDOWN_PROGRESS_INTERVAL=interval)
    return subprocess.run([sys.executable, "-m", "strapdown.analysis", *argv], capture_output=True, text=True, env=env, cwd=ROOT, timeout=300)


def test_a_long_command_writes_progress_lines_to_a_log_and_is_silent_with_quiet():
    argv = ("multistage", "--duration", "6000", "--step", "0.01", "--json")  # 6e5 steps: a few seconds
    r = _cli(*argv)
    assert r.returncode == 0, r.stderr
    lines = r.stderr.splitlines()
    assert lines and all(LINE.match(line) and line.startswith("strapdown multistage: ") for line in lines), r.stderr
    elapsed = [int(LINE.match(line)["elapsed"]) for line in lines]
    assert elapsed == sorted(elapsed)
    quiet = _cli(*argv, "--quiet")
    assert quiet.returncode == 0 and quiet.stderr == "" and quiet.stdout == r.stdout


def test_a_counted_command_reports_its_fraction():
    argv = ("azimuth", "--lat-deg", "60", "--beta0-deg", "2", "--gamma0-deg", "1", "--sigma-xi-deg", "0.5", "--sigma-eta-deg", "0.5", "--rocking", "narrowband", "--samples", "2e6")
    r = _cli(*argv, "--seed", "1", interval="0.1")
    assert r.returncode == 0, r.stderr
    rows = [LINE.match(line) for line in r.stderr.splitlines()]
    assert rows and all(rows), r.stderr
    assert any(m["pct"] is not None for m in rows), r.stderr


def _percentages(text: str) -> list:
    return [int(m["pct"]) for m in (LINE.match(line) for line in text.splitlines()) if m and m["pct"] is not None]


def test_the_fraction_never_goes_backwards_when_an_inner_task_starts_afresh():
    """An outer step with two inner tasks one after the other: the second starts at 0 %, the line does not follow it down."""
    log = io.StringIO()
    with progress.lines("strapdown demo", stream=log, interval=0.02):
        for _ in progress.bar(range(2), desc="section", enabled=True):
            for _ in range(2):  # two inner tasks of the same step, each from 0 to the end
                with progress.bar(total=5, desc="chunks", enabled=True) as inner:
                    for _ in range(5):
                        time.sleep(0.03)
                        inner.update(1)
    shown = _percentages(log.getvalue())
    assert len(shown) >= 4 and shown == sorted(shown), shown
    # without the guard the raw fraction does fall: 50 % of step 1 through the first inner task, then 0 % again
    assert max(shown[: len(shown) // 2]) > 0


def test_expected_seconds_weight_the_steps_and_advance_a_silent_step():
    """Steps expected to take 0.05, 0.05 and 5 s: counted alike the third would start at 67 %; weighted, the line
    stays near 2 % after the short ones and rises with time during the long one, which reports nothing."""
    log = io.StringIO()
    with progress.lines("strapdown demo", stream=log, interval=0.05):
        for i in progress.bar(range(3), desc="section", enabled=True, expected=[0.05, 0.05, 5.0]):
            time.sleep(0.05 if i < 2 else 0.8)
    shown = _percentages(log.getvalue())
    assert shown == sorted(shown) and max(shown) < 33, shown
    assert shown[-1] > shown[0], shown  # it advances with time inside the silent step


def test_expected_seconds_of_the_wrong_length_are_ignored():
    log = io.StringIO()
    with progress.lines("strapdown demo", stream=log, interval=0.02):
        for _ in progress.bar(range(2), desc="section", enabled=True, expected=[1.0]):
            time.sleep(0.08)
    shown = _percentages(log.getvalue())
    assert shown and set(shown) <= {0, 50}, shown


def test_the_progress_flag_does_what_its_help_says():
    """Piped: plain lines by default, tqdm bars with --progress, nothing with --quiet; the help says exactly that."""
    from strapdown.analysis.cli import build_parser
    from strapdown.analysis.cli._options import PROGRESS_HELP

    argv = ("azimuth", "--lat-deg", "60", "--sigma-xi-deg", "0.5", "--sigma-eta-deg", "0.5", "--samples", "3e6", "--json")
    default, flagged, quiet = _cli(*argv, interval="0.05"), _cli(*argv, "--progress", interval="0.05"), _cli(*argv, "--quiet", interval="0.05")
    assert default.returncode == flagged.returncode == quiet.returncode == 0
    assert default.stderr and all(LINE.match(line) for line in default.stderr.splitlines()), default.stderr  # lines, although "default: off"
    assert re.search(r"Monte Carlo: +\d+%\|", flagged.stderr), flagged.stderr  # a tqdm bar, not a plain line
    assert quiet.stderr == ""
    for command in ("azimuth", "align"):
        text = " ".join(build_parser([command, "--help"])._subparsers._group_actions[0].choices[command].format_help().split())
        assert " ".join(PROGRESS_HELP.split()) in text and "progress is shown anyway" in text
