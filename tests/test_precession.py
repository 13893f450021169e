"""Exact solutions of the regular precession and its dual analogue (Lebedev & Panov 1989, §4).

Each closed form is checked two independent ways: by its differential equation
(residual at random times, derivative by complex step, to round-off) and
against a high-accuracy numerical integration with scipy (DOP853, rtol 1e-13).
"""

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from strapdown.analysis.coning.precession import RegularPrecession, exact_state
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.dual import Dual

H = 1e-30  # complex step

MOTIONS = [
    # (eps, nu [rad/s], nutation [rad], nu° [m/s²], nutation° [m/s]) — the variants of the
    # Lebedev & Panov (1989) experiment (section 6) and a generic point
    (-1.0, 2 * np.pi, np.radians(10.0), 0.5, 10.0),
    (0.5, 2 * np.pi, np.radians(10.0), 10.0, 100.0),
    (0.37, 3.1, 1.2, -2.0, 7.0),
]
INITIAL = [
    ((np.cos(np.radians(5)), np.sin(np.radians(5)), 0, 0), (10.0, 0.0, 0.0)),
    ((1.0, 0.0, 0.0, 0.0), (20.0, 35.0, 40.0)),
]


def d_dt(f, t):
    """Derivative of a function of time by complex step (exact to round-off)."""
    value = f(t + 1j * H)
    if isinstance(value, Dual):
        return Dual(value.re.imag / H, value.du.imag / H)
    return np.imag(value) / H


@pytest.fixture(params=MOTIONS, ids=["coning", "precession-0.5", "generic"])
def motion(request):
    return RegularPrecession(*request.param)


def test_attitude_satisfies_kinematics(motion):
    t = np.random.default_rng(0).uniform(0, 100, 64)
    lhs = 2 * d_dt(motion.attitude, t)
    rhs = quat.multiply(motion.attitude(t), quat.vector_to_quat(motion.omega(t)))
    np.testing.assert_allclose(lhs, rhs, atol=2e-14 * motion.nu)


def test_biquaternion_satisfies_dual_kinematics(motion):
    """2P' = P ∘ (ω + s a), eq. (1.4), for P = Q + sR of (4.4)–(4.5)."""
    t = np.random.default_rng(1).uniform(0, 100, 64)
    lhs = 2 * d_dt(motion.biquaternion, t)
    omega = Dual(quat.vector_to_quat(motion.omega(t)), quat.vector_to_quat(motion.accel(t)))
    rhs = quat.multiply(motion.biquaternion(t), omega)
    scale = motion.nu * (1 + abs(motion.nu_dual) * 100 + abs(motion.nutation_dual))
    np.testing.assert_allclose(lhs.re, rhs.re, atol=2e-14 * motion.nu)
    np.testing.assert_allclose(lhs.du, rhs.du, atol=4e-15 * scale)


@pytest.mark.parametrize("attitude0, w0", INITIAL)
def test_velocity_satisfies_1_1_and_1_2(motion, attitude0, w0):
    """W_E* = a − ω × W_E (1.1) and W_I' = Λ a Λ̄ (1.2), from the general solution (1.5)."""
    t = np.random.default_rng(2).uniform(0, 100, 32)
    state = exact_state(motion, t, attitude0, w0)
    dwe = d_dt(lambda s: exact_state(motion, s, attitude0, w0).w_body, t)
    dwi = d_dt(lambda s: exact_state(motion, s, attitude0, w0).w_inertial, t)
    a, w = motion.accel(t), motion.omega(t)
    scale = 1 + np.abs(state.w_body).max()
    np.testing.assert_allclose(dwe, a - np.cross(w, state.w_body), atol=1e-14 * scale * motion.nu)
    np.testing.assert_allclose(dwi, quat.rotate(state.attitude, a), atol=1e-14 * scale * motion.nu)
    # initial conditions are honoured
    s0 = exact_state(motion, 0.0, attitude0, w0)
    np.testing.assert_allclose(s0.w_inertial, w0, atol=1e-13)
    np.testing.assert_allclose(s0.attitude, attitude0, atol=1e-15)


@pytest.mark.parametrize("attitude0, w0", INITIAL)
def test_against_dop853_integration(motion, attitude0, w0):
    """Integrate (1.6), (1.1), (1.2) numerically and compare with the closed form."""

    def rhs(t, y):
        lam, we = y[:4], y[4:7]
        w, a = motion.omega(t), motion.accel(t)
        return np.concatenate([0.5 * quat.multiply(lam, quat.vector_to_quat(w)), a - np.cross(w, we), quat.rotate(lam, a)])

    lam0 = np.asarray(attitude0, float)
    we0 = quat.rotate(quat.conjugate(lam0), w0)
    t_end = 3.0
    sol = solve_ivp(rhs, (0, t_end), np.concatenate([lam0, we0, w0]), method="DOP853", rtol=1e-13, atol=1e-13, dense_output=True)
    t = np.linspace(0, t_end, 7)
    y = sol.sol(t).T
    state = exact_state(motion, t, attitude0, w0)
    np.testing.assert_allclose(y[:, :4], state.attitude, atol=1e-11)
    scale = 1 + np.abs(state.w_body).max()
    np.testing.assert_allclose(y[:, 4:7], state.w_body, atol=1e-11 * scale)
    np.testing.assert_allclose(y[:, 7:], state.w_inertial, atol=1e-11 * scale)


