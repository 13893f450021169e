"""Derivation of Hrechka & Koroliov (5)–(15) and the second-order theory, checked independently."""

import math

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from strapdown.analysis.gyrocompass.azimuth import azimuth_error, azimuth_monte_carlo, bound14, bound15, gradient, second_order_theory
from strapdown.analysis.gyrocompass.formula_checks import check_printed_formulas
from strapdown.analysis.gyrocompass.rocking import GaussianRocking, SineRocking
from strapdown.derivations.gyrocompass import azimuth_error as g
from strapdown.derivations.gyrocompass.published import printed_formula

phi, b0, g0, xi, eta = g.SYMBOLS.phi, g.SYMBOLS.beta0, g.SYMBOLS.gamma0, g.SYMBOLS.xi, g.SYMBOLS.eta


def test_printed_6_9_10_agree_with_derivation():
    p = g.linear_parts()
    assert sp.simplify(p.A_star - printed_formula("(6)").expression) == 0
    assert sp.simplify(p.B_star - printed_formula("(9)").expression) == 0
    assert sp.simplify(p.zeta2 - printed_formula("(10)").expression) == 0


def test_printed_7_is_a_misprint_sin_beta0():
    """(7) prints cos β0 in the ξ term; the derivation (and (5)) give sin β0."""
    p = g.linear_parts()
    printed = printed_formula("(7)").expression
    assert sp.simplify(p.zeta1 - printed) != 0
    fixed = printed.subs(xi * sp.sin(phi) * sp.cos(b0) * sp.sin(g0), xi * sp.sin(phi) * sp.sin(b0) * sp.sin(g0))
    assert sp.simplify(p.zeta1 - fixed) == 0


def test_formula_checks_flag_exactly_the_misprints():
    """The numeric residual confirms each symbolic verdict: A (after (2)) and (7) differ, the rest agree."""
    checks = {c.label: c for c in check_printed_formulas()}
    assert {k for k, c in checks.items() if not c.agrees} == {"A (after (2))", "(7)"}
    for c in checks.values():
        assert (c.residual > 1e-3) == (not c.agrees), c.label


def test_bound14_reduces_to_15_squared():
    assert sp.simplify(g.bound14_rocking().subs({b0: 0, g0: 0}) - g.bound15() ** 2) == 0
    assert g.bound14_reduces_to_15()


def test_linear_error_is_the_arg_difference():
    p = g.linear_parts()
    L = sum(c * xi**i * eta**j for (i, j), c in g.error_series(1).items())
    target = (p.A_star * p.zeta2 - p.B_star * p.zeta1) / (p.A_star**2 + p.B_star**2)
    vals = {phi: 0.7, b0: 0.05, g0: -0.03, xi: 0.3, eta: -0.2}
    assert abs(float((L - target).subs(vals))) < 1e-14


def test_error_series_remainder_is_fourth_order():
    """Halving (ξ, η) shrinks the remainder of the cubic series by 2⁴ = 16."""
    vals = {phi: math.radians(70), b0: math.radians(3), g0: math.radians(-2)}
    series = {k: float(c.subs(vals)) for k, c in g.error_series(3).items()}
    ratios = []
    prev = None
    for h in (0.04, 0.02, 0.01, 0.005):
        x, y = 0.8 * h, -0.6 * h
        exact = azimuth_error(x, y, latitude=vals[phi], beta0=vals[b0], gamma0=vals[g0])
        rem = abs(float(exact) - sum(c * x**i * y**j for (i, j), c in series.items()))
        if prev is not None:
            ratios.append(prev / rem)
        prev = rem
    assert all(14.0 < r < 18.5 for r in ratios), ratios


def test_mse_at_zero_tilt_closed_form():
    m = g.mse_at_zero_tilt()
    t2 = sp.tan(phi) ** 2
    S = g.SYMBOLS
    expected = t2 * S.D_xi * (1 + S.D_eta * (1 + 3 * t2) - S.kappa_xi * S.D_xi * (1 + 2 * t2) / 3)
    assert sp.simplify(m - expected) == 0
    assert sp.simplify(g.bias_second_order().subs({b0: 0})) == 0


def test_gradient_matches_finite_difference():
    lat, bb, gg = math.radians(55), math.radians(4), math.radians(-3)
    h = 1e-6
    gb = float(azimuth_error(h, 0.0, latitude=lat, beta0=bb, gamma0=gg) - azimuth_error(-h, 0.0, latitude=lat, beta0=bb, gamma0=gg)) / (2 * h)
    ge = float(azimuth_error(0.0, h, latitude=lat, beta0=bb, gamma0=gg) - azimuth_error(0.0, -h, latitude=lat, beta0=bb, gamma0=gg)) / (2 * h)
    assert tuple(gradient(lat, bb, gg)) == pytest.approx((gb, ge), rel=1e-7)


