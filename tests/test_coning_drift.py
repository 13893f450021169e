"""Coning drift in closed form: published constants, the general series, the simulator, numerics."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy as sp

from strapdown.analysis.coning.drift_theory import algorithm_key, coning_drift_function, coning_drift_rate
from strapdown.analysis.coning.frequency_response import ROUND_OFF_MARGIN, coning_frequency_response, simulator_check
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.derivations.coning import drift as D
from strapdown.derivations.coning import published as P
from strapdown.derivations.coning.algorithms import Algorithm, Term
from strapdown.derivations.coning.registry import get, names

#: Savage's 1 + 1 (Savage 1998): p_1 + (1/12) p_0 × p_1, p_0 the last sample of the previous step.
SAVAGE = Algorithm("savage-1+1", 1, (Term(Fraction(1, 12), (0, 1)),), "Savage 1 + 1", "Savage (1998)")
#: One sample, no correction: Δφ = p_1.
UNCOMPENSATED = Algorithm("uncompensated", 1, ())

# Coning drift constants of the optimal N-sample algorithms, drift = α² Ω (ΩT)^(2N) ρ_N with
# T = H the update interval, and their lag sums k_1 … k_(N-1) (coefficients of p_(N-l) × p_N),
# as printed (derivations/coning/published.py: PSINS toolbox glv.cs; Ignagni 1990, 1996).
PUBLISHED_RHO = {get(f.algorithm).samples: f.value for f in P.PUBLISHED_ALGORITHM_ERRORS if f.quantity == "coning_coefficient"}
#: Lags N − 1 … 1 of the printed k_1 … k_(N−1), reordered as lags 1 … N − 1 (the order of ``lag_sums``).
PUBLISHED_LAG_SUMS = {n: tuple(reversed(ks)) for n, (ks, _) in P.PUBLISHED_ALGORITHM_COEFFICIENTS.items()}


@pytest.mark.parametrize("N", [2, 3, 4, 5, 6])
def test_optimal_class_reproduces_published_lag_sums_and_constants(N):
    alg = D.optimal_coning_algorithm(N)
    assert D.lag_sums(alg) == tuple(Fraction(k) for k in PUBLISHED_LAG_SUMS[N])
    d = D.coning_drift(alg)
    assert (d.order, d.step_coefficient) == (2 * N, PUBLISHED_RHO[N])


def test_uncompensated_single_sample_is_the_classical_result():
    """Δφ = p: u = ½ α² ω (1 − sin ωh / ωh) + O(α⁴), i.e. ρ_1 = 1/12."""
    d = D.coning_drift(UNCOMPENSATED)
    assert sp.simplify(d.function - (D.X - sp.sin(D.X)) / (2 * D.X)) == 0
    assert (d.order, d.coefficient) == (2, PUBLISHED_RHO[1])


def test_savage_one_plus_one_equals_two_sample_at_the_same_sample_rate():
    """Savage's 1 + 1 (the optimal 1 + 1 of the class) has the two-sample coning drift at equal h, to all orders in ωh."""
    s, two = D.coning_drift(SAVAGE), D.coning_drift(get("two-sample"))
    assert (s.order, s.coefficient, s.history) == (4, Fraction(1, 60), 1)
    assert sp.simplify(s.function - two.function) == 0
    assert D.optimal_coning_algorithm(1, history=1).pairwise == SAVAGE.pairwise


@pytest.mark.parametrize("N, history", [(2, 1), (3, 1), (2, 2), (1, 3)])
def test_optimal_cross_step_class_gains_the_order_of_its_window(N, history):
    """N samples plus `history` earlier ones cancel as many orders as N + history within-step samples."""
    d = D.coning_drift(D.optimal_coning_algorithm(N, history=history))
    assert d.order == 2 * (N + history)


def test_lag_response_depends_on_the_lag_only():
    assert D.lag_response(1) == 2 * sp.sin(D.X) - sp.sin(2 * D.X)
    assert sp.simplify(D.lag_response(4) - (2 * sp.sin(4 * D.X) - sp.sin(3 * D.X) - sp.sin(5 * D.X))) == 0
    with pytest.raises(ValueError, match="lag"):
        D.lag_response(0)


