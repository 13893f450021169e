"""``strapdown log environment``: the vibration environment estimated from a log.

The truth of the synthetic logs is built apart from the estimator: exact increments of a
classical cone (closed form) and of a Gaussian coning band drawn on the record's own
frequency grid (``log_synthetic``).  The Welch estimate is checked against
``scipy.signal.csd``, the intervals by their coverage, the line test by logs of pure band
noise in which it must find nothing.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from log_synthetic import cone, coning_band

from strapdown.analysis import cli
from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H
from strapdown.analysis.logs.cross_spectra import welch_cross_spectra
from strapdown.analysis.logs.environment_estimate import estimate_environment, write_environment
from strapdown.analysis.logs.imu_log import ImuLog
from strapdown.analysis.logs.native import write_log
from strapdown.analysis.vibration.drift import environment_drift
from strapdown.analysis.vibration.environment import Environment, Spectrum, coning_line, load_environment
from strapdown.derivations.coning.registry import get

H = 1e-3
BAND = (40.0, 150.0)
DENSITY = 5e-6  # (rad/s)²/Hz: the band's two-sample drift is about that of the 1° line at 10 Hz


def _band_spectrum(f1, f2, density):
    """The band of :func:`_line_and_band`: x and y fully coherent, y a quarter period ahead of x (coning about −z): ``G_xy = +i G``."""
    f = np.linspace(f1, f2, 64)
    g = np.zeros((f.size, 6, 6), complex)
    g[:, 0, 0] = g[:, 1, 1] = density
    g[:, 0, 1], g[:, 1, 0] = 1j * density, -1j * density
    return Spectrum(f, g, "true band")


def _line_and_band(n=60_000, seed=0, line=True):
    """A 1° cone at 10 Hz and a coning band, both about −z of the body (y a quarter period ahead of x), white sensor noise."""
    rng = np.random.default_rng(seed)
    p = cone().grid_increments(H, 0, n) if line else np.zeros((n, 3))
    bx, by = coning_band(n, H, *BAND, DENSITY, rng)  # y behind x: coning about +z; reversed below
    p[:, 0] += bx
    p[:, 1] -= by
    p += 1e-4 * math.sqrt(H) * rng.standard_normal((n, 3))
    dv = 0.01 * math.sqrt(H) * rng.standard_normal((n, 3)) + np.array([0.0, 0.0, -9.80665 * H])
    lines = (coning_line(10.0, math.radians(1.0), axis=(0.0, 0.0, -1.0)),) if line else ()
    return ImuLog(H * np.arange(1, n + 1), p, dv), Environment(lines, (_band_spectrum(*BAND, DENSITY),), name="truth")


def _run(argv, capsys):
    code = cli.main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_the_estimate_feeds_environment_drift_within_5_percent(tmp_path, capsys):
    """A 1° line at 10 Hz plus a band: environment-drift on the estimated file gives the true environment's two-sample drift within 5 %.

    The band makes half the drift; its estimate scatters by about 2.5 % from one record to
    the next (the Gaussian realisation and the Welch estimate), the line's by 10⁻⁵, so the
    total scatters by about 1.3 % (0.2 % to 1.3 % over five seeds): 5 % is four of those.
    """
    log, truth = _line_and_band()
    write_log(tmp_path / "log.npz", log)
    env_file = tmp_path / "env.toml"
    code, out, err = _run(["log", "environment", str(tmp_path / "log.npz"), "--out", str(env_file), "--json", "--quiet"], capsys)
    assert code == 0, err
    data = json.loads(out)
    assert data["nyquist_hz"] == pytest.approx(500.0)
    assert len(data["lines"]) == 1 and data["lines"][0]["frequency_hz"] == pytest.approx(10.0, abs=1e-4)
    code, out, err = _run(["environment-drift", "--algorithm", "two-sample", "--environment", str(env_file), "--sample-interval", str(H), "--json"], capsys)
    assert code == 0, err
    estimated = np.array(json.loads(out)["total_drift_vector_rad_s"])
    true = environment_drift(get("two-sample"), truth, H)
    assert np.linalg.norm(estimated - true.total_vector) < 0.05 * np.linalg.norm(true.total_vector), (estimated, true.total_vector)
    # both parts count: the band's drift is a sizeable share of the total, in the same sense as the line's
    share = [p.total @ true.coning_axis for p in true.parts]
    assert 0.3 < share[1] / share[0] < 3.0
    assert np.linalg.norm(true.total_vector) * RAD_PER_S_TO_DEG_PER_H > 1e-4


def test_the_line_amplitude_and_relative_phases_hold_their_intervals():
    log, truth = _line_and_band(seed=1)
    e = estimate_environment(log)
    (ln,) = e.lines
    want = truth.lines[0].amplitude * np.exp(-1j * np.angle(truth.lines[0].amplitude[ln.reference]))
    lo, hi = ln.interval(0.95)
    for c in (0, 1):
        assert lo[c] <= abs(want[c]) <= hi[c]
        assert abs(np.angle(ln.amplitude[c] / want[c])) < 4 * ln.sigma[c] / abs(want[c])
    assert list(ln.significant) == [True, True, False, False, False, False]
    # x leads y by a quarter period: the cone of the log turns about −z
    assert np.angle(ln.amplitude[1] / ln.amplitude[0]) == pytest.approx(math.pi / 2, abs=1e-4)


@pytest.mark.parametrize("seed", range(4))
def test_no_line_is_found_in_pure_band_noise(seed):
    """A broad coning band, white noise and a narrow resonance (Q = 30): random, so no line (false-alarm probability 10⁻³)."""
    from scipy.signal import iirpeak, lfilter

    log, _ = _line_and_band(seed=100 + seed, line=False)
    rng = np.random.default_rng(200 + seed)
    b, a = iirpeak(75.0, 30.0, fs=1.0 / H)
    p = log.dtheta.copy()
    p[:, 2] += 1e-3 * lfilter(b, a, rng.standard_normal(log.n_samples))
    e = estimate_environment(ImuLog(log.time, p, log.dv))
    assert e.lines == ()
    assert e.search.candidates >= 1  # the band's peaks were looked at, and refused


def test_a_weak_line_in_the_band_is_found():
    """A line of 0.02 deg/s in the band at 97.3 Hz: its block amplitudes agree, the band's do not."""
    log, _ = _line_and_band(seed=7, line=False)
    t = log.time
    w = 2 * math.pi * 97.3
    amp = math.radians(0.02)
    p = log.dtheta.copy()
    p[:, 2] += amp * (np.sin(w * t) - np.sin(w * (t - H))) / w  # exact increments of amp·cos(wt) on z
    e = estimate_environment(ImuLog(t, p, log.dv))
    assert [round(ln.frequency, 2) for ln in e.lines] == [97.3]
    lo, hi = e.lines[0].interval(0.95)
    assert lo[2] <= amp <= hi[2]