def test_increments_are_integrals(motion):
    """p = ∫ω dt and b = ∫a dt over a sample interval (2.1), against adaptive quadrature."""
    t0, t1 = 12.34, 12.34 + 0.01
    inc = motion.increments(t0, t1)
    for k in range(3):
        p_ref = quad(lambda s, k=k: motion.omega(s)[k], t0, t1, epsabs=1e-14, epsrel=1e-12)[0]
        b_ref = quad(lambda s, k=k: motion.accel(s)[k], t0, t1, epsabs=1e-14, epsrel=1e-12)[0]
        assert inc.re[k] == pytest.approx(p_ref, rel=1e-10, abs=1e-16)
        assert inc.du[k] == pytest.approx(b_ref, rel=1e-10, abs=1e-14)
    np.testing.assert_array_equal(motion.angle_increments(t0, t1), inc.re)


def test_acceleration_is_printed_4_3(motion):
    """The dual part of (4.2) equals the acceleration printed in (4.3)."""
    e, v, th, vd, thd = motion.eps, motion.nu, motion.nutation, motion.nu_dual, motion.nutation_dual
    t = np.linspace(0, 10, 11)
    printed = np.stack(
        [
            e * (v * thd * np.cos(th) + vd * np.sin(th)) * np.sin(v * t) + e * v * vd * t * np.sin(th) * np.cos(v * t),
            e * (v * thd * np.cos(th) + vd * np.sin(th)) * np.cos(v * t) - e * v * vd * t * np.sin(th) * np.sin(v * t),
            vd * (1 + e * np.cos(th)) - e * v * thd * np.sin(th) + 0 * t,
        ],
        axis=-1,
    )
    np.testing.assert_allclose(motion.accel(t), printed, atol=1e-12)


def test_printed_4_5_and_4_6(motion):
    """R(t) of (4.5) and U_E(t) of (4.6) as printed agree with the dual extension of (4.4)."""
    e, v, th, vd, thd = motion.eps, motion.nu, motion.nutation, motion.nu_dual, motion.nutation_dual
    t = np.linspace(0, 50, 13)
    c, s = np.cos(th / 2), np.sin(th / 2)
    a, b = (1 + e) * v * t / 2, (1 - e) * v * t / 2
    r_printed = np.stack(
        [
            -(1 + e) / 2 * vd * t * c * np.sin(a) - thd / 2 * s * np.cos(a),
            -(1 - e) / 2 * vd * t * s * np.sin(b) + thd / 2 * c * np.cos(b),
            -(1 - e) / 2 * vd * t * s * np.cos(b) - thd / 2 * c * np.sin(b),
            (1 + e) / 2 * vd * t * c * np.cos(a) - thd / 2 * s * np.sin(a),
        ],
        axis=-1,
    )
    p = motion.biquaternion(t)
    np.testing.assert_allclose(p.du, r_printed, atol=1e-12)
    u_e = 2 * quat.multiply(quat.conjugate(p.re), p.du)
    u_e_printed = np.stack(
        [0 * t, e * vd * t * np.sin(th) * np.sin(v * t) + thd * np.cos(v * t), e * vd * t * np.sin(th) * np.cos(v * t) - thd * np.sin(v * t), vd * t * (1 + e * np.cos(th))],
        axis=-1,
    )
    np.testing.assert_allclose(u_e, u_e_printed, atol=1e-11)


def test_printed_4_7_needs_nu_dual_in_last_row():
    """(4.7) holds with ν° in its last row; the printed 'Λ°' is a misprint (errata)."""
    from strapdown.analysis.coning.papers.biquaternion_checks import printed_formula_checks

    checks = printed_formula_checks(0)
    assert checks.u_inertial_error < 1e-10
    assert checks.unit_condition_plus < 1e-14
    assert checks.unit_condition_printed > 0.1
    assert checks.mu_vec_error_fixed < 1e-14 < 0.1 < checks.mu_vec_error_printed


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(eps=-1.0, nu=1.0, nutation=0.0), r"`nutation` in \(0, π\), got 0"),
        (dict(eps=-1.0, nu=1.0, nutation=3.5), r"`nutation` in \(0, π\), got 3.5"),
        (dict(eps=np.nan, nu=1.0, nutation=0.1), "`eps` to be finite"),
        (dict(eps=-1.0, nu=np.inf, nutation=0.1), "`nu` to be finite"),
        (dict(eps=-1.0, nu=0.0, nutation=0.1), "`nu` .* to be nonzero"),
        (dict(eps=-1.0, nu=1.0, nutation=0.1, nu_dual=np.nan), "`nu_dual` to be finite"),
    ],
)
def test_bad_parameters(kwargs, match):
    with pytest.raises(ValueError, match=match):
        RegularPrecession(**kwargs)


def test_bad_types_and_times():
    with pytest.raises(TypeError, match="`eps` to be a real number"):
        RegularPrecession(eps="coning", nu=1.0, nutation=0.1)
    m = RegularPrecession(-1.0, 1.0, 0.1)
    with pytest.raises(ValueError, match="`t` to be finite"):
        m.omega([0.0, np.nan])
    with pytest.raises(ValueError, match="`attitude0` to be a unit quaternion"):
        exact_state(m, 0.0, (1.0, 1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    with pytest.raises(ValueError, match=r"`w_inertial0` with shape \(\.\.\., 3\)"):
        exact_state(m, 0.0, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0))
