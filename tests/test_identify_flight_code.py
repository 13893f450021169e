"""``identify`` on flight code as it really is: each integrator of ``tests/integrators/`` gets the verdict its own simulation confirms.

Every integrator is loaded from its file in a child process (as the command line
does, :class:`~strapdown.analysis.coning.integrators.isolation.Isolated`), assessed,
and the verdict checked twice: against what the code is (its coefficients,
written in the file), and against a simulation of the code itself — its coning
drift on the exact increments of classical coning, its one-step error on a
tumbling motion, or, for a verdict of time variance, the same input at two
positions or two calls.  Each verdict is also shown saying yes on a clean
integrator (``tests/test_identification.py`` keeps the registry round trip).
"""

from __future__ import annotations

import importlib.util
import json
import math
import shutil
import subprocess
import sys
import time
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from strapdown.analysis.coning.integrators.assessment import assess
from strapdown.analysis.coning.integrators.interface import step_increments
from strapdown.analysis.coning.integrators.isolation import Isolated
from strapdown.analysis.coning.integrators.recursions import recursion
from strapdown.analysis.coning.integrators.verification import coning_drift_check, coning_drift_rate, velocity_error_exponent
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.derivations.coning.registry import get

HERE = Path(__file__).resolve().parent
FILES = HERE / "integrators"
ROOT = HERE.parent
OMEGA_H = (0.5, 1.0)


def _assess(file: str, n: int, name: str = "integrate", **kwargs):
    with Isolated(f"{FILES / file}:{name}", time_limit=600.0) as child:
        a = assess(child.integrator, n, omega_h=kwargs.pop("omega_h", OMEGA_H), **kwargs)
    json.dumps(a.as_dict(), allow_nan=False)
    return a


def _module(file: str, tag: str):
    """A fresh in-process copy of a file (its own globals), for simulations of the code itself."""
    spec = importlib.util.spec_from_file_location(f"flight_code_{tag}", FILES / file)
    mod = importlib.util.module_from_spec(spec)
    sys.path.insert(0, str(FILES))
    try:
        spec.loader.exec_module(mod)
    finally:
        sys.path.remove(str(FILES))
    return mod


def _compiler(cxx: bool = False):
    names = ("c++", "g++", "clang++") if cxx else ("cc", "gcc", "clang")
    return next((shutil.which(x) for x in names if shutil.which(x)), None)


@pytest.fixture(scope="module")
def built():
    """The C and C++ files built next to their loaders (skipped where no compiler exists)."""
    cc, cxx = _compiler(), _compiler(cxx=True)
    done = {}
    for src, lib, compiler in (
        (FILES / "hang_c.c", "libhang_c.so", cc),
        (FILES / "px4_integrator_coning.c", "libpx4.so", cc),
        (FILES / "per_sample.c", "libper_sample.so", cc),
        (ROOT / "docs" / "integrator_example.cpp", "libintegrator_cpp.so", cxx),
    ):
        if compiler is None:
            continue
        out = subprocess.run([compiler, "-O2", "-shared", "-fPIC", "-o", str(FILES / lib), str(src)], capture_output=True, text=True)
        if out.returncode == 0:
            done[lib] = FILES / lib
    yield done
    for path in done.values():
        path.unlink(missing_ok=True)


def _need(built, lib):
    if lib not in built:
        pytest.skip(f"no compiler built {lib} on this machine")


def _cli(*argv, timeout=300.0):
    return subprocess.run([sys.executable, "-m", "strapdown.analysis.cli", "identify", *argv], capture_output=True, text=True, timeout=timeout, cwd=ROOT)


def _verdicts(a) -> dict:
    return {k: v.holds for k, v in a.assumptions.items()}


# --------------------------------------------------------------------------- the child process
def test_a_hang_is_stopped_within_its_limit_exit_2():
    start = time.monotonic()
    out = _cli("--integrator", f"{FILES / 'hang.py'}:integrate", "--samples-per-step", "2", "--time-limit", "8", "--quiet")
    elapsed = time.monotonic() - start
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "did not return within the time limit of 8 s" in lines[0] and "--time-limit" in lines[0]
    assert "Traceback" not in out.stderr and out.stdout == ""
    assert elapsed < 8 + 20  # the limit, plus the command's own start on a shared machine


