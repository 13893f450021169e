"""The black-box interface and its adapters: checked calls, clear messages, stateful objects, ctypes, peers, files."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from strapdown.analysis.coning.integrators.adapters import algorithm_integrator, as_integrator, compiled, load_integrator, stateful
from strapdown.analysis.coning.integrators.identification import identify
from strapdown.analysis.coning.integrators.interface import Integrator, IntegratorError, step_increments
from strapdown.analysis.coning.integrators.recursions import SavageRecursion, quaternion_composition, recursion
from strapdown.analysis.coning.integrators.verification import attitude_errors
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core import quaternion as quat
from strapdown.derivations.coning.registry import get

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "docs" / "integrator_examples.py"
RNG = np.random.default_rng(7)
GYRO = 0.01 * RNG.standard_normal((24, 3))
ACCEL = RNG.standard_normal((24, 3))


# --------------------------------------------------------------------------- the checked call
def test_rotation_vectors_pass_through():
    out = step_increments(Integrator(lambda g, n: g.reshape(-1, n, 3).sum(axis=1)), GYRO, 4)
    np.testing.assert_array_equal(out.rotation, GYRO.reshape(-1, 4, 3).sum(axis=1))
    assert out.velocity is None


def test_attitude_outputs_become_the_same_steps():
    """A quaternion- or DCM-output integrator gives the steps of the rotation-vector one it wraps (independent composition)."""
    steps = step_increments(quaternion_composition(), GYRO, 3).rotation

    def attitudes(g, n):
        q = quat.identity()
        out = []
        for k in range(0, len(g), n):
            for p in g[k : k + n]:
                q = quat.multiply(q, quat.rotvec_to_quat(p))
            out.append(q)
        return np.array(out)

    from scipy.spatial.transform import Rotation

    q_int = Integrator(attitudes, output="quaternion")
    dcm_int = Integrator(lambda g, n: Rotation.from_quat(attitudes(g, n), scalar_first=True).as_matrix(), output="dcm")
    np.testing.assert_allclose(step_increments(q_int, GYRO, 3).rotation, steps, rtol=0, atol=1e-15)
    np.testing.assert_allclose(step_increments(dcm_int, GYRO, 3).rotation, steps, rtol=0, atol=1e-15)


def test_velocity_from_attitude_outputs_is_in_the_body_axes_at_the_step_start():
    """W_I after each step turned back by the attitude at the step's start is the step's velocity increment."""
    ref = step_increments(recursion(velocity=True), GYRO, 2, ACCEL)

    def run(g, n, a):
        rot, dv = step_increments(recursion(velocity=True), g, n, a)
        lam = quat.identity()
        w = np.zeros(3)
        qs, ws = [], []
        for r, v in zip(rot, dv):
            w = w + quat.rotate(lam, v)
            lam = quat.multiply(lam, quat.rotvec_to_quat(r))
            qs.append(lam)
            ws.append(w)
        return np.array(qs), np.array(ws)

    out = step_increments(Integrator(run, output="quaternion", velocity=True), GYRO, 2, ACCEL)
    np.testing.assert_allclose(out.rotation, ref.rotation, atol=1e-15)
    np.testing.assert_allclose(out.velocity, ref.velocity, atol=1e-14)


@pytest.mark.parametrize(
    "function, output, text",
    [
        (lambda g, n: g, "rotation_vector", "one row per sample? Expected one row per step"),
        (lambda g, n: g.reshape(-1, n, 3).sum(axis=1)[:, :2], "rotation_vector", "shape (6, 2), expected (6, 3)"),
        (lambda g, n: np.full((len(g) // n, 3), np.nan), "rotation_vector", "NaN or infinity"),
        (lambda g, n: "nonsense", "rotation_vector", "returned str"),
        (lambda g, n: 1 / 0, "rotation_vector", "raised ZeroDivisionError: division by zero"),
        (lambda g, n: np.tile([1.0, 0.1, 0.0, 0.0], (len(g) // n, 1)), "quaternion", "expected unit quaternions"),
        (lambda g, n: np.tile(2 * np.eye(3), (len(g) // n, 1, 1)), "dcm", "not a rotation"),
    ],
)
def test_bad_outputs_get_a_message_naming_the_integrator(function, output, text):
    with pytest.raises(IntegratorError, match="integrator 'bad'") as info:
        step_increments(Integrator(function, output=output, name="bad"), GYRO, 4)
    assert text in str(info.value)
    assert "called with 24 samples, 4 per step" in str(info.value)


def test_velocity_integrator_must_return_a_pair():
    with pytest.raises(IntegratorError, match="expected a pair"):
        step_increments(Integrator(lambda g, n, a: g[::n], velocity=True, name="bad"), GYRO, 2, ACCEL)


def test_bad_arguments_name_them():
    with pytest.raises(ValueError, match="`gyro` of shape"):
        step_increments(recursion(), GYRO[:5], 2)
    with pytest.raises(ValueError, match="no `accel`"):
        step_increments(recursion(), GYRO, 2, ACCEL)
    with pytest.raises(TypeError, match="`integrator`"):
        step_increments(lambda g, n: g, GYRO, 2)
    with pytest.raises(ValueError, match="`output`"):
        Integrator(lambda g, n: g, output="euler")
    with pytest.raises(TypeError, match="`function`"):
        Integrator(3)


def test_inputs_are_copies():
    g = GYRO.copy()

    def mutating(gyro, n):
        gyro *= 2.0
        return gyro.reshape(-1, n, 3).sum(axis=1)

    step_increments(Integrator(mutating), g, 4)
    np.testing.assert_array_equal(g, GYRO)


def test_non_determinism_is_reported_by_the_time_invariance_verdict():
    """State kept between calls is not refused: the time-invariance verdict says no (and yes on a clean integrator)."""
    from strapdown.analysis.coning.integrators.assessment import assess

    state = {"calls": 0}

    def drifting(g, n):
        state["calls"] += 1
        return g.reshape(-1, n, 3).sum(axis=1) * (1 + 1e-9 * state["calls"])

    a = assess(Integrator(drifting, name="drifting"), 2, max_previous=1, max_previous_limit=4, verify=False)
    assert not a.assumptions.time_invariance.holds and not a.assumptions.trusted
    assert "NO" in a.assumptions.time_invariance.summary()

    class Leaky:  # a stateful object that does not clear its state on reset
        def __init__(self):
            self.total = np.zeros(3)

        def reset(self):
            pass

        def update(self, g):
            self.total = self.total + g

        def output(self):
            return self.total.copy()

    a = assess(stateful(Leaky()), 1, max_previous=1, max_previous_limit=4, verify=False)
    assert not a.assumptions.time_invariance.holds and a.assumptions.time_invariance.calls > 10
    clean = assess(recursion(), 2, max_previous=1, max_previous_limit=4, verify=False)
    assert clean.assumptions.time_invariance.holds and clean.assumptions.trusted


def test_rate_integrators_take_mean_rates():
    h = 0.01
    integ = Integrator(lambda w, n: h * w.reshape(-1, n, 3).sum(axis=1), input="rate", sample_interval=h, name="rates")
    np.testing.assert_allclose(step_increments(integ, GYRO, 4).rotation, GYRO.reshape(-1, 4, 3).sum(axis=1), rtol=1e-15)
    with pytest.raises(ValueError, match="`sample_interval`"):
        Integrator(lambda w, n: w, input="rate")
    with pytest.raises(ValueError, match="`input`"):
        Integrator(lambda w, n: w, input="angle")
    with pytest.raises(ValueError, match="no `sample_interval`"):
        Integrator(lambda w, n: w, sample_interval=0.01)


def test_the_loader_puts_the_files_directory_on_the_path_and_refuses_sys_exit(tmp_path):
    (tmp_path / "helper_coefficient_mod.py").write_text("C = 0.5\n")
    (tmp_path / "uses_helper.py").write_text("import helper_coefficient_mod\ndef f(g, n):\n    return g.reshape(-1, n, 3).sum(axis=1) * helper_coefficient_mod.C\n")
    assert load_integrator(f"{tmp_path / 'uses_helper.py'}:f").name == "f"
    (tmp_path / "quits.py").write_text("import sys\nsys.exit(3)\n")
    with pytest.raises(ValueError, match=r"called sys.exit\(3\)"):
        load_integrator(f"{tmp_path / 'quits.py'}:f")


# --------------------------------------------------------------------------- adapters
@pytest.mark.parametrize("kwargs", [{}, {"alpha_lag": 2}, {"previous_lag": 0}, {"one_accumulator": True}, {"velocity": True}, {"alpha_lag": 2, "velocity": True}])
@pytest.mark.parametrize("n", [1, 3, 4])
def test_stateful_recursion_equals_the_vectorised_one(kwargs, n):
    """The same recursion one sample per call (plain floats) and vectorised over the steps (numpy): bit for bit."""
    velocity = kwargs.get("velocity", False)
    one = stateful(SavageRecursion(**kwargs), velocity=velocity)
    many = recursion(**kwargs)
    a = ACCEL if velocity else None
    x, y = step_increments(one, GYRO, n, a), step_increments(many, GYRO, n, a)
    np.testing.assert_array_equal(x.rotation, y.rotation)
    if velocity:
        np.testing.assert_allclose(x.velocity, y.velocity, rtol=1e-15, atol=0)


def test_stateful_needs_the_protocol():
    with pytest.raises(TypeError, match="update"):
        stateful(object())

    class NoReset:
        def update(self, g):
            pass

        def output(self):
            return np.zeros(3)

    with pytest.raises(TypeError, match="reset"):
        stateful(NoReset())
    assert stateful(NoReset).name == "NoReset"  # a class is instantiated for every record instead


def test_black_box_simulation_is_the_simulator_bit_for_bit():
    """A registry algorithm run as a black box (its own terms) against the package's parallel computation."""
    motion = RegularPrecession(-1.0, 2 * np.pi, 0.03)
    for name in ("ignagni-1996-1", "panov-4s-3", "lebedev-panov-6"):
        alg = get(name)
        _, error = attitude_errors(algorithm_integrator(alg, velocity=False), alg.samples, motion, 0.04, 40, history=alg.history)
        ref = simulate(alg, motion, 0.04, 40 * alg.samples * 0.04 * (1 + 1e-12), engine="numpy")
        np.testing.assert_allclose(error, ref.attitude_error, rtol=0, atol=1e-17)


