"""Local-error series: exact increment, algorithm series, Table 2 and eq. (2.4)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.dual import Dual
from strapdown.derivations.coning import published as P
from strapdown.derivations.coning import series as S
from strapdown.derivations.coning.algorithms import Algorithm, Term
from strapdown.derivations.coning.registry import get, names


def _eval(vec, values):
    """Evaluate a vector of ring polynomials at ω^(k) = values[k] (shape (7, 3))."""
    flat = np.asarray(values, dtype=float).reshape(-1)
    out = []
    for comp in vec:
        total = 0.0
        for monom, coeff in comp.items():
            term = float(coeff)
            for i, e in enumerate(monom):
                if e:
                    term *= flat[i] ** e
            total += term
        out.append(total)
    return np.array(out)


# ------------------------------------------------------------------ exact increment
def _reference_rotvec(derivs, H):
    """Rotation vector over [−H/2, H/2] of 2Λ' = Λ∘ω for polynomial ω (DOP853, rtol 1e-13)."""
    from math import factorial

    def omega(t):
        return sum(derivs[k] * t**k / factorial(k) for k in range(len(derivs)))

    def rhs(t, q):
        return 0.5 * quat.multiply(q, np.concatenate([[0.0], omega(t)]))

    sol = solve_ivp(rhs, (-H / 2, H / 2), [1.0, 0, 0, 0], method="DOP853", rtol=1e-13, atol=1e-15)
    return quat.quat_to_rotvec(sol.y[:, -1])


def test_exact_series_low_order_terms():
    ex = dict(S.exact_words())
    assert ex[(0,)] == 1 and ex[(2,)] == Fraction(1, 24) and ex[(0, 1)] == Fraction(1, 12)


def test_exact_series_matches_integration_to_ninth_order():
    rng = np.random.default_rng(4)
    derivs = rng.normal(size=(7, 3))
    errors = []
    for H in (0.4, 0.2):
        series = _eval(S.exact_increment(), derivs * np.array([H ** (k + 1) for k in range(7)])[:, None])
        errors.append(np.linalg.norm(series - _reference_rotvec(derivs, H)))
    # truncation at weight 7; the midpoint expansion has no even weights, so the
    # remainder is O(H^9): halving H divides the error by ~512
    assert errors[0] / errors[1] == pytest.approx(512, rel=0.1)
    assert all(not any(S.weight_part(S.exact_increment(), w)) for w in (2, 4, 6))


def test_half_step_series_consistent_with_full_step():
    """exp(φ_[−½,0]) ∘ exp(φ_[0,½]) = exp(φ_[−½,½]) on random derivatives (small step)."""
    rng = np.random.default_rng(5)
    d = rng.normal(size=(7, 3)) * 0.05 ** np.arange(1, 8)[:, None]
    q1 = quat.rotvec_to_quat(_eval(S.exact_increment(Fraction(-1, 2), Fraction(0)), d))
    q2 = quat.rotvec_to_quat(_eval(S.exact_increment(Fraction(0), Fraction(1, 2)), d))
    full = _eval(S.exact_increment(), d)
    np.testing.assert_allclose(quat.quat_to_rotvec(quat.multiply(q1, q2)), full, atol=1e-14)


# ------------------------------------------------------------------ algorithm series
@pytest.mark.parametrize("name", names())
def test_algorithm_series_matches_numeric_evaluation(name):
    """The symbolic Δφ equals strapdown.analysis.coning.evaluation.increment on the increments of a polynomial ω(t)."""
    from strapdown.analysis.coning.evaluation import increment

    alg = get(name)
    rng = np.random.default_rng(6)
    d = rng.normal(size=(7, 3)) * 0.1 ** np.arange(1, 8)[:, None]  # H = 1, small rates
    N = alg.samples
    p = np.array([_eval(pj, d) for pj in S.increments(N)])
    symbolic = _eval(S.algorithm_series(alg), d)
    numeric = increment(alg, p)
    # symbolic is truncated at weight 7: the difference is O(0.1^8)
    np.testing.assert_allclose(symbolic, numeric, atol=1e-8, rtol=0)


@pytest.mark.parametrize(
    "name, order",
    [("two-sample", 4), ("optimal-3", 4), ("lebedev-panov-2", 2), ("lebedev-panov-4", 4), ("lebedev-panov-6", 6)]
    + [(f"panov-4s-{k}", 4) for k in range(1, 6)],
)
def test_orders(name, order):
    assert S.local_error(get(name)).order == order


