"""The parallel-computation simulator: scan, exactness, orders, published tables, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import strapdown.analysis.coning.simulator as sim
from strapdown.analysis.cli import main
from strapdown.analysis.coning.evaluation import increment
from strapdown.analysis.coning.precession import RegularPrecession, exact_state, initial_biquaternion
from strapdown.analysis.coning.simulator import drift_rate, prefix_product, sample_increments, simulate, step_count
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.dual import Dual
from strapdown.analysis.core.units import deg_per_h
from strapdown.derivations.coning import published as P
from strapdown.derivations.coning.registry import get


# --------------------------------------------------------------------------- building blocks
def _sequential(q):
    out = [q[..., 0, :]]
    for k in range(1, q.shape[-2]):
        out.append(quat.multiply(out[-1], q[..., k, :]))
    return np.stack(out, axis=-2)


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 70), st.integers(0, 2**31 - 1))
def test_prefix_product_equals_sequential_product(n, seed):
    rng = np.random.default_rng(seed)
    q = quat.rotvec_to_quat(rng.normal(size=(2, n, 3)))
    np.testing.assert_allclose(prefix_product(q), _sequential(q), rtol=0, atol=1e-13)


def test_prefix_product_of_biquaternions():
    rng = np.random.default_rng(5)
    theta = quat.rotvec_to_quat(Dual(rng.normal(size=(13, 3)), rng.normal(size=(13, 3))))
    got = prefix_product(theta)
    ref = [theta[0]]
    for k in range(1, 13):
        ref.append(quat.multiply(ref[-1], theta[k]))
    np.testing.assert_allclose(got.re, np.stack([r.re for r in ref]), atol=1e-13)
    np.testing.assert_allclose(got.du, np.stack([r.du for r in ref]), atol=1e-12)


def test_prefix_product_rejects_bad_shape():
    with pytest.raises(ValueError, match="Expected `q` with shape"):
        prefix_product(np.zeros((5, 3)))


def test_grid_increments_equal_interval_integrals():
    m = RegularPrecession(0.5, 2 * np.pi, 0.3, nu_dual=2.0, nutation_dual=30.0)
    q = sample_increments(m, 0.01, 50, 4, first_step=7, dual=True)
    t = (7 * 4 + np.arange(201)) * 0.01
    ref = m.increments(t[:-1], t[1:])
    np.testing.assert_allclose(q.re.reshape(-1, 3), ref.re, rtol=0, atol=1e-14)
    np.testing.assert_allclose(q.du.reshape(-1, 3), ref.du, rtol=0, atol=1e-12)


def test_drift_rate_is_least_squares_slope():
    t = np.linspace(0.0, 10.0, 101)
    err = np.stack([2e-6 * t + 1e-3, -3e-6 * t, 0 * t], axis=-1)
    np.testing.assert_allclose(drift_rate(t, err), [2e-6, -3e-6, 0.0], atol=1e-18)


def test_step_count():
    assert step_count(0.01, 100.0, 4) == 2500
    assert step_count(0.01, 0.04, 4) == 1


# --------------------------------------------------------------------------- exactness of the run
def test_velocity_run_equals_recursion_2_6():
    """The prefix-product run equals the step-by-step recursion (2.6) of Lebedev & Panov (1989)."""
    m = RegularPrecession(0.5, 2 * np.pi, np.radians(10.0), 10.0, 100.0)
    lam0 = quat.normalize([0.9, 0.1, -0.2, 0.3])
    w0 = np.array([20.0, 35.0, 40.0])
    alg = get("lebedev-panov-6")
    r = simulate(alg, m, 0.01, 2.0, attitude0=lam0, w_inertial0=w0, velocity=True)
    q = sample_increments(m, 0.01, r.steps, 4, dual=True)
    lam, w_e, w_i = lam0, quat.rotate(quat.conjugate(lam0), w0), w0
    for k in range(r.steps):
        step = quat.rotvec_to_quat(increment(alg, q[k]))
        lam_s, mu_s = step.re, step.du
        dw_e = 2 * quat.multiply(quat.conjugate(lam_s), mu_s)
        dw_i = 2 * quat.multiply(mu_s, quat.conjugate(lam_s))
        w_e = quat.vect(quat.multiply(quat.multiply(quat.conjugate(lam_s), quat.vector_to_quat(w_e)), lam_s) + dw_e)
        w_i = quat.vect(quat.vector_to_quat(w_i) + quat.multiply(quat.multiply(lam, dw_i), quat.conjugate(lam)))
        lam = quat.multiply(lam, lam_s)
    exact = exact_state(m, r.time[-1], lam0, w0)
    # exact minus algorithm (package docstring, "Errors")
    np.testing.assert_allclose(r.dw_body[-1], exact.w_body - w_e, atol=1e-9)
    np.testing.assert_allclose(r.dw_inertial[-1], exact.w_inertial - w_i, atol=1e-9)
    err = quat.quat_to_rotvec(quat.multiply(exact.attitude, quat.conjugate(lam)), canonical=True)
    np.testing.assert_allclose(r.attitude_error[-1], err, atol=1e-12)


def test_result_independent_of_chunking_and_batching(monkeypatch):
    alg = get("panov-4s-5")
    motions = [RegularPrecession(e, 2 * np.pi * 3, 0.2, 1.0, 5.0) for e in (-1.0, 0.5, 1.5)]
    whole = simulate(alg, motions, 0.005, 3.0, velocity=True)
    monkeypatch.setattr(sim, "CHUNK_STEPS", 64)
    monkeypatch.setattr(sim, "TIME_CHUNK", 37)
    for i, m in enumerate(motions):
        part = simulate(alg, m, 0.005, 3.0, velocity=True)
        np.testing.assert_allclose(part.attitude_error, whole.attitude_error[i], rtol=0, atol=1e-14)
        np.testing.assert_allclose(part.dw_inertial, whole.dw_inertial[i], rtol=0, atol=1e-11)


def test_constant_rate_is_integrated_exactly():
    """ε = 0 is a constant rate about the body z axis: all cross products vanish, Δφ = P is exact."""
    spin = RegularPrecession(0.0, 2.0, 0.4)
    r = simulate(get("lebedev-panov-6"), spin, 0.01, 5.0)
    assert np.abs(r.attitude_error).max() < 1e-12


# --------------------------------------------------------------------------- orders of convergence
@pytest.mark.parametrize("order", [2, 4, 6])
@pytest.mark.parametrize("eps", [-1.0, 0.5])
def test_convergence_order_attitude_and_velocity(order, eps):
    """Halving h shrinks the drift and |ΔW_I| of (2.2)/(2.5) truncated at order ρ by 2^ρ."""
    m = RegularPrecession(eps, 2 * np.pi, np.radians(10.0), 10.0, 100.0)
    hs = np.array([0.02, 0.01, 0.005])
    drift, dwi = [], []
    for h in hs:
        r = simulate(get(f"lebedev-panov-{order}"), m, h, 20.0, w_inertial0=(20.0, 35.0, 40.0), velocity=True)
        drift.append(float(deg_per_h(r.drift_rate)))
        dwi.append(float(r.final_dw_inertial))
    for values in (drift, dwi):
        slope = np.polyfit(np.log(hs), np.log(values), 1)[0]
        assert abs(slope - order) < 0.3, (values, slope)


# --------------------------------------------------------------------------- published tables
# Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3, column u* (parallel computation):
# constant drift rate [deg/h] at ϑ = 1°, f = 10 Hz, H = 4h = 0.01 s.  Printed to 3 digits.
TABLE_3_U_STAR = [(r.algorithm, r.eps, r.u_star_deg_per_h) for r in P.BUDENNYI_TABLE_3]


@pytest.mark.parametrize("number, eps, printed", TABLE_3_U_STAR)
def test_budennyi_table_3_u_star(number, eps, printed):
    m = RegularPrecession(eps, 2 * np.pi * 10.0, np.radians(1.0))
    r = simulate(get(f"panov-4s-{number}"), m, 0.0025, 100.0)
    assert float(deg_per_h(r.drift_rate)) == pytest.approx(printed, rel=0.02)


def test_budennyi_table_1_column_2_as_printed_does_not_reproduce_table_3():
    """Erratum evidence: 4/3 (p1×p3 + p2×p4) (printed column 2) misses both Table 3 cells by far."""
    from strapdown.analysis.coning.papers.budennyi_table3 import simulated_drift
    from strapdown.analysis.coning.papers.formula_one import printed_column_2
    from strapdown.analysis.core.units import deg_per_h

    drift = simulated_drift(printed_column_2(), duration=20.0)
    printed = {r.eps: r.u_star_deg_per_h for r in P.BUDENNYI_TABLE_3 if r.algorithm == 2}
    assert deg_per_h(drift.coning) < 0.2 * printed[-1.0] and deg_per_h(drift.precession) > 3 * printed[0.5]


_NUT = np.radians(P.LEBEDEV_PANOV_CONDITIONS.nutation_deg)
_TILTED = (np.cos(_NUT / 2), np.sin(_NUT / 2), 0.0, 0.0)
# Lebedev & Panov (1989), section 6: variants (ν° [m/s²], ϑ° [m/s], W_I(0) [m/s], Λ(0)).
VARIANTS = {v.number: (v.nu_dual, v.nutation_dual, v.w_inertial0, _TILTED if v.tilted_start else (1.0, 0.0, 0.0, 0.0)) for v in P.LEBEDEV_PANOV_CONDITIONS.variants}


def _lp(order, eps, variant, h=0.01):
    nd, td, w0, lam0 = VARIANTS[variant]
    m = RegularPrecession(eps, 2 * np.pi, _NUT, nd, td)
    r = simulate(get(f"lebedev-panov-{order}"), m, h, 100.0, attitude0=lam0, w_inertial0=w0, velocity=True)
    return {"drift": float(deg_per_h(r.drift_rate)), "dW_E": float(r.final_dw_body), "dW_I": float(r.final_dw_inertial)}


# Lebedev & Panov (1989), section 6, table (t = 100 s, ν = 2π s⁻¹, ϑ = 10°, h = 0.01 s):
# the drift row [deg/h] (one variant each) and the ρ = 4 rows of |ΔW_E|, |ΔW_I| [m/s] (every variant).
_DRIFT_VARIANT = {(4, -1.0): 1, (4, 0.5): 2, (6, -1.0): 3, (6, 0.5): 1}
LP_TABLE_REPRODUCED = [(c.quantity, c.order, c.eps, _DRIFT_VARIANT[(c.order, c.eps)], c.value) for c in P.LEBEDEV_PANOV_TABLE if c.quantity == "drift"] + [
    (c.quantity, c.order, c.eps, v, c.value) for c in P.LEBEDEV_PANOV_TABLE if c.quantity != "drift" and c.order == 4 for v in c.variants
]


@pytest.mark.parametrize("quantity, order, eps, variant, printed", LP_TABLE_REPRODUCED)
def test_lebedev_panov_table(quantity, order, eps, variant, printed):
    assert _lp(order, eps, variant)[quantity] == pytest.approx(printed, rel=0.02)


# The ρ = 6 rows of |ΔW_E|, |ΔW_I| in the same table do not reproduce (erratum; evidence in
# reports/algorithms.md).  For these cells we assert what the convergence study establishes:
# our value at h = 0.01 s is in the asymptotic regime of a sixth-order method (halving h divides
# it by 2⁶ within 2%), and it differs from the printed value by more than the 2% tolerance.
_ERRATA_CELLS = {("dW_E", -1.0, 1), ("dW_E", 0.5, 3), ("dW_I", -1.0, 2), ("dW_I", 0.5, 1), ("dW_I", 0.5, 2)}
LP_TABLE_ERRATA = [
    (c.quantity, c.eps, v, c.value) for c in P.LEBEDEV_PANOV_TABLE if c.order == 6 and c.quantity != "drift" for v in c.variants if (c.quantity, c.eps, v) in _ERRATA_CELLS
]


@pytest.mark.parametrize("quantity, eps, variant, printed", LP_TABLE_ERRATA)
def test_lebedev_panov_table_order_6_velocity_erratum(quantity, eps, variant, printed):
    ours = _lp(6, eps, variant)[quantity]
    half = _lp(6, eps, variant, h=0.005)[quantity]
    assert ours / half == pytest.approx(2.0**6, rel=0.02)
    assert abs(ours / printed - 1.0) > 0.1


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "kwargs, exc, fragment",
    [
        ({"sample_interval": 0.0}, ValueError, "`sample_interval` > 0"),
        ({"sample_interval": -0.01}, ValueError, "`sample_interval` > 0"),
        ({"sample_interval": float("nan")}, ValueError, "`sample_interval` to be finite"),
        ({"duration": 0.0}, ValueError, "`duration` > 0"),
        ({"duration": float("inf")}, ValueError, "`duration` to be finite"),
        ({"duration": 0.03}, ValueError, "one step"),
        ({"attitude0": (1.0, 0.1, 0.0, 0.0)}, ValueError, "unit quaternion"),
        ({"attitude0": (1.0, 0.0, 0.0)}, ValueError, r"shape \(\.\.\., 4\)"),
        ({"w_inertial0": (1.0, np.nan, 0.0)}, ValueError, "`w_inertial0` to be finite"),
        ({"motion": "coning"}, TypeError, "RegularPrecession"),
        ({"algorithm": "two-sample"}, TypeError, "Algorithm"),
    ],
)
def test_simulate_rejects_bad_input(kwargs, exc, fragment):
    args = {"algorithm": get("lebedev-panov-4"), "motion": RegularPrecession(-1.0, 2 * np.pi, 0.1), "sample_interval": 0.01, "duration": 1.0}
    args.update(kwargs)
    with pytest.raises(exc, match=fragment):
        simulate(args.pop("algorithm"), args.pop("motion"), args.pop("sample_interval"), args.pop("duration"), **args)


_DRIFT = ["drift", "--algorithm", "panov-4s-3", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1"]


@pytest.mark.parametrize(
    "change, fragment",
    [
        (("--nutation-deg", "180"), "--nutation-deg"),
        (("--nutation-deg", "-5"), "--nutation-deg"),
        (("--nutation-deg", "nan"), "--nutation-deg"),
        (("--sample-interval", "0"), "--sample-interval"),
        (("--sample-interval", "-1"), "--sample-interval"),
        (("--duration", "0"), "--duration"),
        (("--duration", "0.005"), "one step"),
        (("--algorithm", "no-such"), "panov-4s-1"),
        (("--freq-hz", "0"), "--freq-hz"),
    ],
)
def test_cli_drift_bad_input_exits_2(change, fragment, capsys):
    argv = list(_DRIFT)
    argv[argv.index(change[0]) + 1] = change[1]
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1 and fragment in captured.err


def test_cli_drift_json(capsys):
    import json

    assert main(_DRIFT + ["--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["samples"] == 4 and data["step"] == pytest.approx(0.01) and data["steps"] == 100
    assert data["simulated_drift_deg_per_h"] > 0


_VEL = [
    *("velocity-error", "--algorithm", "lebedev-panov-4", "--eps", "-1", "--freq-hz", "1", "--nutation-deg", "10"),
    *("--nu-dual-m-s2", "0.5", "--nutation-dual-m-s", "10", "--w0-m-s", "10,0,0", "--attitude0", "2,0.1,0,0"),
    *("--sample-interval", "0.01", "--duration", "2"),
]


def test_cli_velocity_error_json_normalises_attitude(capsys):
    import json

    assert main(_VEL + ["--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) >= {"dW_E", "dW_I", "simulated_drift_deg_per_h", "samples", "step"}
    assert np.linalg.norm(data["attitude0"]) == pytest.approx(1.0, abs=1e-15)
    expected = simulate(get("lebedev-panov-4"), RegularPrecession(-1.0, 2 * np.pi, _NUT, 0.5, 10.0), 0.01, 2.0, attitude0=quat.normalize([2, 0.1, 0, 0]), w_inertial0=(10, 0, 0), velocity=True)
    assert data["dW_I"] == pytest.approx(float(expected.final_dw_inertial), rel=1e-12)


@pytest.mark.parametrize(
    "change, fragment",
    [
        (("--w0-m-s", "1,2"), "--w0-m-s"),
        (("--w0-m-s", "1,x,3"), "--w0-m-s"),
        (("--attitude0", "0,0,0,0"), "--attitude0"),
        (("--attitude0", "1,0,0,inf"), "--attitude0"),
        (("--nu-dual-m-s2", "nan"), "--nu-dual-m-s2"),
    ],
)
def test_cli_velocity_error_bad_input_exits_2(change, fragment, capsys):
    argv = list(_VEL)
    argv[argv.index(change[0]) + 1] = change[1]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and fragment in err


def test_initial_biquaternion_round_trip():
    theta0 = initial_biquaternion(_TILTED, (20.0, 35.0, 40.0))
    w_i = 2 * quat.vect(quat.multiply(theta0.du, quat.conjugate(theta0.re)))
    np.testing.assert_allclose(w_i, (20.0, 35.0, 40.0), atol=1e-13)
