"""Run every benchmark on one core and record the figures in ``benchmarks/README.md``.

Runs, each in its own child process pinned to CPU 0 (``taskset -c 0`` when
available) with ``OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = MKL_NUM_THREADS = 1``:

1. every ``benchmarks/bench_*.py`` script, in name order, except
   ``bench_first_run.py`` (it needs both cores, since the first run uses the
   second one, and takes about ten minutes: run it on its own);
2. the peer comparisons ``benchmarks/peer_*.py``;
3. the full report, ``strapdown report --out <tmp>``, and ``--quick``.

For each it measures the wall time and the peak resident memory of the child
(``ru_maxrss`` from ``os.wait4`` on that child: its own peak, including
waited-for descendants such as worker processes, and not mixed up with earlier
children as a cumulative ``getrusage(RUSAGE_CHILDREN)`` would be).  The
scripts print small Markdown tables; they are collected verbatim.

With ``--update`` the machine description and the results replace the marked
blocks of ``benchmarks/README.md``; otherwise everything is printed.

Usage::

    python benchmarks/run_all.py [--update] [--skip-report] [--only NAME ...]
"""

from __future__ import annotations

import argparse
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
README = HERE / "README.md"

#: Wall-time targets [s]: the full report on one core, and the quick one.
REPORT_TARGETS = {"report (full)": 30.0, "report (--quick)": 60.0}


@dataclass
class Outcome:
    name: str
    command: str
    seconds: float
    peak_rss_mib: float
    status: int
    stdout: str
    stderr: str


def single_core_env() -> dict:
    env = dict(os.environ)
    env.update(OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1", NUMEXPR_NUM_THREADS="1", PYTHONPATH=str(ROOT) + os.pathsep + env.get("PYTHONPATH", ""))
    env.pop("PYTHONHASHSEED", None)
    return env


def pin() -> list:
    """Command prefix that pins a child to CPU 0, when ``taskset`` exists."""
    return ["taskset", "-c", "0"] if shutil.which("taskset") else []


def run(name: str, argv: list, *, timeout: float | None = None) -> Outcome:
    """Run ``argv`` on one core; wall time and the child's own peak RSS."""
    cmd = pin() + argv
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=ROOT, env=single_core_env(), stdout=out, stderr=err)
        deadline = None if timeout is None else start + timeout
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if deadline is not None and time.perf_counter() > deadline:
                proc.kill()
                pid, status, usage = os.wait4(proc.pid, 0)
                break
            time.sleep(0.01)
        seconds = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode(errors="replace")
        stderr = err.read().decode(errors="replace")
    shown = " ".join(a if a != sys.executable else "python" for a in argv)
    return Outcome(name, shown, seconds, usage.ru_maxrss / 1024.0, proc.returncode, stdout, stderr)


#: Benchmarks that must not run pinned to one core (module docstring); run them on their own.
UNPINNED = frozenset({"bench_first_run.py"})


def benchmark_scripts(only=None) -> list:
    scripts = sorted(HERE.glob("bench_*.py")) + sorted(HERE.glob("peer_*.py"))
    scripts = [s for s in scripts if s.is_file() and s.name not in UNPINNED]
    if only:
        scripts = [s for s in scripts if s.stem in only or s.name in only]
    return scripts


def run_report(quick: bool) -> Outcome:
    with tempfile.TemporaryDirectory(prefix="bench-report-") as tmp:
        argv = [sys.executable, "-m", "strapdown.analysis", "report", "--out", str(Path(tmp) / "reports"), "--no-progress"]
        if quick:
            argv.append("--quick")
        outcome = run("report (--quick)" if quick else "report (full)", argv)
    outcome.command = "strapdown report --out <tmp>" + (" --quick" if quick else "")
    return outcome


# --------------------------------------------------------------------------- machine
def _cmd(argv: list) -> str:
    try:
        return subprocess.run(argv, capture_output=True, text=True, check=False).stdout
    except OSError:
        return ""


def machine() -> str:
    """Markdown description of this machine and the software versions."""
    lscpu = _cmd(["lscpu"])
    fields = dict(re.findall(r"^([^:\n]+):\s*(.+)$", lscpu, flags=re.M))
    mem = _cmd(["free", "-h"]).splitlines()
    mem_total = mem[1].split()[1] if len(mem) > 1 and len(mem[1].split()) > 1 else "unknown"
    os_name = "unknown"
    if Path("/etc/os-release").is_file():
        m = re.search(r'^PRETTY_NAME="?([^"\n]+)', Path("/etc/os-release").read_text(), flags=re.M)
        os_name = m.group(1) if m else os_name
    versions = {}
    for mod in ("numpy", "scipy", "sympy", "matplotlib", "control", "smsfusion", "numba"):
        try:
            from importlib.metadata import version

            versions[mod] = version(mod)
        except Exception:  # not installed
            versions[mod] = "not installed"
    rows = [
        ("CPU", fields.get("Model name", platform.processor() or "unknown")),
        ("Cores", f"{_cmd(['nproc']).strip() or os.cpu_count()} (nproc); {fields.get('Thread(s) per core', '?')} thread(s) per core, {fields.get('Core(s) per socket', '?')} core(s) per socket"),
        ("Memory", f"{mem_total} (free -h)"),
        ("OS", f"{os_name}, {platform.machine()}"),
        ("Python", platform.python_version()),
        ("Libraries", ", ".join(f"{k} {v}" for k, v in versions.items())),
        ("Pinning", ("taskset -c 0" if pin() else "none (no taskset)") + "; OMP/OPENBLAS/MKL_NUM_THREADS=1"),
    ]
    return "\n".join(["| | |", "|---|---|"] + [f"| {k} | {v} |" for k, v in rows])


