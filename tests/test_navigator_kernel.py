"""The compiled navigator's draw of a block's sensor errors has the distribution of its noise model.

The draw adds the parts that drive no state (white noise and each first-order
term's integral innovation independent of its level) as one Gaussian of their
summed variance; the variance of the block error and its covariance with the
updated levels are checked against the discretised model, computed apart from
the kernel, and the check is shown to reject the variance without that part.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from strapdown.analysis.navigation._navigator_kernel import draw_step
from strapdown.analysis.navigation.mechanization import noise_terms


def _draws(white: float, H: float, n: int = 20000, seed: int = 7):
    spec = SimpleNamespace(gauss_markov=lambda: (np.array([H]), np.array([1.0])), rate_random_walk=0.0)
    phi, c, L, var = noise_terms(spec, H)
    g = np.random.default_rng(seed)
    e = np.empty((n, 3))
    x_new = np.empty((n, 3))
    out = np.empty(3)
    for i in range(n):  # each call from an independent stationary level
        x = math.sqrt(var[0]) * g.standard_normal((1, 3))
        draw_step(g, 1, H, white, phi, c, L, x, out)
        e[i], x_new[i] = out, x[0]
    return phi[0], c[0], L[0], var[0], e.ravel(), x_new.ravel()


def test_block_error_has_the_model_variance_and_covariance():
    white, H = 0.3, 0.05
    phi, c, L, v, e, x_new = _draws(white, H)
    expected = white**2 * H + c**2 * v + L[1, 0] ** 2 + L[1, 1] ** 2
    se = math.sqrt(2.0 / e.size)  # relative standard error of a Gaussian sample variance
    assert L[1, 1] ** 2 / expected > 0.02  # the combined part matters in this case
    assert abs(np.var(e) / expected - 1.0) < 5 * se
    cov = np.mean(e * x_new) - np.mean(e) * np.mean(x_new)
    cov_expected = c * phi * v + L[1, 0] * L[0, 0]
    sd = math.sqrt((expected * (phi**2 * v + L[0, 0] ** 2) + cov_expected**2) / e.size)
    assert abs(cov - cov_expected) < 5 * sd
    # the same check says no to a draw that left the integral's independent innovation out
    wrong = expected - L[1, 1] ** 2
    assert abs(np.var(e) / wrong - 1.0) > 5 * se


def test_block_error_without_first_order_terms_is_white():
    empty = (np.zeros(0), np.zeros(0), np.zeros((0, 2, 2)))
    g = np.random.default_rng(3)
    out = np.empty(3)
    samples = np.empty((20000, 3))
    for i in range(samples.shape[0]):
        draw_step(g, 1, 0.01, 2.0, *empty, np.zeros((0, 3)), out)
        samples[i] = out
    se = math.sqrt(2.0 / samples.size)
    assert abs(np.var(samples) / (4.0 * 0.01) - 1.0) < 5 * se