@settings(max_examples=60, deadline=None)
@given(
    lat=st.floats(-85, 85),
    bb=st.floats(-10, 10),
    gg=st.floats(-10, 10),
    sx=st.floats(0, 5),
    se=st.floats(0, 5),
)
def test_bound14_dominates_first_order_rms(lat, bb, gg, sx, se):
    """(14) is a valid bound at first order: |atan x − atan y| ≤ |x − y| and Cauchy–Schwarz."""
    args = (math.radians(lat), math.radians(bb), math.radians(gg), math.radians(sx), math.radians(se))
    if abs(math.cos(args[0]) * math.cos(args[2]) + math.sin(args[0]) * math.cos(args[1]) * math.sin(args[2])) < 1e-3:
        return
    t = second_order_theory(*args)
    assert t.rms_first_order <= bound14(*args) * (1 + 1e-9) + 1e-15


def test_mc_agrees_with_second_order_theory_not_first():
    """Fixed seed; 95 % CI from the batch-means standard error (relative SE ≈ 3e-4)."""
    lat, s = math.radians(80.0), math.radians(1.0)
    mc = azimuth_monte_carlo(lat, 0.0, 0.0, GaussianRocking(s, s), 2_000_000, rng=11)
    lo, hi = mc.result.rms_ci
    assert lo < mc.theory.rms < hi
    assert mc.theory.rms_first_order < lo  # (14) = (15) = first order here: violated
    assert mc.result.covers(mc.bound15) == "fails"


def test_small_rocking_sine_agrees_with_theory():
    lat, s = math.radians(45.0), math.radians(0.05)
    mc = azimuth_monte_carlo(lat, math.radians(2), math.radians(1), SineRocking(s, s), 1_000_000, rng=3)
    lo, hi = mc.result.rms_ci
    assert lo < mc.theory.rms < hi


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(latitude=math.radians(90)), "latitude"),
        (dict(latitude=math.nan), "latitude"),
        (dict(sigma_xi=-1e-3), "sigma_xi"),
        (dict(beta0=math.inf), "beta0"),
    ],
)
def test_bad_input(kwargs, message):
    args = dict(latitude=0.5, beta0=0.0, gamma0=0.0, sigma_xi=1e-3, sigma_eta=1e-3)
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        bound14(**args)


def test_bound15_value():
    assert bound15(math.radians(60), 0.01) == pytest.approx(math.sqrt(3) * 0.01)


def test_skipping_quantiles_keeps_the_draws_and_every_moment():
    import dataclasses

    import numpy as np

    from strapdown.analysis.gyrocompass.azimuth import azimuth_monte_carlo
    from strapdown.analysis.gyrocompass.rocking import GaussianRocking, SineRocking
    from strapdown.analysis.gyrocompass.studies import BoundCase, run_cases

    for rocking, degree in ((GaussianRocking(0.02, 0.01), 0), (SineRocking(0.02, 0.02), 4)):
        full = azimuth_monte_carlo(1.0, 0.01, -0.02, rocking, 20_000, rng=5, steps_per_trial=64, control_degree=degree)
        bare = azimuth_monte_carlo(1.0, 0.01, -0.02, rocking, 20_000, rng=5, steps_per_trial=64, control_degree=degree, quantiles=())
        assert full.result.quantiles and not bare.result.quantiles and not bare.result.quantile_intervals
        for field in dataclasses.fields(full.result):
            if field.name == "histogram":
                assert all(np.array_equal(x, y) for x, y in zip(full.result.histogram, bare.result.histogram))
            elif field.name not in ("quantiles", "quantile_intervals"):
                assert getattr(full.result, field.name) == getattr(bare.result, field.name), field.name
        assert (full.bound14, full.bound15, full.theory, full.controls) == (bare.bound14, bare.bound15, bare.theory, bare.controls)
    case = BoundCase("c", "normal", 1.2, 0.0, 0.0, 0.03)
    (a,), (b,) = run_cases([case], n_samples=8192, rng=2), run_cases([case], n_samples=8192, rng=2, quantiles=())
    assert a.mc.result.rms_ci == b.mc.result.rms_ci and a.mc.result.mean == b.mc.result.mean and not b.mc.result.quantiles


def test_moments_at_python_floats_equal_those_at_numpy_scalars():
    """second_order_theory evaluates the generated moments with Python floats: NumPy's values, bit for bit."""
    import numpy as np

    from strapdown.analysis.gyrocompass import azimuth as az

    rng = np.random.default_rng(11)
    for _ in range(2000):
        lat, b0, g0 = rng.uniform(-1.5, 1.5), *(rng.uniform(-0.3, 0.3, 2) * (rng.random() < 0.7))
        sx, se = 10.0 ** rng.uniform(-6, 0, 2) * (rng.random(2) < 0.9)
        args = (*az._coefficients()(lat, b0, g0), sx * sx, se * se, *rng.choice([1.5, 3.0, rng.uniform(1.0, 5.0)], 2))
        reference = tuple(float(v) for v in az._moments()(*(np.float64(a) for a in args)))
        got = az._scalar_moments(args)
        assert all(type(v) is float for v in got)
        assert got == reference or all(a == b or (math.isnan(a) and math.isnan(b)) for a, b in zip(got, reference))
