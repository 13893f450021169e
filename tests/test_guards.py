"""Work guards of the API and the command line: huge or empty inputs are refused by name, before any work.

Every public function whose allocation or run time grows with a scalar argument
estimates its work first (:mod:`strapdown.analysis.core.budget`) and raises a
``ValueError`` (:class:`~strapdown.analysis.core.budget.BudgetExceeded`) whose
message names the argument, instead of numpy's allocation error or an
hour-long run.  Empty arrays get a message that says they are empty.  Each
call below runs under ``tracemalloc``: a refusal must come before the arrays
it would have allocated (the peak stays far below a gigabyte).
"""

from __future__ import annotations

import math
import subprocess
import sys
import tracemalloc

import numpy as np
import pytest

from strapdown.analysis.core import budget
from strapdown.analysis.vibration.examples import QUALIFICATION
from strapdown.derivations.coning.registry import get

ALG = get("panov-4s-1")
_EXAMPLE_IMU = __import__("pathlib").Path(__import__("strapdown.analysis.navigation", fromlist=["x"]).__file__).parent / "imus" / "tactical.toml"
CONING = dict(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))


def _coning():
    from strapdown.analysis.coning.precession import RegularPrecession

    return RegularPrecession(**CONING)


def _loop():
    from strapdown.analysis.multistage.tilt_loop import StageLoop

    return StageLoop.schuler(9.81, 6.371e6)


def _scenario(duration):
    from strapdown.analysis.multistage.trajectory import Scenario

    return Scenario(duration=duration)


def _alignment_scenario(duration):
    from strapdown.analysis.alignment.imu import Scenario

    return Scenario(math.radians(45.0), duration=duration)


def _narrowband():
    from strapdown.analysis.gyrocompass.rocking import rocking_model

    return rocking_model("narrowband", math.radians(1.0), math.radians(1.0))


def _sweep_case():
    from strapdown.analysis.gyrocompass.bound_sweep import SweepCase

    return SweepCase(latitude=math.radians(45.0), sigma=math.radians(1.0))


def _lines():
    from strapdown.analysis.vibration.environment import Environment, VibrationLine

    return Environment((VibrationLine(60.0, [0.1, 0, 0, 0, 0, 0]), VibrationLine(140.0, [0, 0.1j, 0, 0, 0, 0])))


def _environment():
    from strapdown.analysis.vibration.environment import load_environment

    return load_environment(QUALIFICATION)


def _mount():
    from strapdown.analysis.vibration.examples import AIRFRAME_PROFILE, ISOLATED_MOUNT
    from strapdown.analysis.vibration.mount import load_mount
    from strapdown.analysis.vibration.profile import load_profile

    return load_mount(ISOLATED_MOUNT), load_profile(AIRFRAME_PROFILE)


def _aided_inputs():
    from strapdown.analysis.alignment.aided import AidedTuning, aided_inputs
    from strapdown.analysis.alignment.trajectory import Manoeuvre

    return aided_inputs(Manoeuvre(), AidedTuning(), sample_rate=10.0, duration=20.0)


def _sheet():
    from strapdown.analysis.alignment.sensor_models import GRADES

    return GRADES[1]


def _imu_scenario():
    from strapdown.analysis.alignment.imu import Scenario

    return Scenario(math.radians(45.0), duration=300.0, sample_rate=10.0)


def _integrator():
    from strapdown.analysis.coning.integrators.adapters import algorithm_integrator

    return algorithm_integrator(get("two-sample"))


def _module(name):
    return __import__(f"strapdown.analysis.{name}", fromlist=["x"])


def _bound_case():
    from strapdown.analysis.gyrocompass.studies import BoundCase

    return BoundCase("white", "normal", math.radians(45.0), 0.0, 0.0, math.radians(1.0))


def _log_segment():
    from strapdown.analysis.logs.imu_log import ImuLog

    n = 10_000
    return ImuLog(1e-3 * np.arange(1, n + 1), np.zeros((n, 3)), np.zeros((n, 3)))


