"""Identification of integrators as exact algorithms, and the integrators against the exact solution.

The four points of the work that this checks:

* round trip: every registry algorithm, run from its own terms as a black box, is identified with its exact
  pairwise coefficients (and pyins's integrator as Savage's 1 + 1); the closed-form drift of what was identified
  agrees with the integrator's own simulated drift within 1e-6 relative wherever the round-off floor resolves it;
* the shifted recursion is identified with its true, lower order and coefficient, and its own simulation agrees;
* a composition of exact rotations is identified by its bilinear part, with a remainder of degree three;
* bad integrators get clear messages (also tests/test_integrator_interface.py).
"""

from __future__ import annotations

import json
from fractions import Fraction

import numpy as np
import pytest

from strapdown.analysis.coning.integrators.adapters import algorithm_integrator
from strapdown.analysis.coning.integrators.assessment import assess, linear_error_weight, work
from strapdown.analysis.coning.integrators.identification import identify, max_denominator, probe_samples, rational
from strapdown.analysis.coning.integrators.interface import Integrator
from strapdown.analysis.coning.integrators.recursions import quaternion_composition, recursion
from strapdown.analysis.coning.integrators.sculling_terms import ScullingTerms
from strapdown.analysis.coning.integrators.verification import coning_drift_check, sculling_check, sculling_points
from strapdown.analysis.coning.sculling_motion import ScullingMotion, rectification_error
from strapdown.derivations.coning.algorithms import Algorithm, Term, load_toml, second_order_defect
from strapdown.derivations.coning.drift import coning_drift
from strapdown.derivations.coning.registry import get, names

#: Three ωh where the drift of every registry algorithm is resolved somewhere (the fourth default, 0.25, adds little).
OMEGA_H = (0.5, 1.0, 2.0)


# --------------------------------------------------------------------------- rational reconstruction
def test_rational_reconstruction_is_unique_within_its_tolerance():
    q = max_denominator(1e-9)
    assert q == 22360 and 2 * 1e-9 < 1 / q**2
    assert rational(463 / 924 + 3e-10) == Fraction(463, 924)
    assert rational(0.1 + 5e-9) is None  # no fraction within 1e-9 with q ≤ 22360
    assert rational(1 / 22361) is None  # beyond the denominators the tolerance can tell apart
    with pytest.raises(ValueError, match="tolerance"):
        max_denominator(0.0)


# --------------------------------------------------------------------------- round trip
@pytest.mark.parametrize("name", names(library=True))
def test_every_registry_algorithm_is_recovered_exactly(name):
    alg = get(name)
    ident = identify(algorithm_integrator(alg, velocity=False), alg.samples, max_previous=max(alg.history, 1))
    assert ident.exact and ident.isotropic
    assert ident.algorithm().pairwise == alg.pairwise
    assert ident.linear_is_sum
    assert ident.history == alg.history
    nonlinear = any(t.dots or not all(isinstance(x, int) for x in t.cross) for t in alg.terms)
    if nonlinear:  # the nested terms of Lebedev & Panov's sixth-order algorithm: degree three
        assert ident.remainder.degree == 3
    else:
        assert not ident.remainder.above_roundoff


@pytest.mark.parametrize("name", names(library=True))
def test_closed_form_drift_of_the_identified_algorithm_matches_the_integrator(name):
    alg = get(name)
    integ = algorithm_integrator(alg, velocity=False)
    ident = identify(integ, alg.samples, max_previous=alg.history)
    check = coning_drift_check(integ, alg.samples, ident.algorithm(), omega_h=OMEGA_H)
    assert check.holds is True, [(p.x, p.relative_difference, p.uncertainty) for p in check.points]
    assert check.largest_difference <= 1e-6
    for p in check.resolved:  # resolved: the round-off and the extrapolation leave the comparison a tenth of the tolerance
        assert p.uncertainty <= 1e-7 * abs(p.closed_form)


def test_the_drift_check_can_fail():
    """Savage's recursion against the closed form of the shifted one: every resolved point disagrees."""
    n = 4
    shifted = identify(recursion(alpha_lag=2), n, max_previous=2).algorithm()
    check = coning_drift_check(recursion(), n, shifted, omega_h=OMEGA_H)
    assert check.holds is False
    assert all(p.agrees is False for p in check.resolved)


