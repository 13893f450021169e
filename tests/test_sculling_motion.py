"""Classical sculling: exact solution, rectification error, and the dual extension of Savage's 1 + 1."""

from __future__ import annotations

import json

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad, solve_ivp

from strapdown.analysis.cli import main
from strapdown.analysis.coning.evaluation import increment
from strapdown.analysis.coning.papers.published_check import sculling_error_curve, sculling_simulation_checks
from strapdown.analysis.coning.precession import exact_state
from strapdown.analysis.coning.sculling_motion import ScullingMotion, rectification_error
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.dual import Dual
from strapdown.derivations.coning.registry import get

MOTIONS = [
    ScullingMotion(0.02, 3.0, 2 * np.pi * 5),
    ScullingMotion(0.8, 2.0, 3.0, angle_phase=0.4, accel_phase=1.3, rotation_axis=2, accel_axis=0),
]


@pytest.mark.parametrize("motion", MOTIONS)
def test_attitude_and_biquaternion_satisfy_the_kinematics(motion):
    t = np.linspace(0.0, 3.0, 13)
    d = 1e-6
    dq = (motion.attitude(t + d) - motion.attitude(t - d)) / (2 * d)
    np.testing.assert_allclose(2 * dq, quat.multiply(motion.attitude(t), quat.vector_to_quat(motion.omega(t))), atol=1e-8)
    p_plus, p_minus, p = motion.biquaternion(t + d), motion.biquaternion(t - d), motion.biquaternion(t)
    rate = Dual(quat.vector_to_quat(motion.omega(t)), quat.vector_to_quat(motion.accel(t)))
    rhs = quat.multiply(p, rate)
    np.testing.assert_allclose(2 * (p_plus.du - p_minus.du) / (2 * d), rhs.du, atol=1e-7)


