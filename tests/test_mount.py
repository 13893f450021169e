"""Linear vibration profiles, the six-degree-of-freedom IMU mount and its checks.

The truths are built another way than the library's: power laws integrated by
``scipy.integrate.quad``, natural frequencies and transmissibilities of a
decoupled mount in closed form, and a DOP853 simulation of the rigid block
under random base motion (``strapdown.analysis.vibration.mount_simulation``:
isolator forces from the motion of their attachment points, no transfer
matrix) against which the closed-form cross-spectra and the coning drift are
compared inside intervals from independent realisations.  Every verdict is
shown to say no on a wrong model.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from strapdown.analysis.core import budget
from strapdown.analysis.core.units import DEG, STANDARD_GRAVITY
from strapdown.analysis.vibration.drift import environment_drift
from strapdown.analysis.vibration.environment import load_environment
from strapdown.analysis.vibration.examples import AIRFRAME_PROFILE, ISOLATED_MOUNT
from strapdown.analysis.vibration.mount import Isolator, Mount, load_mount
from strapdown.analysis.vibration.mount_response import environment_toml, mount_drift, mount_environment, output_density, restrict
from strapdown.analysis.vibration.mount_simulation import expected_welch, simulate_mount, simulated_drift, welch_cross_spectra
from strapdown.analysis.vibration.profile import DB_PER_OCTAVE, BaseExcitation, Profile, load_profile, profile_from_breakpoints
from strapdown.derivations.coning.registry import get

G0 = STANDARD_GRAVITY


# --------------------------------------------------------------------------- profiles
def test_a_profile_is_the_power_law_of_its_slopes_and_its_grms_the_integral():
    p = profile_from_breakpoints([20.0, 80.0, 350.0, 2000.0], [None, 0.04, 0.04, None], [None, 3.0, None, -6.0])
    # the level 20 Hz follows from +3 dB/octave over two octaves, the one at 2000 Hz from −6 dB/octave
    assert p.level[0] == pytest.approx(0.04 / 10 ** (3.0 * 2 / 10), rel=1e-12)
    assert p.level[-1] == pytest.approx(0.04 * 10 ** (-6.0 * math.log2(2000 / 350) / 10), rel=1e-12)
    assert p.slope_db_per_octave == pytest.approx([3.0, 0.0, -6.0], abs=1e-12)
    f = np.geomspace(20.0, 2000.0, 97)
    for a, b in zip(f[:-1], f[1:]):  # every step of dB per octave, between any two frequencies of a segment
        j = np.searchsorted(p.frequency, a, side="right") - 1
        if b <= p.frequency[j + 1]:
            assert 10 * math.log10(p.at(b) / p.at(a)) == pytest.approx(p.slope_db_per_octave[j] * math.log2(b / a), abs=1e-9)
    truth = sum(quad(p.at, a, b, epsrel=1e-13)[0] for a, b in zip(p.frequency[:-1], p.frequency[1:]))
    assert p.mean_square() == pytest.approx(truth, rel=1e-11)
    assert p.at([10.0, 2500.0]).tolist() == [0.0, 0.0]


def test_a_segment_of_minus_three_db_per_octave_integrates_as_a_logarithm():
    p = Profile([100.0, 1000.0], [1.0, 0.1])  # exactly f^−1: the series branch of the exact integral
    assert p.slope_db_per_octave[0] == pytest.approx(-DB_PER_OCTAVE, rel=1e-14)
    assert p.mean_square() == pytest.approx(100.0 * math.log(10.0), rel=1e-13)


def test_levels_resolve_backwards_and_bad_tables_are_refused_by_frequency():
    p = profile_from_breakpoints([15.0, 100.0], [None, 0.04], [None, 3.0])
    assert p.level[0] == pytest.approx(0.04 * 10 ** (-0.3 * math.log2(100 / 15)), rel=1e-12)
    with pytest.raises(ValueError, match="none for the breakpoint.*at 350 Hz"):
        profile_from_breakpoints([20.0, 80.0, 350.0], [0.01, 0.04, None], [None, None, None])
    with pytest.raises(ValueError, match="segment 20–80 Hz.*agree with its two levels"):
        profile_from_breakpoints([20.0, 80.0], [0.01, 0.04], [None, 6.0])
    with pytest.raises(ValueError, match="first breakpoint"):
        profile_from_breakpoints([20.0, 80.0], [0.01, None], [3.0, None])
    with pytest.raises(ValueError, match="`freq_hz`"):
        profile_from_breakpoints([80.0, 20.0], [0.01, 0.01])


def test_the_example_profile_file_reads_as_written(tmp_path):
    e = load_profile(AIRFRAME_PROFILE)
    assert e.linear[0] is e.linear[1] is e.linear[2]
    assert e.linear[0].level / G0**2 == pytest.approx([0.04 * 10 ** (-0.3 * math.log2(100 / 15)), 0.04, 0.04, 0.04 * 10**-0.6], rel=1e-12)
    assert e.angular[2].level[0] == pytest.approx(0.002 * DEG**2, rel=1e-12)
    bad = tmp_path / "bad.toml"
    for text, words in [
        ('[[linear]]\nunit = "g"\naxes = "xq"\nbreakpoints = [{freq_hz = 10.0, psd = 0.01}, {freq_hz = 20.0, psd = 0.01}]\n', "'axes'"),
        ('[[linear]]\nunit = "g2"\nbreakpoints = [{freq_hz = 10.0, psd = 0.01}, {freq_hz = 20.0, psd = 0.01}]\n', "'unit'"),
        ('[[linear]]\nunit = "g"\nbreakpoints = [{freq_hz = 10.0, psd = 0.01}, {freq_hz = 20.0, level = 0.01}]\n', "unknown key 'level'"),
        ('[[linear]]\nunit = "g"\nbreakpoints = [{freq_hz = 10.0, psd = 0.01}, {freq_hz = 20.0}]\n', "none for the breakpoint"),
        ('[[linear]]\nunit = "g"\naxes = "x"\nbreakpoints = [{freq_hz = 10.0, psd = 0.01}, {freq_hz = 20.0, psd = 0.01}]\n'
         '[[linear]]\nunit = "g"\naxes = "xy"\nbreakpoints = [{freq_hz = 10.0, psd = 0.01}, {freq_hz = 20.0, psd = 0.01}]\n', "already has a linear profile"),
        ("name = 'empty'\n", "no profile"),
    ]:  # fmt: skip
        bad.write_text(text, encoding="utf-8")
        with pytest.raises(ValueError, match=words) as info:
            load_profile(bad)
        assert str(info.value).startswith(str(bad))


# --------------------------------------------------------------------------- the mount
def _decoupled(k=(2e4, 3e4, 5e4), c=(10.0, 12.0, 20.0), mass=0.8, inertia=(2e-3, 3e-3, 4e-3), a=0.05, b=0.03):
    """Four equal isolators at (±a, ±b, 0), the centre of mass and the IMU at O: six uncoupled modes."""
    isolators = tuple(Isolator([sx * a, sy * b, 0.0], k, c) for sx in (1, -1) for sy in (1, -1))
    return Mount(mass, np.diag(inertia), isolators, gravity=[0.0, 0.0, 0.0])


def test_the_modes_of_a_decoupled_mount_are_the_textbook_frequencies():
    k, a, b, mass, inertia = (2e4, 3e4, 5e4), 0.05, 0.03, 0.8, (2e-3, 3e-3, 4e-3)
    mount = _decoupled(k=k, c=(0.0, 0.0, 0.0), mass=mass, inertia=inertia, a=a, b=b)
    expected = {
        "x": math.sqrt(4 * k[0] / mass), "y": math.sqrt(4 * k[1] / mass), "z": math.sqrt(4 * k[2] / mass),
        "rx": math.sqrt(4 * k[2] * b**2 / inertia[0]), "ry": math.sqrt(4 * k[2] * a**2 / inertia[1]),
        "rz": math.sqrt(4 * (k[0] * b**2 + k[1] * a**2) / inertia[2]),
    }  # fmt: skip
    modes = mount.modes()
    assert len(modes) == 6
    for md in modes:
        (name,) = [n for n, share in zip(("x", "y", "z", "rx", "ry", "rz"), md.energy) if share > 0.999]
        assert md.frequency * 2 * math.pi == pytest.approx(expected[name], rel=1e-10)
        assert md.damping_ratio == pytest.approx(0.0, abs=1e-12)


def test_the_transfer_of_a_decoupled_mount_is_the_single_degree_transmissibility():
    mount = _decoupled()
    f = np.array([5.0, 40.0, 63.0, 300.0])
    w = 2 * math.pi * f
    h = mount.transfer(f)
    kz, cz = 4 * 5e4, 4 * 20.0
    assert h[:, 5, 5] == pytest.approx((kz + 1j * w * cz) / (kz + 1j * w * cz - w**2 * 0.8), rel=1e-10)
    krx, crx = 4 * 5e4 * 0.03**2, 4 * 20.0 * 0.03**2
    assert h[:, 0, 0] == pytest.approx((krx + 1j * w * crx) / (krx + 1j * w * crx - w**2 * 2e-3), rel=1e-10)
    off = h.copy()
    off[:, range(6), range(6)] = 0.0
    assert np.max(np.abs(off)) < 1e-12  # no coupling: no lever arm, no gravity


def test_the_convention_of_the_output_density_is_the_environments():
    # one base channel into one IMU channel: G_out = |H|² G_in, and a coherent pair keeps conj(Z_a) Z_b
    mount = _decoupled()
    lin = profile_from_breakpoints([10.0, 200.0], [1.0, 1.0])
    g = output_density(mount, BaseExcitation(linear=(None, None, lin)), [50.0])[0]
    h = mount.transfer(50.0)[5, 5]
    assert g[5, 5].real == pytest.approx(abs(h) ** 2, rel=1e-12)
    assert np.count_nonzero(np.abs(g) > 1e-12) == 1


def test_a_mount_that_does_not_hold_the_block_is_refused():
    iso = [Isolator([x, 0.0, 0.0], [1e4, 1e4, 1e4]) for x in (-0.05, 0.05)]  # on one line: rolling about it is free
    with pytest.raises(ValueError, match="all six directions"):
        Mount(1.0, np.diag([1e-3] * 3), iso)
    with pytest.raises(ValueError, match="rigid body"):
        Mount(1.0, np.diag([1e-3, 1e-3, 3e-3]), (Isolator([0.0, 0.0, 0.0], [1e4] * 3),))


def test_the_example_mount_file_reads_and_bad_files_name_the_key(tmp_path):
    mount = load_mount(ISOLATED_MOUNT)
    assert len(mount.isolators) == 4 and mount.mass == 1.0
    assert mount.inertia[0, 1] == 1e-4
    bad = tmp_path / "bad.toml"
    good_isolator = "[[isolator]]\nposition_m = [0.0, 0.0, 0.0]\nstiffness_n_m = [1e4, 1e4, 1e4]\n"
    for text, words in [
        ("inertia_kg_m2 = [1e-3, 1e-3, 1e-3]\n" + good_isolator, "missing key 'mass_kg'"),
        ("mass_kg = -1.0\ninertia_kg_m2 = [1e-3, 1e-3, 1e-3]\n" + good_isolator, "'mass_kg'"),
        ("mass_kg = 1.0\ninertia_kg_m2 = [1e-3, 1e-3, 1e-3]\n", "no isolator"),
        ("mass_kg = 1.0\ninertia_kg_m2 = [1e-3, 1e-3, 1e-3]\n[[isolator]]\nposition_m = [0.0, 0.0]\nstiffness_n_m = [1e4, 1e4, 1e4]\n", "'position_m'"),
        ("mass_kg = 1.0\ninertia_kg_m2 = [1e-3, 1e-3, 1e-3]\n[[isolator]]\nposition_m = [0.0, 0.0, 0.0]\nstiffness_n_m = [1e4, -1.0, 1e4]\n", "'stiffness_n_m'"),
        ("mass_kg = 1.0\ninertia_kg_m2 = [1e-3, 1e-3, 1e-3]\nspring = 3\n" + good_isolator, "unknown key 'spring'"),
    ]:
        bad.write_text(text, encoding="utf-8")
        with pytest.raises(ValueError, match=words) as info:
            load_mount(bad)
        assert str(info.value).startswith(str(bad))


# --------------------------------------------------------------------------- the environment
@pytest.fixture(scope="module")
def example():
    return load_mount(ISOLATED_MOUNT), load_profile(AIRFRAME_PROFILE)


def test_the_table_reproduces_the_exact_density_and_the_drift_converges(example):
    mount, excitation = example
    r = mount_environment(mount, excitation)
    assert r.converged and r.table_error <= 1e-3
    (s,) = r.environment.spectra
    u = np.log(s.frequency)
    mid = np.exp(np.concatenate([u[:-1] + 0.3 * np.diff(u), u[:-1] + 0.7 * np.diff(u)]))  # not the midpoints the refinement saw
    exact, table = output_density(mount, excitation, mid), s.at(mid)
    auto = np.real(np.diagonal(exact, axis1=1, axis2=2))
    peak = auto.max(axis=0)
    scale = np.sqrt((auto + 1e-6 * peak)[:, :, None] * (auto + 1e-6 * peak)[:, None, :])
    assert np.max(np.abs(table - exact) / scale) < 3e-3
    algorithms = [get("one-sample"), get("two-sample")]
    coarse, fine = mount_drift(algorithms, r, 1e-3), mount_drift(algorithms, mount_environment(mount, excitation, tolerance=1e-4), 1e-3)
    for a, b in zip(coarse.total_coning, fine.total_coning):
        assert np.linalg.norm(a - b) < 2e-3 * np.linalg.norm(b)


def test_the_mount_environment_is_an_environment_that_environment_drift_takes(example, tmp_path):
    mount, excitation = example
    r = mount_environment(mount, excitation)
    algorithms = [get(n) for n in ("two-sample", "optimal-3")]
    d = mount_drift(algorithms, r, 1e-3)
    for a, total, scull in zip(algorithms, d.total_coning, d.total_sculling):
        ref = environment_drift(a, r.environment, 1e-3)
        assert total == pytest.approx(ref.total_vector, rel=1e-6, abs=1e-9 * np.linalg.norm(ref.total_vector))
        assert scull == pytest.approx(ref.sculling_vector, rel=1e-6, abs=1e-9 * np.linalg.norm(ref.sculling_vector))
    assert [b.modes for b in d.bands] and sum(len(b.modes) for b in d.bands) == len(r.modes)
    path = tmp_path / "env.toml"
    path.write_text(environment_toml(r.environment), encoding="utf-8")
    back = load_environment(path)
    assert np.array_equal(back.spectra[0].frequency, r.environment.spectra[0].frequency)
    assert np.array_equal(back.spectra[0].density, r.environment.spectra[0].density)


def test_profiles_of_different_bands_split_the_table_where_the_density_jumps():
    mount = _decoupled()
    lin = profile_from_breakpoints([10.0, 300.0], [1.0, 1.0])
    ang = profile_from_breakpoints([40.0, 100.0], [1e-4, 1e-4], kind="angular")
    r = mount_environment(mount, BaseExcitation((ang, None, None), (lin, lin, lin)))
    assert [s.band for s in r.environment.spectra] == [(10.0, 40.0), (40.0, 100.0), (100.0, 300.0)]
    assert r.environment.spectra[0].at([30.0])[0, 0, 0] == 0.0 and r.environment.spectra[1].at([60.0])[0, 0, 0] > 0
    part = restrict(r.environment.spectra[2], 150.0, 200.0)
    f = np.geomspace(150.0, 200.0, 7)
    assert np.allclose(part.at(f), r.environment.spectra[2].at(f), rtol=1e-12, atol=0)


# --------------------------------------------------------------------------- the time-domain checks
#: A base excitation on all six channels up to 150 Hz: linear 0.02–0.04 g²/Hz, angular 0.02 (deg/s)²/Hz.
CHECK_EXCITATION = BaseExcitation(
    tuple([profile_from_breakpoints([10.0, 150.0], [0.02 * DEG**2] * 2, kind="angular")] * 3),
    tuple([profile_from_breakpoints([10.0, 40.0, 150.0], [0.02 * G0**2, 0.04 * G0**2, 0.04 * G0**2])] * 3),
)
#: The three frequencies of the cross-spectra check [Hz]: below, among and above the modes (34–68 Hz).
CHECK_FREQUENCIES = (20.0, 60.0, 100.0)


@pytest.fixture(scope="module")
def welch_run(example):
    mount = example[0]
    record = simulate_mount(mount, CHECK_EXCITATION, duration=2.0, sample_interval=0.0025, realisations=24, rng=11, rtol=1e-8)
    return mount, record, welch_cross_spectra(record, segment=100)


def _expected(mount, record, estimate, density=None):
    """The closed form on the multisine's lines, seen through Welch's window, at the check frequencies."""
    period = record.warmup + record.time[-1]
    lines = np.arange(math.ceil(10.0 * period - 1e-9), math.floor(150.0 * period + 1e-9) + 1) / period
    g = output_density(mount, CHECK_EXCITATION, lines) if density is None else density(lines)
    at = estimate.frequency[[int(np.argmin(np.abs(estimate.frequency - f))) for f in CHECK_FREQUENCIES]]
    return at, expected_welch(g, lines, 1.0 / period, estimate, at)


def _outside(estimate, at, expected):
    """Real parts (upper triangle) and imaginary parts (strict upper) outside their Bonferroni intervals (family 95 %)."""
    idx = [int(np.argmin(np.abs(estimate.frequency - f))) for f in at]
    upper, strict = np.triu_indices(6), np.triu_indices(6, 1)
    count = len(idx) * (upper[0].size + strict[0].size)
    level = 1.0 - 0.05 / count
    mean, hw = estimate.mean[idx], estimate.half_width(level)[idx]
    real = np.abs(mean.real - expected.real)[:, upper[0], upper[1]] > hw.real[:, upper[0], upper[1]]
    imag = np.abs(mean.imag - expected.imag)[:, strict[0], strict[1]] > hw.imag[:, strict[0], strict[1]]
    return int(np.count_nonzero(real) + np.count_nonzero(imag)), count


def test_the_closed_form_cross_spectra_lie_in_the_monte_carlo_intervals_at_three_frequencies(welch_run):
    mount, record, estimate = welch_run
    at, expected = _expected(mount, record, estimate)
    outside, count = _outside(estimate, at, expected)
    assert outside == 0, f"{outside} of {count} parts outside their intervals"
    # the intervals are narrow enough to matter: a few per cent on the autospectra of the angular rates
    idx = int(np.argmin(np.abs(estimate.frequency - 60.0)))
    rel = np.real(np.diagonal(estimate.half_width(0.95)[idx]))[:3] / np.real(np.diagonal(expected[1]))[:3]
    assert np.all(rel < 0.2)


@pytest.mark.parametrize(
    "wrong",
    [
        "conjugated convention",  # S = H G Hᴴ in the package's convention: the quadrature parts change sign
        "mass 10 % heavier",
        "IMU at the centre of mass",  # no lever arm between the centre of mass and the sensors
    ],
)
def test_the_cross_spectra_check_rejects_a_wrong_model(welch_run, wrong):
    mount, record, estimate = welch_run
    if wrong == "conjugated convention":

        def density(f):
            h = mount.transfer(f)
            return h @ CHECK_EXCITATION.at(f) @ np.conj(np.swapaxes(h, -1, -2))
    else:
        other = dataclasses.replace(mount, mass=1.1 * mount.mass) if wrong.startswith("mass") else dataclasses.replace(mount, imu=mount.cg)

        def density(f):
            return output_density(other, CHECK_EXCITATION, f)

    at, expected = _expected(mount, record, estimate, density)
    outside, _ = _outside(estimate, at, expected)
    assert outside >= 3


def _diagonal_mount():
    """Rocking axes at 45° to the block's: an angular base motion about x alone cones the block between its rocking modes."""
    a = 0.04

    def iso(sx, sy, kz, cz):
        return Isolator([sx * a, sy * a, 0.0], [2e4, 2e4, kz], [12.0, 12.0, cz])

    isolators = (iso(1, 1, 6e4, 18.0), iso(-1, -1, 6e4, 18.0), iso(1, -1, 3e4, 13.0), iso(-1, 1, 3e4, 13.0))
    return Mount(1.0, np.diag([2e-3, 2e-3, 3e-3]), isolators, cg=[0.0, 0.0, -0.02], imu=[0.01, 0.005, -0.015])