# --------------------------------------------------------------------------- output
def summary(outcomes: list) -> str:
    lines = ["| benchmark | command | wall time [s] | peak RSS [MiB] | status |", "|---|---|---:|---:|---|"]
    for o in outcomes:
        status = "ok" if o.status == 0 else f"FAILED (exit {o.status})"
        target = REPORT_TARGETS.get(o.name)
        if target is not None and o.status == 0:
            status += f", {'within' if o.seconds <= target else 'OVER'} the {target:.0f} s target"
        lines.append(f"| {o.name} | `{o.command}` | {o.seconds:.1f} | {o.peak_rss_mib:.0f} | {status} |")
    return "\n".join(lines)


def details(outcomes: list) -> str:
    parts = []
    for o in outcomes:
        if o.name.startswith("report"):
            continue
        parts += [f"### {o.name}", "", o.stdout.strip() or "(no output)", ""]
        if o.status != 0:
            tail = "\n".join(o.stderr.strip().splitlines()[-15:])
            parts += ["```", tail, "```", ""]
    return "\n".join(parts).strip()


def _block(tag: str):
    start, end = f"<!-- {tag}:start -->", f"<!-- {tag}:end -->"
    return start, end, re.compile(re.escape(start) + r"\n?(.*?)\n?" + re.escape(end), flags=re.S)


def read_block(text: str, tag: str) -> str:
    m = _block(tag)[2].search(text)
    return m.group(1) if m else ""


def replace_block(text: str, tag: str, body: str) -> str:
    start, end, pattern = _block(tag)
    if not pattern.search(text):
        raise SystemExit(f"{README} has no {start} ... {end} block")
    return pattern.sub(lambda _: f"{start}\n{body}\n{end}", text)


def _order(name: str) -> tuple:
    return (name.startswith("report"), name.startswith("peer_"), name)


def merge_summary(old: str, new: str) -> str:
    """Rows of ``new`` replace the rows of the same benchmark in ``old``; others are kept."""
    rows = {}
    for table in (old, new):
        for line in table.splitlines()[2:]:
            if line.startswith("| "):
                rows[line.split("|")[1].strip()] = line
    head = new.splitlines()[:2]
    return "\n".join(head + [rows[k] for k in sorted(rows, key=_order)])


def merge_details(old: str, new: str) -> str:
    parts = {}
    for text in (old, new):
        for chunk in re.split(r"^(?=### )", text, flags=re.M):
            if chunk.startswith("### "):
                parts[chunk.splitlines()[0][4:].strip()] = chunk.strip()
    return "\n\n".join(parts[k] for k in sorted(parts, key=_order))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--update", action="store_true", help="write the figures into benchmarks/README.md")
    parser.add_argument("--skip-report", action="store_true", help="do not time the full and quick report")
    parser.add_argument("--only", nargs="+", metavar="NAME", help="run only these benchmark scripts (stem or file name)")
    args = parser.parse_args(argv)

    outcomes = []
    for script in benchmark_scripts(args.only):
        print(f"running {script.name} ...", file=sys.stderr, flush=True)
        o = run(script.stem, [sys.executable, str(script.relative_to(ROOT))])
        print(f"  {o.seconds:.1f} s, {o.peak_rss_mib:.0f} MiB, exit {o.status}", file=sys.stderr)
        outcomes.append(o)
    if not args.skip_report:
        for quick in (True, False):
            print(f"running strapdown report{' --quick' if quick else ''} ...", file=sys.stderr, flush=True)
            o = run_report(quick)
            print(f"  {o.seconds:.1f} s, {o.peak_rss_mib:.0f} MiB, exit {o.status}", file=sys.stderr)
            outcomes.append(o)

    mach, summ, det = machine(), summary(outcomes), details(outcomes)
    print(mach, summ, det, sep="\n\n")
    if args.update:
        text = README.read_text(encoding="utf-8")
        text = replace_block(text, "machine", mach)
        text = replace_block(text, "summary", merge_summary(read_block(text, "summary"), summ))
        text = replace_block(text, "details", merge_details(read_block(text, "details"), det))
        README.write_text(text, encoding="utf-8")
        print(f"updated {README.relative_to(ROOT)}", file=sys.stderr)
    return 1 if any(o.status != 0 for o in outcomes) else 0


if __name__ == "__main__":
    sys.exit(main())
