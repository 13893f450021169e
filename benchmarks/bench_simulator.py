"""Throughput of the parallel-computation simulator on one core: compiled kernel against the numpy path.

Every figure is a ratio of two engines timed side by side in this run (the
machine is shared: absolute rates move with its load, ratios much less).  Each
pair is timed alternately, best of ``--repeats``:

* single runs of 10⁷ steps (4-sample algorithms) and a batch of 256 points,
  attitude; a biquaternion (velocity) run: ``simulate(engine="compiled")``
  against ``simulate(engine="numpy")``, both returning the full error series;
* the streaming kernel (:func:`strapdown.analysis.coning.batch.simulate_batch`,
  statistics only) on the same runs;
* 65 536 parameter points × 16 steps: arrays in one ``simulate_batch`` call
  against ``simulate`` over a list of 65 536 motions (today's batch path);
* a naive per-step loop (the evaluator, the step quaternion and the product,
  one step per Python iteration);
* peak memory of a streaming run of 10⁸ steps, in a child process;
* the compile time of a kernel on first use, and its load time from numba's
  cache, each in a fresh interpreter with an empty (then warm) cache;
* the data-driven kernel that serves every pairwise algorithm against a
  straight-line kernel specialised to one algorithm (same bits): time per step
  and the run length from which compiling the specialised one pays
  (:data:`strapdown.analysis.coning.kernels.SPECIALISE_MIN_WORK`).

Run: ``python benchmarks/bench_simulator.py [--quick]``; print the machine load
with the figures.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from strapdown.analysis.coning import kernels  # noqa: E402
from strapdown.analysis.coning.batch import simulate_batch  # noqa: E402
from strapdown.analysis.coning.evaluation import increment  # noqa: E402
from strapdown.analysis.coning.precession import RegularPrecession  # noqa: E402
from strapdown.analysis.coning.simulator import sample_increments, simulate  # noqa: E402
from strapdown.analysis.coning.streaming import empty_sums  # noqa: E402
from strapdown.analysis.core import quaternion as quat  # noqa: E402
from strapdown.derivations.coning.registry import get  # noqa: E402

H = 0.0025
CONING = RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(1.0))
DUAL = RegularPrecession(0.5, 2 * np.pi, 0.2, 10.0, 100.0)


def side_by_side(runs: dict, repeats: int) -> dict:
    """Best wall time of each callable, timed alternately."""
    best = {k: float("inf") for k in runs}
    for _ in range(repeats):
        for k, fn in runs.items():
            t = time.perf_counter()
            fn()
            best[k] = min(best[k], time.perf_counter() - t)
    return best


def naive_loop(alg, motion, steps):
    """One step per Python iteration: increments, the evaluator, the step quaternion, the product, the error."""
    p = sample_increments(motion, H, steps, alg.samples)
    lam = motion.attitude(0.0)
    c = quat.multiply(lam, quat.conjugate(motion.attitude(0.0)))
    err = np.empty((steps, 3))
    for k in range(steps):
        lam = quat.multiply(lam, quat.rotvec_to_quat(increment(alg, p[k]), validate=False))
        exact = quat.multiply(c, motion.attitude((k + 1) * alg.samples * H))
        err[k] = quat.quat_to_rotvec(quat.multiply(exact, quat.conjugate(lam)), canonical=True, validate=False)  # exact minus computed
    return err


def child(code: str, env=None) -> tuple:
    """Run ``code`` in a fresh interpreter pinned like this one: (wall seconds, peak RSS MiB, stdout)."""
    t = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, env=env)
    out = proc.stdout.read().decode()
    _, status, usage = os.wait4(proc.pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"child failed: {code}")
    return time.perf_counter() - t, usage.ru_maxrss / 1024.0, out.strip()


def algorithm_rows(alg, points, arrays, scale: int, repeats: int) -> list:
    """Single run, batch of 256 points and velocity run of one algorithm: numpy, compiled and streaming."""
    name, rows = alg.name, []
    simulate(alg, CONING, H, 100 * alg.samples * H, engine="compiled")  # compile or load, outside the timings
    simulate(alg, DUAL, H, 100 * alg.samples * H, velocity=True, engine="compiled")
    n = 10_000_000 // scale
    d = n * alg.samples * H
    t = side_by_side(
        {
            "numpy": lambda: simulate(alg, CONING, H, d, engine="numpy"),
            "compiled": lambda: simulate(alg, CONING, H, d, engine="compiled"),
            "streaming": lambda: simulate_batch(alg, CONING.eps, CONING.nu, CONING.nutation, H, steps=n),
        },
        repeats,
    )
    rows.append((name, f"attitude, single run ({n:.0e} steps)", n, t))
    m = 4000 // scale
    t = side_by_side(
        {
            "numpy": lambda: simulate(alg, points, H, m * alg.samples * H, engine="numpy"),
            "compiled": lambda: simulate(alg, points, H, m * alg.samples * H, engine="compiled"),
            "streaming": lambda: simulate_batch(alg, *arrays, H, steps=m),
        },
        repeats,
    )
    rows.append((name, f"attitude, batch of 256 points × {m} steps", 256 * m, t))
    v = 1_000_000 // scale
    dv = v * alg.samples * H
    t = side_by_side(
        {
            "numpy": lambda: simulate(alg, DUAL, H, dv, velocity=True, engine="numpy"),
            "compiled": lambda: simulate(alg, DUAL, H, dv, velocity=True, engine="compiled"),
            "streaming": lambda: simulate_batch(alg, DUAL.eps, DUAL.nu, DUAL.nutation, H, steps=v, nu_dual=DUAL.nu_dual, nutation_dual=DUAL.nutation_dual, velocity=True),
        },
        repeats,
    )
    rows.append((name, f"velocity (biquaternion), single run ({v:.0e} steps)", v, t))
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="10x smaller runs (a smoke test, not the figures)")
    parser.add_argument("--repeats", type=int, default=2, help="alternating repeats per pair (best kept)")
    args = parser.parse_args(argv)
    scale = 10 if args.quick else 1
    load = os.getloadavg()
    rows = []

    rng = np.random.default_rng(20261122)
    points = [RegularPrecession(rng.uniform(-2, 2), 2 * np.pi * rng.uniform(1, 20), rng.uniform(0.01, 1.0)) for _ in range(256)]
    arrays = [np.array([getattr(m, k) for m in points]) for k in ("eps", "nu", "nutation")]

    for name in ("panov-4s-5", "lebedev-panov-6", "two-sample"):
        rows += algorithm_rows(get(name), points, arrays, scale, args.repeats)

    print(f"machine load (1, 5, 15 min) at start: {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f} on {os.cpu_count()} cores; this process pinned to one")
    print()
    print("| algorithm | case | steps | numpy [steps/s] | compiled [steps/s] | streaming [steps/s] | compiled / numpy | streaming / numpy |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name, case, steps, t in rows:
        r = {k: steps / v for k, v in t.items()}
        print(f"| {name} | {case} | {steps:,} | {r['numpy']:.3g} | {r['compiled']:.3g} | {r['streaming']:.3g} | {t['numpy'] / t['compiled']:.1f}× | {t['numpy'] / t['streaming']:.1f}× |")

    # ------------------------------------------------------------------ many points, few steps
    alg = get("panov-4s-5")
    count = 65536 // scale
    prng = np.random.default_rng(7)
    eps, nu, nut = prng.uniform(-2, 2, count), 2 * np.pi * prng.uniform(1, 20, count), prng.uniform(0.01, 1.0, count)
    motions = [RegularPrecession(a, b, c) for a, b, c in zip(eps, nu, nut)]
    t = side_by_side(
        {
            "numpy": lambda: simulate(alg, motions, H, 16 * alg.samples * H, engine="numpy"),
            "arrays": lambda: simulate_batch(alg, eps, nu, nut, H, steps=16),
        },
        1,
    )
    print()
    print(
        f"**{count:,} parameter points × 16 steps** (panov-4s-5): `simulate` over a list of motions (today's path) "
        f"{count * 16 / t['numpy']:.3g} steps/s; `simulate_batch` with arrays {count * 16 / t['arrays']:.3g} steps/s: "
        f"**{t['numpy'] / t['arrays']:.0f}×**."
    )

    # ------------------------------------------------------------------ naive per-step loop
    n = 2000
    t_naive = side_by_side({"naive": lambda: naive_loop(alg, CONING, n)}, 1)["naive"]
    t_c = side_by_side({"c": lambda: simulate_batch(alg, CONING.eps, CONING.nu, CONING.nutation, H, steps=1_000_000 // scale)}, 1)["c"]
    print()
    print(
        f"**Naive per-step loop** (panov-4s-5, the evaluator and quaternion routines one step per Python iteration): "
        f"{n / t_naive:.3g} steps/s; streaming kernel {1_000_000 // scale / t_c:.3g} steps/s: **{(1_000_000 // scale / t_c) / (n / t_naive):,.0f}×**."
    )

    # ------------------------------------------------------------------ memory of a long streaming run
    n = 100_000_000 // scale
    code = (
        "import numpy as np\n"
        "from strapdown.analysis.coning.batch import simulate_batch\n"
        "from strapdown.derivations.coning.registry import get\n"
        f"r = simulate_batch(get('panov-4s-5'), -1.0, 2 * np.pi * 10, np.radians(1.0), {H}, steps={n})\n"
        "print(float(r.drift_rate))\n"
        "print([line.split()[1] for line in open('/proc/self/status') if line.startswith('VmHWM')][0])\n"
    )
    seconds, _, out = child(code)
    # The child's own high-water mark (VmHWM: ru_maxrss of a forked child starts at the parent's size).
    out, rss = out.split()[0], float(out.split()[1]) / 1024.0
    print()
    print(
        f"**{n:.0e} steps, streaming** (panov-4s-5, Table 3 coning): {seconds:.1f} s wall in a child process, "
        f"peak RSS **{rss:.0f} MiB** (interpreter, numpy, numba and the kernel included); drift {float(out):.4g} deg/h."
    )

    # ------------------------------------------------------------------ compile and load times
    with tempfile.TemporaryDirectory(prefix="bench-kernels-") as cache:
        env = dict(os.environ, STRAPDOWN_CACHE_DIR=cache)
        code = (
            "import time; t = time.perf_counter()\n"
            "import numpy as np\n"
            "from strapdown.analysis.coning.simulator import simulate\n"
            "from strapdown.analysis.coning.precession import RegularPrecession\n"
            "from strapdown.derivations.coning.registry import get\n"
            "m = RegularPrecession(0.5, 2 * np.pi, 0.2, 10.0, 100.0)\n"
            "a = time.perf_counter(); simulate(get('lebedev-panov-6'), m, 0.01, 1.0, engine='compiled'); b = time.perf_counter()\n"
            "simulate(get('lebedev-panov-6'), m, 0.01, 1.0, velocity=True, engine='compiled'); c = time.perf_counter()\n"
            "print(a - t, b - a, c - b)\n"
        )
        cold = [float(x) for x in child(code, env)[2].split()]
        warm = [float(x) for x in child(code, env)[2].split()]
    print()
    print(
        f"**Compile time** (lebedev-panov-6, fresh interpreter, empty cache): attitude kernel {cold[1]:.1f} s, "
        f"velocity kernel {cold[2]:.1f} s; from numba's cache in the next process: {warm[1]:.2f} s and {warm[2]:.2f} s "
        f"(imports before the first call: {warm[0]:.2f} s)."
    )
    # ------------------------------------------------------------------ data-driven against specialised kernels
    print()
    print("**Data-driven kernel (every pairwise algorithm) against one specialised to the algorithm** (one point, same bits):")
    print()
    print("| algorithm | run | steps | data-driven [ns/step] | specialised [ns/step] | saved [ns/step] | compile of the specialised [s] | pays from [steps] |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name in ("two-sample", "panov-4s-5", "ignagni-1996-4"):
        alg = get(name)
        for velocity in (False, True):
            steps = (2_000_000 if not velocity else 1_000_000) // scale
            columns = (np.array([v]) for v in (DUAL.eps, DUAL.nu, DUAL.nutation, DUAL.nu_dual, DUAL.nutation_dual, H))
            par, theta = kernels.parameter_rows(*columns, np.array([1.0, 0, 0, 0]), np.zeros(3), velocity=velocity)
            t0 = time.perf_counter()
            special = kernels.kernel(alg, velocity=velocity, specialised=True)
            kernels.advance(special, par, theta.copy(), np.array([1]), empty_sums(1), 0, 1)
            compile_s = time.perf_counter() - t0  # includes loading when numba's cache already holds it
            driven = kernels.kernel(alg, velocity=velocity, specialised=False)
            kernels.advance(driven, par, theta.copy(), np.array([1]), empty_sums(1), 0, 1)

            def run(k, par=par, theta=theta, steps=steps):
                kernels.advance(k, par, theta.copy(), np.array([steps]), empty_sums(1), 0, steps)

            t = side_by_side({"driven": lambda: run(driven), "special": lambda: run(special)}, args.repeats)  # noqa: B023 - run now, in this iteration
            a, b = t["driven"] / steps * 1e9, t["special"] / steps * 1e9
            pays = f"{compile_s / ((a - b) * 1e-9):.2g}" if a > b else "never"
            print(f"| {name} | {'velocity' if velocity else 'attitude'} | {steps:,} | {a:.0f} | {b:.0f} | {a - b:.0f} | {compile_s:.1f} | {pays} |")
    print(f"\n(`SPECIALISE_MIN_WORK` = {kernels.SPECIALISE_MIN_WORK:,} point-steps; a compile time under 1 s is a load from numba's cache.)")
    print(f"\npeak RSS of this process: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB; load at end: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
