"""Lyapunov analysis of the first-variant stage, Plotnikov (1999), eqs. (3.1)-(3.4)."""

import numpy as np
import pytest
import sympy as sp

from strapdown.analysis.multistage.decay_rates import exact_rate, perturbation_matrix, rest_rate, simulated_rate, strict_rate_bound
from strapdown.derivations.multistage.lyapunov_function import SYMBOLS, derive
from strapdown.derivations.multistage.published import PRINTED_GAINS

#: Stage-1 gains of section 5 of Plotnikov (1999).
K1, L1 = PRINTED_GAINS.stage1


@pytest.fixture(scope="module")
def d():
    return derive()


def test_vdot_is_exactly_minus_l_k_z_zbar(d):
    k, l, z = SYMBOLS.k, SYMBOLS.l, SYMBOLS.z
    assert sp.expand(d.Vdot - (-l * k * sum(c * c for c in z))) == 0
    assert d.vdot_matches and d.vector_part_zero


def test_vdot_free_of_y_and_omega(d):
    """V' is only semidefinite: it contains no y (and the body rate cancels)."""
    y, w = SYMBOLS.y, SYMBOLS.omega
    assert not (d.Vdot.free_symbols & set(y)) and not (d.Vdot.free_symbols & set(w))


def test_lasalle_step(d):
    y = SYMBOLS.y
    assert [sp.simplify(c + yi / 2) for c, yi in zip(d.lasalle_zdot, y)] == [0, 0, 0, 0]


def test_strict_function_derivative(d):
    assert d.wdot_matches


def test_vdot_numerically_along_trajectory():
    """Independent check: V(t) from a numerical solution obeys V' = -lk|z|^2."""
    from scipy.integrate import solve_ivp

    k, l, w = 0.3, 0.2, np.array([0.4, -0.7, 0.25])
    a = perturbation_matrix(k, l, w)
    sol = solve_ivp(lambda t, x: a @ x, (0, 5), np.arange(1.0, 9.0) / 10, rtol=1e-12, atol=1e-14, dense_output=True)
    t = np.linspace(0.5, 4.5, 9)
    x = sol.sol(t)
    def v(tt):
        xx = sol.sol(tt)
        return l * (xx[:4] ** 2).sum(0) + 0.5 * (xx[4:] ** 2).sum(0)

    vdot = (v(t + 1e-5) - v(t - 1e-5)) / 2e-5
    np.testing.assert_allclose(vdot, -l * k * (x[:4] ** 2).sum(0), rtol=1e-6)


def test_rest_rate_matches_charpoly_and_eigenvalues(d):
    assert str(d.charpoly_rest) == "(k*s + l + 2*s**2)**4/16"
    for k, l in [(K1, L1), (0.05, 1e-4), (0.3, 0.001)]:
        assert rest_rate(k, l) == pytest.approx(exact_rate(k, l), rel=1e-9)
    assert rest_rate(K1, L1) == pytest.approx(0.01 / 4)


@pytest.mark.parametrize("k,l,w", [(K1, L1, (0.0, 0.01, 0.0)), (0.05, 1e-4, (0.01, 0.0, 0.02))])
def test_simulated_decay_matches_rate_and_bound(k, l, w):
    exact = exact_rate(k, l, w)
    sim = simulated_rate(k, l, w, step=0.5, duration=14.0 / exact)
    assert sim == pytest.approx(exact, rel=0.02)
    bound, _ = strict_rate_bound(k, l, np.linalg.norm(w))
    assert 0 < bound <= exact


def test_simulated_decay_at_rest():
    sim = simulated_rate(K1, L1, step=0.5)
    assert sim == pytest.approx(0.0025, rel=0.03)  # ripple of the oscillatory pair in log V


def test_rotation_slows_decay():
    assert exact_rate(K1, L1, (0, 0, 0.1)) < exact_rate(K1, L1, (0, 0, 0.01)) < exact_rate(K1, L1)


@pytest.mark.parametrize("bad", [np.nan, np.inf, "x"])
def test_bad_gains(bad):
    with pytest.raises((ValueError, TypeError)):
        exact_rate(bad, 1e-4)
    with pytest.raises((ValueError, TypeError)):
        strict_rate_bound(0.01, bad, 0.0)


def test_bound_needs_positive_gains():
    with pytest.raises(ValueError, match="`k` > 0"):
        strict_rate_bound(0.0, 1e-4, 0.0)
