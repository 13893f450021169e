"""Vibration environments: the closed-form drift of a 200-point spectrum, and the Monte Carlo's gyro samples per second.

* ``environment_drift`` of a two-sample algorithm in an environment with one
  spectrum of 200 table frequencies (10 Hz–2 kHz, a coherent coning part),
  Butterworth-2 analog and digital filters per axis, decimation by 4: wall
  time of one call, best of ``--repeats`` (target < 1 s), and of the first
  call in the process (which loads the algorithm's compiled D from the cache);
* large tables (a spectrum of 2,000 and of 20,000 rows, coherent coning part,
  Butterworth-2 analog and digital filters, decimation by 4): ``environment_drift``
  on the first call (which computes the spectrum's product-integration weights
  once) and the best later call, and one ``rate_design`` with the CLI's default
  grid and margin (61 rates, three environments, five algorithms) beside its
  estimate (``rate_design_estimate``);
* the Monte Carlo (``monte_carlo_drift``), gyro (sensor) samples per second
  on one core — per second of the process's CPU time (what the core gave it,
  the figure that does not move with the load of a shared machine) and per
  wall second — its kernel compiled beforehand (target ≥ 5·10⁶ /s), best of
  ``--repeats`` runs with the median beside it: one coning line through
  first-order filters (one sinusoid per realisation), the same with the
  velocity (sculling) channels, and the package's qualification environment
  (three lines and a spectrum of 16 random sinusoids per realisation), without
  and with the velocity channels.

Run pinned: ``taskset -c 0 python benchmarks/bench_environment.py [--quick]``.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H  # noqa: E402
from strapdown.analysis.vibration.drift import environment_drift  # noqa: E402
from strapdown.analysis.vibration.environment import Environment, Spectrum, coning_line, load_environment  # noqa: E402
from strapdown.analysis.vibration.examples import QUALIFICATION  # noqa: E402
from strapdown.analysis.vibration.monte_carlo import monte_carlo_drift  # noqa: E402
from strapdown.analysis.vibration.sensor_dynamics import ChannelFilter, Sensor, analog_filter, digital_filter  # noqa: E402
from strapdown.derivations.coning.registry import get  # noqa: E402


def spectrum_environment(points: int = 200) -> Environment:
    """One spectrum of ``points`` table frequencies, per-axis filters, decimation by 4."""
    f = np.geomspace(10.0, 2000.0, points)
    s = 1e-4 * (f / 100.0) ** -0.5
    g = np.zeros((points, 6, 6), dtype=complex)
    g[:, 0, 0] = g[:, 1, 1] = s
    g[:, 2, 2] = 0.5 * s
    g[:, 0, 1] = -0.4j * s * (1 + 0.1 * np.sin(f / 50.0))
    g[:, 1, 0] = np.conj(g[:, 0, 1])
    analog = lambda fc: analog_filter("butterworth", cutoff_hz=fc, order=2)  # noqa: E731
    dlpf = digital_filter("butterworth", cutoff_hz=184.0, order=2)
    gyro = Sensor((ChannelFilter(analog(250.0), dlpf), ChannelFilter(analog(270.0), dlpf), ChannelFilter(analog(250.0), dlpf)), 4)
    return Environment((), (Spectrum(f, g, "200-point spectrum"),), gyro, Sensor(gyro.axes, 4), "bench")


def closed_form(repeats: int) -> list:
    env = spectrum_environment()
    alg = get("two-sample")
    t0 = time.perf_counter()
    environment_drift(alg, env, 1e-3)
    first = time.perf_counter() - t0
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        environment_drift(alg, env, 1e-3)
        best = min(best, time.perf_counter() - t0)
    return [("closed-form drift, 200-point spectrum, first call in the process [s]", f"{first:.3f}", "< 1"), ("closed-form drift, 200-point spectrum, best call [s]", f"{best:.4f}", "< 1")]


def large_table(rows: int) -> Environment:
    """One spectrum of ``rows`` table frequencies (10 Hz–2 kHz), the filters of :func:`spectrum_environment`."""
    f = np.geomspace(10.0, 2000.0, rows)
    s = 1e-4 * (f / 100.0) ** -0.5 * (1 + 0.3 * np.sin(f / 37.0))
    g = np.zeros((rows, 6, 6), dtype=complex)
    g[:, 0, 0] = g[:, 1, 1] = s
    g[:, 0, 1] = -0.5j * s
    g[:, 1, 0] = np.conj(g[:, 0, 1])
    base = spectrum_environment(2)
    return Environment((), (Spectrum(f, g, f"{rows}-row spectrum"),), base.gyro, base.accelerometer, "large table")


def large_tables(quick: bool, repeats: int) -> list:
    from strapdown.analysis.vibration.rate_design import rate_design, rate_design_estimate

    rows = []
    alg = get("two-sample")
    for n in (2000,) if quick else (2000, 20000):
        env = large_table(n)
        t0 = time.perf_counter()
        environment_drift(alg, env, 1e-3)
        first = time.perf_counter() - t0
        best = math.inf
        for _ in range(repeats):
            t0 = time.perf_counter()
            environment_drift(alg, env, 1e-3)
            best = min(best, time.perf_counter() - t0)
        rows.append((f"closed-form drift, {n}-row spectrum, first call (weights) [s]; best later call [s]", f"{first:.3f}; {best:.4f}", "—"))
        env = large_table(n)  # fresh objects: the design pays for the weights again
        algorithms = [get(a) for a in ("two-sample", "optimal-3", "ignagni-1996-5")]
        estimate = rate_design_estimate(env, 61, makers=5)
        t0 = time.perf_counter()
        rate_design(env, 0.05 / RAD_PER_S_TO_DEG_PER_H, algorithms=algorithms)
        rows.append((f"rate design (environment-rates defaults), {n}-row spectrum [s]; its estimate [s]", f"{time.perf_counter() - t0:.2f}; {estimate.seconds:.1f}", "within the estimate"))
    return rows


def monte_carlo(quick: bool, repeats: int) -> list:
    lp = ChannelFilter(analog_filter("lowpass1", cutoff_hz=100.0))
    line = Environment((coning_line(10.0, math.radians(1.0)),), (), Sensor((lp,) * 3), Sensor((lp,) * 3))
    qual = load_environment(QUALIFICATION)
    cases = [
        ("one coning line, first-order filters", line, 1e-3, False, 20 if quick else 60, 5.0),
        ("one coning line, with the velocity channels", line, 1e-3, True, 10 if quick else 30, 5.0),
        ("qualification environment (3 lines + 16 band sinusoids)", qual, 1e-3, False, 10 if quick else 30, 2.0),
        ("qualification environment, with the velocity channels", qual, 1e-3, True, 10 if quick else 30, 2.0),
    ]
    rows = []
    for label, env, h, velocity, pairs, duration in cases:
        monte_carlo_drift(get("two-sample"), env, h, pairs=2, duration=0.05, rng=0, velocity=velocity)  # compile or load the kernel
        cpu, wall = [], []
        for _ in range(repeats):
            t0, c0 = time.perf_counter(), time.process_time()
            mc = monte_carlo_drift(get("two-sample"), env, h, pairs=pairs, duration=duration, rng=1, velocity=velocity)
            dt, dc = time.perf_counter() - t0, time.process_time() - c0
            cpu.append(mc.sensor_samples / dc)
            wall.append(mc.sensor_samples / dt)
        rows.append(
            (
                f"Monte Carlo, {label} [gyro samples per CPU second, best of {repeats}; median; per wall second, best]",
                f"{max(cpu):.3g}; {float(np.median(cpu)):.3g}; {max(wall):.3g}",
                "≥ 5e6",
            )
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller runs")
    parser.add_argument("--repeats", type=int, default=5, help="repeats of each measurement (best is kept, the median shown beside)")
    args = parser.parse_args()
    load = os.getloadavg()
    rows = closed_form(args.repeats) + large_tables(args.quick, args.repeats) + monte_carlo(args.quick, args.repeats)
    print("| measurement | value | target |")
    print("|---|---:|---|")
    for name, value, target in rows:
        print(f"| {name} | {value} | {target} |")
    end = os.getloadavg()
    print(f"\nload average (1, 5, 15 min) at start {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f}; at end {end[0]:.2f}, {end[1]:.2f}, {end[2]:.2f} "
          f"on {os.cpu_count()} CPUs; CPUs allowed: {sorted(os.sched_getaffinity(0))} (pinned runs share the core with anything else scheduled on it)")


if __name__ == "__main__":
    main()
