"""Benchmark: the coning series to any weight (issue 12 targets).

Targets, on one core (run pinned: ``taskset -c 0 python benchmarks/bench_series.py``,
or through ``run_all.py``):

* every registry algorithm to h⁹ — local error, error coefficients and the coning
  drift the series implies (what ``strapdown derive local-error --max-order 9``
  computes for each) — in under 10 s;
* one 6-sample algorithm to h¹³ with ``strapdown derive local-error --max-order 13``
  (every weight printed) in under 60 s;
* asking for h⁷ costs what it cost before the weight became a parameter.

Two more stages time what the quoting of a drift costs from a cold cache: ``strapdown drift``
raising its series to the weight the quoted value needs (ignagni-1996-5 at α = 1°, 10 Hz,
h = 1/480 s goes to h¹³) with the exact drift beside it, and ``strapdown derive
coning-drift`` with the range of its leading term (found against the exact drift) and a case.

Each stage runs in a fresh interpreter with an empty cache of generated code, so
nothing derived earlier is reused; wall and CPU time (user + system, from
``os.wait4``) include interpreter start-up and imports.  The machine is shared:
the load average is printed before and after, and CPU time is the figure to
compare with the targets when the load exceeds one.

    python benchmarks/bench_series.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: The optimal 6-sample coning algorithm, as a user would write it (lag sums on p_j × p_6).
OPTIMAL_6 = """name = "optimal-coning-6"
samples = 6
[cross]
"5,6" = "15797/4620"
"4,6" = "7834/4620"
"3,6" = "7296/4620"
"2,6" = "4558/4620"
"1,6" = "2315/4620"
"""

IMPORTS = "import sys\nfrom strapdown.derivations.coning import series as S, drift as D\nfrom strapdown.derivations.coning.registry import get, names\n"
H7 = IMPORTS + "for n in names(): S.local_error(get(n)); S.error_coefficients(get(n))\n"
REGISTRY_TO = IMPORTS + "K = int(sys.argv[1])\nfor n in names():\n    a = get(n); S.local_error(a, K); S.error_coefficients(a, K); D.coning_drift_series(a, K)\n"
DRIFT_TO = REGISTRY_TO + "for n in names(): D.drift_coefficients(get(n), K)\n"
CLOSED = IMPORTS + "for n in names(): D.coning_drift(get(n))\n"
CLI_13 = ["-m", "strapdown.analysis", "derive", "local-error", "--algorithm-file", "{toml}", "--max-order", "13", "--json"]
AUDIT_CASE = ["--algorithm", "ignagni-1996-5", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", repr(1 / 480)]
CLI_DRIFT = ["-m", "strapdown.analysis", "drift", *AUDIT_CASE, "--duration", "2", "--json"]
CLI_CONING = ["-m", "strapdown.analysis", "derive", "coning-drift", *AUDIT_CASE, "--json"]
STAGES = [
    ("h^7, every registry algorithm: local error + coefficients", ["-c", H7], None),
    ("h^9, every registry algorithm: + coning drift series", ["-c", REGISTRY_TO, "9"], 10.0),
    ("h^9, every registry algorithm: + drift coefficients d_w(ε, ϑ)", ["-c", DRIFT_TO, "9"], None),
    ("h^11, every registry algorithm: + coning drift series", ["-c", REGISTRY_TO, "11"], None),
    ("h^13, optimal 6-sample: strapdown derive local-error --max-order 13", CLI_13, 60.0),
    ("closed-form coning drift, every registry algorithm", ["-c", CLOSED], None),
    ("strapdown drift, ignagni-1996-5 at 1°, 10 Hz, h = 1/480 s: series raised to h^13, exact drift", CLI_DRIFT, None),
    ("strapdown derive coning-drift, ignagni-1996-5: next term, range of the leading term, the case", CLI_CONING, None),
]


def _run(argv: list, cache: str) -> tuple:
    env = dict(os.environ, STRAPDOWN_CACHE_DIR=cache, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    start = time.perf_counter()
    proc = subprocess.Popen(argv, cwd=ROOT, env=env, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if status:
        raise SystemExit(f"stage failed ({status}): {' '.join(argv)}")
    return wall, usage.ru_utime + usage.ru_stime


def main() -> None:
    load_before = os.getloadavg()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        toml = Path(tmp) / "optimal6.toml"
        toml.write_text(OPTIMAL_6, encoding="utf-8")
        for k, (name, argv, target) in enumerate(STAGES):
            cache = str(Path(tmp) / f"cache-{k}")
            wall, cpu = _run([sys.executable] + [a.replace("{toml}", str(toml)) for a in argv], cache)
            rows.append((name, wall, cpu, target))
    load_after = os.getloadavg()
    try:
        cpus = sorted(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cpus = []
    before, after = (" ".join(f"{v:.2f}" for v in load) for load in (load_before, load_after))
    print(f"load average (1, 5, 15 min) before: {before}; after: {after}; CPUs allowed: {cpus}")
    print()
    print("| stage | wall [s] | CPU [s] | target [s] | verdict (CPU) |")
    print("|---|---:|---:|---:|---|")
    for name, wall, cpu, target in rows:
        verdict = "" if target is None else ("ok" if cpu < target else "over")
        print(f"| {name} | {wall:.2f} | {cpu:.2f} | {'' if target is None else f'{target:g}'} | {verdict} |")
    print()
    print("(each stage: a fresh interpreter and an empty cache; times include start-up and imports)")


if __name__ == "__main__":
    main()