# (call, the argument its message must name); each call would allocate gigabytes or run for hours.
HUGE = {
    "coning.simulate duration": (lambda: __import__("strapdown.analysis.coning.simulator", fromlist=["simulate"]).simulate(ALG, _coning(), 0.0025, 1e12), "duration"),
    "coning.simulate sample_interval": (lambda: __import__("strapdown.analysis.coning.simulator", fromlist=["simulate"]).simulate(ALG, _coning(), 1e-12, 100.0), "sample_interval"),
    "coning.sample_increments steps": (lambda: __import__("strapdown.analysis.coning.simulator", fromlist=["x"]).sample_increments(_coning(), 0.0025, 10**12, 4), "steps"),
    "coning.window_index steps": (lambda: __import__("strapdown.analysis.coning.simulator", fromlist=["x"]).window_index(10**12, 4, 1), "steps"),
    "RegularPrecession.grid_increments count": (lambda: _coning().grid_increments(0.0025, 0, 10**12), "count"),
    "ScullingMotion.grid_increments count": (
        lambda: __import__("strapdown.analysis.coning.sculling_motion", fromlist=["x"]).ScullingMotion(0.01, 1.0, 2 * np.pi).grid_increments(0.0025, 0, 10**12, dual=True),
        "count",
    ),
    "coning.simulate_long_run duration": (lambda: __import__("strapdown.analysis.coning.long_run", fromlist=["x"]).simulate_long_run(ALG, _coning(), 0.0025, 1e12), "duration"),
    "coning.simulate_batch duration": (
        lambda: __import__("strapdown.analysis.coning.batch", fromlist=["x"]).simulate_batch(ALG, -1.0, 2 * np.pi * 10, np.radians([0.5, 1.0]), 0.0025, 1e30),
        "duration",
    ),
    "coning.simulate_batch steps with series": (
        lambda: __import__("strapdown.analysis.coning.batch", fromlist=["x"]).simulate_batch(ALG, -1.0, 2 * np.pi * 10, np.radians(1.0), 0.0025, steps=10**12, series=True),
        "steps",
    ),
    "coning.simulate_batch broadcast points": (
        lambda: __import__("strapdown.analysis.coning.batch", fromlist=["x"]).simulate_batch(ALG, -np.ones((100_000, 1)), 2 * np.pi * np.ones((1, 100_000)), np.radians(1.0), 0.0025, 1.0),
        "eps",
    ),
    "coning.drift_terms max_weight": (lambda: __import__("strapdown.analysis.coning.drift_theory", fromlist=["x"]).drift_terms(ALG, -1.0, 0.1, max_weight=20), "max_weight"),
    "coning.asymptotic_drift max_weight": (
        lambda: __import__("strapdown.analysis.coning.drift_theory", fromlist=["x"]).asymptotic_drift(ALG, eps=-1.0, nu=10.0, nutation=0.1, step=0.01, max_weight=19),
        "max_weight",
    ),
    "coning.simulator_check periods": (lambda: __import__("strapdown.analysis.coning.frequency_response", fromlist=["x"]).simulator_check(ALG, 0.1, periods=10**12), "periods"),
    "StageLoop.summary horizon": (lambda: _loop().summary(20.0, 20.0, horizon=3e9), "horizon"),
    "StageLoop.pulse_response horizon": (lambda: _loop().pulse_response(20.0, 20.0, horizon=3e9), "horizon"),
    "StageLoop.drift_response points": (lambda: _loop().drift_response(1e-5, 100.0, points=10**10), "points"),
    "multistage.simulate duration": (lambda: __import__("strapdown.analysis.multistage.stages", fromlist=["x"]).simulate(_scenario(1e9)), "duration"),
    "multistage.simulate step": (lambda: __import__("strapdown.analysis.multistage.stages", fromlist=["x"]).simulate(_scenario(1300.0), step=1e-7), "step"),
    "multistage.trajectory.grid duration": (lambda: __import__("strapdown.analysis.multistage.trajectory", fromlist=["x"]).grid(_scenario(1e12), 0.02), "duration"),
    "multistage.simulated_rate duration": (lambda: __import__("strapdown.analysis.multistage.decay_rates", fromlist=["x"]).simulated_rate(1.0, 1.0, duration=1e9), "duration"),
    "multistage.sensor_error_monte_carlo n_trials": (lambda: __import__("strapdown.analysis.multistage.sensor_statistics", fromlist=["x"]).sensor_error_monte_carlo(n_trials=10**9), "n_trials"),
    "multistage.check_printed_formulas samples": (lambda: __import__("strapdown.analysis.multistage.formula_checks", fromlist=["x"]).check_printed_formulas(samples=10**10), "samples"),
    "gyrocompass.azimuth_monte_carlo n_samples": (
        lambda: __import__("strapdown.analysis.gyrocompass.azimuth", fromlist=["x"]).azimuth_monte_carlo(math.radians(45.0), 0.0, 0.0, _narrowband(), 10**12, rng=1),
        "n_samples",
    ),
    "rocking.sample n_trials": (lambda: _narrowband().sample(1, 10**6, 10**6, 0.1), "n_trials"),
    "rocking.mean_variance_factor n_steps": (lambda: __import__("strapdown.analysis.gyrocompass.rocking", fromlist=["x"]).mean_variance_factor(_narrowband(), 10**12, 0.1), "n_steps"),
    "finite_sample.variance_factors max_samples": (lambda: __import__("strapdown.analysis.gyrocompass.finite_sample", fromlist=["x"]).variance_factors(_narrowband(), 10**12, 0.1), "max_samples"),
    "finite_sample.sample_mean_statistics n_samples": (
        lambda: __import__("strapdown.analysis.gyrocompass.finite_sample", fromlist=["x"]).sample_mean_statistics(_narrowband(), 10**12, 0.1),
        "n_samples",
    ),
    "finite_sample.required_averaging max_samples": (
        lambda: __import__("strapdown.analysis.gyrocompass.finite_sample", fromlist=["x"]).required_averaging(1e-3, math.radians(45.0), _narrowband(), 0.1, max_samples=10**12),
        "max_samples",
    ),
    "bound_sweep.sweep n_samples": (lambda: __import__("strapdown.analysis.gyrocompass.bound_sweep", fromlist=["x"]).sweep([_sweep_case()], n_samples=10**12), "n_samples"),
    "studies.run_cases n_samples": (lambda: __import__("strapdown.analysis.gyrocompass.studies", fromlist=["x"]).run_cases([_bound_case()], n_samples=10**12), "n_samples"),
    "gyrocompass.check_printed_formulas n_points": (lambda: __import__("strapdown.analysis.gyrocompass.formula_checks", fromlist=["x"]).check_printed_formulas(n_points=10**10), "n_points"),
    "alignment.simulate_imu n_trials": (lambda: __import__("strapdown.analysis.alignment.imu", fromlist=["x"]).simulate_imu(_alignment_scenario(600.0), n_trials=10**7), "n_trials"),
    "alignment.simulate_imu duration": (lambda: __import__("strapdown.analysis.alignment.imu", fromlist=["x"]).simulate_imu(_alignment_scenario(1e9), n_trials=1), "duration"),
    "alignment.alignment_monte_carlo n_trials": (
        lambda: __import__("strapdown.analysis.alignment.monte_carlo", fromlist=["x"]).alignment_monte_carlo(_alignment_scenario(600.0), method="kalman", n_trials=10**9),
        "n_trials",
    ),
    "base_motion.draw n_trials": (lambda: _alignment_scenario(60.0).motion.draw(1, 10**6, 10**6, 0.1), "n_trials"),
    "vibration monte_carlo_drift pairs": (lambda: _module("vibration.monte_carlo").monte_carlo_drift(get("two-sample"), _environment(), 1e-3, pairs=10**9, duration=10.0, rng=1), "pairs"),
    "vibration monte_carlo_drift duration": (lambda: _module("vibration.monte_carlo").monte_carlo_drift(get("two-sample"), _environment(), 1e-3, pairs=4, duration=1e9, rng=1), "duration"),
    "vibration monte_carlo_drift sample_interval": (
        lambda: _module("vibration.monte_carlo").monte_carlo_drift(get("two-sample"), _environment(), 1e-9, pairs=4, duration=10.0, rng=1),
        "sample_interval",
    ),
    "vibration draw_components count": (lambda: _module("vibration.monte_carlo").draw_components(_environment(), 10**11, np.random.default_rng(1)), "count"),
    "vibration simulate_mount duration": (lambda: _module("vibration.mount_simulation").simulate_mount(*_mount(), duration=1e9, sample_interval=1e-3, rng=1), "duration"),
    "vibration simulate_mount sample_interval": (lambda: _module("vibration.mount_simulation").simulate_mount(*_mount(), duration=1.0, sample_interval=1e-12, rng=1), "sample_interval"),
    "vibration simulate_mount realisations": (
        lambda: _module("vibration.mount_simulation").simulate_mount(*_mount(), duration=1.0, sample_interval=1e-3, realisations=10**9, rng=1),
        "realisations",
    ),
    "vibration mount_environment max_points": (lambda: _module("vibration.mount_response").mount_environment(*_mount(), max_points=10**12), "max_points"),
    "filtered_coning_check periods": (
        lambda: _module("vibration.simulation").filtered_coning_check(get("two-sample"), _environment().gyro, 1e-3, freq_hz=10.0, half_angle=0.01, periods=10**9),
        "periods",
    ),
    "vibration line_drift_check periods": (
        lambda: _module("vibration.simulation").line_drift_check(get("two-sample"), _lines(), 1 / 400, periods=10**9),
        "periods",
    ),
    "vibration noise_monte_carlo realisations": (
        lambda: _module("vibration.noise").noise_monte_carlo(get("two-sample"), _lines(), 1e-3, _module("vibration.noise").SensorNoise(1e-3), realisations=10**9, steps=100),
        "realisations",
    ),
    "vibration rate_design rates": (lambda: _module("vibration.rate_design").rate_design(_environment(), 1e-6, rates=np.geomspace(100.0, 1e4, 10**6)), "rates"),
    "trajectory.position_solution duration": (lambda: _module("alignment.trajectory").position_solution(_module("alignment.trajectory").Manoeuvre(), 1e9), "duration"),
    "trajectory.trajectory_state times": (lambda: _module("alignment.trajectory").trajectory_state(_module("alignment.trajectory").Manoeuvre(), [0.0, 1e9]), "times"),
    "trajectory.trajectory_increments duration": (lambda: _module("alignment.trajectory").trajectory_increments(_module("alignment.trajectory").Manoeuvre(), 100.0, 1e9), "duration"),
    "trajectory.trajectory_increments sample_rate": (lambda: _module("alignment.trajectory").trajectory_increments(_module("alignment.trajectory").Manoeuvre(), 1e9, 600.0), "sample_rate"),
    "aided.aided_sequence duration": (
        lambda: _module("alignment.aided").aided_sequence(_module("alignment.trajectory").Manoeuvre(), _module("alignment.aided").AidedTuning(), sample_rate=20.0, duration=1e9),
        "duration",
    ),
    "aided.aided_inputs duration": (
        lambda: _module("alignment.aided").aided_inputs(_module("alignment.trajectory").Manoeuvre(), _module("alignment.aided").AidedTuning(), sample_rate=20.0, duration=1e9),
        "duration",
    ),
    "aided.aided_alignment n_trials": (lambda: _module("alignment.aided").aided_alignment(_aided_inputs(), _sheet().gyro, _sheet().accel, n_trials=10**9, rng=1), "n_trials"),
    "aided.aided_monte_carlo n_trials": (lambda: _module("alignment.aided").aided_monte_carlo(_aided_inputs(), _sheet().gyro, _sheet().accel, n_trials=10**9, rng=1), "n_trials"),
    "sensor_models.simulate_sensor_errors n_samples": (
        lambda: _module("alignment.sensor_models").simulate_sensor_errors(_sheet().gyro, n_trials=1, n_samples=10**12, dt=0.1, rng=1),
        "n_samples",
    ),
    "sensor_models.simulate_sensor_errors n_trials": (
        lambda: _module("alignment.sensor_models").simulate_sensor_errors(_sheet().gyro, n_trials=10**9, n_samples=1000, dt=0.1, rng=1),
        "n_trials",
    ),
    "comparison.compare_methods n_trials": (
        lambda: _module("alignment.comparison").compare_methods(_imu_scenario(), _module("alignment.imu").SensorErrors(), n_trials=10**9, rng=1, methods=("analytic",)),
        "n_trials",
    ),
    "logs.replay segments": (lambda: _module("logs.replay").replay([_log_segment()] * 10**6, [get("two-sample")]), "segments"),
    "logs.estimate_environment segments": (lambda: _module("logs.environment_estimate").estimate_environment([_log_segment()] * 10**6), "segments"),
    "logs.welch_cross_spectra stretches": (lambda: _module("logs.cross_spectra").welch_cross_spectra([np.zeros((10_000, 6))] * 10**6, 1e-3, 1000), "stretches"),
    "observability.observability duration": (
        lambda: _module("alignment.observability").observability(_module("alignment.observability").stationary_problem(math.radians(45.0), duration=1e12)),
        "duration",
    ),
    "observability.observability duration of a million seconds": (
        lambda: _module("alignment.observability").observability(_module("alignment.observability").stationary_problem(math.radians(45.0), duration=1e6)),
        "duration",
    ),
    "observability.observability_gramian duration": (
        lambda: _module("alignment.observability").observability_gramian(_module("alignment.observability").stationary_problem(math.radians(45.0), duration=1e12)),
        "duration",
    ),
    "navigation.error_budget points": (
        lambda: _module("navigation.error_budget").error_budget(_module("navigation.imu_file").example_imu("tactical"), _module("navigation.error_model").Site(0.7), 3600.0, points=10**9),
        "points",
    ),
    "navigation.monte_carlo n_trials": (
        lambda: _module("navigation.monte_carlo").monte_carlo(
            _module("navigation.imu_file").example_imu("tactical"), _module("navigation.error_model").Site(0.7), [3600.0], n_trials=10**9, algorithm=get("two-sample")
        ),
        "n_trials",
    ),
    "navigation.convergence_study duration": (
        lambda: _module("navigation.convergence").convergence_study(get("two-sample"), _module("coning.precession").RegularPrecession(0.5, 6.0, 0.3, 1.0), 1e9, 0.01),
        "duration",
    ),
    "navigation.simulated_scrolling duration": (
        lambda: _module("navigation.scrolling").simulated_scrolling(get("two-sample"), _module("coning.sculling_motion").ScullingMotion(0.01, 1.0, 60.0), 0.01, 1e12),
        "duration",
    ),
    "integrators.coning_drift_rate steps": (
        lambda: _module("coning.integrators.verification").coning_drift_rate(_integrator(), 2, _module("coning.precession").RegularPrecession(-1.0, 60.0, 0.01), 1e-3, steps=10**12),
        "steps",
    ),
    "integrators.identify max_previous": (
        lambda: _module("coning.integrators.identification").identify(_integrator(), 64, max_previous=64, limits=budget.Limits(seconds=60.0)),
        "max_previous",
    ),
    "integrators.identify_record max_previous": (
        lambda: _module("coning.integrators.records").identify_record(
            _module("coning.integrators.records").Record(np.zeros((200_000, 3)), np.zeros((3125, 3)), np.arange(63, 200_000, 64)), 64, max_previous=64, limits=budget.Limits(memory=1e8)
        ),
        "max_previous",
    ),
    "integrators.sculling_rate periods": (
        lambda: _module("coning.integrators.verification").sculling_rate(
            _integrator(), 2, _module("coning.sculling_motion").ScullingMotion(0.01, 1.0, 2 * np.pi * 10), 1e-3, periods=10**12
        ),
        "periods",
    ),
}


