"""Dual numbers: arithmetic identities, dual part = derivative, unit biquaternions (1.12)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.dual import Dual, dual_extend, dual_part, real_part

real = st.floats(-5.0, 5.0, allow_nan=False, allow_infinity=False)
positive = st.floats(0.1, 5.0, allow_nan=False)


@given(real, real, real, real)
def test_product_rule_and_nilpotent_s(a, b, c, d):
    x, y = Dual(a, b), Dual(c, d)
    z = x * y
    assert z.re == pytest.approx(a * c)
    assert z.du == pytest.approx(a * d + b * c, abs=1e-12)
    s = Dual(0.0, 1.0)
    assert (s * s).re == 0.0 and (s * s).du == 0.0  # s² = 0


@given(real, real, positive, real)
def test_quotient_is_inverse_of_product(a, b, c, d):
    x, y = Dual(a, b), Dual(c, d)
    back = (x / y) * y
    assert back.re == pytest.approx(a, abs=1e-12)
    assert back.du == pytest.approx(b, abs=1e-10)


def _complex_step(f, x, h=1e-30):
    return np.imag(f(x + 1j * h)) / h


@given(st.floats(0.05, 3.0), real)
def test_dual_part_is_derivative(x, dx):
    def f(t):
        return np.sin(t) * np.exp(np.cos(t)) / np.sqrt(t) + np.arctan(t * t)

    value = f(Dual(x, dx))
    assert value.re == pytest.approx(f(x), rel=1e-14)
    assert value.du == pytest.approx(_complex_step(f, x) * dx, rel=1e-12, abs=1e-12)


@given(st.floats(-3, 3), st.floats(0.1, 3), real, real)
def test_arctan2_and_hypot_derivatives(y, x, dy, dx):
    a = np.arctan2(Dual(y, dy), Dual(x, dx))
    expected = (x * dy - y * dx) / (x * x + y * y)
    assert a.du == pytest.approx(expected, rel=1e-12, abs=1e-14)
    h = np.hypot(Dual(y, dy), Dual(x, dx))
    assert h.du == pytest.approx((y * dy + x * dx) / np.hypot(x, y), rel=1e-12, abs=1e-14)


def test_dual_extend_any_elementwise_function():
    sinh = dual_extend(np.sinh, np.cosh)
    x = Dual(np.linspace(-1, 1, 5), 2.0)
    np.testing.assert_allclose(sinh(x).du, 2.0 * np.cosh(x.re))
    np.testing.assert_array_equal(sinh(x.re), np.sinh(x.re))
    assert real_part(3.0) == 3.0
    np.testing.assert_array_equal(dual_part(np.ones(2)), np.zeros(2))


def test_array_functions_dispatch():
    a = Dual(np.arange(6.0).reshape(2, 3), np.ones((2, 3)))
    s = np.sum(a, axis=-1)
    np.testing.assert_array_equal(s.re, [3.0, 12.0])
    np.testing.assert_array_equal(s.du, [3.0, 3.0])
    w = np.where(a.re > 2, a, -a)
    np.testing.assert_array_equal(w.du, [[-1, -1, -1], [1, 1, 1]])
    st_ = np.stack([a, a], axis=-1)
    assert st_.shape == (2, 3, 2)


@given(arrays(float, (3,), elements=st.floats(-3, 3)), arrays(float, (3,), elements=st.floats(-50, 50)))
def test_unit_biquaternion_conditions(phi, phi_dual):
    """Both conditions for θ = Λ + sM from (1.12): |Λ| = 1 and Λ·M = 0, to round-off."""
    theta = quat.rotvec_to_quat(Dual(phi, phi_dual))
    lam, m = theta.re, theta.du
    assert abs(np.dot(lam, lam) - 1.0) < 1e-15
    assert abs(np.dot(lam, m)) < 4e-15 * (1.0 + np.linalg.norm(phi_dual))


@given(arrays(float, (3,), elements=st.floats(-3, 3)).filter(lambda v: np.linalg.norm(v) > 1e-2), arrays(float, (3,), elements=st.floats(-5, 5)))
def test_biquaternion_map_matches_corrected_1_12(phi, phi_dual):
    """(1.12) with the sign of the second term of μ_i corrected (see reports/errata.md)."""
    n = np.linalg.norm(phi)
    pd = phi @ phi_dual
    s, c = np.sin(n / 2), np.cos(n / 2)
    mu0 = -0.5 / n * s * pd
    mui = s / n * phi_dual + n**-2 * (0.5 * c - s / n) * pd * phi
    theta = quat.rotvec_to_quat(Dual(phi, phi_dual))
    np.testing.assert_allclose(theta.du, np.concatenate([[mu0], mui]), atol=1e-14)
    np.testing.assert_allclose(theta.re, np.concatenate([[c], s / n * phi]), atol=1e-15)


def test_biquaternion_product_is_screw_composition():
    """(Λ1 + sM1)(Λ2 + sM2) = Λ1Λ2 + s(Λ1M2 + M1Λ2): the dual product of quaternions."""
    rng = np.random.default_rng(3)
    a = Dual(rng.normal(size=4), rng.normal(size=4))
    b = Dual(rng.normal(size=4), rng.normal(size=4))
    ab = quat.multiply(a, b)
    np.testing.assert_allclose(ab.re, quat.multiply(a.re, b.re))
    np.testing.assert_allclose(ab.du, quat.multiply(a.re, b.du) + quat.multiply(a.du, b.re))


def test_small_dual_vector_has_no_nan():
    theta = quat.rotvec_to_quat(Dual([1e-300, 0.0, 0.0], [1.0, 2.0, 3.0]))
    assert np.all(np.isfinite(theta.re)) and np.all(np.isfinite(theta.du))
    np.testing.assert_allclose(theta.du, [0.0, 0.5, 1.0, 1.5], atol=1e-16)
