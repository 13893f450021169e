"""Control-variate Monte Carlo of the azimuth error: unbiased, honest intervals, at least the precision of the plain run.

The oracle is exact quadrature of the error moments, independent of the Monte Carlo code:
Gauss–Hermite for Gaussian rocking, the trapezoidal rule over the phases for a sinusoid
(spectrally accurate for a smooth periodic integrand).
"""

import math
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest
from scipy import stats

from strapdown.analysis.core import montecarlo
from strapdown.analysis.gyrocompass.azimuth import AzimuthErrorKernel, TaylorControls, azimuth_error, azimuth_monte_carlo, far_rocking_probability
from strapdown.analysis.gyrocompass.bound_sweep import SweepCase, evaluate_case, sweep
from strapdown.analysis.gyrocompass.rocking import GaussianRocking, NarrowbandRocking, SineRocking, mean_law, mean_variance_factor

r = math.radians


def _exact_moments(model: str, latitude, beta0, gamma0, sigma):
    """``(E e, E e²)`` of the error (12) with ξ, η independent, both of standard deviation ``sigma``."""
    if model == "normal":
        x, w = np.polynomial.hermite_e.hermegauss(160)
        w = w / w.sum()
    else:
        n = 256
        x = math.sqrt(2.0) * np.sin(2.0 * np.pi * (np.arange(n) + 0.5) / n)
        w = np.full(n, 1.0 / n)
    X, Y = np.meshgrid(x * sigma, x * sigma, indexing="ij")
    W = np.outer(w, w)
    e = azimuth_error(X, Y, latitude=latitude, beta0=beta0, gamma0=gamma0)
    return math.fsum((W * e).ravel()), math.fsum((W * e * e).ravel())


def _rocking(model, sigma):
    return GaussianRocking(sigma, sigma) if model == "normal" else SineRocking(sigma, sigma)


# (model, latitude, β0, γ0, σ) [deg]: small to large residuals of the controls, zero and non-zero tilts;
# Gaussian rocking runs degree-2 controls, a sinusoid degree 4 (the report's settings)
COVERAGE_CASES = [
    ("normal", 45.0, 0.0, 0.0, 0.05),
    ("normal", 80.0, 0.0, 0.0, 1.0),
    ("normal", 70.0, 0.0, 0.0, 3.1623),
    ("normal", 50.0, 2.0, -2.0, 5.6234),
    ("sine", 60.0, 2.0, -2.0, 3.0),
    ("sine", 75.0, 1.0, -2.0, 5.0),
]


def test_standard_moments_are_the_laws():
    """E u^k of the rocking laws against quadrature (normal) and the mean over phases (sine)."""
    x, w = np.polynomial.hermite_e.hermegauss(40)
    w = w / w.sum()
    phase = math.sqrt(2.0) * np.sin(2.0 * np.pi * (np.arange(64) + 0.5) / 64)
    for k in range(9):
        assert GaussianRocking(1.0, 1.0).standard_moment(k) == pytest.approx(float(np.sum(w * x**k)), abs=1e-9)
        assert NarrowbandRocking(1.0, 1.0).standard_moment(k) == GaussianRocking(1.0, 1.0).standard_moment(k)
        assert SineRocking(1.0, 1.0).standard_moment(k) == pytest.approx(float(np.mean(phase**k)), abs=1e-12)
    # truncated: E[u^k; |u| ≤ c] by the midpoint rule on a fine grid (normal) and over the phases (sine)
    for c in (0.5, 1.3, 3.0):
        grid = np.linspace(-c, c, 200_001)
        mid, h = 0.5 * (grid[1:] + grid[:-1]), grid[1] - grid[0]
        dense = math.sqrt(2.0) * np.sin(2.0 * np.pi * (np.arange(400_000) + 0.5) / 400_000)
        for k in range(0, 9, 2):
            assert GaussianRocking(1.0, 1.0).standard_moment(k, c) == pytest.approx(float(np.sum(mid**k * stats.norm.pdf(mid)) * h), rel=1e-8)
            assert SineRocking(1.0, 1.0).standard_moment(k, c) == pytest.approx(float(np.mean(np.where(np.abs(dense) <= c, dense**k, 0.0))), abs=2e-5)
    with pytest.raises(ValueError, match="bound"):
        GaussianRocking(1.0, 1.0).standard_moment(2, 0.0)


