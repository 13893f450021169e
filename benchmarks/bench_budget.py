"""Work estimates against measurement, and the round-off floor of a simulated drift.

For each hot path with a cost model in ``strapdown.analysis.core.budget``, runs
a few sizes and prints the measured time and peak traced memory next to the
estimate (the ratio measured / estimated should stay below 1: the models err
on the side of refusing).  Then prints the simulated drift of registry
algorithms at sample intervals where their truncation drift is negligible,
against the floor of ``strapdown.analysis.core.roundoff.drift_floor``.

Run from the repository root::

    python benchmarks/bench_budget.py
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import math  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402

import numpy as np  # noqa: E402

from strapdown.analysis.coning.drift_theory import asymptotic_drift  # noqa: E402
from strapdown.analysis.coning.precession import RegularPrecession  # noqa: E402
from strapdown.analysis.coning.simulator import CHUNK_STEPS, simulate  # noqa: E402
from strapdown.analysis.core import budget  # noqa: E402
from strapdown.analysis.core.roundoff import drift_floor  # noqa: E402
from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H  # noqa: E402
from strapdown.derivations.coning.registry import get  # noqa: E402


def measure(run):
    """Wall time [s] (without tracing) and peak traced memory [bytes] (a second, traced run)."""
    start = time.perf_counter()
    run()
    seconds = time.perf_counter() - start
    tracemalloc.start()
    run()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return seconds, peak


def cost_rows():
    rows = []
    coning = RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(1.0))
    dual = RegularPrecession(0.5, 2 * np.pi, 0.2, 10.0, 100.0)
    h = 1e-4
    for name in ("two-sample", "lebedev-panov-6"):
        alg = get(name)
        degree = sum(t.degree for t in alg.terms)
        for steps, velocity in ((200_000, False), (1_000_000, False), (100_000, True)):
            motion = dual if velocity else coning
            seconds, peak = measure(lambda alg=alg, steps=steps, motion=motion, velocity=velocity: simulate(alg, motion, h, steps * alg.samples * h * (1 + 1e-9), velocity=velocity))
            est = budget.coning_simulation(steps, window=alg.window, degree_sum=degree, velocity=velocity, chunk_steps=CHUNK_STEPS, what="")
            rows.append((f"simulate {name}{' (velocity)' if velocity else ''}", steps, seconds, est.seconds, peak, est.memory))
    from strapdown.analysis.gyrocompass.azimuth import azimuth_monte_carlo
    from strapdown.analysis.gyrocompass.rocking import rocking_model

    model = rocking_model("narrowband", math.radians(1.0), math.radians(1.0))
    for samples in (1_000_000, 5_000_000):
        seconds, peak = measure(lambda samples=samples: azimuth_monte_carlo(math.radians(45.0), 0.0, 0.0, model, samples, rng=1))
        est = budget.monte_carlo(samples, what="")
        rows.append(("azimuth Monte Carlo (narrowband)", samples, seconds, est.seconds, peak, est.memory))
    from strapdown.analysis.multistage.stages import plotnikov_1999_stages
    from strapdown.analysis.multistage.stages import simulate as cascade
    from strapdown.analysis.multistage.trajectory import Scenario

    for duration in (1300.0, 5000.0):
        scenario = Scenario(duration=duration)
        stages = plotnikov_1999_stages(scenario.gravity, scenario.earth_radius)
        seconds, peak = measure(lambda scenario=scenario, stages=stages: cascade(scenario, stages, step=0.02, rng=0))
        steps = duration / 0.02
        est = budget.multistage(steps, what="")
        rows.append(("multistage cascade", int(steps), seconds, est.seconds, peak, est.memory))
    from strapdown.analysis.multistage.tilt_loop import StageLoop

    loop = StageLoop(0.01, 5e-5)
    for horizon in (2e5, 1e6):
        seconds, peak = measure(lambda horizon=horizon: loop.pulse_response(20.0, 20.0, horizon=horizon))
        samples = math.ceil(horizon / 20.0) + 1.0
        est = budget.loop_response(samples, what="")
        rows.append(("tilt-loop pulse response (horizon / T samples)", int(samples), seconds, est.seconds, peak, est.memory))
    import subprocess
    import sys

    for weight in (11, 12, 13):
        code = (
            "import resource, sys, time\n"
            "from strapdown.derivations.coning.registry import get\n"
            "from strapdown.derivations.coning.series import error_coefficients, local_error\n"
            "from strapdown.derivations.coning.drift import coning_drift_series\n"
            f"a = get('savage-1+1'); t = time.perf_counter(); error_coefficients(a, {weight}); local_error(a, {weight}); coning_drift_series(a, {weight})\n"
            "print(time.perf_counter() - t, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)\n"
        )
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
        est = budget.series_derivation(weight, what="")
        rows.append((f"series through h^{weight} (`derive local-error --max-order`; peak RSS of a child)", weight, float(out[0]), est.seconds, float(out[1]), est.memory))
    return rows + guard_rows()


def guard_rows():
    """The hot paths of the vibration checks, the drives and the sensor errors."""
    from strapdown.analysis.alignment.aided import AidedTuning, aided_sequence
    from strapdown.analysis.alignment.sensor_models import GRADES, simulate_sensor_errors
    from strapdown.analysis.alignment.trajectory import Manoeuvre, trajectory_increments
    from strapdown.analysis.coning.integrators.adapters import algorithm_integrator
    from strapdown.analysis.coning.integrators.verification import coning_drift_rate
    from strapdown.analysis.vibration.environment import load_environment
    from strapdown.analysis.vibration.examples import QUALIFICATION
    from strapdown.analysis.vibration.monte_carlo import BAND_COMPONENTS, draw_components, monte_carlo_drift
    from strapdown.analysis.vibration.simulation import filtered_coning_check

    rows = []
    env = load_environment(QUALIFICATION)
    alg = get("two-sample")
    K = len(env.lines) + BAND_COMPONENTS * len(env.spectra)
    monte_carlo_drift(alg, env, 1e-3, pairs=2, duration=0.1, rng=1)  # compile
    for duration in (2.0, 8.0):
        result = []
        seconds, peak = measure(lambda duration=duration, result=result: result.append(monte_carlo_drift(alg, env, 1e-3, pairs=4, duration=duration, rng=1)))
        samples = result[0].sensor_samples / 8
        est = budget.vibration_monte_carlo(4, samples, K, velocity=False, chunk=64, what="")
        rows.append(("vibration Monte Carlo (4 pairs, qualification; sensor samples per realisation)", int(samples), seconds, est.seconds, peak, est.memory))
    for count in (2000, 8000):
        seconds, peak = measure(lambda count=count: draw_components(env, count, np.random.default_rng(1)))
        est = budget.VIBRATION_DRAW.estimate(count * K, what="")
        rows.append(("vibration draws (realisations)", count, seconds, est.seconds, peak, est.memory))
    for periods in (2, 8):
        seconds, peak = measure(lambda periods=periods: filtered_coning_check(alg, env.gyro, 1e-3, freq_hz=10.0, half_angle=0.01, periods=periods))
        est = budget.FILTERED_CONING_SAMPLE.estimate((0.1 + periods * 0.1) / 2.5e-4, what="")  # warm-up 0.1 s, sensor interval 0.25 ms
        rows.append(("DOP853 filtered coning (periods)", periods, seconds, est.seconds, peak, est.memory))
    for duration in (600.0, 2400.0):
        seconds, peak = measure(lambda duration=duration: trajectory_increments(Manoeuvre(), 100.0, duration))
        inc, sol = budget.TRAJECTORY_SAMPLE.estimate(100.0 * duration, what=""), budget.TRAJECTORY_STEP.estimate(duration / 3.0 + 1.0, what="")
        rows.append(("drive increments at 100 Hz (samples)", int(100 * duration), seconds, inc.seconds + sol.seconds, peak, inc.memory + sol.memory))
    for duration in (300.0, 1200.0):
        seconds, peak = measure(lambda duration=duration: aided_sequence(Manoeuvre(), AidedTuning(), sample_rate=20.0, duration=duration))
        est = budget.AIDED_FIX.estimate(duration, what="", extra_bytes=8.0 * (5 * duration + 1))  # one fix per second
        rows.append(("aided filter sequence (fixes)", int(duration), seconds, est.seconds, peak, est.memory))
    spec = GRADES[1].gyro
    terms = len(spec.gauss_markov()[0]) + bool(spec.random_walk) + bool(spec.rate_random_walk)
    for n in (4, 16):
        seconds, peak = measure(lambda n=n: simulate_sensor_errors(spec, n_trials=n, n_samples=100_000, dt=0.01, rng=1))
        est = budget.sensor_errors(3 * n * 100_000, terms, what="")
        rows.append((f"sensor errors, {terms} terms (trials of 1e5 samples)", n, seconds, est.seconds, peak, est.memory))
    from strapdown.analysis.alignment.fine import FilterTuning
    from strapdown.analysis.alignment.observability import GRAMIAN_STEP, observability, stationary_problem

    for duration in (300.0, 3000.0):
        problem = stationary_problem(math.radians(45.0), tuning=FilterTuning(epoch=0.1), duration=duration)
        seconds, peak = measure(lambda problem=problem: observability(problem))
        epochs = duration / 0.1
        est = budget.observability(epochs, epochs, duration / GRAMIAN_STEP, states=12, measurements=3, what="")
        rows.append(("observability, stationary (filter epochs of 0.1 s)", int(epochs), seconds, est.seconds, peak, est.memory))
    integrator = algorithm_integrator(alg)
    for steps in (100_000, 400_000):
        seconds, peak = measure(lambda steps=steps: coning_drift_rate(integrator, 2, RegularPrecession(-1.0, 60.0, 0.01), 1e-3, steps=steps))
        est = budget.INTEGRATOR_SAMPLE.estimate(2 * (steps + 1), what="")
        rows.append(("integrator on exact coning (steps of 2 samples)", steps, seconds, est.seconds, peak, est.memory))
    return rows


def floor_rows():
    rows = []
    for name in ("two-sample", "panov-4s-3", "lebedev-panov-6"):
        alg = get(name)
        for eps, freq, nutation in ((-1.0, 10.0, 1.0), (0.5, 10.0, 1.0), (-1.0, 1.0, 10.0)):
            motion = RegularPrecession(eps, 2 * np.pi * freq, np.radians(nutation))
            for h in (1e-5, 2.5e-5):
                r = simulate(alg, motion, h, 10.0)
                u_a = float(asymptotic_drift(alg, eps=eps, nu=2 * np.pi * freq, nutation=np.radians(nutation), step=r.step)) * RAD_PER_S_TO_DEG_PER_H
                floor = drift_floor(2 * np.pi * freq, eps * 2 * np.pi * freq) * RAD_PER_S_TO_DEG_PER_H
                rows.append((name, eps, freq, nutation, h, float(r.drift_rate) * RAD_PER_S_TO_DEG_PER_H, u_a, floor))
    return rows


def main():
    print("### Work estimates (measured / estimated; below 1 means the estimate errs on the side of refusing)\n")
    print("| hot path | size | time [s] | estimated [s] | ratio | peak traced [MB] | estimated [MB] | ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for what, size, t, te, m, me in cost_rows():
        print(f"| {what} | {size:,} | {t:.3g} | {te:.3g} | {t / te:.2f} | {m / 1e6:.3g} | {me / 1e6:.3g} | {m / me:.2f} |")
    print("\n### Round-off floor of the simulated drift (10 s runs; truncation drift u_a far below the floor)\n")
    print("| algorithm | ε | F [Hz] | ϑ [deg] | h [s] | simulated [deg/h] | u_a [deg/h] | floor [deg/h] | simulated / floor |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, eps, freq, nutation, h, sim, u_a, floor in floor_rows():
        print(f"| {name} | {eps:g} | {freq:g} | {nutation:g} | {h:g} | {sim:.3g} | {u_a:.3g} | {floor:.3g} | {sim / floor:.2f} |")


if __name__ == "__main__":
    main()
