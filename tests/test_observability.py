"""Observability of the alignment error states against the classical results, derived here by hand.

The stationary model's unobservable subspace is written down from the error
equations (a constant state that keeps the velocity error at zero), not from
the package; python-control's observability matrix gives the rank a second,
independent way.
"""

import math

import control
import numpy as np
import pytest

from strapdown.analysis.alignment.base_motion import NarrowbandMotion
from strapdown.analysis.alignment.earth import EARTH_RATE, normal_gravity
from strapdown.analysis.alignment.error_model import alignment_error_model, navigation_error_model, state_labels
from strapdown.analysis.alignment.fine import FilterTuning, assumed_disturbance, filter_model
from strapdown.analysis.alignment.imu import Scenario
from strapdown.analysis.alignment.observability import (
    BodyRotation,
    multi_position_problem,
    observability,
    observability_gramian,
    rocking_problem,
    stationary_problem,
)

NAMES = ("phi_N", "phi_E", "phi_D", "dv_N", "dv_E", "dv_D", "eps_N", "eps_E", "eps_D", "acc_N", "acc_E", "acc_D")


def _hand_null_space(lat):
    """The states that keep δv ≡ 0: φ constant with ∇_N = −g φ_E, ∇_E = g φ_N, ε = −ω_ie × φ (φ' = 0), ∇_D = 0."""
    W, g = EARTH_RATE, normal_gravity(lat)
    s, c = math.sin(lat), math.cos(lat)
    out = []
    for phi in np.eye(3):
        v = np.zeros(12)
        v[0:3] = phi
        omega = W * np.array([c, 0.0, -s])
        v[6:9] = -np.cross(omega, phi)
        v[9], v[10] = -g * phi[1], g * phi[0]
        out.append(v)
    return np.array(out).T


@pytest.mark.parametrize("lat_deg", [0.0, 30.0, 45.0, 80.0, -60.0])
def test_stationary_unobservable_subspace_is_the_hand_derived_one(lat_deg):
    lat = math.radians(lat_deg)
    r = observability(stationary_problem(lat))
    assert r.rank == 9 and r.dim == 12
    hand = _hand_null_space(lat)
    m = alignment_error_model(Scenario(lat), FilterTuning())
    np.testing.assert_allclose(m.A @ hand, 0.0, atol=1e-12)  # the hand derivation is right
    np.testing.assert_allclose(m.H @ hand, 0.0, atol=0.0)
    found = np.array([[d.components.get(n, 0.0) for n in NAMES] for d in r.unobservable]).T
    S = m.scales[:, None]
    # the same span: each found direction is a combination of the hand-derived ones (in equivalent angles)
    coef, *_ = np.linalg.lstsq(hand / S, found / S, rcond=None)
    np.testing.assert_allclose(hand / S @ coef, found / S, atol=1e-9)


def test_stationary_pairs_at_45_degrees():
    r = observability(stationary_problem(math.radians(45.0)))
    assert r.pairs == (("north tilt", "east accelerometer bias"), ("east tilt", "north accelerometer bias"), ("azimuth", "east gyro bias"))
    az = r.unobservable[2]
    assert az.components == pytest.approx({"phi_D": 1.0, "eps_E": EARTH_RATE * math.cos(math.radians(45.0))}, rel=1e-12)


def test_rank_agrees_with_the_observability_matrix_of_python_control():
    lat = math.radians(45.0)
    m = alignment_error_model(Scenario(lat), FilterTuning())
    S = m.scales
    A = m.A * S[None, :] / S[:, None] / EARTH_RATE  # equivalent angles, time unit 1/Ω: entries of order one
    O = control.obsv(A, m.H * S[None, :])
    s = np.linalg.svd(O, compute_uv=False)
    assert int(np.sum(s > 1e-9 * s[0])) == 9


def test_the_continuous_model_is_the_fine_filter_model():
    sc = Scenario(math.radians(50.0), heading=0.3, motion=NarrowbandMotion(np.radians([1.0, 2.0, 2.0]), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], duration=60.0)
    tuning = FilterTuning(epoch=0.5, gyro_noise=1e-6, accel_noise=1e-4, disturbance=assumed_disturbance(sc.motion, sc))
    model = alignment_error_model(sc, tuning)
    fm = filter_model(sc, tuning)
    F, Q = model.discretise(fm.epoch)
    np.testing.assert_allclose(F, fm.F, atol=1e-15)
    np.testing.assert_allclose(Q, fm.Q, rtol=1e-12, atol=1e-30)
    np.testing.assert_array_equal(model.H, fm.H)
    assert model.names == fm.names