def test_monomials_are_centred_and_skip_a_still_axis():
    """Sample means of the centred monomials are zero within 4 standard errors (fixed seed)."""
    for model in (GaussianRocking(0.02, 0.03), SineRocking(0.02, 0.03)):
        c = TaylorControls.for_rocking(model, 4)
        xi, eta = model.sample(5, 1, 200_000)
        m = c.monomials(xi, eta)
        assert np.all(np.abs(m.mean(axis=0)) < 4.0 * m.std(axis=0) / math.sqrt(m.shape[0]))
    still = TaylorControls.for_rocking(GaussianRocking(0.02, 0.0), 3)
    assert still.exponents == ((1, 0), (2, 0), (3, 0))


def test_fit_controls_recovers_a_linear_relation_and_refuses_useless_controls():
    rng = np.random.default_rng(1)
    x = rng.standard_normal((4000, 2))
    y = 2.0 + 3.0 * x[:, :1] - x[:, 1:] + 1e-3 * rng.standard_normal((4000, 1))
    fit = montecarlo.fit_controls(np.concatenate([y, rng.standard_normal((4000, 1))], axis=1), x)
    assert fit.coefficients[0] == pytest.approx((3.0, -1.0), abs=1e-4)
    assert fit.variance_ratios[0] < 1e-6
    assert fit.coefficients[1] == (0.0, 0.0) and fit.variance_ratios[1] == 1.0  # independent noise: plain estimator
    zero = montecarlo.fit_controls(y, np.concatenate([x, np.zeros((4000, 1))], axis=1))  # a control without spread
    assert zero.coefficients[0][2] == 0.0 and zero.coefficients[0][0] == pytest.approx(3.0, abs=1e-4)
    with pytest.raises(ValueError, match="pilot draws"):
        montecarlo.fit_controls(y[:5], x[:5])
    with pytest.raises(ValueError, match="values"):
        montecarlo.fit_controls(y[:100], x)


def test_aux_standard_error_and_controlled_result_are_independent_of_chunking():
    lat, b0, g0, rocking = r(70.0), r(2.0), r(-1.0), GaussianRocking(r(1.0), r(1.0))
    xi, eta = rocking.sample(8, 1024, 1)
    controls = TaylorControls.for_rocking(rocking, 4).fitted(xi, eta, azimuth_error(xi, eta, latitude=lat, beta0=b0, gamma0=g0))
    kernel = AzimuthErrorKernel(lat, b0, g0, rocking, n_steps=1, controls=controls)
    a = montecarlo.run(kernel, 3000, rng=4, trials_per_block=256, blocks_per_chunk=1)
    b = montecarlo.run(kernel, 3000, rng=4, trials_per_block=256, blocks_per_chunk=5)
    with ProcessPoolExecutor(2) as ex:
        c = montecarlo.run(kernel, 3000, rng=4, trials_per_block=256, blocks_per_chunk=3, executor=ex)
    assert a.aux_mean == b.aux_mean == c.aux_mean and a.aux_std_error == b.aux_std_error == c.aux_std_error
    rows = montecarlo.collect(lambda n, g: kernel(n, g)[1], 3000, rng=4, trials_per_block=256)
    np.testing.assert_allclose(a.aux_std_error, rows.std(axis=0, ddof=1) / math.sqrt(3000), rtol=1e-9)
    ca = montecarlo.controlled(a, offsets=controls.offsets)
    assert ca.mse == pytest.approx(controls.offsets[1] + rows[:, 1].mean(), rel=1e-12)
    assert ca.histogram[1].sum() == a.histogram[1].sum() and ca.quantiles == a.quantiles
    with pytest.raises(ValueError, match="auxiliary"):
        montecarlo.controlled(montecarlo.run(lambda n, g: g.standard_normal((n, 2)), 10, rng=1), offsets=(0.0, 0.0))