def test_as_integrator_takes_every_kind():
    assert as_integrator(recursion()).name.startswith("Savage")
    assert as_integrator(get("two-sample")).name == "two-sample"
    assert as_integrator(SavageRecursion).name == "SavageRecursion"
    assert as_integrator(lambda g, n: g[::n], name="f").name == "f"
    with pytest.raises(TypeError, match="Expected an Integrator"):
        as_integrator(42)


def test_load_integrator_from_a_file(tmp_path):
    integ = load_integrator(f"{EXAMPLES}:two_sample")
    assert integ.name == "two_sample"
    assert load_integrator(f"{EXAMPLES}:PerSample").name == "PerSample"
    assert load_integrator(f"{EXAMPLES}:savage_with_sculling").velocity
    with pytest.raises(ValueError, match="FILE.py:NAME"):
        load_integrator(str(EXAMPLES))
    with pytest.raises(ValueError, match="not found"):
        load_integrator(f"{tmp_path / 'missing.py'}:f")
    with pytest.raises(ValueError, match="the file defines .*two_sample"):
        load_integrator(f"{EXAMPLES}:nothing_here")
    broken = tmp_path / "broken.py"
    broken.write_text("def f(:\n")
    with pytest.raises(ValueError, match="syntax error at line 1"):
        load_integrator(f"{broken}:f")
    failing = tmp_path / "failing.py"
    failing.write_text("import no_such_module_anywhere\n")
    with pytest.raises(ValueError, match="importing it raised ModuleNotFoundError"):
        load_integrator(f"{failing}:f")


