"""The exact drift from one step in extended precision, and the drift series that converges to it.

The exact drift (:mod:`strapdown.analysis.coning.exact_drift`) shares no code with the series: it
is checked here against long parallel computations, then used as the reference for the series
(with the composition of the steps) and for the truncation error it estimates.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import sympy as sp

from strapdown.analysis.cli import main
from strapdown.analysis.coning.drift_theory import converged_drift_series, drift_series_terms, drift_terms
from strapdown.analysis.coning.exact_drift import exact_coning_drift, exact_drift
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core.units import deg_per_h
from strapdown.derivations.coning.drift import X, coning_drift
from strapdown.derivations.coning.registry import get

#: The audit case: ignagni-1996-5 under classical coning, α = 1°, 10 Hz, h = 1/480 s.
AUDIT = dict(name="ignagni-1996-5", alpha_deg=1.0, freq_hz=10.0, h=1 / 480)


@pytest.mark.parametrize(
    "name, eps, nut_deg, freq_hz, h",
    [("two-sample", 0.5, 5.0, 10.0, 0.004), ("savage-1+1", 0.5, 30.0, 10.0, 0.002), ("panov-4s-3", -1.0, 20.0, 10.0, 0.0025), ("ignagni-1996-2", -1.0, 5.0, 10.0, 0.005)],
)
def test_exact_drift_equals_a_long_parallel_computation(name, eps, nut_deg, freq_hz, h):
    """100 s of simulation (1000 spin periods): the slope along the precession axis equals the one-step drift to 1e-7."""
    alg, motion = get(name), RegularPrecession(eps, 2 * np.pi * freq_hz, np.radians(nut_deg))
    run = simulate(alg, motion, h, 100.0)
    assert run.drift @ motion.precession_axis() == pytest.approx(exact_drift(alg, motion, h), rel=1e-7)


def test_exact_coning_drift_tends_to_the_closed_form_as_the_cone_closes():
    """u / (α² ω D(ωh)) − 1 = O(α²): 1e-4 rad and 1e-3 rad give deviations 100 times apart, both tiny."""
    alg = get("two-sample")
    D = coning_drift(alg)
    x = 0.05
    closed = float(D.function.evalf(40, subs={X: sp.Rational(x)}))  # the closed form cancels: evaluate it in 40 digits
    dev = [exact_coning_drift(alg, cone_angle=a, nu=1.0, sample_interval=x) / (a**2 * closed) - 1 for a in (1e-3, 1e-4)]
    assert abs(dev[1]) < 1e-7
    assert dev[0] / dev[1] == pytest.approx(100, rel=0.01)


def test_exact_drift_refuses_bad_input():
    with pytest.raises(TypeError, match="algorithm"):
        exact_drift("two-sample", RegularPrecession(-1.0, 1.0, 0.1), 0.01)
    with pytest.raises(ValueError, match="sample_interval"):
        exact_drift(get("two-sample"), RegularPrecession(-1.0, 1.0, 0.1), 0.0)
    with pytest.raises(ValueError, match="cone_angle"):
        exact_coning_drift(get("two-sample"), cone_angle=2.0, nu=1.0, sample_interval=0.01)


def _audit():
    alg = get(AUDIT["name"])
    nu, alpha, h = 2 * np.pi * AUDIT["freq_hz"], np.radians(AUDIT["alpha_deg"]), AUDIT["h"]
    return alg, dict(eps=-1.0, nu=nu, nutation=alpha, step=alg.samples * h), exact_drift(alg, RegularPrecession(-1.0, nu, alpha), h)


def test_the_composition_of_the_steps_closes_the_gap_the_axial_series_leaves():
    """Through h^13 the axial series alone stays 6.6e-4 off the exact drift; with the composition term, 3e-6."""
    alg, kw, exact = _audit()
    s = drift_series_terms(alg, **kw, max_weight=13)
    axial = float(s.terms.sum())
    assert abs(axial / exact - 1) > 5e-4
    assert s.signed_total == pytest.approx(exact, rel=1e-5)
    # second order in the transverse step error: the composition is of the sign and size of −|s_⊥|²/(4 tan(μH/2)) / H
    assert s.composition == pytest.approx(exact - axial, rel=1e-2)


def test_a_fixed_weight_quotes_too_much_and_the_converged_series_does_not():
    """The audit case: through h^9 the series is 5.6 % high; the weight is raised to 13, where it is within 1e-5."""
    alg, kw, exact = _audit()
    nine = drift_series_terms(alg, **kw, max_weight=9)
    assert nine.signed_total / exact - 1 == pytest.approx(0.056, abs=0.002)
    assert nine.truncation_error > 1e-3 * nine.total  # the estimate says so
    s = converged_drift_series(alg, **kw)
    assert s.max_weight == 13 and s.truncation_error <= 1e-3 * s.total
    assert s.signed_total == pytest.approx(exact, rel=1e-5)


CASES = [
    (name, eps, nut_deg, freq_hz, h)
    for name in ("two-sample", "optimal-3", "panov-4s-3", "lebedev-panov-6", "savage-1+1", "ignagni-1996-2", "compressed-4")
    for eps, nut_deg, freq_hz, h in ((-1.0, 1.0, 10.0, 0.0025), (0.5, 5.0, 10.0, 0.004), (-0.5, 60.0, 5.0, 0.005))
]


@pytest.mark.parametrize("name, eps, nut_deg, freq_hz, h", CASES)
def test_truncation_error_estimate_bounds_the_error_against_the_exact_drift(name, eps, nut_deg, freq_hz, h):
    alg = get(name)
    nu, nut = 2 * np.pi * freq_hz, np.radians(nut_deg)
    s = converged_drift_series(alg, eps=eps, nu=nu, nutation=nut, step=alg.samples * h)
    exact = exact_drift(alg, RegularPrecession(eps, nu, nut), h)
    assert abs(s.signed_total - exact) <= s.truncation_error + 1e-12 * abs(exact)
    assert s.truncation_error <= 1e-3 * s.total or s.max_weight == 13


def test_truncation_error_is_unknown_while_the_terms_grow():
    """ignagni-1996-2 at 1°: the weight-7 term exceeds the weight-5 one, so through h^7 nothing bounds the remainder."""
    s = drift_series_terms(get("ignagni-1996-2"), eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0), step=0.005, max_weight=7)
    assert abs(s.terms[7]) > abs(s.terms[5]) and s.truncation_error == np.inf
    vals, _ = drift_terms(get("ignagni-1996-2"), -1.0, np.radians(1.0), max_weight=7)
    assert np.count_nonzero(np.abs(vals) > 0) == 2


# ------------------------------------------------------------------ strapdown drift
def _json(capsys, argv):
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _audit_argv():
    return ["drift", "--algorithm", AUDIT["name"], "--freq-hz", "10", "--sample-interval", repr(AUDIT["h"]), "--duration", "2"]


def test_drift_cli_chooses_the_weight_its_quoted_series_needs(capsys):
    _, _, exact = _audit()
    data = _json(capsys, _audit_argv() + ["--half-angle-deg", "1"])
    assert data["series_weight"] == 13 and data["series_converged"] is True
    assert data["series_drift_deg_per_h"] == pytest.approx(abs(deg_per_h(exact)), rel=1e-5)
    assert data["exact_drift_deg_per_h"] == pytest.approx(abs(deg_per_h(exact)), rel=1e-12)
    assert data["series_truncation_error_deg_per_h"] <= 1e-3 * data["series_drift_deg_per_h"]


def test_drift_cli_says_when_the_series_is_cut_short(capsys):
    argv = _audit_argv() + ["--half-angle-deg", "1", "--max-order", "9"]
    data = _json(capsys, argv)
    assert data["series_weight"] == 9 and data["series_converged"] is False
    assert data["series_drift_deg_per_h"] / data["exact_drift_deg_per_h"] - 1 == pytest.approx(0.056, abs=0.002)
    assert data["series_truncation_error_deg_per_h"] > 0.05 * data["series_drift_deg_per_h"]  # the estimate covers the 5.6 %
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "has not reached --series-rtol" in out and "raise --max-order" in out and "estimated truncation error" in out


def test_drift_cli_takes_classical_coning_parameters(capsys):
    """--half-angle-deg α is the regular precession ε = −1, ϑ = α: the same run, the same numbers."""
    common = ["drift", "--algorithm", "two-sample", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1"]
    coning = _json(capsys, common + ["--half-angle-deg", "2"])
    precession = _json(capsys, common + ["--eps", "-1", "--nutation-deg", "2"])
    assert coning["motion"] == "classical coning" and coning["half_angle_deg"] == 2.0
    assert precession["motion"] == "regular precession" and precession["half_angle_deg"] is None
    for key in ("simulated_drift_deg_per_h", "series_drift_deg_per_h", "exact_drift_deg_per_h", "eps", "nutation_deg"):
        assert coning[key] == precession[key]


@pytest.mark.parametrize(
    "extra, fragment",
    [
        (["--half-angle-deg", "1", "--eps", "-1"], "got --half-angle-deg and --eps"),
        (["--eps", "-1"], "got no --nutation-deg"),
        ([], "got no --eps and --nutation-deg"),
        (["--half-angle-deg", "95"], "--half-angle-deg"),
        (["--half-angle-deg", "1", "--series-rtol", "0"], "--series-rtol"),
    ],
)
def test_drift_cli_motion_options_refused_in_one_line(extra, fragment, capsys):
    argv = ["drift", "--algorithm", "two-sample", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1"] + extra
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and fragment in err and "Traceback" not in err


@pytest.mark.parametrize("name, first", [("two-sample", 9), ("ignagni-1996-5", 7)])
def test_composition_enters_the_series_at_weight_2w_minus_1(name, first):
    """The composition's leading term has weight 2w − 1 (w the lowest weight of the step error across n): below it, no term."""
    from strapdown.analysis.coning.drift_theory import composition_drift

    kw = dict(eps=0.5, nu=2 * np.pi * 10, nutation=np.radians(5.0), step=0.008)
    assert float(composition_drift(get(name), **kw, max_weight=first - 1)) == 0.0
    assert float(composition_drift(get(name), **kw, max_weight=first)) != 0.0