def _small_log():
    """A small synthetic log on disk (read under tiny limits: the reader refuses it by its sample count)."""
    import tempfile
    from pathlib import Path

    from strapdown.analysis.logs.synthetic import still_truth, write_synthetic

    return write_synthetic(Path(tempfile.mkdtemp()) / "still.ulg", still_truth(duration=5.0, rate=100.0))


HUGE["logs.read_imu_log path"] = (lambda: _module("logs.reader").read_imu_log(_small_log(), limits=budget.Limits(seconds=300.0, memory=1e6)), "path")


def _drive():
    """A short drive with its GNSS fixes (refused under tiny limits by the size of its log)."""
    from strapdown.analysis.logs.imu_log import ImuLog
    from strapdown.analysis.logs.synthetic import vehicle_truth

    truth, _ = vehicle_truth(_module("alignment.trajectory").Manoeuvre(speed=5.0), duration=10.0, rate=20.0)
    return ImuLog(truth.time, truth.dtheta, truth.dv), truth.gnss


HUGE["logs.aided_log_alignment log"] = (lambda: _module("logs.aided").aided_log_alignment(*_drive(), limits=budget.Limits(seconds=300.0, memory=1e3)), "log")


def _run(call):
    tracemalloc.start()
    try:
        with pytest.raises(ValueError) as info:
            call()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return info.value, peak