def _compiler():
    return shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")


@pytest.fixture(scope="module")
def c_library(tmp_path_factory):
    cc = _compiler()
    if cc is None:
        pytest.skip("no C compiler on this machine")
    lib = tmp_path_factory.mktemp("c") / "libintegrator.so"
    result = subprocess.run([cc, "-O2", "-shared", "-fPIC", "-o", str(lib), str(ROOT / "docs" / "integrator_example.c")], capture_output=True, text=True)
    if result.returncode != 0:
        pytest.skip(f"the C compiler failed: {result.stderr.strip()[:200]}")
    return lib


def test_c_example_is_savage_recursion(c_library):
    c = compiled(c_library, velocity=True)
    for n in (1, 2, 4):
        x, y = step_increments(c, GYRO, n, ACCEL), step_increments(recursion(velocity=True), GYRO, n, ACCEL)
        np.testing.assert_allclose(x.rotation, y.rotation, rtol=0, atol=1e-16)
        np.testing.assert_allclose(x.velocity, y.velocity, rtol=0, atol=1e-15)
    ident = identify(compiled(c_library), 3, max_previous=2)
    assert ident.terms == {"0,1": "1/12", "1,2": "7/12", "1,3": "1/2", "2,3": "7/12"}
    assert ident.exact and not ident.remainder.above_roundoff


def test_c_errors_are_clear(c_library, tmp_path):
    with pytest.raises(ValueError, match="not found"):
        compiled(c_library, "no_such_function")
    with pytest.raises(ValueError, match="loadable shared library"):
        compiled(tmp_path / "missing.so")
    # a nonzero status is an error: the example refuses a record that is not whole steps (status 1)
    c = compiled(c_library)
    with pytest.raises(IntegratorError, match="returned status 1"):
        c.function(np.ascontiguousarray(GYRO[:5]), 2)


def test_peers_are_identified_like_for_like():
    pytest.importorskip("pyins")
    pytest.importorskip("smsfusion")
    from strapdown.analysis.coning.integrators.peers import pyins_increments, pyins_integrator, smsfusion_ins

    loop, incs = pyins_integrator(), pyins_increments()
    np.testing.assert_allclose(step_increments(loop, GYRO, 1).rotation, step_increments(incs, GYRO, 1, ACCEL).rotation, rtol=0, atol=1e-15)
    with pytest.raises(IntegratorError, match="samples_per_step must be 1"):
        step_increments(incs, GYRO, 2, ACCEL)
    sms = step_increments(smsfusion_ins(), GYRO, 1, ACCEL)
    p = GYRO
    angle = np.linalg.norm(p, axis=-1)
    # first order, normalised: the step rotation is 2 atan(|p|/2) about p
    np.testing.assert_allclose(sms.rotation, p * (2 * np.arctan(angle / 2) / angle)[:, None], rtol=1e-12)