def test_pyins_is_savage_one_plus_one_exactly():
    pytest.importorskip("pyins")
    from strapdown.analysis.coning.integrators.peers import pyins_increments, pyins_integrator

    savage = get("savage-1+1")
    for integ in (pyins_integrator(), pyins_increments()):
        a = assess(integ, 1, omega_h=OMEGA_H)
        assert a.identification.terms == {"0,1": "1/12"}
        assert a.algorithm.pairwise == savage.pairwise and a.consistency.consistent
        assert (a.coning.order, a.coning.coefficient) == (4, Fraction(1, 60))
        assert not a.identification.remainder.above_roundoff
        assert a.check.holds is True and a.check.largest_difference <= 1e-6
        if integ.velocity:  # its sculling term is the dual extension of its coning term
            assert a.sculling.dual_extension
            assert a.sculling.terms == ScullingTerms.dual_extension(savage)
            assert a.sculling.check.holds is True


# --------------------------------------------------------------------------- the shifted recursion
def _by_hand(n: int, alpha_lag: int) -> Algorithm:
    """The recursion expanded by hand: ½ α_(m−lag) × Δα_m and (1/12) Δα_(m−1) × Δα_m, summed over the step."""
    c: dict = {}
    for m in range(1, n + 1):
        for i in range(1, m - alpha_lag + 1):  # α_(m−lag) = p_1 + … + p_(m−lag)
            c[(i, m)] = c.get((i, m), Fraction(0)) + Fraction(1, 2)
        c[(m - 1, m)] = c.get((m - 1, m), Fraction(0)) + Fraction(1, 12)
    return Algorithm(f"hand-{n}-{alpha_lag}", n, tuple(Term(v, k) for k, v in c.items()))


@pytest.mark.parametrize("n", [2, 3, 5])
def test_shifted_recursion_has_its_true_lower_order(n):
    a = assess(recursion(alpha_lag=2), n, max_previous=2, omega_h=OMEGA_H)
    hand = _by_hand(n, 2)
    assert a.algorithm.pairwise == hand.pairwise
    assert second_order_defect(a.algorithm) == Fraction(-(n - 1), 2)  # − (N − 1)/2: the second-order condition fails
    assert not a.consistency.consistent and a.consistency.first_order
    drift = coning_drift(hand)
    assert (a.order, a.coning.order, a.coning.coefficient) == (2, 2, drift.coefficient)
    assert abs(a.local_error_exponent - 3.0) < 0.05  # its own one-step error: O(h³)
    assert a.check.holds is True and a.check.largest_difference <= 1e-6
    correct = assess(recursion(), n, max_previous=2, verify=False)
    assert correct.algorithm.pairwise == _by_hand(n, 1).pairwise
    assert (correct.order, correct.coning.order, correct.coning.coefficient) == (3, 4, Fraction(1, 60))


# --------------------------------------------------------------------------- a nonlinear integrator
@pytest.mark.parametrize("n", [2, 3, 4])
def test_quaternion_composition_is_its_bilinear_part_plus_a_cubic_remainder(n):
    a = assess(quaternion_composition(), n, max_previous=1, omega_h=OMEGA_H)
    assert a.algorithm.pairwise == {(i, j): Fraction(1, 2) for i in range(1, n + 1) for j in range(i + 1, n + 1)}
    assert a.identification.exact
    r = a.identification.remainder
    assert r.degree == 3 and abs(r.slope - 3.0) < 0.05
    assert second_order_defect(a.algorithm) == Fraction(-n, 12)
    assert a.order == 2 and abs(a.local_error_exponent - 3.0) < 0.05
    assert a.check.holds is True and a.check.largest_difference <= 1e-6


def test_two_sample_composition_remainder_is_the_bch_cubic_term():
    """log(exp a exp b) − (a + b + ½ a×b) = (1/12)(a×(a×b) + b×(b×a)) + O(5): the measured remainder at small scale."""
    ident = identify(quaternion_composition(), 2, max_previous=0)
    rng = np.random.default_rng(3)
    p = 1e-4 * rng.standard_normal((2, 3))
    got = quaternion_composition().function(p.copy(), 2)[0]
    a, b = p
    model = a + b + 0.5 * np.cross(a, b)
    cubic = (np.cross(a, np.cross(a, b)) + np.cross(b, np.cross(b, a))) / 12
    np.testing.assert_allclose(got - model, cubic, rtol=1e-3)  # the next term is of degree four: 1e-4 of this
    assert ident.remainder.degree == 3


# --------------------------------------------------------------------------- what the model cannot capture
def test_longer_memory_than_probed_shows_in_the_remainder():
    alg = get("ignagni-1996-4")  # reads three samples back
    ident = identify(algorithm_integrator(alg, velocity=False), alg.samples, max_previous=2)
    assert ident.at_limit
    assert ident.remainder.degree == 2


