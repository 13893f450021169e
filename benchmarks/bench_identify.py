"""Identifying an integrator: how long ``identify`` and ``strapdown identify`` take for a 4-sample integrator.

Target: identifying a 4-sample integrator with every assumption test (time
invariance, memory length, isotropy from the full tensors, linearity range,
float precision, orders), not counting the verification runs, takes under 5 s
on one core (``run_all.py`` pins this script to CPU 0).  Measured here, for
five ways of writing the same 4-sample algorithm (Savage's per-sample
recursion):

* a stateful Python object updated one sample per call, as flight code runs it
  (``SavageRecursion`` through ``adapters.stateful``);
* the same recursion vectorised over the steps of a record (numpy);
* the C example of ``docs/`` through ctypes (when a C compiler exists);
* a registry algorithm run from its own terms (compressed-4);
* the stateful object of ``docs/integrator_examples.py`` loaded in a child
  process (:class:`~strapdown.analysis.coning.integrators.isolation.Isolated`,
  as ``strapdown identify`` runs user code; the child's start is included);

the time of ``identify`` (probes, exact fractions, remainder), of ``assess``
without the simulation (adding every assumption test, the series and the
closed-form drift: the target), and of
the whole ``assess`` (adding the integrator's own runs against the exact
solution), in a process whose derived-expression cache starts empty (so the
first symbolic derivation is paid, and later ones of the same algorithm are
not), and the wall time of the command ``strapdown identify`` in a fresh
process (imports included), with and without ``--skip-verification``.

Run: ``python benchmarks/bench_identify.py``.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CACHE = tempfile.mkdtemp(prefix="bench-identify-")
os.environ["STRAPDOWN_CACHE_DIR"] = CACHE  # before the package is imported: an empty cache

from strapdown.analysis.coning.integrators.adapters import algorithm_integrator, compiled, stateful  # noqa: E402
from strapdown.analysis.coning.integrators.assessment import assess  # noqa: E402
from strapdown.analysis.coning.integrators.identification import identify  # noqa: E402
from strapdown.analysis.coning.integrators.isolation import Isolated  # noqa: E402
from strapdown.analysis.coning.integrators.recursions import SavageRecursion, recursion  # noqa: E402
from strapdown.derivations.coning.registry import get  # noqa: E402

TARGET = 5.0
N = 4


def timed(fn):
    start = time.perf_counter()
    out = fn()
    return time.perf_counter() - start, out


def c_integrator():
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc is None:
        return None
    lib = Path(CACHE) / "libintegrator.so"
    done = subprocess.run([cc, "-O2", "-shared", "-fPIC", "-o", str(lib), str(ROOT / "docs" / "integrator_example.c")], capture_output=True)
    return compiled(lib, name="C example (ctypes)") if done.returncode == 0 else None


def cli(args):
    env = dict(os.environ, STRAPDOWN_CACHE_DIR=tempfile.mkdtemp(prefix="bench-identify-cli-"))
    argv = [sys.executable, "-m", "strapdown.analysis.cli", "identify", "--integrator", f"{ROOT / 'docs' / 'integrator_examples.py'}:PerSample", "--samples-per-step", str(N), "--json"] + args
    times = []
    for _ in range(2):  # empty cache, then warm
        start = time.perf_counter()
        done = subprocess.run(argv, capture_output=True, env=env)
        times.append(time.perf_counter() - start)
        if done.returncode != 0:
            raise RuntimeError(done.stderr.decode())
    return times


def main() -> int:
    load = os.getloadavg()
    cases = [
        ("stateful object, one sample per call (SavageRecursion)", stateful(SavageRecursion)),
        ("vectorised recursion (numpy)", recursion()),
        ("C example (ctypes)", c_integrator()),
        ("compressed-4 from its terms", algorithm_integrator(get("compressed-4"), velocity=False)),
    ]
    print(f"machine load (1, 5, 15 min) at start: {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f}; derived-expression cache empty at start")
    print()
    print(f"**Identifying a {N}-sample integrator** (max_previous = 4; target: identification with every assumption test, no verification, under {TARGET:g} s on one core)")
    print()
    print("| integrator | samples fed to identify | per sample [µs] | identify [s] | with every assumption test, no simulation, first [s] | whole, with its runs [s] | within target |")
    print("|---|---:|---:|---:|---:|---:|---|")
    for label, integ in cases:
        if integ is None:
            print(f"| {label} | – | – | – | – | – | no C compiler |")
            continue
        t_id, ident = timed(lambda integ=integ: identify(integ, N))
        t_an, quick = timed(lambda integ=integ: assess(integ, N, verify=False))
        t_all, a = timed(lambda integ=integ: assess(integ, N))
        assert a.identification.exact and a.check.holds and a.assumptions.trusted and all(v.holds for _, v in quick.assumptions.items()), label
        ok = "yes" if t_an < TARGET else "no"
        print(f"| {label} | {ident.probe_samples:,} | {t_id / ident.probe_samples * 1e6:.1f} | {t_id:.2f} | {t_an:.2f} | {t_all:.2f} | {ok} |")
    spec = f"{ROOT / 'docs' / 'integrator_examples.py'}:PerSample"

    def isolated():
        with Isolated(spec, time_limit=600.0) as child:
            return assess(child.integrator, N, verify=False)

    t_iso, a = timed(isolated)
    assert a.identification.exact and a.assumptions.trusted
    print(f"| PerSample in a child process (start included) | – | – | – | {t_iso:.2f} | – | {'yes' if t_iso < TARGET else 'no'} |")
    print()
    skip = cli(["--skip-verification"])
    full = cli([])
    print(f"`strapdown identify --integrator docs/integrator_examples.py:PerSample --samples-per-step {N}` (a fresh process, imports included):")
    print()
    print("| command | empty cache [s] | warm cache [s] |")
    print("|---|---:|---:|")
    print(f"| with `--skip-verification` | {skip[0]:.2f} | {skip[1]:.2f} |")
    print(f"| whole (with the runs against the exact solution) | {full[0]:.2f} | {full[1]:.2f} |")
    print()
    print("`identify`: probes, exact fractions, remainder. The first `assess` of an algorithm pays its symbolic derivation (series, closed-form drift;")
    print("the cache starts empty), the second finds it cached and adds the integrator's runs against the exact solution.")
    shutil.rmtree(CACHE, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