def test_a_line_above_the_nyquist_frequency_is_seen_at_its_alias():
    """What the log cannot see: a 700 Hz line sampled at 1 kHz is found at 300 Hz."""
    n = 20_000
    t = H * np.arange(1, n + 1)
    w = 2 * math.pi * 700.0
    p = np.zeros((n, 3))
    p[:, 0] = 0.1 * (np.sin(w * t) - np.sin(w * (t - H))) / w
    p += 1e-5 * np.random.default_rng(0).standard_normal((n, 3))
    e = estimate_environment(ImuLog(t, p, np.tile([0.0, 0.0, -9.80665 * H], (n, 1))))
    assert [round(ln.frequency, 3) for ln in e.lines] == [300.0]
    assert e.nyquist == pytest.approx(500.0)


def test_welch_is_scipy_csd():
    from scipy.signal import csd

    rng = np.random.default_rng(1)
    x = rng.standard_normal((30_000, 3))
    x[:, 1] += 0.5 * np.roll(x[:, 0], 3)
    s = welch_cross_spectra([x[:10_000], x[10_000:]], H, 256, block=5)
    for a in range(3):
        for b in range(3):
            g = sum(csd(part[:, a], part[:, b], fs=1.0 / H, nperseg=256)[1] * k for part, k in ((x[:10_000], 77), (x[10_000:], 155))) / 232
            np.testing.assert_allclose(s.density[:, a, b], g, rtol=1e-12, atol=1e-14 * np.abs(g).max())
    assert s.segments == 232


def test_the_intervals_cover():
    """White noise of known density: about 95 % of the auto-spectrum intervals and of the quadrature intervals hold the truth.

    Eight records of 255 bins each; the coverage of one record scatters by about 1.4 %, that
    of the eight by 0.5 %: the bounds are four of those from 95 %.
    """
    auto, quad = [], []
    for seed in range(8):
        x = np.random.default_rng(seed).standard_normal((200_000, 2))
        s = welch_cross_spectra(x, H, 512)
        lo, hi = s.auto_factors(0.95)
        g = s.density[1:-1, 0, 0].real
        auto.append(np.mean((g * lo <= 2 * H) & (2 * H <= g * hi)))
        _, sq = s.part_sigmas()
        quad.append(np.mean(np.abs(s.density[1:-1, 0, 1].imag) <= 1.96 * sq[1:-1, 0, 1]))
    assert 0.93 < np.mean(auto) < 0.97, auto
    assert 0.93 < np.mean(quad) < 0.97, quad


def test_the_file_says_the_filters_are_in_the_samples(tmp_path):
    log, _ = _line_and_band(n=20_000)
    e = estimate_environment(log)
    path = write_environment(tmp_path / "env.toml", e)
    text = path.read_text()
    assert 'filter = "none"' in text and "decimation = 1" in text and "Nyquist" in text
    env = load_environment(path)
    assert env.gyro.response(np.array([2 * math.pi * 100.0]), H) == pytest.approx(env.gyro.response(np.array([2 * math.pi * 100.0]), H))
    np.testing.assert_array_equal(env.spectra[0].density, e.environment.spectra[0].density)  # every digit written
    assert env.lines[0].frequency == e.lines[0].frequency


def test_a_failed_write_leaves_nothing(tmp_path, monkeypatch):
    import strapdown.analysis.logs.environment_estimate as module

    log, _ = _line_and_band(n=20_000)
    e = estimate_environment(log)
    target = tmp_path / "env.toml"
    target.write_text("previous")

    def refuse(path):
        raise ValueError("refused")

    monkeypatch.setattr(module, "load_environment", refuse)
    with pytest.raises(ValueError, match="refused"):
        write_environment(target, e)
    assert target.read_text() == "previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["env.toml"]


def test_the_figure_is_drawn(tmp_path, capsys):
    log, _ = _line_and_band(n=20_000)
    write_log(tmp_path / "log.npz", log)
    code, _, err = _run(["log", "environment", str(tmp_path / "log.npz"), "--out", str(tmp_path / "e.toml"), "--figure", str(tmp_path / "e.png"), "--quiet"], capsys)
    assert code == 0, err
    assert (tmp_path / "e.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_long_table_is_merged_within_its_rows(tmp_path):
    log, _ = _line_and_band(n=20_000)
    e = estimate_environment(log, resolution=0.25, max_rows=100)
    assert e.frequency.size <= 100 and e.merged > 1
    assert e.dof > 1.5 * estimate_environment(log, resolution=0.25).dof
    load_environment(write_environment(tmp_path / "e.toml", e))