def test_a_hung_c_function_that_ignores_sigterm_is_killed(built):
    _need(built, "libhang_c.so")
    start = time.monotonic()
    with pytest.raises(ValueError, match="did not return within the time limit of 3 s"):
        with Isolated(f"{FILES / 'hang_c.py'}:integrate", time_limit=3.0) as child:
            step_increments(child.integrator, np.zeros((4, 3)), 2)
    assert time.monotonic() - start < 3.0 + 5.0  # SIGTERM ignored: SIGKILL after the grace


def test_a_segfault_is_one_line_exit_2():
    out = _cli("--integrator", f"{FILES / 'segfault.py'}:integrate", "--samples-per-step", "2", "--quiet")
    assert out.returncode == 2 and "SIGSEGV (segmentation fault)" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1 and "Traceback" not in out.stderr


def test_sys_exit_at_import_is_one_line_exit_2():
    out = _cli("--integrator", f"{FILES / 'exits_at_import.py'}:integrate", "--samples-per-step", "2", "--quiet")
    assert out.returncode == 2, out
    assert "importing it called sys.exit(3)" in out.stderr and len(out.stderr.strip().splitlines()) == 1


def test_a_sibling_module_imports():
    a = _assess("sibling_import.py", 2, verify=False)
    assert a.identification.terms == {"1,2": "2/3"} and a.assumptions.trusted


# --------------------------------------------------------------------------- time invariance
def test_global_state_is_not_time_invariant_and_its_simulation_drifts_differently_on_later_calls():
    a = _assess("global_state.py", 2)
    assert _verdicts(a)["time_invariance"] is False and not a.assumptions.trusted
    assert a.assumptions.memory.holds is False and a.assumptions.precision.holds is False  # not decided without invariance
    # the code itself: the same coning run as its first call and as a later call
    mod = _module("global_state.py", "global")
    from strapdown.analysis.coning.integrators.interface import Integrator

    integ = Integrator(mod.integrate)
    motion = RegularPrecession(-1.0, 2 * math.pi, 0.02)
    first = coning_drift_rate(integ, 2, motion, 0.5 / (2 * math.pi))
    for _ in range(5):
        coning_drift_rate(integ, 2, motion, 0.5 / (2 * math.pi))
    later = coning_drift_rate(integ, 2, motion, 0.5 / (2 * math.pi))
    assert abs(first - later) > 1e-3 * abs(first)


def test_a_coefficient_that_alternates_every_step_is_not_time_invariant():
    a = _assess("alternating.py", 2, verify=False)
    assert _verdicts(a)["time_invariance"] is False
    # the code itself: one physical step of a coning record, given at an even and at an odd step
    mod = _module("alternating.py", "alternating")
    inc = RegularPrecession(-1.0, 2 * math.pi, 0.05).grid_increments(0.05, 0, 8)
    even = mod.integrate(inc, 2)[-1]
    odd = mod.integrate(np.vstack([np.zeros((2, 3)), inc]), 2)[-1]
    assert np.abs(even - odd).max() > 1e-9


def test_a_clean_integrator_is_time_invariant():
    a = _assess("cross_step_state.py", 1, verify=False)
    assert a.assumptions.time_invariance.holds and a.assumptions.time_invariance.calls <= 10


# --------------------------------------------------------------------------- memory
def test_memory_beyond_k_raises_k_to_what_the_code_reads():
    a = _assess("memory_six_back.py", 1)  # --max-previous 4 by default
    mem = a.assumptions.memory
    assert mem.holds and mem.needed == 6 and mem.used == 6 and mem.start == 4
    assert a.identification.terms == {"-5,1": "1/10"} and a.identification.exact and a.identification.isotropic
    assert not a.identification.remainder.above_roundoff
    assert a.check.holds is True  # the code's simulated drift agrees with the closed form of p1 + (1/10) p_(-5) x p1


def test_memory_longer_than_the_longest_probed_says_no():
    a = _assess("memory_six_back.py", 1, max_previous=2, max_previous_limit=5, verify=False)
    assert a.assumptions.time_invariance.holds  # the blocks keep twice the longest memory probed clear
    assert a.assumptions.memory.holds is False and a.assumptions.memory.needed is None