#: Angular base vibration about x only, 10–150 Hz, 1e-4 (rad/s)²/Hz.
CONING_EXCITATION = BaseExcitation((profile_from_breakpoints([10.0, 150.0], [1e-4, 1e-4], kind="angular"), None, None))
H = 0.0025


@pytest.fixture(scope="module")
def coning_run():
    mount = _diagonal_mount()
    record = simulate_mount(mount, CONING_EXCITATION, duration=2.0, sample_interval=H, realisations=16, rng=7, rtol=1e-8)
    return mount, record, mount_environment(mount, CONING_EXCITATION)


def test_the_coning_drift_of_the_mount_spectra_is_that_of_an_algorithm_run_on_the_simulated_motion(coning_run):
    mount, record, response = coning_run
    algorithms = [get("one-sample"), get("two-sample")]
    closed = mount_drift(algorithms, response, H)
    level = 1.0 - 0.05 / (3 * len(algorithms))  # all the components of both algorithms, family 95 %
    for a, total in zip(algorithms, closed.total_coning):
        sim = simulated_drift(a, record)
        assert np.all(np.abs(sim.mean - total) <= sim.half_width(level)), (a.name, sim.mean, total, sim.half_width(level))
        # the drift is resolved: the interval is a small part of it, and a drift of the wrong size is rejected
        assert sim.half_width(0.95)[2] < 0.15 * abs(total[2])
        assert not np.all(np.abs(sim.mean - 0.7 * total) <= sim.half_width(level))
    # an algorithm run at half the interval is not the one the closed form describes
    wrong = mount_drift([get("one-sample")], response, H / 2).total_coning[0]
    assert not np.all(np.abs(simulated_drift(get("one-sample"), record).mean - wrong) <= simulated_drift(get("one-sample"), record).half_width(level))