@pytest.mark.parametrize("name", sorted(HUGE))
def test_a_huge_request_is_refused_by_name_before_it_allocates(name):
    call, argument = HUGE[name]
    exc, peak = _run(call)
    assert isinstance(exc, budget.BudgetExceeded), f"{type(exc).__name__}: {exc}"
    assert f"`{argument}`" in str(exc), str(exc)
    assert "exceeds the limit" in str(exc)
    assert peak < 2e8, f"{peak / 1e6:.0f} MB traced before the refusal"


def test_larger_limits_let_a_request_through():
    from strapdown.analysis.coning.simulator import simulate

    small = budget.Limits(seconds=300.0, memory=1e5)
    with pytest.raises(budget.BudgetExceeded, match="`duration`"):
        simulate(ALG, _coning(), 0.0025, 10.0, limits=small)
    run = simulate(ALG, _coning(), 0.0025, 10.0, limits=budget.Limits(seconds=300.0, memory=1e9))
    assert run.steps == 1000


def test_limits_of_the_wrong_type_are_refused():
    from strapdown.analysis.coning.simulator import simulate

    with pytest.raises(TypeError, match="`limits`"):
        simulate(ALG, _coning(), 0.0025, 1.0, limits=2e9)


def test_the_estimate_of_a_large_run_is_checked_and_passes():
    """A run of 2e5 s at h = 2.5 ms (2e7 steps, about 0.8 GB of error series and times) is estimated and within the defaults."""
    steps = 2e5 / (ALG.samples * 0.0025)
    est = budget.coning_simulation(steps, window=ALG.window, degree_sum=sum(t.degree for t in ALG.terms), velocity=False, chunk_steps=65536, what="")
    assert 0.5e9 < est.memory <= budget.DEFAULT_MEMORY_LIMIT
    budget.check(est)


