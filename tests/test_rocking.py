"""Rocking models: distributions, correlation, exact narrow-band generation."""

import math

import numpy as np
import pytest

from strapdown.analysis.gyrocompass.rocking import GaussianRocking, NarrowbandRocking, SineRocking, mean_variance_factor, rocking_model


def test_shapes_and_reproducibility():
    for m in (GaussianRocking(0.1, 0.2), SineRocking(0.1, 0.2, 5, 7), NarrowbandRocking(0.1, 0.2, 8, 0.2)):
        a = m.sample(7, 3, 50, dt=0.1)
        b = m.sample(np.random.default_rng(7), 3, 50, dt=0.1)
        assert a[0].shape == (3, 50) and a[1].shape == (3, 50)
        np.testing.assert_array_equal(a[0], b[0])


@pytest.mark.parametrize("model", [GaussianRocking(0.3, 0.1), SineRocking(0.3, 0.1, 9.0, 4.0), NarrowbandRocking(0.3, 0.1, 6.0, 0.3)])
def test_variance_and_kurtosis(model):
    xi, eta = model.sample(1, 200, 1000, dt=None)
    n = xi.size
    # SE of the variance estimate is σ² √((κ − 1)/n) < 2e-3 σ²
    assert np.var(xi) == pytest.approx(0.09, rel=8e-3)
    assert np.var(eta) == pytest.approx(0.01, rel=8e-3)
    kurt = np.mean(xi**4) / np.mean(xi**2) ** 2
    assert kurt == pytest.approx(model.kappa, abs=0.05)
    assert n == 200_000


def test_sine_is_arcsine_distributed():
    xi, _ = SineRocking(1.0, 0.0, 3.0, 3.0).sample(2, 1, 100_000)
    a = math.sqrt(2.0)
    assert np.max(np.abs(xi)) <= a
    # arcsine CDF: F(x) = 1/2 + asin(x/a)/π; Kolmogorov bound at n = 1e5 is ≈ 0.0052 (α = 0.1 %)
    x = np.sort(xi.ravel())
    cdf = 0.5 + np.arcsin(x / a) / math.pi
    assert np.max(np.abs(cdf - np.arange(1, x.size + 1) / x.size)) < 0.0062


@pytest.mark.parametrize("period, damping, dt", [(7.0, 0.15, 0.2), (8.0, 0.02, 0.1), (3.0, 0.7, 1.3)])
def test_narrowband_has_the_exact_stationary_covariance(period, damping, dt):
    """The generator is linear in its normal draws: feeding it unit vectors gives its
    Jacobian J, and J Jᵀ must equal the Toeplitz autocovariance of the shaping filter."""
    m = NarrowbandRocking(1.0, 1.0, period, damping)
    n = 25
    eye = np.eye(n + 1)
    x = m.series_from_normals(eye[:, :3], eye[:, 3:], n, dt)  # row i: response to normal i
    cov = x.T @ x
    lags = np.abs(np.subtract.outer(np.arange(n), np.arange(n))) * dt
    np.testing.assert_allclose(cov, m.autocorrelation(lags), rtol=0, atol=1e-12)


def test_narrowband_innovations_match_state_noise():
    """The MA(1) factor reproduces the variance and lag-1 covariance of the state-noise combination."""
    m = NarrowbandRocking(1.0, 1.0, 7.0, 0.15)
    t, d, theta, s2 = m.innovations(0.2)
    F, Q = m.discretisation(0.2)
    g2 = (F - t * np.eye(2))[0]
    assert abs(theta) < 1
    assert s2 * (1 + theta**2) == pytest.approx(Q[0, 0] + g2 @ Q @ g2, rel=1e-12)
    assert s2 * theta == pytest.approx(g2 @ Q[:, 0], rel=1e-12)


def test_narrowband_autocorrelation_and_stationarity():
    m = NarrowbandRocking(1.0, 1.0, 8.0, 0.1)
    xi, _ = m.sample(5, 500, 400, dt=0.5)
    assert np.var(xi[:, 0]) == pytest.approx(1.0, abs=0.2)  # stationary start (SE ≈ 0.06)
    lags = np.arange(8)
    emp = np.array([np.mean(xi[:, : 400 - k] * xi[:, k:]) for k in lags])
    np.testing.assert_allclose(emp, m.autocorrelation(lags * 0.5), atol=0.03)


def test_mean_variance_factor_against_simulation():
    m = NarrowbandRocking(1.0, 1.0, 8.0, 0.1)
    v = mean_variance_factor(m, 300, 0.1)
    xi, _ = m.sample(9, 4000, 300, dt=0.1)
    emp = np.var(xi.mean(axis=1))
    assert emp == pytest.approx(v, rel=0.08)  # SE of a variance from 4000 Gaussian means: 2.2 %


@pytest.mark.parametrize(
    "factory, message",
    [
        (lambda: GaussianRocking(-1.0, 0.0), "sigma_xi"),
        (lambda: SineRocking(0.1, math.nan), "sigma_eta"),
        (lambda: NarrowbandRocking(0.1, 0.1, 8.0, 1.5), "damping"),
        (lambda: NarrowbandRocking(0.1, 0.1, 0.0, 0.5), "period"),
        (lambda: rocking_model("chaotic", 0.1, 0.1), "rocking"),
        (lambda: GaussianRocking(0.1, 0.1).sample(1, 0, 3), "n_trials"),
        (lambda: GaussianRocking(0.1, 0.1).sample(-3, 1, 3), "rng"),
    ],
)
def test_bad_input(factory, message):
    with pytest.raises(ValueError, match=message):
        factory()


def test_rng_type_error():
    with pytest.raises(TypeError, match="rng"):
        GaussianRocking(0.1, 0.1).sample("seed", 1, 3)
