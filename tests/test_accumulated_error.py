"""Accumulated attitude and apparent-velocity error: asymptotic theory (5.1)–(5.6) against parallel computation."""

from __future__ import annotations

import numpy as np
import pytest

from strapdown.analysis.coning.drift_theory import RAD_PER_S_TO_DEG_PER_H, asymptotic_attitude_error, asymptotic_velocity_error
from strapdown.analysis.coning.precession import RegularPrecession, exact_state
from strapdown.analysis.coning.simulator import simulate
from strapdown.derivations.coning import published as P
from strapdown.derivations.coning.registry import get

_C = P.LEBEDEV_PANOV_CONDITIONS
NU, NUTATION, H_SAMPLE, DURATION = 2 * np.pi * _C.spin_freq_hz, np.radians(_C.nutation_deg), _C.sample_interval, _C.duration
_HALF = NUTATION / 2
_TILTED = (np.cos(_HALF), np.sin(_HALF), 0.0, 0.0)
#: Lebedev & Panov (1989), section 6: variants 1–3 (ν° [m/s²], ϑ° [m/s], W_I(0) [m/s], Λ(0)).
VARIANTS = {v.number: (v.nu_dual, v.nutation_dual, v.w_inertial0, _TILTED if v.tilted_start else (1.0, 0.0, 0.0, 0.0)) for v in _C.variants}
#: Lebedev & Panov (1989), section 6, table: |ΔW_I| [m/s] at t = 100 s, (ρ, ε, variant, printed).
#: The ρ = 6 cells are errata (reports/errata.md): the theory below and the simulation agree, the print does not.
PRINTED_DW_I = [(c.order, c.eps, c.variants[0], c.value, c.order == 6) for c in P.LEBEDEV_PANOV_TABLE if c.quantity == "dW_I"]
#: Relative agreement of theory and simulation: through weight 7 the ρ = 4 estimate misses
#: terms of relative size (νH)^4 ≈ 4e-3 times small coefficients (observed < 1e-4); the ρ = 6
#: estimate keeps only its leading weight 7 and misses relative (νH)^2 terms (observed < 3e-3).
TOLERANCE = {4: 2e-4, 6: 5e-3}


def _theory(order, eps, variant):
    nu_d, th_d, w0, lam0 = VARIANTS[variant]
    err = asymptotic_velocity_error(get(f"lebedev-panov-{order}"), DURATION, eps=eps, nu=NU, nutation=NUTATION,
                                    nu_dual=nu_d, nutation_dual=th_d, step=4 * H_SAMPLE)
    motion = RegularPrecession(eps, NU, NUTATION, nu_d, th_d)
    w_body = exact_state(motion, DURATION, lam0, w0).w_body
    return float(err.dw_inertial), float(np.linalg.norm(err.dw_body(w_body)))


def _simulated(order, eps, variant):
    nu_d, th_d, w0, lam0 = VARIANTS[variant]
    motion = RegularPrecession(eps, NU, NUTATION, nu_d, th_d)
    r = simulate(get(f"lebedev-panov-{order}"), motion, H_SAMPLE, DURATION, attitude0=lam0, w_inertial0=w0, velocity=True)
    return float(r.final_dw_inertial), float(r.final_dw_body)


@pytest.mark.parametrize("order", [4, 6])
@pytest.mark.parametrize("eps", [-1.0, 0.5])
@pytest.mark.parametrize("variant", [1, 2, 3])
def test_theory_matches_parallel_computation(order, eps, variant):
    theory, simulated = _theory(order, eps, variant), _simulated(order, eps, variant)
    np.testing.assert_allclose(theory, simulated, rtol=TOLERANCE[order])


@pytest.mark.parametrize("order, eps, variant, printed, erratum", PRINTED_DW_I)
def test_theory_against_printed_table(order, eps, variant, printed, erratum):
    theory = _theory(order, eps, variant)[0]
    if erratum:
        assert abs(theory / printed - 1) > 0.3
    else:
        assert theory == pytest.approx(printed, rel=0.01)


def test_dw_inertial_does_not_depend_on_initial_conditions():
    # Variants 2 and 3 share ν°, ϑ° and differ in W_I(0), Λ(0): one printed |ΔW_I| cell.
    assert _theory(6, 0.5, 2)[0] == _theory(6, 0.5, 3)[0]
    assert _theory(6, 0.5, 2)[1] != pytest.approx(_theory(6, 0.5, 3)[1], rel=1e-4)


def test_dual_part_is_the_directional_derivative():
    alg, t, step = get("lebedev-panov-6"), np.array([7.3, 100.0]), 0.04
    nu_d, th_d, d = 10.0, 100.0, 1e-7
    err = asymptotic_velocity_error(alg, t, eps=0.5, nu=NU, nutation=NUTATION, nu_dual=nu_d, nutation_dual=th_d, step=step)
    plus = asymptotic_attitude_error(alg, t, eps=0.5, nu=NU + d * nu_d, nutation=NUTATION + d * th_d, step=step)
    minus = asymptotic_attitude_error(alg, t, eps=0.5, nu=NU - d * nu_d, nutation=NUTATION - d * th_d, step=step)
    assert err.velocity.shape == (2, 3)
    np.testing.assert_allclose(err.velocity, (plus - minus) / (2 * d), rtol=1e-5, atol=1e-6 * np.abs(err.velocity).max())
    np.testing.assert_allclose(err.attitude, asymptotic_attitude_error(alg, t, eps=0.5, nu=NU, nutation=NUTATION, step=step))


def test_attitude_error_grows_at_the_drift_rate():
    # Secular part: |δφ(t)| / t tends to the simulated constant drift (least-squares slope over 100 s).
    alg, eps = get("lebedev-panov-6"), -1.0
    simulated = float(simulate(alg, RegularPrecession(eps, NU, NUTATION), H_SAMPLE, DURATION).drift_rate) * RAD_PER_S_TO_DEG_PER_H
    theory = np.linalg.norm(asymptotic_attitude_error(alg, 1e4, eps=eps, nu=NU, nutation=NUTATION, step=4 * H_SAMPLE)) / 1e4
    assert theory * RAD_PER_S_TO_DEG_PER_H == pytest.approx(simulated, rel=5e-3)


@pytest.mark.parametrize(
    "kwargs, exc, match",
    [
        ({"eps": 0.0}, ValueError, "`eps` nonzero"),
        ({"nutation": 4.0}, ValueError, r"`nutation` in \(0, π\)"),
        ({"nu": -1.0}, ValueError, "`nu` > 0"),
        ({"step": float("nan")}, ValueError, "`step` to be finite"),
        ({"nu_dual": float("inf")}, ValueError, "`nu_dual` to be finite"),
        ({"nutation_dual": "a"}, TypeError, "`nutation_dual` to be a real number"),
        ({"t": -1.0}, ValueError, "`t` >= 0"),
    ],
)
def test_rejects_bad_input(kwargs, exc, match):
    args = {"t": 1.0, "eps": -1.0, "nu": NU, "nutation": NUTATION, "nu_dual": 1.0, "nutation_dual": 1.0, "step": 0.04} | kwargs
    t = args.pop("t")
    with pytest.raises(exc, match=match):
        asymptotic_velocity_error(get("lebedev-panov-4"), t, **args)


def test_dw_body_rejects_bad_shape():
    err = asymptotic_velocity_error(get("lebedev-panov-4"), 1.0, eps=-1.0, nu=NU, nutation=NUTATION, nu_dual=1.0, nutation_dual=1.0, step=0.04)
    with pytest.raises(ValueError, match="`w_body` with shape"):
        err.dw_body([1.0, 2.0])