# (call, the argument its message must name, a word of the message)
EMPTY = {
    "simulate_batch nutation=[]": (lambda: __import__("strapdown.analysis.coning.batch", fromlist=["x"]).simulate_batch(ALG, -1.0, 2 * np.pi * 10, [], 0.0025, 1.0), "nutation", "empty"),
    "drift_rate time=[]": (lambda: __import__("strapdown.analysis.coning.simulator", fromlist=["x"]).drift_rate([], np.zeros((0, 3))), "time", "two"),
    "responses time=[]": (lambda: __import__("strapdown.analysis.multistage.tilt_loop", fromlist=["x"]).responses(_loop(), []), "time", "empty"),
    "complementary_filter omega=[]": (lambda: __import__("strapdown.analysis.multistage.tilt_loop", fromlist=["x"]).complementary_filter(_loop(), []), "omega", "empty"),
    "root_locus_k ks=[]": (lambda: __import__("strapdown.analysis.multistage.tilt_loop", fromlist=["x"]).root_locus_k(1e-3, []), "ks", "empty"),
    "root_locus_l ls=[]": (lambda: __import__("strapdown.analysis.multistage.tilt_loop", fromlist=["x"]).root_locus_l(1e-3, []), "ls", "empty"),
    "validity_map latitudes=[]": (lambda: __import__("strapdown.analysis.gyrocompass.bound_sweep", fromlist=["x"]).validity_map([], [0.01], n_samples=100), "latitudes", "empty"),
    "sweep cases=[]": (lambda: __import__("strapdown.analysis.gyrocompass.bound_sweep", fromlist=["x"]).sweep([], n_samples=100), "cases", "none"),
    "preintegrate dtheta=[]": (lambda: __import__("strapdown.analysis.alignment.preintegration", fromlist=["x"]).preintegrate([], [], 0.01, 10), "dtheta", "shape"),
    "load_toml path=''": (lambda: __import__("strapdown.derivations.coning.algorithms", fromlist=["x"]).load_toml(""), "path", "empty"),
    "drift_across_band frequency=[]": (
        lambda: _module("vibration.tuning").drift_across_band([get("two-sample")], _environment(), 1e-3, [], half_angle=0.01),
        "frequency",
        "empty",
    ),
    "report generate out=''": (lambda: __import__("strapdown.analysis.report", fromlist=["x"]).generate(""), "out", "empty"),
}


