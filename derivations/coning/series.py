"""Local-error series of rotation-vector algorithms, up to h⁷.

Expand the body rate about the middle ``t_m`` of the step ``H = N h``,

    ω(t_m + τ) = Σ_k ω_m^(k) τ^k / k!,

and write ``x_{αβ…γδ} = ω_m^(α) × (ω_m^(β) × … × (ω_m^(γ) × ω_m^(δ)))`` for
the right-nested cross products of Lebedev & Panov (1989), eq. (2.4).  The
symbol ``ω^(k)`` carries the *weight* ``k + 1``: a product of weight ``w``
multiplies ``H^w`` (or ``h^w``), so the series in the step is the series in
the weight, and everything is truncated at weight :data:`MAX_WEIGHT` = 7.

Two representations, each where it is cheapest:

* **Exact increment (free Lie algebra).**  The attitude obeys
  ``2Λ' = Λ ∘ ω``, so the step quaternion is the time-ordered exponential
  ``Σ_n ∫_{t_1<…<t_n} X(t_1)…X(t_n)`` with ``X = ω/2`` as a pure quaternion.
  Its coefficients on words in the letters ``ω^(k)`` are iterated integrals
  of monomials (exact rationals); the logarithm of that series is ``φ/2``
  (the Magnus expansion), and the Dynkin–Specht–Wever map turns it into
  right-nested brackets, i.e. into the ``x_w`` above.  With ``[u, v] = 2 u×v``
  for pure quaternions, a Lie element ``Σ c_w w`` of word length ``n`` is
  ``φ = Σ (c_w / n) x_w``.  No symbolic ``expand`` is involved: words are
  tuples and coefficients are :class:`fractions.Fraction`.

* **Algorithms (component polynomials).**  The increments ``p_j`` are linear
  in the 21 components of ``ω^(0) … ω^(6)``; cross and dot products are taken
  component by component in a :mod:`sympy.polys.rings` ring over QQ with
  graded truncation (only pieces whose weights add up to at most 7 are
  multiplied).  Dot-product factors such as ``(p_2·p_3) p_2×p_3`` are
  therefore as easy as cross products.

The local error is ``δφ = Δφ_algorithm − Δφ_exact`` on the same ω(t).  Its
parts are returned in units of ``H`` (set ``H = 1``); multiply the weight-w
part by ``H^w = N^w h^w``.  In R³ the nested products are not independent
(Jacobi identity, and R³-only identities such as
``a×(a×(a×b)) = −|a|² a×b``), so series are compared by *value*: as
polynomials in the 21 components, which is equality for all ω-derivatives.

References
----------
Lebedev & Panov (1989), eqs. (2.2)–(2.4).
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (2) and Table 2.
Bortz (1971); Magnus (1954) for the exponential representation.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import factorial

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.rings import ring

from .algorithms import Algorithm

__all__ = [
    "MAX_WEIGHT",
    "RING",
    "OMEGA",
    "weight",
    "exact_words",
    "exact_increment",
    "nested",
    "lie_vector",
    "increments",
    "algorithm_series",
    "LocalError",
    "local_error",
    "express",
    "ORDER4_BASIS",
    "fourth_order_coefficients",
    "canonical_basis",
    "ErrorCoefficients",
    "error_coefficients",
    "lie_basis_reduce",
    "word_latex",
    "series_latex",
    "dual_words",
]

#: Highest weight kept (the series runs to ``h**MAX_WEIGHT``).
MAX_WEIGHT = 7

_DERIVS = MAX_WEIGHT  # ω^(0) … ω^(6)
_NAMES = [f"w{k}{c}" for k in range(_DERIVS) for c in "xyz"]
RING, *_GENS = ring(_NAMES, QQ)
#: ``OMEGA[k]`` is the symbolic vector ω_m^(k) as a triple of ring generators.
OMEGA = tuple(tuple(_GENS[3 * k + i] for i in range(3)) for k in range(_DERIVS))
_WEIGHTS = tuple(k + 1 for k in range(_DERIVS) for _ in range(3))
_ZERO = RING.zero


def weight(word) -> int:
    """Weight ``Σ (k + 1)`` of a word of derivative orders.

    >>> weight((0, 3))
    5
    """
    return sum(k + 1 for k in word)


def _monomial_weight(monom) -> int:
    return sum(w * e for w, e in zip(_WEIGHTS, monom) if e)


# ---------------------------------------------------------------------------
# Exact increment: time-ordered exponential, logarithm, Dynkin map
# ---------------------------------------------------------------------------
def _poly_integrate(coeffs: dict, lower: Fraction) -> dict:
    """∫_lower^t of the polynomial ``{power: coefficient}`` in t."""
    out = {}
    for n, c in coeffs.items():
        out[n + 1] = out.get(n + 1, 0) + c / (n + 1)
    const = -sum(c * lower**n for n, c in out.items())
    if const:
        out[0] = out.get(0, 0) + const
    return out


def _poly_eval(coeffs: dict, t: Fraction) -> Fraction:
    return sum((c * t**n for n, c in coeffs.items()), Fraction(0))


def _time_ordered(lower: Fraction, upper: Fraction, max_weight: int) -> dict:
    """Coefficients of the time-ordered exponential on words (letters X_k = ω^(k)/2 · τ^k/k!).

    ``U = Σ_w I_w w`` with ``I_{(k1…kn)} = ∫_{lower<t1<…<tn<upper} Π t_i^{k_i}/k_i!``;
    the left letter is the earliest (``U' = U X``).
    """
    out: dict = {}
    # depth-first over words, carrying F_w(t) = ∫ … (polynomial in t)
    stack = [((), {0: Fraction(1)})]
    while stack:
        word, f = stack.pop()
        w = weight(word)
        for k in range(_DERIVS):
            if w + k + 1 > max_weight:
                break
            g = {n + k: c / factorial(k) for n, c in f.items()}
            g = _poly_integrate(g, lower)
            new = word + (k,)
            out[new] = _poly_eval(g, upper)
            stack.append((new, g))
    return out


def _word_mul(a: dict, b: dict, max_weight: int) -> dict:
    out: dict = {}
    for wa, ca in a.items():
        wta = weight(wa)
        for wb, cb in b.items():
            if wta + weight(wb) > max_weight:
                continue
            key = wa + wb
            out[key] = out.get(key, 0) + ca * cb
    return {k: v for k, v in out.items() if v}


@cache
def exact_words(lower: Fraction = Fraction(-1, 2), upper: Fraction = Fraction(1, 2), max_weight: int = MAX_WEIGHT) -> tuple:
    """Exact rotation-vector increment over ``[t_m + lower·H, t_m + upper·H]`` as nested products.

    Parameters
    ----------
    lower, upper : Fraction
        Interval ends in units of ``H`` relative to the expansion point t_m.
    max_weight : int
        Truncation weight.

    Returns
    -------
    tuple of (word, Fraction)
        ``φ = Σ c_w x_w`` (``H = 1``), with right-nested words whose last two
        letters are in increasing order; words are sorted by (weight, length, word).

    Examples
    --------
    >>> dict(exact_words())[(0, 1)]
    Fraction(1, 12)
    """
    lower, upper = Fraction(lower), Fraction(upper)
    u = _time_ordered(lower, upper, max_weight)
    # log U = Σ (−1)^{n+1} (U − 1)^n / n, U − 1 = u (no empty word)
    log: dict = {}
    power = dict(u)
    n = 1
    while power:
        for k, v in power.items():
            log[k] = log.get(k, 0) + Fraction((-1) ** (n + 1), n) * v
        power = _word_mul(power, u, max_weight)
        n += 1
    # Dynkin–Specht–Wever: a Lie element of length n equals (1/n) Σ c_w [w]
    # (right-nested); with X = ω/2 this is φ = Σ (c_w / n) x_w.
    out: dict = {}
    for word, c in log.items():
        if not c:
            continue
        if len(word) >= 2:
            a, b = word[-2], word[-1]
            if a == b:
                continue
            if a > b:
                word, c = word[:-2] + (b, a), -c
        out[word] = out.get(word, 0) + c / len(word)
    items = [(w, c) for w, c in out.items() if c]
    return tuple(sorted(items, key=lambda wc: (weight(wc[0]), len(wc[0]), wc[0])))


# ---------------------------------------------------------------------------
# Component polynomials with graded truncation
# ---------------------------------------------------------------------------
def _graded(p) -> list:
    return [(m, c, _monomial_weight(m)) for m, c in p.items()]


def _mul(p, q, max_weight: int = MAX_WEIGHT):
    """Product of two ring elements, keeping monomials of weight ≤ ``max_weight``."""
    if not p or not q:
        return _ZERO
    gp = sorted(_graded(p), key=lambda t: t[2])
    gq = sorted(_graded(q), key=lambda t: t[2])
    out: dict = {}
    for mp, cp, wp in gp:
        room = max_weight - wp
        for mq, cq, wq in gq:
            if wq > room:
                break
            m = tuple(a + b for a, b in zip(mp, mq))
            v = out.get(m)
            out[m] = cp * cq if v is None else v + cp * cq
    return RING.from_dict({m: c for m, c in out.items() if c})


def _cross(a, b, max_weight: int = MAX_WEIGHT):
    return (
        _mul(a[1], b[2], max_weight) - _mul(a[2], b[1], max_weight),
        _mul(a[2], b[0], max_weight) - _mul(a[0], b[2], max_weight),
        _mul(a[0], b[1], max_weight) - _mul(a[1], b[0], max_weight),
    )


def _dot(a, b, max_weight: int = MAX_WEIGHT):
    return _mul(a[0], b[0], max_weight) + _mul(a[1], b[1], max_weight) + _mul(a[2], b[2], max_weight)


def _scale(v, c):
    return tuple(c * x for x in v)


def _add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def _sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def _truncate(v, max_weight: int):
    return tuple(RING.from_dict({m: c for m, c in x.items() if _monomial_weight(m) <= max_weight}) for x in v)


def _weight_part(v, w: int):
    return tuple(RING.from_dict({m: c for m, c in x.items() if _monomial_weight(m) == w}) for x in v)


def nested(word) -> tuple:
    """``x_w`` as three ring polynomials.

    >>> nested((0, 1))[2] == OMEGA[0][0] * OMEGA[1][1] - OMEGA[0][1] * OMEGA[1][0]
    True
    """
    word = tuple(word)
    v = OMEGA[word[-1]]
    for k in reversed(word[:-1]):
        v = _cross(OMEGA[k], v, 10**6)
    return v


def lie_vector(series) -> tuple:
    """``Σ c_w x_w`` (``series``: iterable of (word, coefficient)) as three ring polynomials."""
    total = (_ZERO, _ZERO, _ZERO)
    for word, c in series:
        total = _add(total, _scale(nested(word), QQ(c.numerator, c.denominator) if isinstance(c, Fraction) else c))
    return total


@cache
def exact_increment(lower: Fraction = Fraction(-1, 2), upper: Fraction = Fraction(1, 2)) -> tuple:
    """Exact increment :func:`exact_words` as component polynomials (``H = 1``)."""
    return lie_vector(exact_words(Fraction(lower), Fraction(upper)))


@cache
def increments(samples: int) -> tuple:
    """Series of the increments ``p_j = ∫ ω dt`` over the N sub-intervals of the step (``H = 1``).

    ``p_j = Σ_k ω^(k) (b^{k+1} − a^{k+1})/(k+1)!`` with ``a = −1/2 + (j−1)/N``,
    ``b = a + 1/N`` (Lebedev & Panov 1989, eq. (2.3)).
    """
    out = []
    for j in range(1, samples + 1):
        a = Fraction(-1, 2) + Fraction(j - 1, samples)
        b = a + Fraction(1, samples)
        vec = [_ZERO, _ZERO, _ZERO]
        for k in range(_DERIVS):
            c = (b ** (k + 1) - a ** (k + 1)) / factorial(k + 1)
            for i in range(3):
                vec[i] = vec[i] + QQ(c.numerator, c.denominator) * OMEGA[k][i]
        out.append(tuple(vec))
    return tuple(out)


def _term_value(expr, p):
    if isinstance(expr, int):
        return p[expr - 1]
    a, b = expr
    return _cross(_term_value(a, p), _term_value(b, p))


def algorithm_series(algorithm: Algorithm) -> tuple:
    """Increment ``Δφ`` of ``algorithm`` as component polynomials to weight 7 (``H = 1``).

    Every term of the data model is supported: nested cross products of any
    depth and dot-product factors.
    """
    p = increments(algorithm.samples)
    total = (_ZERO, _ZERO, _ZERO)
    for pj in p:
        total = _add(total, pj)
    for term in algorithm.terms:
        value = _term_value(term.cross, p)
        for i, j in term.dots:
            d = _dot(p[i - 1], p[j - 1])
            value = tuple(_mul(d, x) for x in value)
        c = term.coefficient
        total = _add(total, _scale(value, QQ(c.numerator, c.denominator)))
    return total


# ---------------------------------------------------------------------------
# Local error
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class LocalError:
    """Local error ``δφ = Δφ_algorithm − Δφ_exact`` of one step, by weight.

    Attributes
    ----------
    algorithm : Algorithm
    parts : tuple
        ``parts[w]`` (w = 0 … 7) is the weight-w part as three ring polynomials
        in units of H (``H = 1``); ``parts[0]`` is zero.
    """

    algorithm: Algorithm
    parts: tuple

    @property
    def leading_weight(self) -> int | None:
        """Smallest weight with a nonzero part (None if zero through weight 7)."""
        for w, v in enumerate(self.parts):
            if any(v):
                return w
        return None

    @property
    def order(self) -> int | None:
        """Order ρ of the algorithm: local error O(h^(ρ+1))."""
        w = self.leading_weight
        return None if w is None else w - 1

    def part(self, w: int, *, unit: str = "H") -> tuple:
        """Weight-w part; ``unit="h"`` rescales it to the coefficient of ``h^w`` (``H = N h``)."""
        v = self.parts[w]
        if unit == "H":
            return v
        if unit == "h":
            return _scale(v, QQ(self.algorithm.samples) ** w)
        raise ValueError(f"Expected `unit` to be 'H' or 'h', got {unit!r}")


@cache
def local_error(algorithm: Algorithm) -> LocalError:
    """Local-error series of ``algorithm`` through weight 7 (algorithm minus exact).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> local_error(get("two-sample")).order
    4
    >>> local_error(get("lebedev-panov-2")).order
    2
    """
    delta = _sub(algorithm_series(algorithm), exact_increment())
    parts = tuple(_weight_part(delta, w) for w in range(MAX_WEIGHT + 1))
    return LocalError(algorithm, parts)


# ---------------------------------------------------------------------------
# Expressing a series in a basis of nested products (by value)
# ---------------------------------------------------------------------------
def _flatten(v) -> dict:
    out = {}
    for i, comp in enumerate(v):
        for m, c in comp.items():
            out[(i, m)] = c
    return out


def express(vector, words) -> dict:
    """Coefficients ``c`` with ``vector = Σ c_w x_w`` exactly, as Fractions.

    Parameters
    ----------
    vector : tuple of three ring polynomials
    words : sequence of tuples
        The nested products allowed.  If they are linearly dependent in R³ the
        solution with the free parameters set to zero is returned.

    Raises
    ------
    ValueError
        If ``vector`` is not in the span of the ``x_w`` (the residual is nonzero).
    """
    from sympy.polys.matrices import DomainMatrix

    cols = [_flatten(nested(w)) for w in words]
    target = _flatten(vector)
    keys = sorted(set(target).union(*[set(c) for c in cols]))
    rows = [[col.get(k, QQ(0)) for col in cols] + [target.get(k, QQ(0))] for k in keys]
    if not rows:
        return {tuple(w): Fraction(0) for w in words}
    m = DomainMatrix(rows, (len(rows), len(words) + 1), QQ)
    rref, pivots = m.rref()
    if len(words) in pivots:
        raise ValueError("Expected a vector in the span of the given nested products, got a nonzero residual")
    sol = {tuple(w): Fraction(0) for w in words}
    rr = rref.to_Matrix()
    for r, col in enumerate(pivots):
        val = rr[r, len(words)]
        sol[tuple(words[col])] = Fraction(int(val.p), int(val.q))
    return sol


#: Basis of the fourth-order local error, Budennyi, Kalinovsky, Panov et al., eq. (2):
#: ``x03, x12, x002, x110, x0001``.
ORDER4_BASIS = ((0, 3), (1, 2), (0, 0, 2), (1, 1, 0), (0, 0, 0, 1))


def fourth_order_coefficients(algorithm: Algorithm) -> dict:
    """Weight-5 local error in the basis :data:`ORDER4_BASIS`, coefficients of ``h⁵``.

    Returns
    -------
    dict
        ``{word: Fraction}``: ``δφ = h⁵ Σ c_w x_w + O(h⁶)`` (algorithm minus exact,
        ``H = N h``).
    """
    return express(local_error(algorithm).part(5, unit="h"), ORDER4_BASIS)


@cache
def canonical_basis(w: int) -> tuple:
    """Nested products of weight ``w`` independent as vector polynomials in R³.

    Candidates are right-nested words with increasing last pair, tried in the
    order (length, word) and kept when independent (by value) of those kept
    before.  For ``w = 5`` this is :data:`ORDER4_BASIS` up to order.
    """
    from itertools import combinations_with_replacement, permutations

    from sympy.polys.matrices import DomainMatrix

    cands = set()
    for n in range(1, w + 1):
        for letters in combinations_with_replacement(range(_DERIVS), n):
            if weight(letters) != w:
                continue
            for p in permutations(letters):
                if n == 1 or p[-2] < p[-1]:
                    cands.add(p)
    basis, cols = [], []
    for cand in sorted(cands, key=lambda p: (len(p), p)):
        col = _flatten(nested(cand))
        if not col:
            continue
        trial = cols + [col]
        ks = sorted(set().union(*[set(c) for c in trial]))
        mat = DomainMatrix([[c.get(k, QQ(0)) for c in trial] for k in ks], (len(ks), len(trial)), QQ)
        if mat.rank() == len(trial):
            basis.append(cand)
            cols.append(col)
    return tuple(basis)


@dataclass(frozen=True)
class ErrorCoefficients:
    """Leading local error in the convention of Budennyi, Kalinovsky, Panov et al., Table 2.

    ``Δφ_exact − Δφ_algorithm = δ h^(ρ+1) Σ_w k_w x_w + O(h^(ρ+2))`` with h the
    sample interval (H = N h) and ``δ = 1 / lcm`` of the denominators, so that
    the ``k_w`` are coprime-denominator integers.

    Attributes
    ----------
    order : int or None
        ρ (None if the error vanishes through h⁷).
    delta : Fraction
    coefficients : dict
        ``{word: Fraction}`` (integers under this normalisation).
    basis : tuple of words
    """

    order: int | None
    delta: Fraction
    coefficients: dict
    basis: tuple

    def latex(self, *, dual: bool = False) -> str:
        """``δφ = δ h^{ρ+1}(Σ k x)`` as LaTeX (``dual=True``: its dual part by the transfer principle)."""
        if self.order is None:
            return "\\delta\\varphi = O(h^{8})"
        series = [(w, c) for w, c in self.coefficients.items() if c]
        d = sp.latex(sp.Rational(self.delta.numerator, self.delta.denominator))
        head = f"{d}\\, h^{{{self.order + 1}}}"
        if not dual:
            return f"\\delta\\varphi = {head} \\left({series_latex(series)}\\right)"
        terms = []
        for w, i, c in dual_words(series):
            sign = "-" if c < 0 else "+"
            mag = abs(c)
            coef = "" if mag == 1 else f"{mag} "
            terms.append(f"{sign} {coef}{word_latex(w, i)}")
        body = " ".join(terms).lstrip("+ ")
        if body.startswith("- "):
            body = "-" + body[2:]
        return f"\\delta\\varphi^\\circ = {head} \\left({body}\\right)"


@cache
def error_coefficients(algorithm: Algorithm) -> ErrorCoefficients:
    """Leading local-error coefficients (Table 2 convention, see :class:`ErrorCoefficients`).

    The basis is :data:`ORDER4_BASIS` for ρ = 4 and :func:`canonical_basis`
    otherwise.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> e = error_coefficients(get("panov-4s-3"))
    >>> e.order, e.delta, [int(e.coefficients[w]) for w in ORDER4_BASIS]
    (4, Fraction(1, 45), [0, 0, 64, 192, -64])
    """
    import math

    err = local_error(algorithm)
    rho = err.order
    if rho is None:
        return ErrorCoefficients(None, Fraction(0), {}, ())
    basis = ORDER4_BASIS if rho == 4 else canonical_basis(rho + 1)
    raw = express(_scale(err.part(rho + 1, unit="h"), QQ(-1)), basis)
    lcm = 1
    for c in raw.values():
        lcm = lcm * c.denominator // math.gcd(lcm, c.denominator)
    delta = Fraction(1, lcm)
    return ErrorCoefficients(rho, delta, {w: c / delta for w, c in raw.items()}, tuple(basis))


# ---------------------------------------------------------------------------
# Free-Lie-algebra reduction (unique coefficients for display)
# ---------------------------------------------------------------------------
def _bracket_expand(word) -> dict:
    """Right-nested bracket ``[a1,[a2,…]]`` expanded into associative words."""
    cur = {(word[-1],): 1}
    for a in reversed(word[:-1]):
        nxt: dict = {}
        for w, c in cur.items():
            nxt[(a,) + w] = nxt.get((a,) + w, 0) + c
            nxt[w + (a,)] = nxt.get(w + (a,), 0) - c
        cur = {k: v for k, v in nxt.items() if v}
    return cur


def lie_basis_reduce(series) -> tuple:
    """Rewrite ``Σ c_w x_w`` on an independent set of right-nested words of the free Lie algebra.

    Words are tried in the order (weight, length, word) and kept when independent
    of those kept before; the result is unique for a given ordering.  This uses
    only the Jacobi identity and antisymmetry, not identities special to R³.
    """
    from sympy.polys.matrices import DomainMatrix

    series = [(tuple(w), Fraction(c)) for w, c in series if c]
    out = []
    groups: dict = {}
    for w, c in series:
        groups.setdefault((weight(w), tuple(sorted(w))), []).append((w, c))
    for key in sorted(groups):
        items = groups[key]
        # candidate words: all arrangements with increasing last pair, in order
        from itertools import permutations

        letters = key[1]
        cands = sorted({p for p in permutations(letters) if len(p) == 1 or p[-2] < p[-1]})
        basis, vecs = [], []
        assoc_keys: list = []
        for cand in cands:
            e = _bracket_expand(cand)
            trial = vecs + [e]
            ks = sorted(set().union(*trial))
            mat = DomainMatrix([[QQ(v.get(k, 0)) for v in trial] for k in ks], (len(ks), len(trial)), QQ)
            if mat.rank() == len(trial):
                basis.append(cand)
                vecs.append(e)
                assoc_keys = ks
        target: dict = {}
        for w, c in items:
            for k, v in _bracket_expand(w).items():
                target[k] = target.get(k, 0) + c * v
        ks = sorted(set(assoc_keys) | set(target))
        rows = [[QQ(v.get(k, 0)) for v in vecs] + [QQ(target.get(k, 0).numerator, target.get(k, 0).denominator) if isinstance(target.get(k, 0), Fraction) else QQ(target.get(k, 0))] for k in ks]
        mat = DomainMatrix(rows, (len(ks), len(vecs) + 1), QQ)
        rref, piv = mat.rref()
        rr = rref.to_Matrix()
        for r, col in enumerate(piv):
            if col < len(vecs) and rr[r, len(vecs)] != 0:
                val = rr[r, len(vecs)]
                out.append((basis[col], Fraction(int(val.p), int(val.q))))
    return tuple(sorted(out, key=lambda wc: (weight(wc[0]), len(wc[0]), wc[0])))


# ---------------------------------------------------------------------------
# Dual (velocity) series by the transfer principle
# ---------------------------------------------------------------------------
def dual_words(series) -> tuple:
    """Dual part of ``Σ c_w x_w`` under ``ω^(k) → ω^(k) + s a^(k)`` (transfer principle).

    Each ``x_w`` is multilinear, so its dual part is the sum of the products
    with one factor ``ω^(k)`` replaced by ``a^(k)``.  A marked word is returned
    as ``(word, position)``: ``x°_{w,i}`` has ``a^(w_i)`` in place ``i``.

    >>> dual_words([((0, 1), Fraction(1, 12))])
    (((0, 1), 0, Fraction(1, 12)), ((0, 1), 1, Fraction(1, 12)))
    """
    return tuple((tuple(w), i, Fraction(c)) for w, c in series for i in range(len(w)))


# ---------------------------------------------------------------------------
# LaTeX
# ---------------------------------------------------------------------------
def word_latex(word, marked: int | None = None) -> str:
    """``x_{αβ…}`` with an optional dual mark ``°`` on one index."""
    idx = "".join(f"{k}^\\circ" if i == marked else str(k) for i, k in enumerate(word))
    return f"x_{{{idx}}}"


def series_latex(series, *, power: str = "", factor: Fraction | None = None) -> str:
    """``factor · power · (Σ c_w x_w)`` as LaTeX (terms in the given order)."""
    terms = []
    for w, c in series:
        c = Fraction(c)
        if factor:
            c = c / factor
        if not c:
            continue
        sign = "-" if c < 0 else "+"
        mag = abs(c)
        coef = "" if mag == 1 else sp.latex(sp.Rational(mag.numerator, mag.denominator)) + " "
        terms.append(f"{sign} {coef}{word_latex(w)}")
    body = " ".join(terms).lstrip("+ ").strip() or "0"
    if body.startswith("- "):
        body = "-" + body[2:]
    head = ""
    if factor is not None and factor != 1:
        head = sp.latex(sp.Rational(factor.numerator, factor.denominator)) + " "
    if factor is not None or power:
        return f"{head}{power}\\left({body}\\right)"
    return body
