"""Data-sheet sensor errors: the Allan deviation of a simulated sensor against its specification.

The measured curve comes from ``allantools`` (an independent implementation)
on rates drawn by the package; the specification's curve is the closed form of
each term.  The read-back of N, B and K is the classical three-term fit.
"""

import math

import numpy as np
import pytest

from strapdown.analysis.alignment.imu import Scenario, simulate_imu
from strapdown.analysis.alignment.sensor_models import FLICKER_FLOOR, GRADES, SensorSpec, add_sensor_errors, allan_deviation, fit_allan, simulate_sensor_errors

# A sensor whose three terms all show within a two-hour record: random walk down to 3 s, the flicker
# floor from 3 s to 300 s, rate random walk above.
N0 = 1e-4
B0 = N0 / math.sqrt(3.0) / FLICKER_FLOOR
K0 = math.sqrt(3.0) * FLICKER_FLOOR * B0 / math.sqrt(300.0)
SPEC = SensorSpec(N0, B0, K0, flicker_band=(0.3, 3000.0))


@pytest.fixture(scope="module")
def measured():
    e = simulate_sensor_errors(SPEC, n_trials=1, n_samples=2**16, dt=0.1, rng=3)
    return [allan_deviation(e.increments[0, :, k] / 0.1, 0.1, spec=SPEC) for k in range(3)]


def test_allan_deviation_of_the_simulated_sensor_matches_its_specification(measured):
    """Each axis: the closed form inside the 95 % interval (Greenhall's edf) at nearly every τ."""
    inside, total = 0, 0
    for a in measured:
        spec = np.sqrt(SPEC.allan_variance(a.taus))
        ok = (spec >= a.low) & (spec <= a.high)
        inside += int(ok.sum())
        total += ok.size
    # 3 × 16 points at 95 % each: fewer than 7 outside has probability above 0.99 (binomial)
    assert total - inside <= 6, (inside, total)


def test_data_sheet_coefficients_read_back(measured):
    for a in measured:
        fit = fit_allan(a.taus, a.adev, weights=a.edf)
        assert fit.random_walk == pytest.approx(N0, rel=0.05)
        assert fit.bias_instability == pytest.approx(B0, rel=0.12)
        # the rate random walk shows only over the last decade, a few degrees of freedom
        assert fit.rate_random_walk == pytest.approx(K0, rel=0.5)


def test_gauss_markov_sum_has_the_flicker_floor_inside_its_band():
    spec = SensorSpec(bias_instability=1.0, flicker_band=(1.0, 1e5), terms_per_decade=3)
    tau = np.geomspace(30.0, 3000.0, 9)
    np.testing.assert_allclose(np.sqrt(spec.allan_variance(tau)), FLICKER_FLOOR, rtol=0.04)


def test_gauss_markov_term_limits():
    """For τ ≪ T a Gauss–Markov term is a rate random walk of K² = 2q/T, for τ ≫ T white noise of N² = 2qT."""
    T = 100.0
    spec = SensorSpec(bias_instability=1.0, flicker_band=(T, 2 * T), terms_per_decade=1)
    taus, var = spec.gauss_markov()
    t = np.array([1e-3, 1e6])
    terms = spec.allan_terms(t)["flicker"]
    expected = sum(np.array([2 * v / c / 3 * t[0], 2 * v * c / t[1]]) for c, v in zip(taus, var))
    np.testing.assert_allclose(terms, expected, rtol=2e-3)
    # the series and the closed form meet without a step at x = 0.05
    s = SensorSpec(bias_instability=1.0, flicker_band=(1.0, 2.0), terms_per_decade=1)
    a, b = s.allan_terms([0.05 * (1 - 1e-9), 0.05 * (1 + 1e-9)])["flicker"]
    assert a == pytest.approx(b, rel=1e-8)


def test_turn_on_bias_and_mean_bias():
    spec = SensorSpec(turn_on_bias=2.0)
    e = simulate_sensor_errors(spec, n_trials=4000, n_samples=10, dt=0.5, rng=2)
    assert e.turn_on.std() == pytest.approx(2.0, rel=0.03)
    np.testing.assert_allclose(e.mean_bias, e.turn_on, rtol=1e-12)
    np.testing.assert_allclose(e.increments.sum(axis=1) / 5.0, e.turn_on, rtol=1e-12)


