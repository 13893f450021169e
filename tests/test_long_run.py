"""A run of any length at constant memory (``coning.long_run``): same results as the series, an estimate that matches the peak."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from strapdown.analysis.coning import kernels
from strapdown.analysis.coning.long_run import PERIODIC_WINDOW, simulate_long_run
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.coning.streaming import window_peak
from strapdown.analysis.core import budget
from strapdown.derivations.coning.registry import get

needs_numba = pytest.mark.skipif(not kernels.available(), reason="numba is not installed")
CONING = RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(1.0))


def test_window_peak_is_the_distance_from_the_least_squares_line():
    """Against a direct least-squares fit (numpy.polyfit), per component, on rows of unequal length."""
    rng = np.random.default_rng(1)
    e = rng.standard_normal((2, 70000, 3)) + np.linspace(0, 50, 70000)[None, :, None]
    got = window_peak(e, rows=[70000, 900])
    for i, m in enumerate((70000, 900)):
        k = np.arange(m)
        fit = np.stack([np.polyval(np.polyfit(k, e[i, :m, j], 1), k) for j in range(3)], axis=-1)
        assert got[i] == pytest.approx(np.linalg.norm(e[i, :m] - fit, axis=-1).max(), rel=1e-9)
    assert window_peak(e[:, :2])[0] == 0.0  # two rows lie on their line


@needs_numba
@pytest.mark.parametrize("name", ["panov-4s-3", "ignagni-1996-4"])
def test_the_compiled_run_equals_the_numpy_series_window_by_window(name):
    """Several windows (1024 steps each, a partial last one): kernel and numpy reference agree to round-off."""
    alg = get(name)
    h = 0.0025
    duration = 3.3 * 1024 * alg.samples * h
    a = simulate_long_run(alg, CONING, h, duration, window=1024, engine="compiled")
    b = simulate_long_run(alg, CONING, h, duration, window=1024, engine="numpy")
    assert (a.engine, b.engine, a.steps) == ("compiled", "numpy", b.steps)
    # round-off of n step products and of the exact solution's phase ν t (as tests/test_kernels.py)
    eps = np.finfo(float).eps
    roundoff = 2 * eps * a.steps + 8 * eps * CONING.nu * a.duration
    np.testing.assert_allclose(a.drift, b.drift, rtol=0, atol=3 * roundoff / a.duration)
    np.testing.assert_allclose(a.final_error, b.final_error, rtol=0, atol=roundoff)
    assert abs(a.periodic_error - b.periodic_error) <= 2 * roundoff
    assert abs(a.rms_error - b.rms_error) <= roundoff and abs(a.max_error - b.max_error) <= roundoff
    # one window as long as the run: the periodic error of the whole series
    whole = simulate(alg, CONING, h, duration, engine="numpy")
    single = simulate_long_run(alg, CONING, h, duration, window=4096, engine="compiled")
    assert abs(single.periodic_error - float(whole.periodic_error)) <= 2 * roundoff
    assert abs(single.drift_rate - float(whole.drift_rate)) <= 3 * roundoff / a.duration
    assert abs(a.periodic_error - single.periodic_error) > 10 * roundoff  # the windows change it: the check can fail


def test_bad_windows_and_motions_are_refused():
    with pytest.raises(ValueError, match="`window`"):
        simulate_long_run(get("panov-4s-3"), CONING, 0.0025, 1.0, window=1000)
    with pytest.raises(TypeError, match="`motion`"):
        simulate_long_run(get("panov-4s-3"), [CONING], 0.0025, 1.0)


_PEAK = """
import json, sys, tracemalloc
import numpy as np
from strapdown.analysis.coning.long_run import simulate_long_run, PERIODIC_WINDOW
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core import budget
from strapdown.derivations.coning.registry import get
alg, h = get("panov-4s-3"), 0.0025
m = RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(1.0))
simulate_long_run(alg, m, h, 1.0)  # load the kernel before measuring
simulate(alg, m, h, 1.0, engine="numpy")
tracemalloc.start()
out = {}
degree = sum(t.degree for t in alg.terms)
for steps in (int(sys.argv[1]), 4 * int(sys.argv[1])):
    duration = steps * alg.samples * h
    for kind in ("long", "series"):
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        r = simulate_long_run(alg, m, h, duration) if kind == "long" else simulate(alg, m, h, duration, engine="numpy")
        peak = tracemalloc.get_traced_memory()[1] - base
        del r
        if kind == "long":
            est = budget.coning_long_run(steps, window=min(PERIODIC_WINDOW, steps), samples=alg.samples, degree_sum=degree, series=False, what="")
        else:
            est = budget.coning_simulation(steps, window=alg.window, degree_sum=degree, velocity=False, chunk_steps=16384, what="")
        out[f"{kind} {steps}"] = [peak, est.memory]
print(json.dumps(out))
"""


@needs_numba
def test_the_memory_estimates_match_the_measured_peaks():
    """In a child process (tracemalloc, the kernel loaded first): each estimate within a factor 1.5 of the
    measured peak, and the long run's peak the same for a run four times longer."""
    steps = 3 * PERIODIC_WINDOW  # three windows, then twelve
    out = subprocess.run([sys.executable, "-c", _PEAK, str(steps)], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    peaks = json.loads(out.stdout)
    for key, (peak, estimate) in peaks.items():
        assert peak / 1.5 <= estimate <= 1.5 * peak, (key, peak, estimate)
    short, long = peaks[f"long {steps}"][0], peaks[f"long {4 * steps}"][0]
    assert long <= 1.05 * short  # constant memory in the run length
    assert peaks[f"series {4 * steps}"][0] > 3 * peaks[f"series {steps}"][0]  # the series grows (the check can fail)


def test_the_estimate_refuses_what_the_series_could_not_hold():
    """Through the CLI a long run streams: 2e7 steps fit the default limit, and a tight limit still refuses them."""
    from strapdown.analysis.cli import main

    argv = ["drift", "--algorithm", "panov-4s-3", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "200000", "--json", "--quiet"]
    assert main(argv + ["--memory-limit-mb", "5"]) == 2
    steps = 2e7
    est = budget.coning_long_run(steps, window=PERIODIC_WINDOW, samples=4, degree_sum=4, series=False, what="")
    assert est.memory < 20e6 < budget.coning_simulation(steps, window=4, degree_sum=4, velocity=False, chunk_steps=16384, what="").memory
