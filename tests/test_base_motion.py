"""Broadband rocking of the whole-system alignment against closed forms that share nothing with it.

The checks are the variance of the T-second mean of the rocking:

* the second-order narrow-band process ``θ'' + 2ζω0 θ' + ω0² θ = w``, whose
  autocovariance is ``R(τ) = σ² e^{−ζω0|τ|}(cos ω_d τ + ζ/√(1−ζ²) sin ω_d|τ|)``;
  the variance of its continuous mean is ``(2/T²) ∫_0^T (T − τ) R(τ) dτ`` in
  closed form, that of the mean of n samples ``(1/n²) Σ_jk R((j − k) dt)``;
* white samples: ``σ²/n``.

The library's theory integrates the model's spectral density by quadrature; its
realisations are spectral syntheses on an FFT grid; the closed forms use the
time-domain autocovariance.  The Monte Carlo bounds are 3.5 standard errors
(two-sided probability 5e-4 of a false alarm for a correct simulation), with
fixed seeds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import simpson

from strapdown.analysis.alignment.base_motion import NarrowbandMotion, WhiteMotion, mean_transfer, mean_variance
from strapdown.analysis.alignment.imu import Scenario
from strapdown.analysis.alignment.monte_carlo import AlignmentOptions, alignment_monte_carlo

PERIOD, DAMPING = 8.0, 0.1
DURATIONS = (30.0, 120.0, 300.0)
Z = 3.5


def _second_order(sigma2: float, period: float, damping: float):
    """``(a, b, κ)`` of ``R(τ) = σ² Re[κ e^{−(a − ib)τ}]``, τ ≥ 0."""
    w0 = 2.0 * math.pi / period
    a, b = damping * w0, w0 * math.sqrt(1.0 - damping * damping)
    return a, b, 1.0 - 1j * a / b


def closed_form_mean_variance(sigma2: float, period: float, damping: float, T: float) -> float:
    """Variance of the continuous T-mean of the second-order process, ``(2σ²/T²) Re[κ (T/s − (1 − e^{−sT})/s²)]``."""
    a, b, k = _second_order(sigma2, period, damping)
    s = a - 1j * b
    return float(2.0 * sigma2 / T**2 * (k * (T / s - (1.0 - np.exp(-s * T)) / s**2)).real)


def closed_form_sample_mean_variance(sigma2: float, period: float, damping: float, n: int, dt: float) -> float:
    """Variance of the mean of n samples, ``(1/n²) Σ_{|l|<n} (n − |l|) R(l dt)``."""
    a, b, k = _second_order(sigma2, period, damping)
    lag = np.arange(n) * dt
    R = sigma2 * (k * np.exp(-(a - 1j * b) * lag)).real
    weights = np.where(np.arange(n) == 0, n, 2.0 * (n - np.arange(n)))
    return float(np.sum(weights * R) / n**2)


# ---------------------------------------------------------------- theory (quadrature of the density)
@pytest.mark.parametrize("T", DURATIONS)
def test_theory_of_the_mean_equals_the_closed_form_of_the_second_order_process(T):
    # cut off far out (40 ω0) the density is the shaping filter's to 7e-7 of its power
    far = NarrowbandMotion(math.sqrt(2.0), PERIOD, DAMPING, cutoff=40.0)
    assert mean_variance(far, T, 0.05)[1] == pytest.approx(closed_form_mean_variance(1.0, PERIOD, DAMPING, T), rel=2e-6)
    # the default cut-off at 4 ω0 moves 0.07 % of the power to the band: the variance of a long mean by as much
    default = NarrowbandMotion(math.sqrt(2.0), PERIOD, DAMPING)
    assert mean_variance(default, T, 0.1)[1] == pytest.approx(closed_form_mean_variance(1.0, PERIOD, DAMPING, T), rel=1.5e-3)


@pytest.mark.parametrize("T", DURATIONS)
def test_theory_of_the_mean_of_white_rocking_is_sigma2_over_n(T):
    dt = 0.1
    n = round(T / dt)
    # the continuous mean of the band-limited process: σ²/n less the band beyond Nyquist, 2/(π² n)
    v = mean_variance(WhiteMotion(math.sqrt(2.0)), T, dt)[1]
    assert v * n == pytest.approx(1.0, abs=2.0 / (math.pi**2 * n) + 1e-9)
    assert v * n < 1.0


def test_mean_transfer_is_the_mean_of_a_sinusoid():
    T, w = 17.0, np.array([0.0, 1e-7, 0.3, 2.0])
    t = np.linspace(0.0, T, 200001)
    direct = [simpson(np.exp(1j * x * t), x=t) / T for x in w]
    np.testing.assert_allclose(mean_transfer(T)(w), direct, rtol=1e-9, atol=1e-12)


# ---------------------------------------------------------------- realisations (Monte Carlo)
def _sample_means(model, n: int, dt: float, trials: int, seed: int) -> np.ndarray:
    out = []
    for k in range(trials // 1000):
        (a,) = model.draw(np.random.default_rng([seed, k]), 1000, n + 1, dt).evaluate(n, derivatives=0)
        out.append(a[:, :, 1].mean(axis=1))
    return np.concatenate(out)


@pytest.mark.parametrize("T", DURATIONS)
def test_realisations_have_the_variance_of_the_mean_of_the_closed_form(T):
    dt = 0.1
    n = round(T / dt)
    x = _sample_means(NarrowbandMotion(math.sqrt(2.0), PERIOD, DAMPING), n, dt, 4000, int(T))
    v, se = np.mean(x * x), np.std(x * x, ddof=1) / math.sqrt(x.size)
    truth = closed_form_sample_mean_variance(1.0, PERIOD, DAMPING, n, dt)
    assert abs(v - truth) < Z * se, (v, truth, se)


def test_white_realisations_are_independent_samples():
    dt, n = 0.1, 300
    x = _sample_means(WhiteMotion(math.sqrt(2.0)), n, dt, 4000, 5)
    v, se = np.mean(x * x), np.std(x * x, ddof=1) / math.sqrt(x.size)
    assert abs(v * n - 1.0) < Z * se * n, (v * n, se * n)
    (a,) = WhiteMotion(math.sqrt(2.0)).draw(np.random.default_rng(9), 200, n + 1, dt).evaluate(n, derivatives=0)
    c1 = np.mean(a[:, 1:, 1] * a[:, :-1, 1])  # lag-one covariance: 0, standard error 1/√(200·299)
    assert abs(c1) < Z / math.sqrt(200 * 299)


def test_realisations_have_the_autocovariance_of_the_closed_form():
    dt = 0.1
    m = NarrowbandMotion(math.sqrt(2.0), PERIOD, DAMPING)
    (a,) = m.draw(np.random.default_rng(11), 3000, 401, dt).evaluate(400, derivatives=0)
    lags = np.array([0, 10, 40, 150, 390])
    a_, b_, k_ = _second_order(1.0, PERIOD, DAMPING)
    for lag in lags:
        prod = a[:, 0, 1] * a[:, lag, 1]  # independent across trials
        est, se = prod.mean(), prod.std(ddof=1) / math.sqrt(prod.size)
        truth = float((k_ * np.exp(-(a_ - 1j * b_) * lag * dt)).real)
        assert abs(est - truth) < Z * se + 2e-3, (lag, est, truth, se)  # 2e-3: the 0.07 % tail beyond the cut-off and the band-edge bin
    # the library's autocovariance (quadrature of the density) against the closed form
    np.testing.assert_allclose(m.autocovariance(lags * dt)[1], (k_ * np.exp(-(a_ - 1j * b_) * lags * dt)).real, atol=2e-3)


# ---------------------------------------------------------------- the alignment itself
@pytest.mark.parametrize("T", DURATIONS)
def test_align_tilt_estimates_and_theory_agree_with_the_closed_form(T):
    """The analytic alignment in the paper's setting: the tilt estimates (16) are the T-means of the rocking."""
    lat, sd = math.radians(60.0), 0.01  # σ = 0.01 rad per tilt axis
    motion = NarrowbandMotion(np.array([0.0, sd, sd]) * math.sqrt(2.0), PERIOD, DAMPING)
    sc = Scenario(lat, motion=motion, sample_rate=10.0, duration=T, rocking_in_gyros=False)
    mc = alignment_monte_carlo(sc, method="analytic", n_trials=384, rng=int(T), options=AlignmentOptions(formula="paper"))
    truth = sd * sd * closed_form_mean_variance(1.0, PERIOD, DAMPING, T)
    aux, se = np.asarray(mc.result.aux_mean), np.asarray(mc.result.aux_std_error)
    for axis in (0, 1):  # β̂, γ̂
        assert abs(aux[axis] - truth) < Z * se[axis] + 2e-3 * truth, (axis, aux[axis], truth, se[axis])
    # first-order theory: the azimuth gain of the tilts times the closed-form standard deviation of the mean
    from strapdown.analysis.alignment.theory import analytic_gain_values

    G = analytic_gain_values(sc, "paper")
    assert mc.theory.rocking == pytest.approx(float(np.linalg.norm(G.G_tilt)) * math.sqrt(truth), rel=2e-3)
    lo, hi = mc.result.rms_ci  # a 95 % interval: widened to Z standard errors
    assert abs(mc.result.rms - mc.theory.rocking) < Z / 1.96 * (hi - lo) / 2