@pytest.mark.parametrize("case", COVERAGE_CASES)
def test_controlled_estimates_agree_with_quadrature(case):
    """Within 4 standard errors (a 6e-5 chance of failing per check, fixed seed)."""
    model, lat, b0, g0, s = case
    mean, ms = _exact_moments(model, r(lat), r(b0), r(g0), r(s))
    mc = azimuth_monte_carlo(r(lat), r(b0), r(g0), _rocking(model, r(s)), 1_000_000, rng=21, control_degree=4)
    res = mc.result
    assert abs(res.mse - ms) <= 4.0 * res.mse_std_error
    assert abs(res.mean - mean) <= 4.0 * (res.mean_ci[1] - res.mean) / montecarlo.Z95
    assert mc.controls.plain_equivalent >= 1_000_000


def test_interval_coverage():
    """95 % intervals of the rms and of the mean cover the exact value as often as they should.

    200 independent runs per case (6 cases), each matching a plain run of 200 000 samples; each
    tail should miss 2.5 %.  The bounds are three binomial standard errors above that, pooled
    (1200 runs: 30 ± 5.4 per tail) and per case (200 runs: 5 ± 2.2 per tail).  The seeds are
    fixed, so the test is deterministic.
    """
    reps = 200
    pooled = np.zeros(4, dtype=int)
    for k, (model, lat, b0, g0, s) in enumerate(COVERAGE_CASES):
        mean, ms = _exact_moments(model, r(lat), r(b0), r(g0), r(s))
        misses = np.zeros(4, dtype=int)
        for i in range(reps):
            mc = azimuth_monte_carlo(r(lat), r(b0), r(g0), _rocking(model, r(s)), 200_000, rng=np.random.SeedSequence(77, spawn_key=(k, i)), control_degree=4)
            assert mc.controls.degree == (4 if model == "sine" else 2)
            res = mc.result
            misses += (ms > res.rms_ci[1] ** 2, ms < res.rms_ci[0] ** 2, mean > res.mean_ci[1], mean < res.mean_ci[0])
        assert np.all(misses <= 5 + 3 * 2.2 + 1), (model, lat, misses)
        pooled += misses
    assert np.all(pooled <= 30 + 3 * 5.4), pooled
    assert pooled.sum() >= 60  # not grossly conservative either (expected 120)


@pytest.mark.parametrize("case", [("sine", 75.0, 0.0, 0.0, 10.0), ("sine", 80.0, 2.0, -2.0, 10.0), ("normal", 30.0, 0.0, 0.0, 5.0), ("normal", 60.0, 2.0, -2.0, 0.3)])
def test_intervals_at_least_as_narrow_as_the_plain_run(case):
    """The controlled run is sized to the plain run's precision; checked against an actual plain run."""
    model, lat, b0, g0, s = case
    n = 400_000
    plain = azimuth_monte_carlo(r(lat), r(b0), r(g0), _rocking(model, r(s)), n, rng=5)
    cv = azimuth_monte_carlo(r(lat), r(b0), r(g0), _rocking(model, r(s)), n, rng=6, control_degree=4)
    assert cv.controls.degree == (4 if model == "sine" else 2) and cv.controls.plain_equivalent >= n
    width = lambda res: res.rms_ci[1] - res.rms_ci[0]  # noqa: E731
    # the plain width is itself estimated (heavy tails: up to ~10 % off)
    assert width(cv.result) <= 1.1 * width(plain.result)
    assert cv.result.mean_ci[1] - cv.result.mean_ci[0] <= 1.1 * (plain.result.mean_ci[1] - plain.result.mean_ci[0])
    assert cv.controls.samples < n


