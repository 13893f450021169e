"""Linearisation (3.7)-(3.8) and Schuler tuning (3.11) of Plotnikov (1999)."""

import numpy as np
import pytest
import sympy as sp

from strapdown.analysis.multistage.tilt_loop import StageLoop
from strapdown.derivations.multistage import published
from strapdown.derivations.multistage.schuler import SYMBOLS, derive

s = SYMBOLS.s


@pytest.fixture(scope="module")
def d():
    return derive()


def _f(d, name):
    return getattr(SYMBOLS, name)


def test_linearised_equations_are_printed_3_8(d):
    """(3.8) as printed (published.py), in the form θ' = χ' + ω3 + k(χ + n1 − θ − n3β) + y3."""
    printed = published.PRINTED_LINEARISED_3_8
    assert set(printed) == set(d.rates)
    for key, expr in printed.items():
        assert sp.expand(d.rates[key] - expr) == 0, key


def test_w3_sign_differs_from_print(d):
    """Derived W3(1) = W3 − gα + W1β; the paper prints −W1β (erratum)."""
    g = SYMBOLS.g
    al, be, n1, n3 = (_f(d, n) for n in ("alpha", "beta", "n1", "n3"))
    assert sp.expand(d.W1[2] - g * (n3 - al + n1 * be)) == 0
    assert sp.expand(d.W1[2] - g * (n3 - al - n1 * be)) != 0


def test_tf_identically_zero_under_schuler(d):
    k, l, g, R = SYMBOLS.k, SYMBOLS.l, SYMBOLS.g, SYMBOLS.R
    assert d.schuler_residual == 0
    assert sp.simplify(d.tf_accel.subs({k: 0, l: g / R})) == 0
    assert sp.simplify(d.tf_velocity.subs({k: 0, l: g / R})) == 0


@pytest.mark.parametrize("kk,ll", [(0, 1.01), (1e-3, 1.0), (0.01, 32.47)])
def test_tf_nonzero_when_detuned(d, kk, ll):
    """ll in units of g/R."""
    k, l, g, R = SYMBOLS.k, SYMBOLS.l, SYMBOLS.g, SYMBOLS.R
    tf = d.tf_accel.subs({k: kk, l: sp.nsimplify(ll) * g / R, g: sp.Rational(981, 100), R: 6371000})
    assert sp.simplify(tf) != 0
    loop = StageLoop(kk, ll * 9.81 / 6.371e6)
    assert loop.peak_tilt_error(20.0, 20.0) > 1e-5


def test_tf_closed_form(d):
    k, l, g, R = SYMBOLS.k, SYMBOLS.l, SYMBOLS.g, SYMBOLS.R
    assert sp.simplify(d.tf_accel - (k * s + l - g / R) / (g * (s**2 + k * s + l))) == 0
    assert sp.simplify(d.tf_accel_roll + d.tf_accel) == 0


def test_numeric_tf_and_peak_zero_under_schuler():
    loop = StageLoop.schuler()
    assert loop.peak_tilt_error(20.0, 20.0) == 0.0
    assert loop.stability == "marginal"
    assert loop.schuler_period == pytest.approx(2 * np.pi * np.sqrt(6.371e6 / 9.81))
