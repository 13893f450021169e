"""One sign for every error of the coning domain: exact minus algorithm (package docstring, "Errors").

The theory (:mod:`strapdown.analysis.coning.drift_theory`), the parallel
computation in both engines and the streaming statistics give the same signed
vectors, not only the same magnitudes.
"""

from __future__ import annotations

import numpy as np
import pytest

from strapdown.analysis.coning import kernels
from strapdown.analysis.coning.batch import simulate_batch
from strapdown.analysis.coning.drift_theory import asymptotic_drift_vector, asymptotic_velocity_error
from strapdown.analysis.coning.precession import RegularPrecession, exact_state
from strapdown.analysis.coning.sculling_motion import ScullingMotion, rectification_error
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core import quaternion as quat
from strapdown.derivations.coning.registry import get

needs_numba = pytest.mark.skipif(not kernels.available(), reason="numba not installed")
ENGINES = ["numpy", pytest.param("compiled", marks=needs_numba)]

#: A tilted start, so that frame I differs from the frame of the particular solution (4.4).
LAM0 = quat.normalize(np.array([0.9, 0.1, -0.2, 0.3]))
W0 = np.array([20.0, 35.0, 40.0])
#: Precession (not coning): ε = 0.5, ϑ = 10°, panov-4s-1 (ρ = 4), H = 4 h = 0.01 s.
EPS, NUTATION, H_SAMPLE = 0.5, np.radians(10.0), 0.0025
#: 640 s is 320 precession periods at 1 Hz: the transverse, periodic part of the error
#: (5.2) biases the least-squares slope by O(1/(μT)²), here below 1e-4 of the drift.
DURATION = 640.0


def _drift_gap(engine, freq_hz):
    alg, motion = get("panov-4s-1"), RegularPrecession(EPS, 2 * np.pi * freq_hz, NUTATION)
    simulated = simulate(alg, motion, H_SAMPLE, DURATION, attitude0=LAM0, engine=engine).drift
    theory = asymptotic_drift_vector(alg, eps=EPS, nu=motion.nu, nutation=NUTATION, step=4 * H_SAMPLE, attitude0=LAM0)
    return simulated, theory, motion.precession_axis(LAM0)


@pytest.mark.parametrize("engine", ENGINES)
def test_simulated_drift_vector_is_the_asymptotic_drift_vector(engine):
    """Same sign, same direction, and the gap is the (νH)² remainder of the asymptotic term."""
    gaps = []
    for freq in (1.0, 2.0):
        simulated, theory, axis = _drift_gap(engine, freq)
        assert np.sign(simulated @ axis) == np.sign(theory @ axis) != 0
        cosine = simulated @ theory / (np.linalg.norm(simulated) * np.linalg.norm(theory))
        assert cosine > 1 - 1e-6
        gaps.append(np.linalg.norm(simulated - theory) / np.linalg.norm(theory))
    assert gaps[0] < 3e-3
    # halving ν halves νH: the gap shrinks by 2² (the next weight of the series is two up)
    assert gaps[1] / gaps[0] == pytest.approx(4.0, rel=0.05)


def test_velocity_errors_have_the_theory_sign():
    """ΔW_I = Λ δφ° Λ̄ and ΔW_E = δφ° + W_E × δφ (Lebedev & Panov 1989, (3.5)), signed, against the simulator."""
    alg, t = get("lebedev-panov-4"), 100.0
    motion = RegularPrecession(EPS, 2 * np.pi, NUTATION, 0.5, 10.0)
    r = simulate(alg, motion, 0.01, t, attitude0=LAM0, w_inertial0=W0, velocity=True)
    err = asymptotic_velocity_error(alg, t, eps=EPS, nu=motion.nu, nutation=NUTATION, nu_dual=0.5, nutation_dual=10.0, step=0.04)
    exact = exact_state(motion, t, LAM0, W0)
    scale = np.linalg.norm(r.dw_inertial[-1])
    np.testing.assert_allclose(r.dw_inertial[-1], quat.rotate(exact.attitude, err.velocity), rtol=0, atol=1e-3 * scale)
    np.testing.assert_allclose(r.dw_body[-1], err.dw_body(exact.w_body), rtol=0, atol=1e-3 * np.linalg.norm(r.dw_body[-1]))
    np.testing.assert_allclose(r.attitude_error[-1], quat.rotate(exact.attitude, err.attitude), rtol=0, atol=1e-3 * np.linalg.norm(r.attitude_error[-1]))


def _close(actual, desired):
    """Equal to 1e-6 of the vector's size (round-off of the attitude product is far below)."""
    np.testing.assert_allclose(actual, desired, rtol=0, atol=1e-6 * np.abs(desired).max())


@needs_numba
@pytest.mark.parametrize("velocity", [False, True])
def test_numpy_and_compiled_engines_agree_in_sign(velocity):
    alg = get("panov-4s-3")
    motion = RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(1.0), 0.5, 10.0)
    runs = {e: simulate(alg, motion, H_SAMPLE, 2.0, attitude0=LAM0, w_inertial0=W0, velocity=velocity, engine=e) for e in ("numpy", "compiled")}
    ref, got = runs["numpy"], runs["compiled"]
    # the cone axis −n: both engines drift along it, positive (the computed attitude lags the coning)
    cone = -motion.precession_axis(LAM0)
    assert ref.drift @ cone > 0 and got.drift @ cone > 0
    big = np.abs(ref.drift) > 1e-3 * np.abs(ref.drift).max()
    np.testing.assert_array_equal(np.sign(got.drift[big]), np.sign(ref.drift[big]))
    _close(got.drift, ref.drift)
    _close(got.attitude_error[-1], ref.attitude_error[-1])
    stats = simulate_batch(alg, -1.0, motion.nu, motion.nutation, H_SAMPLE, 2.0, nu_dual=0.5, nutation_dual=10.0, attitude0=LAM0, w_inertial0=W0, velocity=velocity).statistics
    _close(stats.drift, ref.drift)
    _close(stats.final_error, ref.attitude_error[-1])
    if velocity:
        for name in ("dw_body", "dw_inertial"):
            _close(getattr(got, name)[-1], getattr(ref, name)[-1])
        _close(stats.final_dw_inertial, ref.dw_inertial[-1])


def test_rectification_error_has_the_simulated_sign():
    """The one-step rectification error and the simulated slope of W_I* − W_I: one sign (the two-sample algorithm under-rectifies)."""
    motion = ScullingMotion(1e-3, 1.0, 2 * np.pi * 10)
    axis = np.cross(motion.e_r, motion.e_a)
    h = 0.005
    alg = get("two-sample")
    theory = rectification_error(alg, motion, h)
    r = simulate(alg, motion, h, 4.0, velocity=True)
    assert theory.rate > 0 and r.velocity_error_rate @ axis > 0
    assert r.velocity_error_rate @ axis == pytest.approx(theory.rate, rel=1e-3)