def test_far_excursions_set_the_run():
    """Rocking that reaches towards the horizon of the tilt correction often enough for a plain run to meet it:
    a controlled run with at least 100 such excursions, or the plain run where even it would expect fewer."""
    assert far_rocking_probability(r(80.0), 0.0, 0.0, GaussianRocking(r(0.1), r(0.1))) == 0.0
    assert far_rocking_probability(r(80.0), r(6.0), r(6.0), GaussianRocking(r(0.1), r(0.1))) == 1.0
    rocking = GaussianRocking(r(10.0), r(10.0))
    p = far_rocking_probability(r(45.0), 0.0, 0.0, rocking)
    assert p == pytest.approx(1.0 - (1.0 - 2.0 * stats.norm.sf(0.9 * 45.0 / 10.0)) ** 2, rel=1e-9)
    assert 200_000 * p >= 0.05
    plain = azimuth_monte_carlo(r(45.0), 0.0, 0.0, rocking, 200_000, rng=2, control_degree=4, steps_per_trial=256)
    assert plain.controls.degree == 0 and plain.result.n_samples == plain.controls.samples >= 200_000
    run = azimuth_monte_carlo(r(45.0), 0.0, 0.0, rocking, 4_000_000, rng=2, control_degree=4)
    assert 4_000_000 * p >= 100 and run.controls.degree == 2 and 100 / p <= run.controls.samples < 2_000_000
    # at least 100 excursions would take more than half the plain run: the plain run (its draws are cheaper)
    often = far_rocking_probability(r(50.0), 0.0, 0.0, rocking)
    run = azimuth_monte_carlo(r(50.0), 0.0, 0.0, rocking, 200_000, rng=2, control_degree=4)
    assert 100 / often > 100_000 and run.controls.degree == 0 and run.controls.pilot_samples > 0
    sine = SineRocking(r(10.0), r(10.0))
    often = far_rocking_probability(r(80.0), r(2.0), r(-2.0), sine)
    run = azimuth_monte_carlo(r(80.0), r(2.0), r(-2.0), sine, 200_000, rng=2, control_degree=4)
    assert 200_000 * often >= 100 and run.controls.degree == 4 and run.controls.samples >= 100 / often


def test_mean_law_is_the_law_of_the_record_means():
    """Means of simulated records against :func:`mean_law`: variance (narrow band) and the arcsine law (sine)."""
    nb = NarrowbandRocking(1.0, 0.5, 8.0, 0.1)
    law = mean_law(nb, 300, 0.1)
    assert isinstance(law, GaussianRocking)
    assert law.sigma_xi**2 == pytest.approx(mean_variance_factor(nb, 300, 0.1))
    assert law.sigma_eta == pytest.approx(0.5 * law.sigma_xi)
    sine = SineRocking(1.0, 1.0, 7.0, 7.0)
    law = mean_law(sine, 100, 0.1)
    xi, _ = sine.sample(4, 20_000, 100, dt=0.1)
    m = np.sort(xi.mean(axis=1))
    a = law.sigma_xi * math.sqrt(2.0)
    assert np.max(np.abs(m)) <= a * (1 + 1e-12)
    cdf = 0.5 + np.arcsin(np.clip(m / a, -1.0, 1.0)) / math.pi
    assert np.max(np.abs(cdf - np.arange(1, m.size + 1) / m.size)) < 0.015  # Kolmogorov, n = 2e4, α = 0.1 %: 0.0138
    with pytest.raises(ValueError, match="dt"):
        mean_law(sine, 100, None)
    with pytest.raises(TypeError, match="model"):
        mean_law("sine", 100, 0.1)


def _sweep_cases():
    return [
        SweepCase(r(30.0), r(0.5), "normal"),
        SweepCase(r(75.0), r(4.0), "sine", beta0=r(2.0), gamma0=r(-1.0)),
        SweepCase(r(60.0), r(1.0), "narrowband", estimate="sample-mean", averaging_time=5.0, period=4.0, damping=0.2),
    ]


