"""Quaternion algebra: identities (hypothesis), rotation-vector maps, bad input."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from strapdown.analysis.core import blocks
from strapdown.analysis.core import quaternion as quat

finite = st.floats(-10.0, 10.0, allow_nan=False, allow_infinity=False)
quats = arrays(float, (4,), elements=finite)
vecs = arrays(float, (3,), elements=finite)


def unit(q):
    n = np.linalg.norm(q)
    return q / n if n > 1e-3 else np.array([1.0, 0.0, 0.0, 0.0])


def test_basis_products():
    i, j, k = np.eye(4)[1], np.eye(4)[2], np.eye(4)[3]
    np.testing.assert_array_equal(quat.multiply(i, j), k)
    np.testing.assert_array_equal(quat.multiply(j, k), i)
    np.testing.assert_array_equal(quat.multiply(k, i), j)
    np.testing.assert_array_equal(quat.multiply(i, i), -np.eye(4)[0])


@given(quats, quats, quats)
def test_associative(a, b, c):
    lhs = quat.multiply(quat.multiply(a, b), c)
    rhs = quat.multiply(a, quat.multiply(b, c))
    scale = np.linalg.norm(a) * np.linalg.norm(b) * np.linalg.norm(c) + 1.0
    np.testing.assert_allclose(lhs, rhs, atol=1e-13 * scale)


@given(quats, quats)
def test_norm_multiplicative_and_conjugate_of_product(a, b):
    ab = quat.multiply(a, b)
    scale = np.linalg.norm(a) * np.linalg.norm(b) + 1.0
    np.testing.assert_allclose(quat.norm(ab), quat.norm(a) * quat.norm(b), atol=1e-13 * scale)
    np.testing.assert_allclose(quat.conjugate(ab), quat.multiply(quat.conjugate(b), quat.conjugate(a)), atol=1e-13 * scale)


@given(quats, vecs, quats)
def test_rotation_preserves_norm_and_composes(a, v, b):
    qa, qb = unit(a), unit(b)
    r = quat.rotate(qa, v)
    np.testing.assert_allclose(np.linalg.norm(r), np.linalg.norm(v), atol=1e-12 * (1 + np.linalg.norm(v)))
    both = quat.rotate(quat.multiply(qa, qb), v)
    np.testing.assert_allclose(both, quat.rotate(qa, quat.rotate(qb, v)), atol=1e-12 * (1 + np.linalg.norm(v)))


def test_rotate_matches_scipy():
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(1)
    phi = rng.normal(size=(50, 3))
    v = rng.normal(size=(50, 3))
    expected = Rotation.from_rotvec(phi).apply(v)
    np.testing.assert_allclose(quat.rotate(quat.rotvec_to_quat(phi), v), expected, atol=1e-14)


@settings(max_examples=300)
@given(
    st.floats(0.0, 2 * np.pi * (1 - 1e-9), allow_nan=False),
    arrays(float, (3,), elements=st.floats(-1, 1)).filter(lambda u: np.linalg.norm(u) > 1e-3),
)
def test_rotvec_round_trip_full_range(angle, direction):
    phi = angle * direction / np.linalg.norm(direction)
    q = quat.rotvec_to_quat(phi)
    assert abs(np.linalg.norm(q) - 1.0) < 1e-15
    back = quat.quat_to_rotvec(q)
    # The map is ill-conditioned only as |φ| → 2π (the axis is lost there).
    cond = 1.0 / max(np.sin(angle / 2.0), 1e-300) if angle > np.pi else 1.0
    np.testing.assert_allclose(back, phi, atol=8e-16 * max(angle, 1.0) * cond, rtol=4e-16 * cond)


@pytest.mark.parametrize("angle", [1e-300, 1e-200, 1e-20, 1e-8, 1e-4, 0.5e-2, 1.5e-2])
def test_small_angles_exact_to_machine_precision(angle):
    direction = np.array([0.6, -0.48, 0.64])
    phi = angle * direction
    q = quat.rotvec_to_quat(phi)
    # reference: cos(θ/2) and sin(θ/2)/θ in 50-digit arithmetic
    import mpmath

    with mpmath.workdps(50):
        th = mpmath.mpf(angle)
        c = mpmath.cos(th / 2)
        s = mpmath.sin(th / 2) / th
    assert q[0] == pytest.approx(float(c), rel=2e-16, abs=0)
    np.testing.assert_allclose(q[1:], float(s) * phi, rtol=2e-16, atol=0)
    back = quat.quat_to_rotvec(q)
    np.testing.assert_allclose(back, phi, rtol=4e-16, atol=0)


def test_canonical_shortest_rotation():
    phi = np.array([0.0, 0.0, 1.5 * np.pi])
    q = quat.rotvec_to_quat(phi)
    np.testing.assert_allclose(quat.quat_to_rotvec(q), phi, atol=1e-15)
    np.testing.assert_allclose(quat.quat_to_rotvec(q, canonical=True), [0, 0, -0.5 * np.pi], atol=1e-15)
    np.testing.assert_allclose(quat.quat_to_rotvec(-q, canonical=True), [0, 0, -0.5 * np.pi], atol=1e-15)


def test_batched_shapes():
    rng = np.random.default_rng(0)
    phi = rng.normal(size=(7, 5, 3))
    q = quat.rotvec_to_quat(phi)
    assert q.shape == (7, 5, 4)
    assert quat.multiply(q, q[0]).shape == (7, 5, 4)
    assert quat.quat_to_rotvec(q).shape == (7, 5, 3)


@pytest.mark.parametrize(
    "func, arg, match",
    [
        (quat.rotvec_to_quat, [np.nan, 0, 0], "`phi` to be finite"),
        (quat.rotvec_to_quat, [np.inf, 0, 0], "`phi` to be finite"),
        (quat.rotvec_to_quat, [1.0, 0.0], r"`phi` with shape \(\.\.\., 3\), got shape \(2,\)"),
        (quat.quat_to_rotvec, [1.0, 0.0, 0.0], r"`q` with shape \(\.\.\., 4\)"),
        (quat.quat_to_rotvec, [2.0, 0.0, 0.0, 0.0], "`q` to be a unit quaternion"),
        (quat.quat_to_rotvec, [1.0, np.nan, 0.0, 0.0], "`q` to be finite"),
        (quat.normalize, [0.0, 0.0, 0.0, 0.0], "`q` to be a nonzero quaternion"),
    ],
)
def test_bad_input(func, arg, match):
    with pytest.raises(ValueError, match=match):
        func(arg)


def test_non_numeric_input_is_type_error():
    with pytest.raises(TypeError, match="`phi` to be a numeric array"):
        quat.rotvec_to_quat(["a", "b", "c"])


def test_rotate_is_the_quaternion_sandwich_exactly():
    """rotate writes out vect(q ∘ {0, v} ∘ q̄) component by component: the same products, the same bits, any broadcasting."""
    rng = np.random.default_rng(4)
    q = quat.normalize(rng.normal(size=(50, 4)))
    v = rng.normal(size=(50, 3)) * 10.0 ** rng.integers(-8, 4, size=(50, 1))
    sandwich = quat.vect(quat.multiply(quat.multiply(q, quat.vector_to_quat(v)), quat.conjugate(q)))
    np.testing.assert_array_equal(quat.rotate(q, v), sandwich)
    np.testing.assert_array_equal(quat.rotate(q[0], v), quat.vect(quat.multiply(quat.multiply(q[0], quat.vector_to_quat(v)), quat.conjugate(q[0]))))
    assert quat.rotate(q[:, None, :], v[None, :5, :]).shape == (50, 5, 3)


@pytest.mark.parametrize(
    "a_shape, b_shape, v_shape",
    [
        ((9000, 4), (9000, 4), (9000, 3)),
        ((4,), (9000, 4), (9000, 3)),
        ((3000, 3, 4), (3000, 3, 4), (3000, 3, 3)),
        ((6000, 1, 4), (1, 3, 4), (6000, 3, 3)),
        ((2, 5000, 4), (5000, 4), (2, 5000, 3)),
    ],
)
def test_large_products_in_blocks_are_the_whole_array_products(monkeypatch, a_shape, b_shape, v_shape):
    """multiply and rotate evaluate large arrays block by block: the same values to the bit as in one pass, any broadcasting."""
    rng = np.random.default_rng(7)
    a, b = (rng.normal(size=s) * 10.0 ** rng.integers(-8, 8, size=s) for s in (a_shape, b_shape))
    v = rng.normal(size=v_shape) * 10.0 ** rng.integers(-8, 8, size=v_shape)
    a.reshape(-1)[0] = np.nan
    blocked = quat.multiply(a, b), quat.multiply(b, a), quat.rotate(a, v), quat.rotate(b, v)
    monkeypatch.setattr(blocks, "BLOCK", 10**9)  # one pass
    whole = quat.multiply(a, b), quat.multiply(b, a), quat.rotate(a, v), quat.rotate(b, v)
    for x, y in zip(blocked, whole):
        assert x.shape == y.shape and x.dtype == y.dtype
        assert x.tobytes() == y.tobytes()
