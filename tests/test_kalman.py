"""The filterpy calls used by the package, and the estimator comparison."""

import math

import numpy as np
import pytest

from strapdown.analysis.core import kalman
from strapdown.analysis.gyrocompass.rocking import GaussianRocking, NarrowbandRocking, SineRocking
from strapdown.analysis.gyrocompass.tilt_estimation import compare_estimators, tilt_filter_model


@pytest.mark.parametrize("rocking", [GaussianRocking(0.01, 0.01), SineRocking(0.01, 0.01, 6.0, 6.0), NarrowbandRocking(0.01, 0.01, 8.0, 0.1)])
def test_vectorised_gains_equal_filterpy_batch_filter(rocking):
    m = tilt_filter_model(rocking, 0.1, prior_sigma=0.03, noise_sigma=1e-4)
    rng = np.random.default_rng(0)
    zs = rng.normal(0.0, 0.01, size=(3, 120, 1))
    gains, covs = kalman.gain_sequence(m.F, m.Q, m.H, m.R, m.P0, 120)
    fast = kalman.apply_gains(m.F, m.H, gains, np.zeros(m.F.shape[0]), zs)
    for t in range(3):
        means, ref_covs = kalman.filterpy_batch(m.F, m.Q, m.H, m.R, np.zeros(m.F.shape[0]), m.P0, zs[t])
        np.testing.assert_allclose(fast[t], means, rtol=1e-10, atol=1e-14)
        np.testing.assert_allclose(covs, ref_covs, rtol=1e-10, atol=1e-18)


def test_nees_is_filterpy_nees():
    rng = np.random.default_rng(1)
    e = rng.normal(size=(5, 2))
    P = np.stack([np.array([[2.0, 0.3], [0.3, 1.0]])] * 5)
    manual = np.einsum("ki,kij,kj->k", e, np.linalg.inv(P), e)
    np.testing.assert_allclose(kalman.nees(e, P), manual, rtol=1e-12)


def test_white_rocking_filter_is_the_weighted_mean():
    s, p = 0.01, 0.05
    m = tilt_filter_model(GaussianRocking(s, s), 0.1, prior_sigma=p, noise_sigma=1e-6)
    zs = np.random.default_rng(2).normal(0.02, s, size=(1, 50, 1))
    gains, _ = kalman.gain_sequence(m.F, m.Q, m.H, m.R, m.P0, 50)
    x = kalman.apply_gains(m.F, m.H, gains, [0.0], zs)[0, :, 0]
    k = np.arange(1, 51)
    R = s**2 + 1e-12
    expected = np.cumsum(zs[0, :, 0]) / (k + R / p**2)
    np.testing.assert_allclose(x, expected, rtol=1e-9)


def test_comparison_kalman_consistent_and_better_under_sine_rocking():
    s = math.radians(1.0)
    c = compare_estimators(math.radians(60), SineRocking(s, s, 8.0, 8.0), dt=0.1, averaging_times=[1.0, 4.0, 20.0], n_trials=300, rng=4)
    assert np.all(c.rms_kalman[1:] < 0.1 * c.rms_mean[1:])
    lo, hi = c.nees_band
    # 3 checks at 95 % each; the band is exact for a consistent linear-Gaussian prior, widen by 15 %
    assert np.all((c.nees_mean > 0.85 * lo) & (c.nees_mean < 1.15 * hi))


def test_filter_sequence_converges_to_the_riccati_solution():
    """An oracle independent of filterpy: the prior covariance of a long run solves the discrete algebraic Riccati equation."""
    from scipy.linalg import solve_discrete_are

    rng = np.random.default_rng(5)
    F = np.array([[0.99, 0.1, 0.0], [-0.05, 0.97, 0.1], [0.0, 0.0, 0.999]])
    A = rng.standard_normal((3, 3))
    Q = 1e-4 * (A @ A.T + np.eye(3))
    H = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    R = np.diag([1e-2, 4e-2])
    seq = kalman.filter_sequence(F, Q, H, R, np.eye(3), 2000)
    P = solve_discrete_are(F.T, H.T, Q, R)
    np.testing.assert_allclose(seq.prior[-1], P, rtol=1e-9)
    S = H @ P @ H.T + R
    np.testing.assert_allclose(seq.innovation[-1], S, rtol=1e-9)
    np.testing.assert_allclose(seq.gains[-1], P @ H.T @ np.linalg.inv(S), rtol=1e-8)
    Pp = P - seq.gains[-1] @ S @ seq.gains[-1].T
    np.testing.assert_allclose(seq.posterior[-1], Pp, rtol=1e-8, atol=1e-14)


