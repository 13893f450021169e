"""Self-alignment on a rocking base: sensor simulation, the three methods, the design chart, CLI start-up.

Run: ``python benchmarks/bench_alignment.py``.  Prints

* sensor samples simulated per second (narrow-band rocking, lever arm, sensor errors);
* alignment trials per second for each method (two minutes at 10 Hz);
* the time of one admissible-rocking chart per method;
* ``strapdown azimuth ... --samples 1000`` and ``strapdown align ...`` wall and CPU time, cold (empty
  code cache: the derivations run) and warm, and the in-process time of the command without the
  parser (which imports every command module).
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import math  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from strapdown.analysis.alignment.base_motion import NarrowbandMotion  # noqa: E402
from strapdown.analysis.alignment.design import admissible_rocking  # noqa: E402
from strapdown.analysis.alignment.fine import Disturbance  # noqa: E402
from strapdown.analysis.alignment.imu import Scenario, simulate_imu  # noqa: E402
from strapdown.analysis.alignment.monte_carlo import alignment_monte_carlo  # noqa: E402
from strapdown.analysis.alignment.studies import DESIGN_SCENARIO, NAVIGATION_GRADE, kalman_options  # noqa: E402

AZIMUTH = ["azimuth", "--lat-deg", "60", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1", "--samples", "1000", "--json"]
ALIGN = ["align", "--method", "analytic", "--lat-deg", "60", "--gyro-bias-deg-per-h", "0,0.01,0", "--duration", "60", "--sample-rate-hz", "10", "--trials", "50", "--json"]


def _child_time(argv, env):
    """Wall and CPU seconds of one ``strapdown`` child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run([sys.executable, "-m", "strapdown.analysis", *argv], env=env, check=True, capture_output=True)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def cli_timings() -> None:
    print(f"{'command':<44} {'cache':>6} {'wall [s]':>9} {'CPU [s]':>8}")
    for name, argv in (("strapdown azimuth ... --samples 1000", AZIMUTH), ("strapdown align --method analytic ...", ALIGN)):
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, STRAPDOWN_CACHE_DIR=cache)
            for label in ("cold", "warm", "warm"):
                wall, cpu = _child_time(argv, env)
                print(f"{name:<44} {label:>6} {wall:>9.2f} {cpu:>8.2f}")
    code = "\n".join(
        [
            "import contextlib, io, sys, time",
            "t = time.perf_counter()",
            "from strapdown.analysis.cli import build_parser, main",
            "build_parser()",
            "t1 = time.perf_counter()",
            "with contextlib.redirect_stdout(io.StringIO()):",
            f"    main({AZIMUTH!r})",
            "t2 = time.perf_counter()",
            "print(f'{t1 - t:.2f} {t2 - t1:.2f} {\"sympy\" in sys.modules}')",
        ]
    )
    for _ in range(2):  # the first run may fill the code cache of a changed source tree
        out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
    print(f"warm, one process: importing every command module and building the parser {out[0]} s; the azimuth command itself {out[1]} s; SymPy imported: {out[2]}")


def _warm_up(lat, motion) -> None:
    """Steady-state rates: numba and every compiled loop loaded first (a process's first small runs take the numpy
    forms, ``alignment_kernels.use_compiled``; the start-up is in the command-line timings below)."""
    import numba  # noqa: F401

    sc = Scenario(lat, heading=0.5, motion=motion, lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=10.0)
    for method in ("analytic", "inertial", "kalman"):
        opts = kalman_options(sc, NAVIGATION_GRADE) if method == "kalman" else None
        alignment_monte_carlo(sc, NAVIGATION_GRADE, method=method, n_trials=8, rng=0, options=opts)


def main() -> None:
    lat = math.radians(60.0)
    motion = NarrowbandMotion(np.radians([0.5, 1.0, 1.0]), 8.0, 0.1)
    _warm_up(lat, motion)
    sc = Scenario(lat, heading=0.5, motion=motion, lever_arm=[0.5, 0.3, 1.0], sample_rate=100.0, duration=120.0)
    t = time.perf_counter()
    rec = simulate_imu(sc, NAVIGATION_GRADE, n_trials=32, rng=1)
    el = time.perf_counter() - t
    n = rec.dtheta.shape[0] * rec.dtheta.shape[1]
    print(f"{'case':<52} {'seconds':>8} {'rate':>16}")
    print(f"{'sensor record, narrow-band rocking, 100 Hz':<52} {el:>8.2f} {n / el:>10.3g} samples/s")
    sc10 = Scenario(lat, heading=0.5, motion=motion, lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=120.0)
    for method, trials in (("analytic", 256), ("inertial", 256), ("kalman", 256)):
        opts = kalman_options(sc10, NAVIGATION_GRADE) if method == "kalman" else None
        t = time.perf_counter()
        alignment_monte_carlo(sc10, NAVIGATION_GRADE, method=method, n_trials=trials, rng=2, options=opts)
        el = time.perf_counter() - t
        print(f"{method + ' alignment, 120 s at 10 Hz, rocking, 256 trials':<52} {el:>8.2f} {trials / el:>10.3g} trials/s")
    freqs = np.geomspace(0.05, 0.4, 6)
    for method in ("analytic", "inertial", "kalman"):
        opts = kalman_options(DESIGN_SCENARIO, NAVIGATION_GRADE, disturbance=Disturbance("shaping", 0.01)) if method == "kalman" else None
        t = time.perf_counter()
        admissible_rocking(method, math.radians(0.2), DESIGN_SCENARIO, freqs, NAVIGATION_GRADE, options=opts, n_trials=64, rtol=0.1, rng=3)
        el = time.perf_counter() - t
        print(f"{'admissible-rocking chart, ' + method + ', 6 frequencies':<52} {el:>8.2f}")
    print()
    cli_timings()


if __name__ == "__main__":
    main()