@pytest.mark.parametrize("angle_deg", [90.0, 180.0, 45.0])
@pytest.mark.parametrize("axis", ["x", "z"])
def test_a_rotation_makes_every_state_observable(axis, angle_deg):
    p = multi_position_problem(math.radians(45.0), [BodyRotation(150.0, axis, math.radians(angle_deg))], 300.0)
    r = observability(p)
    assert r.rank == 12 and r.unobservable == ()
    if axis == "z":  # turned about the vertical, the azimuth is learned below the stationary floor σ_ε/(Ω cos φ) (over the prior)
        floor = observability(stationary_problem(math.radians(45.0))).posterior_ratio[2]
        assert r.posterior_ratio[2] < 0.75 * floor and r.posterior_ratio[7] < 0.5


@pytest.mark.parametrize("rotations", [[], [BodyRotation(100.0, "z", 2 * math.pi)]], ids=["one-position", "full-turn"])
def test_no_rotation_or_a_full_turn_leaves_the_classical_rank(rotations):
    r = observability(multi_position_problem(math.radians(45.0), rotations, 300.0))
    assert r.rank == 9
    assert r.pairs == (("north tilt", "accelerometer bias y"), ("east tilt", "accelerometer bias x"), ("azimuth", "gyro bias y"))


def test_rocking_states_are_observable_through_the_lever_arm_but_one_mode():
    sc = Scenario(math.radians(45.0), motion=NarrowbandMotion(np.radians([1.0, 2.0, 2.0]), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], duration=300.0)
    r = observability(rocking_problem(sc))
    assert (r.rank, r.dim) == (13, 18)
    assert r.pairs[:3] == (("north tilt", "east accelerometer bias"), ("east tilt", "north accelerometer bias"), ("azimuth", "east gyro bias"))
    assert {d.state for d in r.unobservable[3:]} <= {"psi_r", "psi_r'", "beta_r", "beta_r'", "gamma_r", "gamma_r'"}


def test_degree_of_observability_is_the_floor_over_the_prior_for_the_azimuth():
    """After a long horizon the azimuth is known to its floor σ_ε/(Ω cos φ): the ratio to a 1° prior."""
    lat = math.radians(45.0)
    tuning = FilterTuning(gyro_bias=math.radians(0.01) / 3600, accel_bias=1e-5)
    r = observability(stationary_problem(lat, tuning=tuning, duration=1200.0))
    floor = tuning.gyro_bias / (EARTH_RATE * math.cos(lat))
    expected = floor * tuning.prior_heading / math.hypot(floor, tuning.prior_heading) / tuning.prior_heading
    assert r.posterior_ratio[2] == pytest.approx(expected, rel=0.02)
    # three null directions: zero to the round-off of the largest eigenvalue (n ε λ_max, the numerical-rank rule), the rest far above it
    ev = r.gramian_eigenvalues
    round_off = ev.size * np.finfo(float).eps * ev[0]
    assert np.abs(ev[-3:]).max() < round_off < 1e-4 * ev[-4]


def test_rocking_about_the_lever_arm_is_unobservable():
    """A rotation about the axis through the block does not move it: that rocking mode joins the three pairs."""
    sc = Scenario(math.radians(45.0), motion=NarrowbandMotion(np.radians([1.0, 2.0, 2.0]), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], duration=300.0)
    p = rocking_problem(sc)
    r = observability(p)
    m = p.models[0]
    L = m.H[:, 13::2]  # velocity per rocking rate
    n = np.linalg.svd(L)[2][-1]  # the rates that turn the block about its lever arm
    mode = np.zeros((18, 2))
    mode[12::2, 0], mode[13::2, 1] = n, n
    np.testing.assert_allclose(m.H @ mode, 0.0, atol=1e-15)
    W = observability_gramian(p)
    S = np.sqrt(np.diag(p.P0))
    x = mode / S[:, None]
    assert np.abs(x.T @ W @ x).max() < 1e-12 * np.abs(W).max()
    # and the analysis finds it: the mode lies in the span of the directions it reports
    found = np.array([[d.components.get(k, 0.0) for k in r.names] for d in r.unobservable]).T
    coef, *_ = np.linalg.lstsq(found, mode, rcond=None)
    np.testing.assert_allclose(found @ coef, mode, atol=1e-9)