# ------------------------------------------------------------------ Table 2
# Budennyi, Kalinovsky, Panov et al. (Part 2), Table 2: δ4 and k03, k12, k002, k110, k0001,
# convention exact − algorithm, coefficient of h^5.  Entries marked "erratum" are
# contradicted by the derivation (evidence in reports/derivations.md).
_TABLE_2_ERRATA = {4: {2: 448, 4: -448}}
TABLE_2 = [(c.algorithm, c.delta, c.k, _TABLE_2_ERRATA.get(c.algorithm)) for c in P.BUDENNYI_TABLE_2]


@pytest.mark.parametrize("number, delta, printed, erratum", TABLE_2)
def test_table_2(number, delta, printed, erratum):
    derived = S.error_coefficients(get(f"panov-4s-{number}"))
    products = [derived.delta * derived.coefficients[w] for w in S.ORDER4_BASIS]
    expected = [delta * k for k in printed]
    for i, (got, want) in enumerate(zip(products, expected)):
        if erratum and i in erratum:
            assert got != want
            assert got == delta * erratum[i]
        else:
            assert got == want


@pytest.mark.parametrize("number", [2, 3, 4, 5])
def test_table_2_normalisation(number):
    """δ4 = 1/lcm of the denominators reproduces the printed δ4 (algorithm 1 factors a further 4)."""
    delta = dict((n, d) for n, d, _, _ in TABLE_2)[number]
    assert S.error_coefficients(get(f"panov-4s-{number}")).delta == delta


def test_table_1_row_2_as_printed_contradicts_table_2():
    """4/3 (p1×p3 + p2×p4), Table 1 row 2 as printed, gives k12 = 4, not the printed 124."""
    printed_row = Algorithm("t1-row2", 4, (Term(Fraction(4, 3), (1, 3)), Term(Fraction(4, 3), (2, 4))))
    c = S.error_coefficients(printed_row)
    assert c.delta * c.coefficients[(1, 2)] == Fraction(4, 45)


# ------------------------------------------------------------------ eq. (2.4)
# Lebedev & Panov (1989), eq. (2.4): δφ = c h^7 (Σ c_w x_w), c = P.EQ_2_4_FACTOR, exact − algorithm.
EQ_2_4 = P.EQ_2_4


def _eq_2_4():
    return S.lie_vector([(tuple(int(ch) for ch in k), P.EQ_2_4_FACTOR * v) for k, v in EQ_2_4.items()])


def test_eq_2_4_equals_derived_series_exactly():
    err = S.local_error(get("lebedev-panov-6"))
    assert all(not any(err.parts[w]) for w in range(7))
    derived = err.part(7, unit="h")
    assert all(a == b for a, b in zip(derived, _eq_2_4()))


def test_eq_2_4_by_value_on_random_derivatives():
    rng = np.random.default_rng(24)
    derived = S.local_error(get("lebedev-panov-6")).part(7, unit="h")
    printed = _eq_2_4()
    for _ in range(5):
        d = rng.normal(size=(7, 3))
        np.testing.assert_allclose(_eval(derived, d), _eval(printed, d), rtol=1e-12, atol=1e-12)


def test_eq_2_4_detects_a_changed_coefficient():
    """A one-unit change of any printed coefficient is caught (the comparison can fail)."""
    derived = S.local_error(get("lebedev-panov-6")).part(7, unit="h")
    wrong = dict(EQ_2_4, **{"1101": 245})
    vec = S.lie_vector([(tuple(int(ch) for ch in k), P.EQ_2_4_FACTOR * v) for k, v in wrong.items()])
    assert any(a != b for a, b in zip(derived, vec))


def test_dot_product_term_cancels_fourth_order_x0001():
    """Without (p2·p3) p2×p3 the printed sixth-order algorithm drops to order 4 (x0001 remains)."""
    lp6 = get("lebedev-panov-6")
    trimmed = Algorithm("trim", 4, tuple(t for t in lp6.terms if not t.dots))
    c = S.error_coefficients(trimmed)
    assert c.order == 4
    assert [w for w, v in c.coefficients.items() if v] == [(0, 0, 0, 1)]


# ------------------------------------------------------------------ bases and the dual part
def test_canonical_basis_weight_5_is_order4_basis():
    assert set(S.canonical_basis(5)) - {(4,)} == {(0, 3), (1, 2), (0, 0, 2), (1, 0, 1), (0, 0, 0, 1)}


def test_express_rejects_vector_outside_span():
    with pytest.raises(ValueError, match="span"):
        S.express(S.nested((0, 3)), [(1, 2)])