def test_controlled_sweep_serial_equals_process_pool():
    serial = sweep(_sweep_cases(), n_samples=20_000, rng=9, control_degree=4)
    with ProcessPoolExecutor(2) as ex:
        assert sweep(_sweep_cases(), n_samples=20_000, rng=9, executor=ex, control_degree=4) == serial


@pytest.mark.parametrize("damping, sigma", [(0.2, 1.0), (0.02, 5.0)])
def test_sample_mean_case_agrees_with_the_simulated_records(damping, sigma):
    """The controlled sample-mean case (means drawn from their exact law; plug-in with controls) against the plain
    simulation of whole records: rms Δ and plug-in (14) within 4 standard errors of the plain ones (fixed seeds)."""
    case = SweepCase(r(60.0), r(sigma), "narrowband", estimate="sample-mean", averaging_time=30.0, period=8.0, damping=damping)
    plain = evaluate_case(case, 600_000, np.random.SeedSequence(3))
    cv = evaluate_case(case, 6_000_000, np.random.SeedSequence(4), control_degree=4)
    assert cv.controls.degree == 2 and cv.controls.samples < 20_000
    se_plain = (plain.rms_hi - plain.rms_lo) / (2.0 * montecarlo.Z95)
    assert cv.rms_hi - cv.rms_lo < 0.5 * (plain.rms_hi - plain.rms_lo)
    assert abs(cv.rms - plain.rms) < 4.0 * se_plain
    assert cv.plugin_controls.plain_equivalent >= 6_000_000 // case.n_steps
    # plain plug-in: mean of (14)² over 2000 records; its standard error from the same records
    kernel = AzimuthErrorKernel(case.latitude, 0.0, 0.0, case.rocking(), n_steps=case.n_steps, dt=case.dt, estimate="sample-mean")
    b14sq = montecarlo.collect(lambda n, g: kernel(n, g)[1][:, :1], 2000, rng=5)
    se = b14sq.std(ddof=1) / math.sqrt(b14sq.size) / (2.0 * math.sqrt(b14sq.mean()))
    assert abs(cv.plugin14 - math.sqrt(b14sq.mean())) < 4.0 * se
    # a short reference (2000 records): the shortest controlled run, still far tighter than the plain one
    few = evaluate_case(case, 600_000, np.random.SeedSequence(4), control_degree=4)
    assert few.controls.degree == 2 and few.controls.samples == 4096
    assert few.rms_hi - few.rms_lo < 0.5 * (plain.rms_hi - plain.rms_lo)


def test_bad_control_arguments():
    with pytest.raises(ValueError, match="control_degree"):
        azimuth_monte_carlo(0.5, 0.0, 0.0, GaussianRocking(0.01, 0.01), 1000, control_degree=-1)
    with pytest.raises(ValueError, match="pilot_samples"):
        azimuth_monte_carlo(0.5, 0.0, 0.0, GaussianRocking(0.01, 0.01), 1000, control_degree=4, pilot_samples=10)
    with pytest.raises(ValueError, match="controls"):
        AzimuthErrorKernel(0.5, 0.0, 0.0, GaussianRocking(0.01, 0.01), controls=TaylorControls.for_rocking(GaussianRocking(0.01, 0.01), 2))
    with pytest.raises(TypeError, match="controls"):
        AzimuthErrorKernel(0.5, 0.0, 0.0, GaussianRocking(0.01, 0.01), controls="taylor")
    with pytest.raises(ValueError, match="degree"):
        TaylorControls.for_rocking(GaussianRocking(0.01, 0.01), 0)


def test_fit_controls_refuses_non_finite_pilots():
    with pytest.raises(ValueError, match="`values`"):
        montecarlo.fit_controls(np.full((20, 1), np.nan), np.ones((20, 2)))
    with pytest.raises(ValueError, match="`controls`"):
        montecarlo.fit_controls(np.ones((20, 1)), np.full((20, 2), np.inf))