# --------------------------------------------------------------------------- isotropy
def test_a_correction_on_z_only_is_described_per_axis_and_each_axis_drift_agrees_with_its_simulation():
    a = _assess("z_axis_only.py", 2, omega_h=(0.25, 0.5, 1.0, 2.0))
    iso = a.assumptions.isotropy
    assert iso.holds is False and a.coning is None
    by_axis = {c.name: c for c in iso.corrections}
    assert by_axis["z"].terms == {"1,2": "2/3"} and by_axis["x"].terms == {} and by_axis["y"].terms == {}
    for k, c in enumerate(iso.corrections):
        check = iso.checks[k]
        assert check is not None and check.holds is True, (c.name, [(p.closed_form, p.simulated) for p in check.points])
        assert all(abs(p.simulated / p.closed_form - 1) < 0.01 for p in check.points)  # within 1 % on each axis (here far better)
    # cones about x drift far more than cones about z: the closed forms of the two algorithms
    dx, dz = by_axis["x"].drift_function(), by_axis["z"].drift_function()
    assert dx(0.25) / dz(0.25) > 100


def test_a_dropped_z_increment_fails_the_first_order_condition_and_the_code_errs_at_h():
    a = _assess("drops_z.py", 2)
    assert not a.consistency.first_order and not a.assumptions.isotropy.holds
    assert a.order == 0 and abs(a.local_error_exponent - 1.0) < 0.1  # its own one-step error: O(h)


# --------------------------------------------------------------------------- linearity
def test_a_clip_is_found_and_the_probes_go_below_it():
    a = _assess("clips.py", 2)
    lin = a.assumptions.linearity
    assert lin.saturates and 0.005 <= lin.range <= 0.01 and lin.holds and lin.probe_amplitude <= lin.range
    assert a.identification.terms == {"1,2": "2/3"} and a.identification.linear_is_sum
    assert max(a.cone_angles) * 2 * math.sin(max(OMEGA_H) / 2) <= lin.range  # the check's increments stay below the clip
    assert a.check.consistent and a.check.holds is not False
    loose = coning_drift_check(_module_integrator("clips.py"), 2, a.algorithm, omega_h=OMEGA_H, cone_angles=a.cone_angles, tolerance=1e-3)
    assert loose.holds is True


def test_probes_set_above_the_clip_are_refused_as_outside_the_range():
    a = _assess("clips.py", 2, amplitude=0.02, verify=False)
    assert a.assumptions.linearity.holds is False and not a.assumptions.trusted
    assert not a.identification.exact  # the clipped probes spoil the extrapolation: no exact fractions


def test_a_huge_coefficient_is_identified_and_checked_at_cone_angles_small_enough():
    a = _assess("huge_coefficient.py", 2)
    assert a.identification.terms == {"1,2": "1000000"} and a.order == 2 and a.coning.order == 2
    assert a.cone_angles[0] <= 0.04 / 1e6
    assert a.check.consistent
    loose = coning_drift_check(_module_integrator("huge_coefficient.py"), 2, a.algorithm, omega_h=OMEGA_H, cone_angles=a.cone_angles, tolerance=1e-2)
    assert loose.holds is True


def _module_integrator(file):
    from strapdown.analysis.coning.integrators.adapters import as_integrator

    return as_integrator(_module(file, file.removesuffix(".py")).integrate)


# --------------------------------------------------------------------------- precision
def test_float32_uncertainty_covers_the_difference_from_the_float64_run_of_the_same_code():
    a32 = _assess("float32.py", 2, verify=False)
    a64 = _assess("float32.py", 2, name="integrate_float64", verify=False)
    assert a32.assumptions.precision.holds is False and a64.assumptions.precision.holds is True
    assert a32.assumptions.precision.measured > 1e-9
    i32, i64 = a32.identification, a64.identification
    for key, c in list(i32.pairwise.items()) + list(i32.linear.items()):
        ref = (i64.pairwise | i64.linear)[key]
        assert abs(c.value - ref.value) <= c.uncertainty, (key, c.value, ref.value, c.uncertainty)
    assert i64.exact and i64.terms == {"1,2": "2/3"}
    assert not a32.assumptions.drift_order.holds  # its orders are not decided by coefficients known to 1e-3


# --------------------------------------------------------------------------- orders from the coefficients
def test_a_coefficient_off_by_1e7_gives_drift_order_two_and_the_simulation_agrees():
    a = _assess("off_by_1e7.py", 2, omega_h=(0.25, 0.5))
    c = a.identification.pairwise[(1, 2)]
    assert c.exact is None and c.fraction != Fraction(2, 3) and abs(float(c.fraction) - (2 / 3 + 1e-7)) <= 4 * c.uncertainty
    assert a.assumptions.drift_order.holds and a.coning.order == 2 and a.order == 2
    assert a.check.holds is True  # the code's simulated drift: that of the exact coefficient
    rounded = coning_drift_check(_module_integrator("off_by_1e7.py"), 2, get("two-sample"), omega_h=(0.25, 0.5))
    assert not rounded.consistent  # and not that of 2/3


