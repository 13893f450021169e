"""Shared and cached paths of the coning analysis agree bit for bit with the computations they replace."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from strapdown.analysis.coning import drift_theory as T
from strapdown.analysis.coning import sculling_motion as SM
from strapdown.analysis.coning.algorithm_summary import summarize
from strapdown.analysis.coning.local_error import TumblingMotion, error_coefficients, local_error
from strapdown.analysis.coning.papers.budennyi_table3 import _small_cone_limit
from strapdown.derivations.coning import drift as D
from strapdown.derivations.coning import series as S
from strapdown.derivations.coning.leading_drift import small_cone_limit
from strapdown.derivations.coning.registry import get


class _Unshared(TumblingMotion):
    """The same motion, of another type: :func:`local_error` computes its steps afresh."""


@pytest.mark.parametrize("name", ["panov-4s-1", "panov-4s-3", "lebedev-panov-4", "two-sample"])
def test_local_error_shared_steps_equal_fresh_ones(name):
    alg = get(name)
    for t, step in ((0.4, 0.08), (1.7, 0.02), (0.4, 0.08)):  # the repeated step comes from the shared store
        shared = local_error(alg, TumblingMotion(), t, step)
        fresh = local_error(alg, _Unshared(), t, step)
        np.testing.assert_array_equal(shared, fresh)
        assert shared.flags.writeable


def test_local_error_shared_steps_follow_the_motion():
    alg = get("panov-4s-1")
    a = local_error(alg, TumblingMotion(1.0), 1.0, 0.08)
    b = local_error(alg, TumblingMotion(1.5), 1.0, 0.08)
    assert not np.array_equal(a, b)


def test_error_coefficients_shared_basis_equal_fresh_one():
    alg = get("panov-4s-2")
    times = np.linspace(0.2, 3.0, 4)
    for motion in (TumblingMotion(), TumblingMotion()):  # the second call reads the shared basis
        shared, res_shared = error_coefficients(alg, motion=motion, times=times)
        fresh, res_fresh = error_coefficients(alg, motion=_Unshared(), times=times)
        np.testing.assert_array_equal(shared, fresh)
        assert res_shared == res_fresh


def _reference_rectification(algorithm, motion, h):
    """The rectified-error rate with every phasor recomputed where it is used."""
    n = algorithm.samples
    with mpmath.workdps(SM.RECTIFICATION_DIGITS):
        hm = mpmath.mpf(h)
        cur = [SM._phasors(motion, hm, j) for j in range(1, n + 1)]
        p_sum, b_sum = sum(p for p, _ in cur), sum(b for _, b in cur)
        theta_k = motion.angle_amplitude * mpmath.expj(motion.angle_phase)
        total = SM._mean(theta_k, b_sum) + SM._mean(p_sum, b_sum) / 2
        for (i, j), c in algorithm.pairwise.items():
            pi, bi = SM._phasors(motion, hm, i)
            pj, bj = SM._phasors(motion, hm, j)
            total += mpmath.mpf(c.numerator) / c.denominator * (SM._mean(pi, bj) - SM._mean(bi, pj))
        exact = mpmath.mpf(motion.angle_amplitude) * motion.accel_amplitude * mpmath.cos(mpmath.mpf(motion.accel_phase) - motion.angle_phase) / 2
        return float(exact - total / (n * hm))


@pytest.mark.parametrize("name", ["two-sample", "panov-4s-3", "ignagni-1996-5", "savage-1+1"])
def test_rectification_error_equals_phasor_by_phasor_sum(name):
    alg = get(name)
    motion = SM.ScullingMotion(1e-3, 1.0, 1.0)
    for h in (0.02, 0.3):
        assert SM.rectification_error(alg, motion, h).rate == _reference_rectification(alg, motion, h)


@pytest.mark.parametrize("name", ["panov-4s-1", "panov-4s-3", "two-sample"])
def test_asymptotic_drift_from_one_evaluation_of_the_terms(name):
    alg = get(name)
    eps = np.array([-1.0, 0.5, -0.3])
    nutation = np.radians([1.0, 5.0, 20.0])
    vals, _ = T.drift_terms(alg, eps, nutation)
    rho = T.asymptotic_order(alg, eps, nutation)
    w = rho + 1
    lead = np.take_along_axis(vals, np.clip(w, 0, vals.shape[-1] - 1)[..., None], axis=-1)[..., 0]
    expected = np.where(rho >= 0, np.abs(lead * 30.0**w * 0.01 ** (w - 1)), np.nan)
    np.testing.assert_array_equal(T.asymptotic_drift(alg, eps=eps, nu=30.0, nutation=nutation, step=0.01), expected)


@pytest.mark.parametrize(("samples", "history"), [(2, 0), (3, 0), (5, 0), (1, 1)])
def test_optimal_coning_algorithm_cached_equals_derived(samples, history):
    ours = T.optimal_coning_algorithm(samples, history=history)
    theirs = D.optimal_coning_algorithm(samples, history=history)
    assert ours == theirs
    assert D.lag_sums(ours) == D.lag_sums(theirs)


def test_optimal_coning_algorithm_cached_refuses_bad_input():
    with pytest.raises(ValueError, match="samples"):
        T.optimal_coning_algorithm(1)
    with pytest.raises(TypeError, match="samples"):
        T.optimal_coning_algorithm(2.0)


@pytest.mark.parametrize("name", ["savage-1+1", "panov-4s-3", "two-sample"])
def test_summary_order_equals_series_order(name):
    alg = get(name)
    assert summarize(alg).accuracy_order == S.local_error(alg).order


@pytest.mark.parametrize(("name", "weight"), [("two-sample", 5), ("panov-4s-3", 7)])
def test_small_cone_limit_cached_equals_derived(name, weight):
    assert _small_cone_limit(get(name), weight) == small_cone_limit(get(name), weight)


def test_per_sample_fit_grid_search_equals_point_by_point_sums():
    from strapdown.analysis.coning.computational_load import operation_count
    from strapdown.analysis.coning.papers import budennyi_loads as L
    from strapdown.analysis.coning.papers.budennyi_table3 import table3_conditions
    from strapdown.derivations.coning import published as P

    conditions = table3_conditions()
    m = P.BUDENNYI_CONDITIONS.multiplication_cost
    cells = L._cells(conditions, 20.0)
    fits = L.per_sample_fit()
    for fit, eps in zip(fits, sorted({c.row.eps for c in cells})):
        data = [(c.printed, conditions.samples * operation_count(get(f"panov-4s-{c.row.algorithm}")).cost(m), c.step) for c in cells if c.row.eps == eps]
        grid = np.arange(0.0, 3000.0, 1.0)
        err = [sum((np.log((cost + q) / H / 1e3) - np.log(b)) ** 2 for b, cost, H in data) for q in grid]
        assert fit.eps == eps
        assert fit.sigma_q == float(grid[int(np.argmin(err))])


@pytest.mark.parametrize("name", ["panov-4s-3", "two-sample"])
def test_drift_terms_of_one_motion_kept_equal_evaluated_ones(name):
    alg = get(name)
    for eps, nutation in ((-1.0, 0.02), (0.5, 0.3), (-1.0, 0.02)):
        vals, mags = T.drift_terms(alg, eps, nutation)
        ref_vals, ref_mags = T._evaluate_drift_terms(alg, np.asarray(eps), np.asarray(nutation), T.DEFAULT_MAX_WEIGHT)
        np.testing.assert_array_equal(vals, ref_vals)
        np.testing.assert_array_equal(mags, ref_mags)
        vals[...] = 0.0  # the caller's copy: the kept terms are untouched
    np.testing.assert_array_equal(T.drift_terms(alg, 0.5, 0.3)[0], T._evaluate_drift_terms(alg, np.asarray(0.5), np.asarray(0.3), T.DEFAULT_MAX_WEIGHT)[0])
    with pytest.raises(ValueError, match="nutation"):
        T.drift_terms(alg, -1.0, 4.0)
