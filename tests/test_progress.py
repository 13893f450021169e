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