def test_an_axis_treated_differently_is_reported():
    def skewed(g, n):
        p = g.reshape(-1, n, 3)
        out = p.sum(axis=1) + 0.5 * np.cross(p[:, 0], p[:, 1])
        out[:, 2] *= 1.0 + 0.5 * (np.abs(p[:, 0, 0]) > 0)  # the z component depends on x
        return out

    ident = identify(Integrator(skewed, name="skewed"), 2, max_previous=1)
    assert not ident.isotropic


def test_a_wrong_linear_part_is_reported_not_refused():
    def dropped(g, n):  # the first sample of each step counted twice, the last not at all
        p = g.reshape(-1, n, 3)
        return 2 * p[:, 0] + p[:, 1:-1].sum(axis=1)

    a = assess(Integrator(dropped, name="dropped"), 3, max_previous=1)
    assert not a.consistency.first_order and not a.consistency.consistent
    assert a.identification.linear_part == {1: Fraction(2), 2: Fraction(1)}
    assert linear_error_weight(a.identification.linear_part, 3) == 2
    assert a.order == 1 and a.coning is None and a.check is None
    json.dumps(a.as_dict(), allow_nan=False)


def test_a_constant_output_is_a_remainder_of_degree_zero():
    ident = identify(Integrator(lambda g, n: g.reshape(-1, n, 3).sum(axis=1) + 1e-6, name="bias"), 1, max_previous=1)
    assert ident.remainder.constant == pytest.approx(np.sqrt(3) * 1e-6)
    assert ident.remainder.above_roundoff
    assert ident.terms == {} and ident.exact


def test_a_noisy_integrator_is_approximate_not_refused():
    def single(g, n):  # single precision arithmetic: coefficients known to about 1e-6 only
        p = g.reshape(-1, n, 3).astype(np.float32)
        return (p.sum(axis=1) + np.float32(2 / 3) * np.cross(p[:, 0], p[:, 1])).astype(float)

    ident = identify(Integrator(single, name="single"), 2, max_previous=0)
    assert not ident.exact
    assert abs(float(ident.pairwise[(1, 2)].fraction) - 2 / 3) < 1e-3
    assert "not reconstructed" in ident.toml()


# --------------------------------------------------------------------------- sculling
@pytest.mark.parametrize("name", ["savage-1+1", "two-sample", "optimal-3", "ignagni-1996-2", "compressed-4"])
def test_sculling_closed_form_is_the_package_rectification_error_for_a_dual_extension(name):
    """Two derivations of the same rate: the general bilinear form here, the dual-extension form of sculling_motion."""
    alg = get(name)
    motion = ScullingMotion(1e-3, 2.0, 2 * np.pi * 10, angle_phase=0.3, accel_phase=1.1)
    for h in (0.002, 0.005):
        mine = ScullingTerms.dual_extension(alg).rectification_error(motion, h)
        ref = rectification_error(alg, motion, h)
        assert mine.rate == pytest.approx(ref.rate, rel=1e-12, abs=1e-25)


def test_sculling_is_identified_and_checked():
    a = assess(recursion(velocity=True), 3, max_previous=1)
    assert a.sculling.dual_extension and not a.sculling.remainder.above_roundoff
    assert a.sculling.check.holds is True and a.sculling.check.largest_difference <= 1e-6
    comp = assess(quaternion_composition(velocity=True), 2, max_previous=1)
    assert {key: d for _, key, d in comp.sculling.defect} == {(1, 1): Fraction(-1, 2), (2, 2): Fraction(-1, 2)}
    assert comp.sculling.check.holds is True


def test_the_sculling_check_can_fail():
    terms = ScullingTerms.dual_extension(get("two-sample"))
    check = sculling_check(quaternion_composition(velocity=True), 2, terms)
    assert check.holds is False


def test_sculling_points_avoid_a_step_of_half_a_period():
    for n in range(1, 13):
        for x in sculling_points(n):
            k = 2 * np.pi / x
            assert abs(k - round(k)) < 1e-9 and (2 * n) % round(k) != 0


# --------------------------------------------------------------------------- algorithm files and estimates
def test_identified_algorithm_round_trips_through_an_algorithm_file(tmp_path):
    ident = identify(recursion(alpha_lag=2), 4, max_previous=2)
    path = tmp_path / "px4.toml"
    path.write_text(ident.toml("px4-4"))
    loaded = load_toml(path, allow_inconsistent=True)
    assert loaded.name == "px4-4" and loaded.samples == 4 and loaded.pairwise == ident.algorithm().pairwise
    assert "second-order condition missed" in path.read_text()


def test_probe_count_and_work_estimate():
    ident = identify(recursion(velocity=True), 3, max_previous=2)
    assert ident.probe_samples == probe_samples(3, 2, velocity=True)
    est = work(recursion(), 3, max_previous=2)
    assert est.seconds > 0 and "identifying" in est.what