# --------------------------------------------------------------------------- sculling
def test_a_missing_rotation_term_costs_an_order_of_velocity():
    a = _assess("sculling_no_half.py", 2, max_previous=1)
    sc = a.sculling
    assert not sc.dual_extension and {key for _, key, _ in sc.defect} == {(1, 1), (1, 2), (2, 1), (2, 2)}
    assert all(w == 2 for *_, w in sc.consequences) and sc.departures_weight == 2
    assert sc.velocity_order == 1 and sc.decided_by == "bilinear part"
    assert abs(sc.velocity_exponent - 2.0) < 0.1  # the code's own velocity error: O(h²)
    with_term = velocity_error_exponent(recursion(velocity=True), 2, history=1)
    assert abs(with_term - 3.0) < 0.1  # with the rotation term: O(h³)


# --------------------------------------------------------------------------- flight code that meets every assumption
@pytest.mark.parametrize(
    "file, n, terms",
    [
        ("miller_unusual.py", 3, {"1,2": "27/40", "1,3": "9/20", "2,3": "27/40"}),
        ("ignagni_unusual.py", 2, {"0,2": "-1/30", "1,2": "11/15"}),
        ("sign_slip.py", 2, {"1,2": "-2/3"}),
        ("dcm_integrator.py", 3, {"1,2": "1/2", "1,3": "1/2", "2,3": "1/2"}),
        ("quaternion_integrator.py", 2, {"1,2": "2/3"}),
        ("bortz.py", 3, {"1,2": "1/2", "1,3": "1/2", "2,3": "1/2"}),
        ("cross_step_state.py", 1, {"0,1": "1/12"}),
        ("rate_input.py", 2, {"1,2": "2/3"}),
    ],
)
def test_flight_code_meeting_every_assumption_is_identified_and_its_simulation_agrees(file, n, terms):
    a = _assess(file, n, max_previous=2)
    assert all(_verdicts(a).values()), {k: v.summary() for k, v in a.assumptions.items()}
    assert a.identification.terms == terms and a.identification.exact
    assert a.check.holds is True
    assert abs(a.local_error_exponent - (a.order + 1)) < 0.1


def test_ardupilot_accumulator_is_savage_bilinear_part_plus_a_cubic_remainder():
    a = _assess("ardupilot_accumulator.py", 4)
    assert a.identification.algorithm().pairwise == _savage(4)
    assert a.identification.remainder.degree == 3 and a.consistency.consistent
    assert a.check.holds is True


def _savage(n):
    from strapdown.analysis.coning.integrators.identification import identify

    return identify(recursion(), n, max_previous=1).algorithm().pairwise


def test_px4_integrator_coning_in_python_float32_rates():
    a = _assess("px4_integrator_coning.py", 4)
    assert a.assumptions.precision.holds is False  # float32
    lin = a.identification.linear_part
    assert lin == {0: Fraction(1, 2), 1: Fraction(1), 2: Fraction(1), 3: Fraction(1), 4: Fraction(1, 2)}  # the trapezoid on mean rates
    assert not a.consistency.first_order and a.order == 1
    assert abs(a.local_error_exponent - 2.0) < 0.1  # its own one-step error: O(h²)


def test_px4_integrator_coning_in_c_is_the_python_one(built):
    _need(built, "libpx4.so")
    a = _assess("px4_integrator_coning_c.py", 4, verify=False)
    b = _assess("px4_integrator_coning.py", 4, verify=False)
    assert a.identification.linear_part == b.identification.linear_part
    assert a.identification.terms == b.identification.terms


def test_per_sample_c_api_and_the_cpp_shim_are_savage_recursion(built):
    _need(built, "libper_sample.so")
    _need(built, "libintegrator_cpp.so")
    for file in ("per_sample_c.py", "cpp_shim.py"):
        a = _assess(file, 3, max_previous=2)
        assert a.identification.terms == {"0,1": "1/12", "1,2": "7/12", "1,3": "1/2", "2,3": "7/12"}
        assert all(_verdicts(a).values()) and a.check.holds is True