def test_a_realisation_does_not_depend_on_how_many_run_with_it(coning_run):
    mount = coning_run[0]
    one = simulate_mount(mount, CONING_EXCITATION, duration=0.1, sample_interval=H, realisations=1, warmup=0.05, rng=3, rtol=1e-10)
    two = simulate_mount(mount, CONING_EXCITATION, duration=0.1, sample_interval=H, realisations=2, warmup=0.05, rng=3, rtol=1e-10)
    assert np.allclose(one.rate[0], two.rate[0], rtol=0, atol=1e-8 * np.max(np.abs(one.rate)))
    assert not np.allclose(two.rate[0], two.rate[1])


def test_the_expected_welch_estimate_of_a_flat_density_is_the_density():
    from scipy.signal import get_window

    from strapdown.analysis.vibration.mount_simulation import WelchEstimate

    est = WelchEstimate(np.zeros(1), np.zeros((1, 1, 6, 6), complex), 64, get_window("hann", 64), 1e-3)  # only the window and interval matter
    lines = np.arange(1, 4000) * 0.125
    g = np.broadcast_to(np.eye(6) * 2.0, (lines.size, 6, 6))
    out = expected_welch(g, lines, 0.125, est, [100.0, 200.0])
    assert np.allclose(np.real(np.diagonal(out, axis1=1, axis2=2)), 2.0, rtol=2e-3)


