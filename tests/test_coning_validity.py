"""Where the leading coning term holds: the next term in α, the range of α and ωh, and ``derive coning-drift``.

The reference throughout is the exact drift from one step in extended precision
(:func:`strapdown.analysis.coning.exact_drift.exact_coning_drift`, checked against parallel
computations in ``test_exact_drift.py``); nothing here is checked against the series it prints.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest

from strapdown.analysis.cli import main
from strapdown.analysis.coning.coning_validity import coning_case, leading_term_range, next_coning_term
from strapdown.analysis.coning.drift_theory import coning_drift_function
from strapdown.analysis.coning.exact_drift import exact_coning_drift
from strapdown.derivations.coning.drift import coning_drift
from strapdown.derivations.coning.registry import get


def _json(capsys, argv):
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("name, x", [("two-sample", 0.02), ("ignagni-1996-5", 0.02), ("lebedev-panov-6", 0.02)])
def test_next_term_is_the_alpha4_coefficient_of_the_exact_drift(name, x):
    """(u_exact − α² ω D(ωh)) / (α⁴ ω) at two angles, extrapolated to α → 0 (Richardson, α⁶ removed), against c₄ (ωh)^k."""
    alg = get(name)
    t = next_coning_term(alg)
    D = float(np.asarray(coning_drift_function(alg)(x)))
    quartic = [(exact_coning_drift(alg, cone_angle=a, nu=1.0, sample_interval=x) - a**2 * D) / a**4 for a in (0.02, 0.01)]
    limit = (4 * quartic[1] - quartic[0]) / 3
    series = sum(float(c) * x**k for k, c in t.series)
    assert limit == pytest.approx(series, rel=2e-3)  # the α⁴ series through h^7 leaves O((ωh)²) of its next term
    assert limit == pytest.approx(float(t.coefficient) * x**t.order, rel=0.05)  # its leading term, up to O(x²)


def test_next_term_of_the_optimal_algorithms_starts_at_the_fourth_power():
    for name, c4 in (("two-sample", Fraction(-1, 60)), ("ignagni-1996-5", Fraction(-1, 224))):
        t = next_coning_term(get(name))
        assert (t.order, t.coefficient) == (4, c4)


def _ratio(alg, alpha, x):
    d = coning_drift(alg)
    return float(d.coefficient) * alpha**2 * x**d.order / exact_coning_drift(alg, cone_angle=alpha, nu=1.0, sample_interval=x)


@pytest.mark.parametrize("name, x", [("ignagni-1996-5", 0.1), ("two-sample", 0.3), ("compressed-4", 0.05)])
def test_half_angle_limit_is_where_the_leading_term_leaves_the_tolerance(name, x):
    alg = get(name)
    r = leading_term_range(alg, omega_h=(x,))
    limit = r.half_angle_limits[0]
    assert 0 < limit < math.radians(80)
    assert abs(_ratio(alg, 0.99 * limit, x) - 1) <= 0.1 < abs(_ratio(alg, 1.01 * limit, x) - 1)
    assert all(abs(_ratio(alg, a, x) - 1) <= 0.1 for a in limit * np.logspace(-3, -0.05, 8))  # the whole range below


@pytest.mark.parametrize("name", ["two-sample", "ignagni-1996-5", "panov-4s-3"])
def test_omega_h_limit_agrees_with_the_closed_form(name):
    """As α → 0 the exact drift is α² ω D(ωh): the leading term leaves 10 % of the closed form at the same ωh."""
    alg = get(name)
    d = coning_drift(alg)
    r = leading_term_range(alg, omega_h=(0.01,))
    x = r.omega_h_limit
    D = coning_drift_function(alg)
    deviation = [abs(float(d.coefficient) * y**d.order / float(np.asarray(D(y))) - 1) for y in (0.99 * x, 1.01 * x)]
    assert deviation[0] <= 0.1 < deviation[1]


def test_the_audit_case_is_outside_the_range():
    """ignagni-1996-5 at α = 1°, 10 Hz, h = 1/480 s: the leading term is 13 times the exact drift."""
    case = coning_case(get("ignagni-1996-5"), cone_angle=math.radians(1.0), nu=2 * math.pi * 10, sample_interval=1 / 480)
    assert case.ratio == pytest.approx(13.1, abs=0.1) and case.within is False
    assert case.cone_angle > case.range.half_angle_limits[0]


def test_range_refuses_bad_input():
    with pytest.raises(ValueError, match="tolerance"):
        leading_term_range(get("two-sample"), tolerance=1.5)
    with pytest.raises(ValueError, match="omega_h"):
        leading_term_range(get("two-sample"), omega_h=(0.0,))
    with pytest.raises(TypeError, match="algorithm"):
        leading_term_range("two-sample")


# ------------------------------------------------------------------ derive coning-drift
AUDIT = ["derive", "coning-drift", "--algorithm", "ignagni-1996-5", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", repr(1 / 480)]


def test_derive_coning_drift_warns_on_the_audit_case(capsys):
    data = _json(capsys, AUDIT)
    case = data["case"]
    assert case["within_range"] is False and case["leading_over_exact"] == pytest.approx(13.1, abs=0.1)
    assert case["exact_drift_deg_per_h"] == pytest.approx(2.0594e-8, rel=1e-4)
    assert case["half_angle_limit_deg"] < 1.0 and len(data["warnings"]) == 1 and "13.1×" in data["warnings"][0]
    assert data["next_term"]["power"] == 4 and data["next_term"]["coefficient"] == "-1/224"
    assert data["coning_drift_order"] == 8
    assert main(AUDIT) == 0
    out = capsys.readouterr().out
    assert "next term in α: -1/224 · α⁴ ω (ωh)^4" in out and "warning: the leading term is 13.1× the exact drift" in out


def test_derive_coning_drift_case_inside_the_range_has_no_warning(capsys):
    argv = ["derive", "coning-drift", "--algorithm", "two-sample", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025"]
    data = _json(capsys, argv)
    assert data["case"]["within_range"] is True and data["warnings"] == []
    assert data["case"]["leading_over_exact"] == pytest.approx(1.0, abs=0.02)


def test_derive_coning_drift_prints_the_range(capsys):
    data = _json(capsys, ["derive", "coning-drift", "--algorithm", "two-sample", "--omega-h-rad", "0.1,0.5"])
    rng = data["leading_term_range"]
    assert rng["tolerance"] == 0.1 and 0.5 < rng["omega_h_limit_rad"] < 1.0
    limits = {row["omega_h_rad"]: row["half_angle_limit_deg"] for row in rng["half_angle_limits"]}
    assert set(limits) == {0.1, 0.5} and all(10 < a < 30 for a in limits.values())
    assert main(["derive", "coning-drift", "--algorithm", "two-sample"]) == 0
    out = capsys.readouterr().out
    assert "the leading term is within 10% of the exact drift" in out and "as α → 0: for ωh ≤" in out


@pytest.mark.parametrize(
    "extra, fragment",
    [
        (["--half-angle-deg", "1", "--freq-hz", "10"], "got no --sample-interval"),
        (["--half-angle-deg", "85", "--freq-hz", "10", "--sample-interval", "0.001"], "--half-angle-deg"),
        (["--half-angle-deg", "1", "--freq-hz", "1000", "--sample-interval", "0.01"], "ωh"),
        (["--tolerance", "0"], "--tolerance"),
        (["--tolerance", "1e-320"], "--tolerance"),
        (["--half-angle-deg", "1e-300", "--freq-hz", "10", "--sample-interval", "0.001"], "--half-angle-deg"),
        (["--half-angle-deg", "1", "--freq-hz", "1e-9", "--sample-interval", "0.001"], "ωh"),
        (["--omega-h-rad", "5"], "--omega-h-rad"),
    ],
)
def test_derive_coning_drift_bad_case_exit_2(extra, fragment, capsys):
    assert main(["derive", "coning-drift", "--algorithm", "two-sample"] + extra) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and fragment in err and "Traceback" not in err