def test_errors():
    with pytest.raises(ValueError, match="axis"):
        BodyRotation(1.0, "w", 0.1)
    with pytest.raises(ValueError, match="rotations"):
        multi_position_problem(0.5, [BodyRotation(400.0, "z", 0.1)], 300.0)
    with pytest.raises(TypeError, match="problem"):
        observability("stationary")


def test_words_for_the_states():
    assert state_labels(["phi_E", "dv_N", "eps_x", "acc_D", "gamma_r'"]) == ("east tilt", "north velocity", "gyro bias x", "down accelerometer bias", "rocking rate γ")
    m = navigation_error_model(0.3, velocity=[10.0, 0.0, 0.0], transport=True, position=True)
    assert m.names[6:9] == ("dp_N", "dp_E", "dp_D") and m.H.shape == (6, 15)


def test_gramian_eigenvalues_are_information_in_units_of_the_prior():
    """``gramian_eigenvalues`` are eigenvalues of W (prior units): W by quadrature apart from the package, and
    with no process noise the filter's posterior in prior units is ``(I + W)⁻¹`` (filterpy, discrete epochs)."""
    from scipy.integrate import quad_vec
    from scipy.linalg import expm

    lat = math.radians(45.0)
    tuning = FilterTuning(epoch=0.1, gyro_noise=0.0, accel_noise=0.0, gyro_bias=math.radians(0.05) / 3600, accel_bias=5e-4)
    p = stationary_problem(lat, tuning=tuning, duration=240.0)
    r = observability(p)
    m = p.models[0]
    S = np.sqrt(np.diag(p.P0))
    A = m.A * S[None, :] / S[:, None]
    H = m.H * S[None, :]
    Ninv = np.linalg.inv(p.R * p.epoch)
    W, _ = quad_vec(lambda t: (lambda Phi: Phi.T @ H.T @ Ninv @ H @ Phi)(expm(A * t)), 0.0, p.duration, epsrel=1e-10)
    np.testing.assert_allclose(observability_gramian(p), W, rtol=1e-6, atol=1e-9 * np.abs(W).max())
    np.testing.assert_allclose(r.gramian_eigenvalues, np.linalg.eigvalsh(W)[::-1], rtol=1e-6, atol=1e-9 * np.abs(W).max())
    # eigenvalues, not singular values: those of the three unobservable pairs are zero to rounding, of either sign
    assert np.all(r.gramian_eigenvalues[:-3] > 0.0) and np.abs(r.gramian_eigenvalues[-3:]).max() < 1e-8 * r.gramian_eigenvalues[0]
    posterior = np.linalg.inv(np.eye(12) + W)
    np.testing.assert_allclose(r.posterior_ratio, np.sqrt(np.diag(posterior)), rtol=0.02)


def test_rank_is_not_degree_turning_about_the_vertical():
    """Turning the block about the vertical makes every state observable in rank, yet within 300 s the filter
    learns nothing of the z-gyro bias (the vertical axis is never turned): its degree stays 1."""
    lat = math.radians(45.0)
    tuning = FilterTuning(gyro_bias=math.radians(0.01) / 3600, accel_bias=1e-4, epoch=1.0)
    r = observability(multi_position_problem(lat, [BodyRotation(300.0 * k / 4, "z", math.radians(90.0)) for k in (1, 2, 3)], 300.0, tuning=tuning))
    assert r.rank == r.dim
    assert r.posterior_ratio[r.names.index("eps_z")] > 0.99


def test_an_epoch_longer_than_the_horizon_is_refused():
    with pytest.raises(ValueError, match="`epoch` at most the horizon `duration`"):
        observability(stationary_problem(math.radians(45.0), tuning=FilterTuning(epoch=1000.0), duration=10.0))


@pytest.mark.parametrize(
    "argv, option",
    [
        (["--epoch", "1000", "--duration", "10"], "--epoch"),
        (["--lat-deg", "90"], "--lat-deg"),
        (["--lat-deg", "90", "--model", "multi-position", "--rotation-angles-deg", "90"], "--lat-deg"),
    ],
)
def test_cli_refuses_by_the_option_at_fault(argv, option, capsys):
    from strapdown.analysis import cli

    assert cli.main(["observability", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and option in err and "Traceback" not in err
    assert "--rotation-angles-deg" not in err.split("error:")[1].split("Expected")[0]