@pytest.mark.parametrize("name", sorted(EMPTY))
def test_an_empty_input_gets_a_message_that_says_so(name):
    call, argument, word = EMPTY[name]
    exc, _ = _run(call)
    assert f"`{argument}`" in str(exc), str(exc)
    assert word in str(exc), str(exc)


# --------------------------------------------------------------------------- command line
def _cli(*argv):
    return subprocess.run([sys.executable, "-m", "strapdown.analysis", *argv], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (("stability", "--schuler", "--accel-m-s2", "20", "--accel-duration", "20", "--horizon", "3e9"), "--horizon"),
        (("derive", "local-error", "--algorithm", "savage-1+1", "--max-order", "20"), "--max-order"),
        (("multistage", "--duration", "1e9"), "--duration"),
        (("budget", "--imu", str(_EXAMPLE_IMU), "--lat-deg", "45", "--duration", "3600", "--points", "1e9", "--quiet"), "--points"),
        (("budget", "--imu", str(_EXAMPLE_IMU), "--lat-deg", "45", "--duration-s", "1e12", "--quiet"), "--duration"),
        # a gigahertz sample rate: the spectrum's response integral cannot converge; refused in seconds, not minutes and gigabytes
        (("environment-drift", "--algorithm", "two-sample", "--environment", str(QUALIFICATION), "--sample-interval", "1e-9", "--quiet"), "--sample-interval"),
    ],
)
def test_a_command_refuses_a_huge_request_naming_the_option(argv, option):
    r = _cli(*argv)
    assert r.returncode == 2, r.stderr
    assert option in r.stderr and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (("report", "--out", ""), ("--out", "empty name")),
        (("drift", "--algorithm-file", "", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1"), ("--algorithm-file", "empty file name")),
        (("derive", "coning-drift", "--algorithm", "savage-1+1", "--omega-h-rad", "0.1,inf"), ("--omega-h-rad", "finite", "'inf'")),
        (("derive", "coning-drift", "--algorithm", "savage-1+1", "--omega-h-rad", ""), ("--omega-h-rad", "empty")),
        (("velocity-error", "--algorithm", "savage-1+1", "--motion", "sculling", "--freq-hz", "20", "--sample-interval", "0.0025", "--duration", "1", "--w0-m-s", "inf,0,0"), ("--w0-m-s", "finite")),
        (("report", "--only", ""), ("--only", "''")),
    ],
)
def test_a_command_says_what_is_wrong_with_an_empty_or_infinite_value(argv, words):
    r = _cli(*argv)
    assert r.returncode == 2, r.stderr
    for w in words:
        assert w in r.stderr, r.stderr
    assert "Traceback" not in r.stderr