def test_nested_and_dot_terms_do_not_reach_alpha_squared():
    """lebedev-panov-6 has triple and dot-product terms: the closed form counts them (zero at α²)."""
    lp6 = get("lebedev-panov-6")
    pairs_only = Algorithm("pairs", 4, tuple(t for t in lp6.terms if not t.dots and isinstance(t.cross[1], int)))
    assert D.coning_drift(lp6).nonpairwise == 0
    assert D.coning_drift(lp6).function == D.coning_drift(pairs_only).function


# ------------------------------------------------------------------ against the general series
@pytest.mark.parametrize("name", names())
def test_closed_form_equals_the_general_series(name):
    """The Taylor coefficients of D(x) equal the α²-terms of the drift series through h^9 (two derivations)."""
    alg = get(name)
    N = alg.samples
    series = D.coning_drift_series(alg, 9)
    taylor = D.coning_drift(alg).taylor_coefficients(9)
    assert [c * N ** (w - 1) for w, c in enumerate(series) if w >= 1] == list(taylor[:9])


def test_closed_form_equals_the_series_for_cross_step_and_six_samples():
    s = D.coning_drift_series(SAVAGE, 9)
    assert [c for c in s[1:]] == list(D.coning_drift(SAVAGE).taylor_coefficients(9))
    six = D.optimal_coning_algorithm(6)
    series = D.coning_drift_series(six, 13)
    assert [w for w, c in enumerate(series) if c] == [13]
    assert series[13] * 6**12 == D.coning_drift(six).coefficient == Fraction(1, 24024)


def test_alpha_fourth_term_dominates_the_six_sample_algorithm_at_one_degree():
    """At α = 1°, ωh = 0.1 the optimal 6-sample drift is all α⁴ (its α² term is at (ωh)^12): simulator vs series."""
    alg = D.optimal_coning_algorithm(6)
    alpha, nu, x = np.radians(1.0), 2 * np.pi * 10, 0.1
    terms = {k: D.coning_drift_series(alg, 11, alpha_power=k) for k in (2, 4, 6)}
    assert not any(terms[2])
    H = 6 * x / nu
    theory = sum(alpha**k * nu * sum(float(c) * (nu * H) ** (w - 1) for w, c in enumerate(cs)) for k, cs in terms.items())
    run = simulate(alg, RegularPrecession(-1.0, nu, alpha), x / nu, 200 * 2 * np.pi / nu)
    simulated = float(run.drift @ -np.array([0.0, np.sin(alpha), np.cos(alpha)]))  # along the cone axis −n
    assert simulated == pytest.approx(theory, rel=1e-4)
    assert simulated > 1e6 * float(coning_drift_rate(alg, cone_angle=alpha, nu=nu, sample_interval=x / nu))


# ------------------------------------------------------------------ numerics of D(x)
@pytest.mark.parametrize("alg", [get("two-sample"), get("panov-4s-4"), get("lebedev-panov-6"), D.optimal_coning_algorithm(6), SAVAGE, UNCOMPENSATED])
def test_compiled_function_is_accurate_at_every_omega_h(alg):
    """The compiled D(x) (Taylor polynomial below the switch, closed form above) against 50-digit mpmath."""
    d = D.coning_drift(alg)
    f = sp.lambdify(D.X, d.function, "mpmath")
    x = np.geomspace(1e-3, 3.0, 40)
    with mpmath.workdps(50):
        exact = np.array([float(f(mpmath.mpf(float(v)))) for v in x])
    got = coning_drift_function(alg)(x)
    np.testing.assert_allclose(got, exact, rtol=1e-9)


def test_algorithm_key_is_the_content_not_the_name():
    renamed = Algorithm("other name", 2, get("two-sample").terms)
    assert algorithm_key(renamed) == algorithm_key(get("two-sample"))
    assert algorithm_key(SAVAGE) != algorithm_key(get("two-sample"))


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(cone_angle=0.0, nu=1.0, sample_interval=0.01), "cone_angle"),
        (dict(cone_angle=2.0, nu=1.0, sample_interval=0.01), "cone_angle"),
        (dict(cone_angle=0.01, nu=-1.0, sample_interval=0.01), "nu"),
        (dict(cone_angle=0.01, nu=1.0, sample_interval=np.nan), "sample_interval"),
    ],
)
def test_coning_drift_rate_rejects_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        coning_drift_rate(get("two-sample"), **kwargs)