def test_the_simulation_is_guarded_by_name():
    mount = _diagonal_mount()
    for kwargs, name in [
        (dict(duration=1e9, sample_interval=H), "duration"),
        (dict(duration=1.0, sample_interval=1e-12), "sample_interval"),
        (dict(duration=1.0, sample_interval=H, realisations=10**9), "realisations"),
    ]:
        with pytest.raises(budget.BudgetExceeded, match=f"^`{name}`"):
            simulate_mount(mount, CONING_EXCITATION, rng=1, **kwargs)
    with pytest.raises(budget.BudgetExceeded, match="^`max_points`"):
        mount_environment(mount, CONING_EXCITATION, max_points=10**12)


# --------------------------------------------------------------------------- the command
def test_mount_environment_writes_an_environment_and_quotes_vectors_and_magnitudes(tmp_path):
    import json

    from cli_contract import run, violations

    sensors = tmp_path / "sensors.toml"
    sensors.write_text('[gyro]\nfilter = "lowpass1"\ncutoff_hz = 200.0\n[sampling]\ndecimation = 2\n', encoding="utf-8")
    out = tmp_path / "env.toml"
    argv = ["mount-environment", "--profile", str(AIRFRAME_PROFILE), "--mount", str(ISOLATED_MOUNT), "--sensors", str(sensors), "--out", str(out),
            "--sample-interval", "1e-3", "--algorithms", "two-sample,optimal-3", "--json"]  # fmt: skip
    outcome = run(argv, timeout=300.0)
    assert not violations(outcome, expect="accept", argv=argv), outcome
    data = json.loads(outcome.out)
    assert data["written"] == str(out) and data["table"]["converged"] and len(data["modes"]) == 6
    env = load_environment(out)
    assert env.decimation == 2 and env.gyro.axes[0].analog.order == 1
    for row in data["drift"]["algorithms"]:
        reference = environment_drift(get(row["algorithm"]), env, 1e-3).total_vector
        assert row["total_drift_vector_rad_s"] == pytest.approx(reference, rel=1e-6, abs=1e-9 * np.linalg.norm(reference))
        assert row["total_drift_magnitude_rad_s"] == pytest.approx(np.linalg.norm(reference), rel=1e-6)
        assert sum(np.array(b["drift_vector_rad_s"]) for b in row["bands"]) == pytest.approx(row["total_drift_vector_rad_s"], rel=1e-9, abs=1e-15)


@pytest.mark.parametrize(
    "extra, words",
    [
        (["--tolerance", "0.7"], "--tolerance"),
        (["--algorithms", "two-sample"], "--algorithms"),
        (["--sample-interval", "1e-3", "--algorithms", "no-such"], "--algorithms"),
        (["--sensors", str(Path(__file__).resolve().parents[1] / "analysis" / "vibration" / "environments" / "qualification.toml")], "--sensors"),
        (["--max-points", "1e12"], "--max-points"),
    ],
)
def test_mount_environment_refuses_bad_input_in_one_line(extra, words):
    from cli_contract import run, violations

    argv = ["mount-environment", "--profile", str(AIRFRAME_PROFILE), "--mount", str(ISOLATED_MOUNT)] + extra
    outcome = run(argv, timeout=300.0)
    assert not violations(outcome, expect="refuse", names=(words,), argv=argv), outcome
