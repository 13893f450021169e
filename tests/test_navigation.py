"""Navigation over the rotating Earth and its error budget: each claim against an independent truth.

* the integration converges at each algorithm's order against DOP853 on the kinematics;
* the scrolling error's closed form against parallel computation on classical sculling (1 %);
* the budget's Schuler responses against the textbook formulas (2 %), and through the command line;
* the budget against the nonlinear navigator (Monte Carlo), per source and in total, at 1, 10, 60 min;
* bad IMU and environment files: one line, exit status 2.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.sculling_motion import ScullingMotion
from strapdown.analysis.navigation.convergence import convergence_study
from strapdown.analysis.navigation.error_budget import error_budget
from strapdown.analysis.navigation.error_model import Site
from strapdown.analysis.navigation.imu_file import ImuSpec, TriadErrors, example_imu, load_imu
from strapdown.analysis.navigation.monte_carlo import compare, monte_carlo, single_source
from strapdown.analysis.navigation.scrolling import sculling_errors, simulated_scrolling
from strapdown.derivations.coning.registry import get
from strapdown.derivations.navigation.position_algorithm import position_algorithm, scrolling_kernel

IMUS = Path(__import__("strapdown.analysis.navigation", fromlist=["x"]).__file__).parent / "imus"
G0 = 9.80665
R_EARTH = 6371000.0


# --------------------------------------------------------------------------- position algorithm
def test_position_weights_integrate_a_constant_specific_force_exactly():
    for n in range(1, 6):
        a = position_algorithm(n)
        # S = h Σ s_j b_j = ½ f H² for b_j = f h, H = N h
        assert sum(a.weights) == pytest.approx(n * n / 2.0, rel=0, abs=1e-15)


def test_scrolling_kernel_taylor_and_closed_form_agree():
    import sympy as sp

    from strapdown.derivations.navigation.position_algorithm import X

    k = scrolling_kernel(get("two-sample"))
    f = sp.lambdify(X, k.function, "numpy")
    for x in (0.6, 1.0):
        poly = sum(float(c) * x**i for i, c in enumerate(k.taylor_real)) + 1j * sum(float(c) * x**i for i, c in enumerate(k.taylor_imag))
        assert abs(complex(f(x)) - poly) < 1e-10 * abs(poly)


# --------------------------------------------------------------------------- convergence
MOTION = RegularPrecession(eps=0.5, nu=2 * np.pi * 2, nutation=0.3, nu_dual=3.0, nutation_dual=1.0)


@pytest.mark.parametrize(("name", "h", "orders"), [("one-sample", 0.01, (2, 2, 2)), ("two-sample", 0.01, (4, 4, 4)), ("lebedev-panov-6", 0.02, (6, 6, 4))])
def test_the_integration_converges_at_the_algorithms_order(name, h, orders):
    s = convergence_study(get(name), MOTION, 1.0, h, halvings=2)
    for quantity, order in zip(("attitude", "velocity", "position"), orders):
        observed = s.observed_orders(quantity)[-1]
        assert abs(observed - order) < 0.25, (quantity, s.observed_orders(quantity))


def test_the_convergence_check_can_fail():
    """One-sample attitude is second order: a claim of fourth order would be refused."""
    s = convergence_study(get("one-sample"), MOTION, 1.0, 0.01, halvings=1)
    assert abs(s.observed_orders("attitude")[-1] - 4) > 1.5


# --------------------------------------------------------------------------- scrolling
@pytest.mark.parametrize("name", ["one-sample", "two-sample", "optimal-3"])
@pytest.mark.parametrize("phase", [0.0, 0.7])
def test_scrolling_closed_form_agrees_with_simulation_within_one_percent(name, phase):
    m = ScullingMotion(1e-3, 5.0, 2 * np.pi * 10, accel_phase=phase, angle_phase=0.2)
    closed = sculling_errors(get(name), m, 0.004)
    sim = simulated_scrolling(get(name), m, 0.004, 10.0)
    assert sim.position_rate == pytest.approx(closed.position_rate, rel=0.01)
    assert sim.velocity_rate == pytest.approx(closed.velocity_rate, rel=0.01)


def test_the_scrolling_check_can_fail():
    """The closed form at another sample interval is more than 1 % off the simulation."""
    m = ScullingMotion(1e-3, 5.0, 2 * np.pi * 10, accel_phase=0.7)
    wrong = sculling_errors(get("two-sample"), m, 0.0044)
    sim = simulated_scrolling(get("two-sample"), m, 0.004, 10.0)
    assert abs(sim.position_rate / wrong.position_rate - 1.0) > 0.01


# --------------------------------------------------------------------------- textbook Schuler responses
SITE = Site(math.radians(45.0), 0.0)
WS = math.sqrt(SITE.gravity / R_EARTH)


@pytest.mark.parametrize("fraction", [0.25, 0.5])
def test_accelerometer_bias_gives_the_schuler_response(fraction):
    b = 100e-6 * G0
    t = fraction * 2 * math.pi / WS
    r = error_budget(ImuSpec("x", 100.0, accel=TriadErrors(bias=[b, 0, 0])), SITE, t, report_times=[t])
    north = r.line("accel bias").mean[-1, 6]
    assert north == pytest.approx(b / WS**2 * (1 - math.cos(WS * t)), rel=0.02)


@pytest.mark.parametrize("fraction", [0.25, 0.5])
def test_east_gyro_bias_gives_the_schuler_response(fraction):
    """``δp_N = −R ε (t − sin(ω_s t)/ω_s)`` (estimate minus truth; C̃ = (I − [φ×]) C)."""
    eps = math.radians(0.01) / 3600.0
    t = fraction * 2 * math.pi / WS
    r = error_budget(ImuSpec("x", 100.0, gyro=TriadErrors(bias=[0, eps, 0])), SITE, t, report_times=[t])
    north = r.line("gyro bias").mean[-1, 6]
    assert north == pytest.approx(-R_EARTH * eps * (t - math.sin(WS * t) / WS), rel=0.02)


def test_the_textbook_check_can_fail():
    """The same bias read at a third of the period does not follow the half-period value."""
    b = 100e-6 * G0
    t = math.pi / WS
    r = error_budget(ImuSpec("x", 100.0, accel=TriadErrors(bias=[b, 0, 0])), SITE, t, report_times=[t / 3])
    north = r.line("accel bias").mean[r.index(r.report_times[0]), 6]
    assert abs(north / (2 * b / WS**2) - 1) > 0.02


def _cli(*argv, timeout=300):
    return subprocess.run([sys.executable, "-m", "strapdown.analysis", *argv], capture_output=True, text=True, timeout=timeout)


def test_the_command_line_gives_the_schuler_response(tmp_path):
    f = tmp_path / "imu.toml"
    f.write_text('sample_rate_hz = 100.0\n[accel]\nbias_ug = [100.0, 0.0, 0.0]\n')
    t = math.pi / WS
    r = _cli("budget", "--imu", str(f), "--lat-deg", "45", "--heading-deg", "0", "--duration-s", repr(t), "--alignment", "none", "--json", "--quiet")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    b = 100e-6 * G0
    north = d["sources"]["accel bias"]["north_east_position_m"][0]
    assert north == pytest.approx(2 * b / WS**2, rel=0.02)
    for key in ("horizontal_position_error_m", "velocity_error_m_s", "attitude_error_deg"):
        assert key in d["total"] and key in d["sources"]["accel bias"]
        assert len(d["sources"]["accel bias"]["series"][key]) == len(d["times_s"])
    assert d["dominant"]["position"] == "accel bias"


# --------------------------------------------------------------------------- the budget against the Monte Carlo
TIMES = (60.0, 600.0, 3600.0)
SIM_SITE = Site(math.radians(45.0), 0.3)
ALG = get("two-sample")


def _agreement(imu, name, *, trials, alignment="none"):
    r = error_budget(imu, SIM_SITE, 3600.0, report_times=TIMES, alignment=alignment, alignment_time=120.0)
    mc = monte_carlo(imu, SIM_SITE, TIMES, n_trials=trials, algorithm=ALG, alignment=alignment, alignment_time=120.0, rng=20261122)
    line = r.total if name == "total" else r.line(name)
    return compare(line, mc), r, mc


@pytest.mark.parametrize("name", ["gyro bias", "accel bias"])
def test_fixed_sources_agree_with_the_navigator(name):
    imu = ImuSpec("x", 10.0, gyro=TriadErrors(bias=[1e-6, 2e-6, -1e-6]), accel=TriadErrors(bias=[5e-4, -3e-4, 0.0]))
    a, _, _ = _agreement(single_source(imu, name), name, trials=1)
    assert a.all, (a.model, a.simulated)


@pytest.mark.parametrize("name", ["gyro turn-on bias", "ARW", "VRW", "gyro bias instability", "accel misalignment"])
def test_random_sources_agree_with_the_navigator(name):
    imu = replace_rate(example_imu("tactical"), 10.0)
    a, _, _ = _agreement(single_source(imu, name), name, trials=120)
    assert a.all, (a.model, a.low, a.high)


def test_the_total_after_alignment_agrees_with_the_navigator():
    imu = replace_rate(example_imu("tactical"), 10.0)
    a, r, _ = _agreement(imu, "total", trials=120, alignment="analytic")
    assert a.all, (a.model, a.low, a.high)
    assert r.dominant() == "gyro turn-on bias"


def test_the_monte_carlo_comparison_can_fail():
    """The same simulation against a line 30 % too large is refused."""
    imu = single_source(replace_rate(example_imu("tactical"), 10.0), "ARW")
    a, r, mc = _agreement(imu, "ARW", trials=120)
    line = r.line("ARW")
    from dataclasses import replace

    wrong = replace(line, cov=line.cov * 1.3**2)
    assert not compare(wrong, mc).all


def replace_rate(imu, rate):
    from dataclasses import replace

    return replace(imu, sample_rate=rate)


# --------------------------------------------------------------------------- files
@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("[gyro]\narw_deg_per_rt_h = 0.1\n", ("sample_rate_hz",)),
        ("sample_rate_hz = 100\n[gyro]\narw_deg_per_rt_hour = 0.1\n", ("unknown key", "arw_deg_per_rt_hour")),
        ("sample_rate_hz = 100\n[gyro]\nbias_deg_per_h = [1.0, 2.0]\n", ("bias_deg_per_h", "3 numbers")),
        ("sample_rate_hz = 100\n[accel]\nvrw_m_s_per_rt_h = -1\n", ("vrw_m_s_per_rt_h", ">= 0")),
        ("sample_rate_hz = 'fast'\n", ("sample_rate_hz", "number")),
        ("sample_rate_hz = 100\n[gyro\n", ("not valid TOML",)),
    ],
)
def test_a_bad_imu_file_gets_one_line_and_status_2(tmp_path, text, words):
    f = tmp_path / "imu.toml"
    f.write_text(text)
    with pytest.raises(ValueError):
        load_imu(f)
    r = _cli("budget", "--imu", str(f), "--lat-deg", "45", "--duration", "60", "--quiet")
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr
    for w in words:
        assert w in r.stderr, r.stderr


def test_a_bad_environment_file_gets_one_line_and_status_2(tmp_path):
    f = tmp_path / "env.toml"
    f.write_text("[[line]]\nfreq_hz = -3\nhalf_angle_deg = 0.1\n")
    r = _cli("budget", "--imu", str(IMUS / "tactical.toml"), "--environment", str(f), "--lat-deg", "45", "--duration", "60", "--quiet")
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr
    assert "freq_hz" in r.stderr


def test_an_environment_adds_the_algorithm_lines():
    from strapdown.analysis.vibration.environment import load_environment
    from strapdown.analysis.vibration.examples import QUALIFICATION

    r = error_budget(example_imu("mems"), SITE, 600.0, environment=load_environment(QUALIFICATION), algorithm=get("two-sample"))
    names = {ln.name for ln in r.lines}
    assert {"coning", "pseudo-coning", "sculling", "pseudo-sculling", "scrolling"} <= names
    assert all(r.line(n).deterministic for n in ("coning", "sculling", "scrolling"))


def test_example_imus_load():
    for name in ("tactical", "mems"):
        imu = example_imu(name)
        assert imu.sample_rate > 0 and imu.gyro.random_walk > 0


def test_the_budgets_memory_estimate_is_within_a_factor_1_5_of_its_peak():
    """The guard's estimate against the traced peak of a long series (it once said 771 MB for 10 MB)."""
    import tracemalloc

    from strapdown.analysis.core import budget
    from strapdown.analysis.navigation import error_budget as eb

    imu, site, points = example_imu("tactical"), Site(math.radians(45.0), 0.0), 2000
    seen = []
    real_check = budget.check
    try:
        budget.check = lambda estimate, limits=None: seen.append(estimate) or real_check(estimate, limits)
        tracemalloc.start()
        eb.error_budget(imu, site, 600.0, alignment="none", points=points)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
        budget.check = real_check
    assert 1 / 1.5 <= seen[0].memory / peak <= 1.5, (seen[0].memory, peak)
