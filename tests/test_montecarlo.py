"""Monte Carlo engine and sweep: reproducibility across chunking, workers and dask."""

import math
import os
import re
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from strapdown.analysis.core import montecarlo
from strapdown.analysis.gyrocompass.azimuth import AzimuthErrorKernel, azimuth_monte_carlo
from strapdown.analysis.gyrocompass.bound_sweep import SweepCase, sweep
from strapdown.analysis.gyrocompass.rocking import GaussianRocking, NarrowbandRocking


def _normal_kernel(n, rng):
    return rng.standard_normal((n, 50))


def _same(a, b):
    assert (a.mean, a.mse, a.rms_ci, a.mean_ci, a.minimum, a.maximum) == (b.mean, b.mse, b.rms_ci, b.mean_ci, b.minimum, b.maximum)
    np.testing.assert_array_equal(a.histogram[1], b.histogram[1])
    assert list(a.quantiles.values()) == list(b.quantiles.values())
    assert list(a.quantile_intervals.values()) == list(b.quantile_intervals.values())


def test_block_seed_is_spawn():
    root = np.random.SeedSequence(123)
    kids = np.random.SeedSequence(123).spawn(5)
    for i, k in enumerate(kids):
        assert montecarlo.block_seed(root, i).generate_state(4).tolist() == k.generate_state(4).tolist()


def test_independent_of_chunking_and_workers():
    kernel = AzimuthErrorKernel(math.radians(70), 0.01, -0.02, NarrowbandRocking(0.02, 0.03, 6.0, 0.2), n_steps=64, dt=0.1)
    serial = montecarlo.run(kernel, 300, rng=42, trials_per_block=16, blocks_per_chunk=1)
    _same(serial, montecarlo.run(kernel, 300, rng=42, trials_per_block=16, blocks_per_chunk=7))
    with ProcessPoolExecutor(2) as ex:
        _same(serial, montecarlo.run(kernel, 300, rng=42, trials_per_block=16, blocks_per_chunk=3, executor=ex))


def test_generator_and_seed_sequence_inputs():
    a = montecarlo.run(_normal_kernel, 20, rng=np.random.SeedSequence(5), trials_per_block=4)
    b = montecarlo.run(_normal_kernel, 20, rng=5, trials_per_block=4)
    _same(a, b)
    c = montecarlo.run(_normal_kernel, 20, rng=np.random.default_rng(5), trials_per_block=4)
    d = montecarlo.run(_normal_kernel, 20, rng=np.random.default_rng(5), trials_per_block=4)
    _same(c, d)


def test_statistics_of_a_standard_normal():
    r = montecarlo.run(_normal_kernel, 4000, rng=1, trials_per_block=100, scale=1.0)
    assert r.n_samples == 200_000
    assert r.rms_ci[0] < 1.0 < r.rms_ci[1]
    assert r.mean_ci[0] < 0.0 < r.mean_ci[1]
    # order statistics of 200 000 samples against the normal quantiles (SE of a quantile ≈ 0.003-0.006);
    # the samples of a trial are independent here too, so the trial-clustered interval should cover
    for level, q in r.quantiles.items():
        lo, hi = r.quantile_intervals[level]
        assert q == pytest.approx(stats.norm.ppf(level), abs=0.03)
        assert lo <= q <= hi and hi - lo < 0.08
    covered = [lo <= stats.norm.ppf(level) <= hi for level, (lo, hi) in r.quantile_intervals.items()]
    assert sum(covered) >= len(covered) - 1  # nine 95 % intervals: one miss is within chance (p ≈ 0.07)


def test_identical_trials_have_their_common_value_as_every_quantile():
    r = montecarlo.run(lambda n, g: np.full((n, 1), 0.125), 10, rng=1, trials_per_block=3)
    assert set(r.quantiles.values()) == {0.125}
    for lo, hi in r.quantile_intervals.values():
        assert lo == 0.125 or math.isnan(lo)
        assert hi == 0.125 or math.isnan(hi)
    assert math.isnan(r.quantile_intervals[0.995][1])  # ten trials do not reach the upper end of that interval


def test_quantiles_are_order_statistics_with_binomial_intervals():
    from strapdown.analysis.core.quantiles import sample_quantiles

    x = np.arange(1.0, 101.0)[::-1]  # 100 independent trials, values 1 … 100
    (median, tail) = sample_quantiles(x[:, None], [0.5, 0.95])
    assert median.value == 50.0 and tail.value == 95.0  # x_(⌈pM⌉)
    # ranks of the distribution-free 95 % interval: P(l ≤ B < u) ≥ 0.95, B ~ Bin(100, p)
    assert stats.binom.cdf(median.high - 1, 100, 0.5) - stats.binom.cdf(median.low - 1, 100, 0.5) >= 0.95
    assert (median.low, median.high) == (40.0, 61.0)
    # coverage of the interval of the median of a skewed law, 2000 repetitions of 31 trials
    g = np.random.default_rng(8)
    truth = stats.expon.ppf(0.5)
    hits = sum(q.low <= truth <= q.high for q in (sample_quantiles(g.exponential(size=(31, 1)), [0.5])[0] for _ in range(2000)))
    assert 0.95 - 3.5 * math.sqrt(0.05 * 0.95 / 2000) <= hits / 2000