@pytest.mark.parametrize("motion", MOTIONS)
def test_apparent_velocity_against_quadrature_and_ode(motion):
    t1 = 2.7
    f = [lambda s, k=k: quat.rotate(motion.attitude(s), motion.accel(s))[k] for k in range(3)]
    ref = [quad(fk, 0.0, t1, epsabs=1e-13, epsrel=1e-13, limit=200)[0] for fk in f]
    np.testing.assert_allclose(motion.apparent_velocity(t1), ref, atol=1e-11)
    # independent: integrate 2Λ' = Λ∘ω, W' = Λ a Λ̄ with DOP853 from Q(0)
    def rhs(s, y):
        lam = y[:4]
        return np.concatenate([0.5 * quat.multiply(lam, quat.vector_to_quat(motion.omega(s))), quat.rotate(lam, motion.accel(s))])

    sol = solve_ivp(rhs, (0.0, t1), np.concatenate([motion.attitude(0.0), np.zeros(3)]), method="DOP853", rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(sol.y[:4, -1], motion.attitude(t1), atol=1e-10)
    np.testing.assert_allclose(sol.y[4:, -1], motion.apparent_velocity(t1), atol=1e-9)


@pytest.mark.parametrize("motion", MOTIONS)
def test_increments_are_integrals_and_grid_matches(motion):
    t0, t1 = 0.3, 0.37
    p = motion.increments(t0, t1)
    for k in range(3):
        assert p.re[k] == pytest.approx(quad(lambda s, k=k: motion.omega(s)[k], t0, t1, epsabs=1e-14)[0], abs=1e-13)
        assert p.du[k] == pytest.approx(quad(lambda s, k=k: motion.accel(s)[k], t0, t1, epsabs=1e-14)[0], abs=1e-13)
    g = motion.grid_increments(0.01, -3, 7, dual=True)
    ref = motion.increments(np.arange(-3, 4) * 0.01, np.arange(-2, 5) * 0.01)
    np.testing.assert_allclose(g.re, ref.re, atol=1e-15)
    np.testing.assert_allclose(g.du, ref.du, atol=1e-14)


def test_rectified_acceleration_is_the_mean():
    m = MOTIONS[1]
    period = 2 * np.pi / m.nu
    mean = (m.apparent_velocity(10 * period) - m.apparent_velocity(0.0)) / (10 * period)
    np.testing.assert_allclose(mean, m.rectified_acceleration(), atol=1e-12)


@pytest.mark.parametrize("kwargs, fragment", [
    ({"nu": 0.0}, "nu"),
    ({"rotation_axis": 1}, "different"),
    ({"accel_axis": 3}, "0, 1 or 2"),
    ({"angle_amplitude": float("nan")}, "finite"),
])
def test_bad_parameters(kwargs, fragment):
    base = {"angle_amplitude": 0.1, "accel_amplitude": 1.0, "nu": 1.0} | kwargs
    with pytest.raises(ValueError, match=fragment):
        ScullingMotion(**base)


def test_exact_state_through_the_general_solution():
    m = MOTIONS[1]
    s = exact_state(m, np.array([0.0, 1.0]), attitude0=(1.0, 0.0, 0.0, 0.0), w_inertial0=(1.0, 2.0, 3.0))
    np.testing.assert_allclose(s.w_inertial[0], [1.0, 2.0, 3.0], atol=1e-14)
    np.testing.assert_allclose(s.attitude[0], [1.0, 0.0, 0.0, 0.0], atol=1e-14)


# --------------------------------------------------------------------------- dual extension of Savage's 1 + 1
def _cross(a, b):
    return np.cross(a, b)


def test_dual_extension_of_savage_1_plus_1_is_the_standard_sculling_term():
    """Dual part of (1/12) p0 × p1 is (1/12)(θ_prev × v + v_prev × θ), exactly (round-off)."""
    rng = np.random.default_rng(12)
    p, v = rng.normal(size=(50, 2, 3)) * 1e-2, rng.normal(size=(50, 2, 3))
    out = increment(get("savage-1+1"), Dual(p, v))
    theta_prev, theta, v_prev, v_cur = p[:, 0], p[:, 1], v[:, 0], v[:, 1]
    np.testing.assert_allclose(out.re, theta + _cross(theta_prev, theta) / 12, rtol=0, atol=1e-17)
    np.testing.assert_allclose(out.du, v_cur + (_cross(theta_prev, v_cur) + _cross(v_prev, theta)) / 12, rtol=0, atol=1e-15)


def test_velocity_step_of_savage_1_plus_1_is_half_theta_cross_v_plus_sculling():
    """The biquaternion step exp(ΔΦ/2) gives ΔV = v + ½ θ×v + (1/12)(θ_prev×v + v_prev×θ) + O(θ² v)."""
    rng = np.random.default_rng(3)
    p0, v0 = rng.normal(size=(2, 3)), rng.normal(size=(2, 3))
    residuals = []
    for scale in (1e-2, 5e-3):
        p = p0 * scale
        phi = increment(get("savage-1+1"), Dual(p, v0))
        step = quat.rotvec_to_quat(phi)
        dv = 2 * quat.vect(quat.multiply(step.du, quat.conjugate(step.re)))
        theta_prev, theta, v_prev, v = p[0], p[1], v0[0], v0[1]
        standard = v + 0.5 * _cross(theta, v) + (_cross(theta_prev, v) + _cross(v_prev, theta)) / 12
        residuals.append(np.linalg.norm(dv - standard))
    assert residuals[0] < 1e-4
    assert np.log2(residuals[0] / residuals[1]) == pytest.approx(2.0, abs=0.1)  # the remainder is O(θ²)


def test_dual_extension_symbolically():
    """d/ds of (1/12)(p0 + s v0) × (p1 + s v1) at s = 0 is (1/12)(p0 × v1 + v0 × p1)."""
    s = sp.Symbol("s")
    p0, p1, v0, v1 = (sp.Matrix(sp.symbols(f"{n}_x {n}_y {n}_z")) for n in ("p0", "p1", "v0", "v1"))
    term = sp.Rational(1, 12) * (p0 + s * v0).cross(p1 + s * v1)
    dual_part = sp.diff(term, s).subs(s, 0)
    assert sp.simplify(dual_part - sp.Rational(1, 12) * (p0.cross(v1) + v0.cross(p1))) == sp.zeros(3, 1)


# --------------------------------------------------------------------------- rectification
@pytest.mark.parametrize("name, nu_h", [("savage-1+1", 0.1), ("two-sample", 0.2), ("ignagni-1996-2", 0.3), ("compressed-3", 0.25)])
def test_rectification_theory_against_simulation(name, nu_h):
    (pt,) = sculling_simulation_checks([(name, nu_h)], cycles=20)
    assert pt.relative_difference == pytest.approx(0.0, abs=1e-3), pt


def test_rectification_orders():
    curves = {c.algorithm: c for c in sculling_error_curve(["one-sample", "savage-1+1", "two-sample", "compressed-3", "ignagni-1996-5", "compressed-4"])}
    expected = {"one-sample": 2, "savage-1+1": 4, "two-sample": 4, "compressed-3": 6, "ignagni-1996-5": 8, "compressed-4": 8}
    for name, order in expected.items():
        assert curves[name].slope == pytest.approx(order, abs=0.1), name


def test_rectification_error_bad_input():
    m = ScullingMotion(1e-3, 1.0, np.pi)
    with pytest.raises(ValueError, match="multiple of π"):
        rectification_error(get("two-sample"), m, 0.5)
    with pytest.raises(TypeError, match="ScullingMotion"):
        rectification_error(get("two-sample"), "m", 0.01)


def test_large_amplitude_simulation_rectifies_j1():
    """At θ₀ = 0.5 rad the exact rectified acceleration is A J₁(θ₀), and a fine-step run reproduces it."""
    m = ScullingMotion(0.5, 1.0, 2 * np.pi)
    r = simulate(get("compressed-4"), m, 0.005, 10.0, velocity=True)
    rel = r.velocity_error_rate[2] / m.rectified_acceleration()[2]
    assert abs(rel) < 1e-6


def test_cli_velocity_error_sculling(capsys):
    argv = ["velocity-error", "--algorithm", "savage-1+1", "--motion", "sculling", "--freq-hz", "10", "--sample-interval", "0.002", "--duration", "2", "--json"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["motion"] == "sculling" and d["history"] == 1
    assert d["velocity_error_rate_m_s2"][2] == pytest.approx(d["rectification_error_small_amplitude_m_s2"], rel=1e-3)
    assert main(argv[:-1] + ["--eps", "1"]) == 2
    assert "--eps" in capsys.readouterr().err
    assert main(["velocity-error", "--algorithm", "two-sample", "--freq-hz", "1", "--sample-interval", "0.01", "--duration", "1"]) == 2
    assert "--eps" in capsys.readouterr().err
    assert main(argv[:-1] + ["--rotation-axis", "y"]) == 2
    assert "different" in capsys.readouterr().err