def test_dual_words_is_the_transfer_principle():
    """Dual part of x_w(ω + s a) (Dual arithmetic) = Σ_i x_w with a in place i."""
    rng = np.random.default_rng(7)
    w_re, w_du = rng.normal(size=(7, 3)), rng.normal(size=(7, 3))
    word = (1, 0, 0, 2)

    def nested_num(vals, word):
        v = vals[word[-1]]
        for k in reversed(word[:-1]):
            v = quat.cross(vals[k], v)
        return v

    dual = nested_num([Dual(w_re[k], w_du[k]) for k in range(7)], word)
    total = np.zeros(3)
    for w, i, c in S.dual_words([(word, Fraction(1))]):
        # only position i is replaced, even when the letter repeats
        v = w_re[w[-1]] if i != len(w) - 1 else w_du[w[-1]]
        for pos in range(len(w) - 2, -1, -1):
            v = quat.cross(w_du[w[pos]] if pos == i else w_re[w[pos]], v)
        total += float(c) * v
    np.testing.assert_allclose(dual.du, total, atol=1e-12)


# ------------------------------------------------------------------ any weight
#: Savage's "1 + 1" algorithm: one sample per step and the last sample of the previous step,
#: Δφ = p_1 + (1/12) p_0 × p_1 (Savage 1998).  Defined here: the registry of this module's
#: branch does not carry it.
SAVAGE = Algorithm("savage-1+1", 1, (Term(Fraction(1, 12), (0, 1)),), "Savage 1 + 1", "Savage (1998)")


def _polynomial_motion(derivs):
    """ω(t) = Σ_k derivs[k] t^k / k! about t = 0, its exact increments and the DOP853 rotation vector."""
    from math import factorial

    K = len(derivs)

    def integral(a, b):
        return sum(derivs[k] * (b ** (k + 1) - a ** (k + 1)) / factorial(k + 1) for k in range(K))

    def rotvec(a, b):
        def rhs(t, q):
            w = sum(derivs[k] * t**k / factorial(k) for k in range(K))
            return 0.5 * quat.multiply(q, np.concatenate([[0.0], w]))

        sol = solve_ivp(rhs, (a, b), [1.0, 0, 0, 0], method="DOP853", rtol=1e-13, atol=1e-16)
        return quat.quat_to_rotvec(sol.y[:, -1])

    return integral, rotvec


def _eval_many(vec, derivs):
    flat = np.zeros(3 * S.WEIGHT_LIMIT)
    flat[: derivs.size] = np.asarray(derivs, dtype=float).reshape(-1)
    return _eval(vec, flat.reshape(-1, 3))


def test_exact_increment_to_weight_13_matches_integration():
    """Through h^13 the series leaves O(H^15) (no even weights): halving H divides the error by ~2^15."""
    rng = np.random.default_rng(13)
    derivs = rng.normal(size=(13, 3))
    errors = []
    for H in (0.5, 0.25):
        _, rotvec = _polynomial_motion(derivs)
        scaled = derivs * np.array([H ** (k + 1) for k in range(13)])[:, None]
        errors.append(np.linalg.norm(_eval_many(S.exact_increment(max_weight=13), scaled) - rotvec(-H / 2, H / 2)))
    assert errors[0] / errors[1] == pytest.approx(2**15, rel=0.15)
    assert all(not any(S.weight_part(S.exact_increment(max_weight=13), w)) for w in (2, 4, 6, 8, 10, 12))


def test_series_of_higher_weight_extends_the_lower_one():
    """Asking for h^9 after h^7 keeps the parts of weight ≤ 7 (they are built once, by weight)."""
    alg = get("panov-4s-5")
    low, high = S.local_error(alg, 7), S.local_error(alg, 9)
    assert high.parts[:8] == low.parts and high.max_weight == 9
    assert S.exact_increment_series().part(7) is S.exact_increment_series().part(7)
    assert all(a == b for a, b in zip(S.exact_increment(max_weight=9), tuple(x + y for x, y in zip(S.exact_increment(), S.weight_part(S.exact_increment(max_weight=9), 9)))))


@pytest.mark.parametrize("bad, exc", [(0, ValueError), (S.WEIGHT_LIMIT + 1, ValueError), (7.0, TypeError), (True, TypeError)])
def test_max_weight_is_validated(bad, exc):
    with pytest.raises(exc, match="max_weight"):
        S.local_error(get("two-sample"), bad)


#: A made-up algorithm with pairs and a triple product reaching two samples back.
TWO_PLUS_TWO = Algorithm("two-plus-two", 2, (Term(Fraction(32, 45), (1, 2)), Term(Fraction(-1, 180), (-1, 1)), Term(Fraction(-1, 90), (0, 2)), Term(Fraction(1, 7), (0, (1, -1)))))