def test_bad_quantile_inputs():
    from strapdown.analysis.core.quantiles import sample_quantiles

    with pytest.raises(ValueError, match="errors"):
        sample_quantiles(np.zeros((0, 1)), [0.5])
    with pytest.raises(ValueError, match="finite"):
        sample_quantiles(np.array([[np.nan]]), [0.5])
    with pytest.raises(ValueError, match="levels"):
        sample_quantiles(np.zeros((3, 1)), [1.0])
    with pytest.raises(ValueError, match="levels"):
        montecarlo.run(_normal_kernel, 4, rng=1, quantiles=(0.0,))


def test_ci_width_matches_standard_error():
    r = montecarlo.run(_normal_kernel, 1000, rng=2, trials_per_block=50)
    # per-trial mean square of 50 N(0,1) samples has variance 2/50
    se = math.sqrt(2 / 50 / 1000)
    assert r.mse_std_error == pytest.approx(se, rel=0.1)


def test_bad_sizes():
    with pytest.raises(ValueError, match="n_trials"):
        montecarlo.run(_normal_kernel, 1, rng=1)
    with pytest.raises(ValueError, match="n_samples"):
        azimuth_monte_carlo(0.5, 0.0, 0.0, GaussianRocking(0.01, 0.01), 1)


def _cases():
    r = math.radians
    return [
        SweepCase(r(30.0), r(0.5), "normal"),
        SweepCase(r(75.0), r(4.0), "sine", beta0=r(2.0), gamma0=r(-1.0)),
        SweepCase(r(60.0), r(1.0), "narrowband", estimate="sample-mean", averaging_time=5.0, period=4.0, damping=0.2),
    ]


def test_sweep_serial_equals_process_pool():
    serial = sweep(_cases(), n_samples=20_000, rng=9)
    with ProcessPoolExecutor(2) as ex:
        assert sweep(_cases(), n_samples=20_000, rng=9, executor=ex) == serial


def test_sweep_on_dask_local_cluster_is_bit_identical(monkeypatch):
    distributed = pytest.importorskip("distributed")
    root = str(Path(__file__).resolve().parents[1])
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([root, os.environ.get("PYTHONPATH", "")]))
    serial = sweep(_cases(), n_samples=20_000, rng=9)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, processes=True) as cluster, distributed.Client(cluster) as client:
        remote = sweep(_cases(), n_samples=20_000, rng=9, executor=client)
        mc_remote = montecarlo.run(_normal_kernel, 64, rng=3, trials_per_block=8, blocks_per_chunk=2, executor=client)
    assert remote == serial
    _same(mc_remote, montecarlo.run(_normal_kernel, 64, rng=3, trials_per_block=8))


def test_components_match_direct_trigonometry_over_all_angles():
    """The hot path takes cos from sin (√(1 − sin²)); beyond ±π/2 it must fall back to cos."""
    import math

    from strapdown.analysis.gyrocompass.azimuth import tilt_components

    rng = np.random.default_rng(7)
    beta = rng.uniform(-3.0, 3.0, 10_000)
    gamma = rng.uniform(-3.0, 3.0, 10_000)
    sphi, cphi = math.sin(0.7), math.cos(0.7)
    A, B = tilt_components(beta, gamma, sphi, cphi)
    np.testing.assert_allclose(A, cphi * np.cos(gamma) + sphi * np.cos(beta) * np.sin(gamma), rtol=0, atol=2e-15)
    np.testing.assert_allclose(B, sphi * np.sin(beta), rtol=0, atol=1e-15)


def test_vectorised_binomial_ranks_agree_with_the_scalar_law():
    from strapdown.analysis.core.quantiles import _binomial_rank_table

    levels = montecarlo.QUANTILES
    for m in (1, 2, 7, 31, 100, 4096, 200_001, 4_000_000):
        table = _binomial_rank_table(m, levels)
        scalar = [(int(stats.binom.ppf(0.025, m, p)), int(stats.binom.ppf(0.975, m, p)) + 1) for p in levels]
        assert table == scalar


def test_one_partial_sort_gives_the_order_statistics_of_a_full_sort():
    from strapdown.analysis.core.quantiles import sample_quantiles

    x = np.random.default_rng(3).standard_normal(5001)
    s = np.sort(x)
    for q in sample_quantiles(x[:, None], montecarlo.QUANTILES):
        lo, hi = (int(r) for r in (stats.binom.ppf(0.025, x.size, q.level), stats.binom.ppf(0.975, x.size, q.level) + 1))
        assert q.value == s[math.ceil(q.level * x.size - 1e-12) - 1]
        assert q.low == (s[lo - 1] if lo >= 1 else q.low) and q.high == (s[hi - 1] if hi <= x.size else q.high)
    assert sample_quantiles(x[:, None], ()) == ()