@pytest.mark.parametrize("n, m", [(1, 1), (3, 2), (9, 3)])
def test_filter_sequence_equals_filterpy_to_the_bit(n, m):
    """The cycles without the filter object repeat filterpy's KalmanFilter.predict and update exactly."""
    rng = np.random.default_rng(n * 10 + m)
    F = np.eye(n) + 0.1 * rng.standard_normal((n, n))
    A, B = rng.standard_normal((n, n)), rng.standard_normal((m, m))
    Q, R = 1e-3 * (A @ A.T), 1e-2 * (B @ B.T + np.eye(m))
    H = rng.standard_normal((m, n))
    P0 = np.diag(rng.uniform(0.5, 2.0, n))
    fast = kalman.filter_sequence(F, Q, H, R, P0, 50)
    ref = kalman.filter_sequence(F, Q, H, R, P0, 50, reference=True)
    for name in fast._fields:
        assert np.array_equal(getattr(fast, name), getattr(ref, name)), name


def test_filter_sequence_of_the_alignment_filter_equals_filterpy_to_the_bit():
    """The fine-alignment filter with rocking shaping states (15 states), over a two-minute alignment."""
    from strapdown.analysis.alignment import studies as st
    from strapdown.analysis.alignment.fine import Disturbance, filter_model

    sc = st.DESIGN_SCENARIO
    m = filter_model(sc, st.kalman_options(sc, st.NAVIGATION_GRADE, disturbance=Disturbance("shaping", 0.01)).tuning)
    E = sc.n_samples // m.samples_per_epoch
    fast = kalman.filter_sequence(m.F, m.Q, m.H, m.R, m.P0, E)
    ref = kalman.filter_sequence(m.F, m.Q, m.H, m.R, m.P0, E, reference=True)
    for name in fast._fields:
        assert np.array_equal(getattr(fast, name), getattr(ref, name)), name


def test_filter_sequence_refuses_shapes_that_do_not_fit():
    with pytest.raises(ValueError, match=r"`H` with shape \(1, 2\)"):
        kalman.filter_sequence(np.eye(2), np.eye(2), np.ones((1, 3)), np.eye(1), np.eye(2), 3)
    with pytest.raises(ValueError, match="`n_steps` >= 0"):
        kalman.filter_sequence(np.eye(2), np.eye(2), np.ones((1, 2)), np.eye(1), np.eye(2), -1)


def test_filter_sequence_refuses_a_singular_innovation_covariance_as_numpy_inv_does():
    """No measurement noise and a measurement that sees nothing: S = 0 cannot be inverted."""
    with pytest.raises(np.linalg.LinAlgError, match="Singular matrix"):
        kalman.filter_sequence(np.eye(2), np.eye(2), np.zeros((1, 2)), np.zeros((1, 1)), np.eye(2), 3)


def test_nees_of_one_state_is_filterpy_nees_to_the_bit():
    """The one-state fast path against filterpy's loop (which inverts each 1×1 covariance)."""
    from filterpy.stats import NEES

    rng = np.random.default_rng(4)
    k = 3000
    e = rng.standard_normal((k, 1)) * 10.0 ** rng.uniform(-9, 4, (k, 1))
    e[:3, 0] = (0.0, -0.0, np.nan)
    p = rng.standard_normal(k) * 10.0 ** rng.uniform(-20, 8, k)  # negative variances too: the arithmetic is the same
    P = p[:, None, None]
    reference = np.asarray(NEES(np.zeros_like(e), e, P), dtype=float)
    np.testing.assert_array_equal(kalman.nees(e, P), reference)
    shared = np.broadcast_to(np.array([[2.5e-7]]), (k, 1, 1))  # as the estimator comparison passes them
    np.testing.assert_array_equal(kalman.nees(e, shared), np.asarray(NEES(np.zeros_like(e), e, shared), dtype=float))


def test_nees_of_one_state_with_a_zero_variance_fails_as_filterpy():
    e, P = np.ones((2, 1)), np.array([[[1.0]], [[0.0]]])
    with pytest.raises(np.linalg.LinAlgError):
        kalman.nees(e, P)