def test_align_at_the_admissible_amplitude_of_azimuth_design_meets_the_budget():
    """``azimuth-design`` (tilt channel, exact discrete-time autocovariance) and ``align`` (whole system) agree."""
    from strapdown.analysis.gyrocompass.admissible_rocking import admissible_amplitude

    lat, budget, T, f = math.radians(60.0), math.radians(0.1), 300.0, 0.125
    d = admissible_amplitude(budget, lat, T, [f], rocking="narrowband", damping=DAMPING, sample_rate=10.0)
    a = float(d.amplitude[0])
    sc = Scenario(lat, motion=NarrowbandMotion(np.array([0.0, a, a]), 1.0 / f, DAMPING), sample_rate=10.0, duration=T, rocking_in_gyros=False)
    mc = alignment_monte_carlo(sc, method="analytic", n_trials=1024, rng=3, options=AlignmentOptions(formula="paper"))
    lo, hi = mc.result.rms_ci
    assert lo < budget < hi, (math.degrees(lo), math.degrees(hi))
    assert mc.theory.rocking == pytest.approx(budget, rel=3e-3)  # first order against the second-order root: the curvature is small here


@pytest.mark.parametrize("pattern", [(0.0, 1.0, 1.0), (1.0, 0.0, 0.5), (0.0, 0.0, 2.0)])
def test_rescaled_draw_skips_only_the_axes_of_zero_amplitude(pattern):
    """A rescaled Gaussian draw with some axes at zero amplitude transforms only the others: the same numbers on
    those axes, to the bit, as the draw at full amplitude, and zero on the removed ones."""
    unit = NarrowbandMotion(np.ones(3), 8.0, 0.1)
    draw = unit.draw(np.random.default_rng(4), 5, 300, 0.1)
    scaled = draw.rescaled(NarrowbandMotion(np.array(pattern), 8.0, 0.1))
    full = unit.draw(np.random.default_rng(4), 5, 300, 0.1)  # the same coefficients, its own kept evaluations
    keep = [a for a in range(3) if pattern[a]]
    for offset in (0.0, 0.05):
        parts, scale = scaled.unit_evaluation(300, offset, derivatives=2)
        whole, ones = full.unit_evaluation(300, offset, derivatives=2)
        assert np.array_equal(scale, pattern) and np.array_equal(ones, np.ones(3))
        for p, w in zip(parts, whole):
            assert np.array_equal(p[:, :, keep], w[:, :, keep])
            assert not np.any(np.delete(p, keep, axis=2))
        angles = scaled.evaluate(300, offset, derivatives=0)[0]
        assert np.array_equal(angles[:, :, keep], (np.asarray(pattern) * whole[0])[:, :, keep])


@pytest.mark.parametrize("lines", [1, 3], ids=["sine", "multi-sine"])
def test_compiled_sum_of_sinusoids_is_the_numpy_sum(lines):
    """The sum of sinusoids of the sine rockings in one compiled pass: the numpy form's products and sums, to the last bit."""
    from strapdown.analysis.alignment.base_motion import MultiSineMotion, SineMotion

    a = np.radians([0.2, 1.0, 2.0])
    model = SineMotion(a, 7.0) if lines == 1 else MultiSineMotion(np.outer([1.0, 0.5, 0.3], a), (7.0, 3.0, 11.0))
    r = model.draw(np.random.default_rng(5), 4, 301, 0.1)
    c = r.coefficients * (1j * r.spectrum.omega) ** 2
    for t in (0.03 + 0.1 * np.arange(300), np.array([0.0, 30.0])):
        assert np.array_equal(r._sinusoids(c, t, compiled=True), r._sinusoids(c, t, compiled=False))