def test_grades_and_records():
    assert [g.name for g in GRADES] == ["marine", "navigation", "intermediate", "tactical"]
    assert np.all(np.diff([g.gyro.turn_on_bias for g in GRADES]) > 0)
    sc = Scenario(0.7, duration=10.0, sample_rate=10.0)
    ideal = simulate_imu(sc, None, n_trials=2, rng=0)
    rec = add_sensor_errors(ideal, GRADES[3], rng=1)
    assert rec.dtheta.shape == ideal.dtheta.shape and not np.array_equal(rec.dtheta, ideal.dtheta)
    with pytest.raises(ValueError, match="flicker_band"):
        SensorSpec(bias_instability=1.0, flicker_band=(10.0, 1.0))


@pytest.mark.parametrize("tau", [0.7, 40.0, math.inf])
def test_first_order_loop_equals_the_numpy_form_to_the_last_bit(tau):
    # the fused compiled loop against the numpy form (lfilter) on the same draws: Gauss–Markov terms and the random walk
    from strapdown.analysis.alignment.sensor_models import _first_order

    ref_inc, ref_mean = _first_order(np.random.default_rng(3), (4, 257, 3), 0.1, tau, 2.5e-7, compiled=False)
    inc, mean = _first_order(np.random.default_rng(3), (4, 257, 3), 0.1, tau, 2.5e-7, compiled=True)
    assert np.array_equal(inc, ref_inc) and np.array_equal(mean, ref_mean)
    # and the comparison can tell: another variance gives other increments
    other, _ = _first_order(np.random.default_rng(3), (4, 257, 3), 0.1, tau, 3.0e-7, compiled=True)
    assert not np.array_equal(other, inc)


@pytest.mark.parametrize("tau", [0.7, math.inf])
@pytest.mark.parametrize("k", [3, 1])
@pytest.mark.parametrize("compiled", [True, False])
def test_first_order_into_a_running_total_equals_adding_its_increments_to_the_last_bit(tau, k, compiled):
    # the increments added in place (draws into a given buffer) against a new array added afterwards
    from strapdown.analysis.alignment.sensor_models import _first_order

    base = np.random.default_rng(7).standard_normal((4, 257, k)) * 1e-3
    inc, mean = _first_order(np.random.default_rng(3), (4, 257, k), 0.1, tau, 2.5e-7, compiled=False)
    total, draws = base.copy(), np.full((2, 4, 257, k), np.nan)
    got, got_mean = _first_order(np.random.default_rng(3), (4, 257, k), 0.1, tau, 2.5e-7, compiled=compiled, total=total, draws=draws)
    assert got is total and np.array_equal(got, base + inc) and np.array_equal(got_mean, mean)


def test_simulate_sensor_errors_equals_its_terms_added_one_by_one():
    # the running total of simulate_sensor_errors against the terms drawn as new arrays, in the same order
    from strapdown.analysis.alignment.sensor_models import _first_order

    spec, n, N, dt = GRADES[1].gyro, 3, 501, 0.1
    got = simulate_sensor_errors(spec, n_trials=n, n_samples=N, dt=dt, rng=5)
    g = np.random.default_rng(5)
    turn_on = spec.turn_on_bias * g.standard_normal((n, 3))
    inc, mean = np.broadcast_to(turn_on[:, None, :] * dt, (n, N, 3)).copy(), turn_on.copy()
    inc += spec.random_walk * math.sqrt(dt) * g.standard_normal((n, N, 3))
    for tau, q in [*zip(*spec.gauss_markov()), (math.inf, spec.rate_random_walk**2)]:
        d, m = _first_order(g, (n, N, 3), dt, float(tau), float(q))
        inc += d
        mean += m
    assert np.array_equal(got.increments, inc) and np.array_equal(got.mean_bias, mean) and np.array_equal(got.turn_on, turn_on)


def test_first_order_add_refuses_a_total_it_cannot_write():
    from strapdown.analysis.alignment import kernels

    with pytest.raises(TypeError, match="total"):
        kernels.first_order_add(np.zeros((2, 4, 10, 3)), np.zeros((4, 1, 3)), 0.9, 0.1, np.eye(2), np.zeros((4, 10, 3), dtype=np.float32))
    with pytest.raises(ValueError, match="total"):
        kernels.first_order_add(np.zeros((2, 4, 10, 3)), np.zeros((4, 1, 3)), 0.9, 0.1, np.eye(2), np.zeros((4, 11, 3)))


def test_first_order_loop_refuses_shapes_that_do_not_fit():
    from strapdown.analysis.alignment import kernels

    with pytest.raises(ValueError, match="start"):
        kernels.first_order_loop(np.zeros((2, 4, 10, 3)), np.zeros((3, 1, 3)), 0.9, 0.1, np.eye(2))
    with pytest.raises(ValueError, match="draws"):
        kernels.first_order_loop(np.zeros((4, 10, 3)), np.zeros((4, 1, 3)), 0.9, 0.1, np.eye(2))