def test_cos_from_sin_equals_the_masked_computation_bit_for_bit():
    """The wide-tilt test by two reductions gives the cosines of the masked test, NaN and wide tilts included."""
    from strapdown.analysis.gyrocompass.azimuth import _QUARTER_PI, _cos_from_sin

    def masked(angle, sine):  # the computation before the reductions decided the common case
        c = np.sqrt(1.0 - sine * sine)
        wide = np.abs(angle) > _QUARTER_PI
        if wide.any():
            c[wide] = np.cos(angle[wide])
        return c

    rng = np.random.default_rng(7)
    narrow = rng.uniform(-0.7, 0.7, (64, 33))
    wide = rng.uniform(-1.5, 1.5, (64, 33))
    with_nan = wide.copy()
    with_nan[3, 4] = np.nan
    only_nan = np.full(5, np.nan)
    edge = np.array([-_QUARTER_PI, _QUARTER_PI, np.nextafter(_QUARTER_PI, 1.0), 0.0])
    for angle in (narrow, wide, with_nan, only_nan, edge, np.empty(0)):
        got, want = _cos_from_sin(angle, np.sin(angle)), masked(angle, np.sin(angle))
        np.testing.assert_array_equal(got, want)


def test_histogram_scaled_in_place_equals_the_previous_counts():
    """summarise's histogram (binned in place, in passes over a long run) has the counts of the one-pass expression."""
    rng = np.random.default_rng(3)
    errors = rng.standard_normal((3 * 1024 + 5, 64)) * 0.3  # three passes and a part
    errors[0, :3] = (-1e9, 1e9, 0.0)  # underflow, overflow
    errors[1024, :2] = (-1e9, 1e9)  # at the start of the second pass
    scale, half_width, n_bins = 0.1, 20.0, 8000
    result = montecarlo.summarise([(errors[:20], None), (errors[20:], None)], scale=scale, half_width=half_width, n_bins=n_bins, quantiles=())
    u = errors.ravel() * (n_bins / (2.0 * half_width * scale)) + (n_bins / 2.0 + 1.0)
    counts = np.bincount(np.clip(u, 0.0, n_bins + 1.0).astype(np.int64), minlength=n_bins + 2)[: n_bins + 2]
    edges, inner, under, over = result.histogram
    np.testing.assert_array_equal(inner, counts[1:-1])
    assert (under, over) == (int(counts[0]), int(counts[-1]))


def test_solve_adds_the_tiny_ridge_on_the_diagonal_only():
    """The ridge by stride is the ridge of diag_indices_from: the same solution bit for bit."""
    rng = np.random.default_rng(5)
    a = rng.standard_normal((50, 4))
    a[:, 2] = 0.0  # a control without spread
    gram, rhs = a.T @ a, a.T @ rng.standard_normal((50, 2))
    ridged = gram.copy()
    ridged[np.diag_indices_from(ridged)] += 1e-300
    np.testing.assert_array_equal(montecarlo._solve(gram, rhs), np.linalg.solve(ridged, rhs))


def test_silent_serial_map_tasks_runs_every_task_in_order():
    calls = []

    def task(i):
        return lambda: calls.append(i) or i * i

    assert montecarlo.map_tasks(None, [task(i) for i in range(5)]) == [0, 1, 4, 9, 16]
    assert calls == [0, 1, 2, 3, 4]
    assert montecarlo.map_tasks(None, [task(i) for i in range(3)], progress=True) == [0, 1, 4]


@pytest.mark.parametrize(
    ("quantiles", "error", "words"),
    [
        (0.5, TypeError, "sequence of levels"),
        (None, TypeError, "sequence of levels"),
        ("0.5", TypeError, "sequence of levels"),
        ((float("nan"),), ValueError, "finite"),
        ((0.5, 1.5), ValueError, "levels in (0, 1), got 1.5"),
    ],
)
def test_quantile_levels_are_refused_naming_the_argument(quantiles, error, words):
    with pytest.raises(error, match=re.escape(words)) as run_error:
        montecarlo.run(_normal_kernel, 4, rng=1, quantiles=quantiles)
    assert "`quantiles`" in str(run_error.value)
    with pytest.raises(error, match=re.escape(words)):
        azimuth_monte_carlo(0.8, 0.01, 0.01, GaussianRocking(0.01, 0.01), 4096, rng=0, quantiles=quantiles)
    assert montecarlo.run(_normal_kernel, 4, rng=1, quantiles=[]).quantiles == {}  # none asked: none computed
