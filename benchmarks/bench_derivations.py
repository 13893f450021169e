"""Benchmark: symbolic series to h⁷ for every registry algorithm, the drift functions, and the report.

Targets: series + drift functions < 30 s on one core; ``reports/derivations.md`` < 2 min.
Each stage runs in a fresh interpreter so that no cache is shared (the cache of generated
code is a fresh directory per stage).  Higher weights: ``bench_series.py``.

    python benchmarks/bench_derivations.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

STAGES = {
    "exact series (words, log, Dynkin)": "from strapdown.derivations.coning import series as S; S.exact_words(); S.exact_increment()",
    "series + local error, all registry": (
        "from strapdown.derivations.coning import series as S; from strapdown.derivations.coning.registry import get, names\n"
        "for n in names(): S.local_error(get(n)); S.error_coefficients(get(n))"
    ),
    "series + drift functions, all registry": (
        "from strapdown.derivations.coning import series as S, drift as D; from strapdown.derivations.coning.registry import get, names\n"
        "for n in names():\n"
        "    a = get(n); S.local_error(a); S.error_coefficients(a); D.drift_coefficients(a); D.structure_functions(a)\n"
        "for N in (2, 3, 4): D.coning_constant(N)"
    ),
    "compiled u_a, all registry": (
        "from strapdown.analysis.coning.drift_theory import asymptotic_drift; from strapdown.derivations.coning.registry import get, names\n"
        "for n in names(): asymptotic_drift(get(n), eps=-1.0, nu=62.8, nutation=0.1, step=0.01)"
    ),
}


def _time(code: str) -> float:
    with tempfile.TemporaryDirectory() as cache:
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True, env=dict(os.environ, STRAPDOWN_CACHE_DIR=cache))
        return time.perf_counter() - t


def main() -> None:
    rows = [(name, _time(code)) for name, code in STAGES.items()]
    with tempfile.TemporaryDirectory() as out:
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "strapdown.analysis", "report", "--only", "derivations", "--out", out], check=True, stderr=subprocess.DEVNULL, stdout=subprocess.DEVNULL)
        rows.append(("report derivations.md (full)", time.perf_counter() - t))
    print(f"{'stage':<42} {'wall [s]':>9}")
    for name, secs in rows:
        print(f"{name:<42} {secs:>9.2f}")
    print("(each stage includes interpreter start-up and imports)")


if __name__ == "__main__":
    main()