@pytest.mark.parametrize("alg", [SAVAGE, TWO_PLUS_TWO])
def test_cross_step_series_matches_direct_computation(alg):
    """Indices ≤ 0: the series through h^9 equals Δφ_exact − Δφ_alg computed from exact increments and DOP853.

    ω(t) is a polynomial about the middle of the current step; the increments of
    the earlier samples are its exact integrals over the intervals before the step.
    """
    from strapdown.analysis.coning.evaluation import increment

    rng = np.random.default_rng(9)
    derivs = rng.normal(size=(9, 3))
    integral, rotvec = _polynomial_motion(derivs)
    N, residuals = alg.samples, []
    for H in (0.4, 0.2):
        h = H / N
        window = np.array([integral(-H / 2 + (j - 1) * h, -H / 2 + j * h) for j in range(alg.first_index, N + 1)])
        direct = rotvec(-H / 2, H / 2) - increment(alg, window)
        scaled = derivs * np.array([H ** (k + 1) for k in range(9)])[:, None]
        series = sum(_eval_many(part, scaled) for part in S.local_error(alg, 9).parts)
        residuals.append(np.linalg.norm(series - direct))
    # the remainder starts at weight 10: the residual falls by 2^10 per halving of H
    assert residuals[0] / residuals[1] == pytest.approx(2**10, rel=0.2)
    assert residuals[1] < 1e-9


def _chebyshev_derivatives(motion, t, count, radius=0.05):
    """ω and its derivatives at t of a TumblingMotion, from a Chebyshev fit (test-side oracle)."""
    nodes = t + radius * np.cos(np.pi * (np.arange(61) + 0.5) / 61)
    w = motion.omega(nodes)
    out = np.empty((count, 3))
    for c in range(3):
        fit = np.polynomial.Chebyshev.fit(nodes, w[:, c], 30, domain=[t - radius, t + radius])
        for k in range(count):
            out[k, c] = fit.deriv(k)(t) if k else fit(t)
    return out


def test_savage_local_error_on_a_tumbling_motion():
    """Savage 1 + 1 on a closed-form tumbling motion, with the sample of the previous step.

    Independent of the series: the exact rotation comes from the closed-form
    attitude and the increments from Gauss–Legendre quadrature.  The local error is
    O(h⁴) (order 3), and its h⁴ coefficient equals the series' ``(1/24) ω × ω''``.
    """
    from strapdown.analysis.coning.evaluation import increment
    from strapdown.analysis.coning.local_error import TumblingMotion

    motion = TumblingMotion()
    t_mid = 0.7
    lead = S.local_error(SAVAGE).part(4, unit="h")
    derivs = _chebyshev_derivatives(motion, t_mid, 3)
    predicted = _eval_many(lead, derivs)
    errors = []
    for h in (0.02, 0.01, 0.005):
        t0 = t_mid - h / 2
        window = motion.increments(t0 - h, h, 2)  # p_0 (previous step) and p_1
        exact = quat.quat_to_rotvec(quat.multiply(quat.conjugate(motion.attitude(t0)), motion.attitude(t0 + h)))
        errors.append((exact - increment(SAVAGE, window)) / h**4)
    errors = np.array(errors)
    # (δφ/h⁴) → the h⁴ coefficient, with an O(h) remainder
    dev = np.linalg.norm(errors - predicted, axis=-1)
    assert dev[-1] < 0.02 * np.linalg.norm(predicted)
    assert dev[1] / dev[2] == pytest.approx(2, rel=0.2)
    assert S.local_error(SAVAGE).order == 3
    c = S.error_coefficients(SAVAGE)
    assert (c.order, c.delta, c.coefficients[(0, 2)]) == (3, Fraction(1, 24), 1)


def test_optimal_six_sample_to_weight_13():
    """The compressed optimal 6-sample algorithm: order 3 for general motion, its series runs to h^13."""
    from strapdown.derivations.coning.drift import optimal_coning_algorithm

    err = S.local_error(optimal_coning_algorithm(6), 13)
    assert err.order == 3 and err.max_weight == 13
    assert [w for w, p in enumerate(err.parts) if any(p)] == list(range(4, 14))