# ------------------------------------------------------------------ against the simulator
@pytest.mark.parametrize("name", names())
def test_closed_form_agrees_with_the_simulator(name):
    """Every registry algorithm the simulator runs: sign and size of the drift along the cone axis."""
    alg = get(name)
    checks = [simulator_check(alg, x) for x in (0.25, 0.5, 1.0)]
    done = [c for c in checks if c.simulated is not None]
    assert done, [c.note for c in checks]
    for c in done:
        assert abs(c.theory) > c.round_off_floor
        assert c.relative_difference == pytest.approx(0.0, abs=1e-3)


def test_simulator_check_covers_cross_step_algorithms_once_supported():
    """Savage 1 + 1: compared where the simulator accepts samples of earlier steps, otherwise said so."""
    for c in (simulator_check(SAVAGE, x) for x in (0.5, 1.0)):
        if c.simulated is None:
            assert c.note.startswith("not run by the simulator")
        else:
            assert c.relative_difference == pytest.approx(0.0, abs=1e-3)


def test_simulator_check_skips_points_below_the_round_off_floor():
    c = simulator_check(D.optimal_coning_algorithm(6), 0.25)
    assert c.simulated is None and "round-off" in c.note
    assert abs(c.theory) < c.round_off_floor == pytest.approx(ROUND_OFF_MARGIN * np.finfo(float).eps * c.steps / c.duration)


def test_frequency_response_is_typed_and_follows_the_leading_term():
    r = coning_frequency_response([get("two-sample"), get("optimal-3")], np.geomspace(1e-3, 1e-1, 5), check_omega_h=())
    for resp in r.responses:
        np.testing.assert_allclose(resp.drift[:2], resp.leading[:2], rtol=1e-3)
        assert resp.checks == ()
    with pytest.raises(TypeError, match="Algorithm"):
        coning_frequency_response(["two-sample"])
    with pytest.raises(ValueError, match="omega_h"):
        coning_frequency_response([get("two-sample")], [0.0, 0.1], check_omega_h=())


def test_coning_studies_take_the_simulator_engine():
    """The studies that simulate pass ``engine`` through: the numpy path (no compilation) agrees with the kernels."""
    from strapdown.analysis.coning.drift_crosscheck import drift_ratios
    from strapdown.analysis.coning.order_study import drift_orders
    from strapdown.analysis.coning.papers.budennyi_table3 import coning_error_histories

    motion = RegularPrecession(-1.0, 2 * np.pi * 10.0, np.radians(10.0))
    with pytest.raises(ValueError, match="engine"):
        drift_orders(motion, steps=(0.04,), duration=0.2, algorithms=["two-sample"], engine="fortran")
    a = drift_orders(motion, steps=(0.04, 0.02), duration=2.0, algorithms=["two-sample"], engine="numpy")[0]
    b = drift_orders(motion, steps=(0.04, 0.02), duration=2.0, algorithms=["two-sample"], engine="compiled")[0]
    np.testing.assert_allclose(a.drifts, b.drifts, rtol=1e-8)
    a = drift_ratios([motion], steps=(0.02,), duration=2.0, algorithms=["two-sample"], engine="numpy")[0]
    b = drift_ratios([motion], steps=(0.02,), duration=2.0, algorithms=["two-sample"], engine="compiled")[0]
    np.testing.assert_allclose(a.ratios, b.ratios, rtol=1e-8)
    x = coning_frequency_response([get("two-sample")], [0.1, 0.5], check_omega_h=(0.5,), engine="numpy").responses[0].checks[0]
    y = coning_frequency_response([get("two-sample")], [0.1, 0.5], check_omega_h=(0.5,), engine="compiled").responses[0].checks[0]
    assert x.simulated is not None and x.simulated == pytest.approx(y.simulated, rel=1e-8)
    h = coning_error_histories(duration=0.5, engine="numpy")
    k = coning_error_histories(duration=0.5, engine="compiled")
    for p, q in zip(h, k):
        np.testing.assert_allclose(p.error[1:], q.error[1:], rtol=1e-6)