# ------------------------------------------------------------------ graded series
def test_rotation_quaternion_and_vector_are_inverse():
    """log(exp(v)) = v weight by weight, and exp(v) is a unit quaternion (the one-step error rests on both)."""
    from strapdown.derivations.coning import graded as G

    v = S.exact_increment_series()
    q = G.rotation_quaternion(v)
    back = G.rotation_vector(q)
    for w in range(1, 10):
        assert back.part(w) == v.part(w)
    norm = G.combine([(1, G.dot(G.components(q, (0, 1, 2)), G.components(q, (0, 1, 2)))), (1, G.times(G.components(q, (3,)), G.components(q, (3,))))])
    assert norm.part(0)[0] == 1 and all(not norm.part(w)[0] for w in range(1, 10))


def test_graded_power_series_rejects_a_weight_zero_argument():
    from strapdown.derivations.coning import graded as G

    one = G.Graded.from_parts(S.RING, 1, {0: (S.RING.one,)})
    with pytest.raises(ValueError, match="weight 1"):
        G.power_series(one, lambda k: 1)


# ------------------------------------------------------------------ every weight of the local error
def _word(key: str) -> tuple:
    """``"x02"`` → (0, 2); ``"x0,10"`` → (0, 10) (the key syntax of ``derive local-error``)."""
    body = key[1:]
    return tuple(int(k) for k in (body.split(",") if "," in body else body))


def _nested_value(word, derivs):
    v = derivs[word[-1]]
    for k in reversed(word[:-1]):
        v = np.cross(derivs[k], v)
    return v


@pytest.mark.parametrize("name, window_start, remainder", [("two-sample", 0, 9), ("savage-1+1", 1, 8)])
def test_local_error_json_series_of_every_weight_is_the_local_error(name, window_start, remainder, capsys):
    """``derive local-error --max-order 7`` gives every weight; summed, they leave only the remainder beyond h⁷ of the true local error.

    A symmetric within-step algorithm (two-sample) has no even weight, so its remainder starts at h⁹.

    Independent of the series: the exact rotation from the closed-form tumbling attitude, the
    increments by quadrature, ω and its derivatives from a Chebyshev fit.
    """
    import json

    from strapdown.analysis.cli import main
    from strapdown.analysis.coning.evaluation import increment
    from strapdown.analysis.coning.local_error import TumblingMotion

    assert main(["derive", "local-error", "--algorithm", name, "--max-order", "7", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    alg = get(name)
    weights = [t["weight"] for t in data["series"]]
    assert weights == data["nonzero_weights"] and len(weights) >= 2 and weights[0] == data["local_error_order"] == data["accuracy_order"] + 1
    motion, t_mid = TumblingMotion(), 0.7
    derivs = _chebyshev_derivatives(motion, t_mid, 7)
    residual = []
    for h in (0.08, 0.04):
        H = alg.samples * h
        t0 = t_mid - H / 2
        window = motion.increments(t0 - window_start * h, h, alg.window)
        exact = quat.quat_to_rotvec(quat.multiply(quat.conjugate(motion.attitude(t0)), motion.attitude(t0 + H)))
        predicted = sum(
            Fraction(t["delta"]) * h ** t["weight"] * sum(float(Fraction(k)) * _nested_value(_word(w), derivs) for w, k in t["coefficients"].items())
            for t in data["series"]
        )
        residual.append(np.linalg.norm(exact - increment(alg, window) - predicted.astype(float)))
    assert residual[0] / residual[1] == pytest.approx(2**remainder, rel=0.3)


def test_every_weight_reconstructs_the_local_error_exactly():
    """lebedev-panov-6 (dot-product terms) through h^11: Σ δ_w k_x x_w equals each weight's part as polynomials."""
    alg = get("lebedev-panov-6")
    err = S.local_error(alg, 11)
    terms = S.error_series(alg, 11)
    assert [t.weight for t in terms] == [w for w, p in enumerate(err.parts) if any(p)] == [7, 9, 11]
    for t in terms:
        assert S.lie_vector([(w, t.delta * c) for w, c in t.coefficients.items()]) == err.part(t.weight, unit="h")


def test_canonical_basis_is_the_greedy_choice_over_all_candidates():
    """Chosen content by content, the basis is the one a single greedy pass over every candidate picks."""

    def compositions(w):  # every word of weight w: the letters k = p − 1 of the ordered parts p of w
        if w == 0:
            yield ()
        for p in range(1, w + 1):
            for rest in compositions(w - p):
                yield (p - 1,) + rest

    for w in range(2, 10):
        candidates = sorted((c for c in compositions(w) if len(c) == 1 or c[-2] < c[-1]), key=lambda p: (len(p), p))
        echelon, greedy = S._Echelon(), []
        for c in candidates:
            if echelon.add(S._flatten(S.nested(c))):
                greedy.append(c)
        assert S.canonical_basis(w) == tuple(greedy), w
