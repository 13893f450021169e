"""Local-error series of rotation-vector algorithms, to any weight.

Expand the body rate about the middle ``t_m`` of the step ``H = N h``,

    ω(t_m + τ) = Σ_k ω_m^(k) τ^k / k!,

and write ``x_{αβ…γδ} = ω_m^(α) × (ω_m^(β) × … × (ω_m^(γ) × ω_m^(δ)))`` for
the right-nested cross products of Lebedev & Panov (1989), eq. (2.4).  The
symbol ``ω^(k)`` carries the *weight* ``k + 1``: a product of weight ``w``
multiplies ``H^w`` (or ``h^w``), so the series in the step is the series in
the weight.  Every series is a :class:`~strapdown.derivations.coning.graded.Graded`
series whose parts are computed on demand: the weight of a result is a
parameter (``max_weight``, default :data:`DEFAULT_MAX_WEIGHT` = 7, at most
:data:`WEIGHT_LIMIT`), and asking for ``h⁷`` costs only the work of the weights
up to 7.

Two representations, each where it is cheapest:

* **Exact increment (free Lie algebra).**  The Magnus expansion of
  :mod:`strapdown.derivations.coning.magnus`: iterated integrals, their
  logarithm and the Dynkin map give the increment as nested products ``x_w``
  with exact rational coefficients, weight by weight.

* **Component polynomials.**  The ``x_w``, the increments ``p_j`` (linear in
  the components of ``ω^(0) … ω^(K−1)``) and every term of an algorithm are
  vectors of polynomials in the ring :data:`RING` over QQ.  Cross and dot
  products of homogeneous parts are exact products (weights add), so nothing
  is truncated and dot-product factors such as ``(p_2·p_3) p_2×p_3`` are as
  easy as cross products.

**Sign convention** (the package docstring, "Errors"): the local error
is ``δφ = Δφ_exact − Δφ_algorithm`` on the same ω(t).  Its parts are returned
in units of ``H`` (set ``H = 1``); multiply the weight-w part by
``H^w = N^w h^w``.  In R³ the nested products are not independent (Jacobi
identity, and R³-only identities such as ``a×(a×(a×b)) = −|a|² a×b``), so
series are compared by *value*: as polynomials in the components, which is
equality for all ω-derivatives.

**Sample indices.**  With N samples per step, ``p_1 … p_N`` are the samples of
the current step and ``p_0, p_{−1}, …`` those of earlier steps
(:mod:`strapdown.derivations.coning.algorithms`); every increment is expanded
about the middle of the *current* step, ``p_j`` over
``[−1/2 + (j−1)/N, −1/2 + j/N]`` in units of H, so cross-step terms need
nothing else.

References
----------
Lebedev & Panov (1989), eqs. (2.2)–(2.4).
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (2) and Table 2.
Bortz (1971); Magnus (1954) for the exponential representation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import factorial

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.rings import ring

from . import graded as G
from .algorithms import Algorithm
from .magnus import evaluate, exact_words, rotation_series, weight

__all__ = [
    "DEFAULT_MAX_WEIGHT",
    "WEIGHT_LIMIT",
    "MAX_WEIGHT",
    "RING",
    "OMEGA",
    "omega",
    "check_max_weight",
    "weight",
    "monomial_weight",
    "weight_part",
    "truncate",
    "exact_words",
    "exact_increment_series",
    "exact_increment",
    "nested",
    "lie_vector",
    "increment_series",
    "increments",
    "algorithm_increment_series",
    "algorithm_series",
    "LocalError",
    "local_error",
    "express",
    "ORDER4_BASIS",
    "fourth_order_coefficients",
    "canonical_basis",
    "ErrorCoefficients",
    "error_coefficients",
    "ErrorTerm",
    "error_series",
    "lie_basis_reduce",
    "word_latex",
    "series_latex",
    "dual_words",
]

#: Weight of a series when none is asked for (the series run to ``h**7``).
DEFAULT_MAX_WEIGHT = 7
#: Highest weight the component ring supports (ω^(0) … ω^(WEIGHT_LIMIT − 1)).
WEIGHT_LIMIT = 20
#: The default weight under its earlier name.
MAX_WEIGHT = DEFAULT_MAX_WEIGHT

_NAMES = [f"w{k}{c}" for k in range(WEIGHT_LIMIT) for c in "xyz"]
#: Polynomials over QQ in the components of ω^(0) … ω^(WEIGHT_LIMIT − 1).
RING, *_GENS = ring(_NAMES, QQ)
#: ``OMEGA[k]`` is the symbolic vector ω_m^(k) as a triple of ring generators.
OMEGA = tuple(tuple(_GENS[3 * k + i] for i in range(3)) for k in range(WEIGHT_LIMIT))
_WEIGHTS = tuple(k + 1 for k in range(WEIGHT_LIMIT) for _ in range(3))
_ZERO = RING.zero


def check_max_weight(max_weight) -> int:
    """``max_weight`` validated: an integer in ``1 … WEIGHT_LIMIT``.

    Parameters
    ----------
    max_weight : int
        Highest weight (power of h) of a series.

    Returns
    -------
    int

    Raises
    ------
    TypeError
        If it is not an integer.
    ValueError
        If it is outside ``1 … WEIGHT_LIMIT``.
    """
    if isinstance(max_weight, bool) or not isinstance(max_weight, int):
        raise TypeError(f"Expected `max_weight` to be an integer, got {type(max_weight).__name__}")
    if not 1 <= max_weight <= WEIGHT_LIMIT:
        raise ValueError(f"Expected `max_weight` in 1..{WEIGHT_LIMIT}, got {max_weight}")
    return max_weight


def omega(k: int) -> tuple:
    """The letter ``ω^(k)`` as three generators of :data:`RING`.

    Parameters
    ----------
    k : int
        Derivative order, ``0 ≤ k < WEIGHT_LIMIT``.

    Returns
    -------
    tuple of three ring generators

    Raises
    ------
    ValueError
        For a derivative order the ring does not hold.
    """
    if not 0 <= k < WEIGHT_LIMIT:
        raise ValueError(f"Expected a derivative order in 0..{WEIGHT_LIMIT - 1} (weight at most {WEIGHT_LIMIT}), got {k}")
    return OMEGA[k]


def monomial_weight(monom) -> int:
    """Weight of a monomial of :data:`RING` (its exponent tuple).

    Parameters
    ----------
    monom : tuple of int
        Exponents of the generators.

    Returns
    -------
    int
    """
    return sum(w * e for w, e in zip(_WEIGHTS, monom) if e)


def weight_part(vector, w: int) -> tuple:
    """The monomials of weight ``w`` of a vector of :data:`RING` polynomials.

    Parameters
    ----------
    vector : sequence of ring elements
        Components.
    w : int
        Weight kept.

    Returns
    -------
    tuple of ring elements
    """
    return tuple(RING.from_dict({m: c for m, c in x.items() if monomial_weight(m) == w}) for x in vector)


def truncate(vector, max_weight: int) -> tuple:
    """The monomials of weight ≤ ``max_weight`` of a vector of :data:`RING` polynomials.

    Parameters
    ----------
    vector : sequence of ring elements
        Components.
    max_weight : int
        Highest weight kept.

    Returns
    -------
    tuple of ring elements
    """
    return tuple(RING.from_dict({m: c for m, c in x.items() if monomial_weight(m) <= max_weight}) for x in vector)


def _scale(v, c):
    return tuple(c * x for x in v)


# ---------------------------------------------------------------------------
# Exact increment as component polynomials
# ---------------------------------------------------------------------------
@cache
def exact_increment_series(lower=Fraction(-1, 2), upper=Fraction(1, 2)) -> G.Graded:
    """Exact rotation-vector increment over ``[lower, upper]`` (units of H) as a graded vector of :data:`RING`.

    Parameters
    ----------
    lower, upper : Fraction
        Interval ends relative to the expansion point t_m, in units of H.

    Returns
    -------
    Graded
        Part w is the weight-w part of the increment (``H = 1``), built on demand
        from :func:`strapdown.derivations.coning.magnus.words`.
    """
    return rotation_series(RING, omega, Fraction(lower), Fraction(upper))


def exact_increment(lower=Fraction(-1, 2), upper=Fraction(1, 2), max_weight: int = DEFAULT_MAX_WEIGHT) -> tuple:
    """Exact increment :func:`exact_words` as component polynomials (``H = 1``), through ``max_weight``.

    Parameters
    ----------
    lower, upper : Fraction
        Interval ends relative to t_m, in units of H.
    max_weight : int
        Highest weight kept.

    Returns
    -------
    tuple of three ring elements
    """
    return exact_increment_series(Fraction(lower), Fraction(upper)).total(check_max_weight(max_weight))


def nested(word) -> tuple:
    """``x_w`` as three ring polynomials.

    Parameters
    ----------
    word : sequence of int
        Derivative orders, left to right (``x_{αβ…} = ω^(α) × (ω^(β) × …)``).

    Returns
    -------
    tuple of three ring elements

    Examples
    --------
    >>> nested((0, 1))[2] == OMEGA[0][0] * OMEGA[1][1] - OMEGA[0][1] * OMEGA[1][0]
    True
    """
    return evaluate([(tuple(word), 1)], omega)


def lie_vector(series) -> tuple:
    """``Σ c_w x_w`` as three ring polynomials.

    Parameters
    ----------
    series : iterable of (word, coefficient)
        Nested products and their coefficients (Fraction or int).

    Returns
    -------
    tuple of three ring elements
    """
    items = [(tuple(w), Fraction(c)) for w, c in series if c]
    return evaluate(items, omega) if items else (_ZERO, _ZERO, _ZERO)


# ---------------------------------------------------------------------------
# Increments and algorithms
# ---------------------------------------------------------------------------
def _increment_interval(j: int, samples: int) -> tuple:
    a = Fraction(-1, 2) + Fraction(j - 1, samples)
    return a, a + Fraction(1, samples)


def increment_series(samples: int, *, first_index: int = 1, ring=RING, letter=omega) -> tuple:
    """The increments ``p_j = ∫ ω dt``, j = first_index … N, as graded vector series (``H = 1``).

    ``p_j = Σ_k ω^(k) (b^{k+1} − a^{k+1})/(k+1)!`` over ``[a, b]`` with
    ``a = −1/2 + (j−1)/N``, ``b = a + 1/N`` (Lebedev & Panov 1989, eq. (2.3));
    indices ``j ≤ 0`` are samples of earlier steps.

    Parameters
    ----------
    samples : int
        N, samples per step.
    first_index : int, keyword-only
        Lowest sample index (``1 − history``; ≤ 0 for cross-step algorithms).
    ring : PolyRing, keyword-only
        Ring of the letter values (default :data:`RING`).
    letter : callable, keyword-only
        ``k -> (x, y, z)``: value of ω^(k) in ``ring`` (default the generators).

    Returns
    -------
    tuple of Graded
        ``p_{first_index} … p_N``, oldest first.
    """
    out = []
    for j in range(first_index, samples + 1):
        a, b = _increment_interval(j, samples)

        def rule(w, a=a, b=b):
            c = G.coefficient(ring, (b**w - a**w) / factorial(w))
            return tuple(x * c for x in letter(w - 1))

        out.append(G.Graded(ring, 3, rule, low=1))
    return tuple(out)


def increments(samples: int, *, first_index: int = 1, max_weight: int = DEFAULT_MAX_WEIGHT) -> tuple:
    """Series of the increments ``p_j`` (``H = 1``) as component polynomials through ``max_weight``.

    Parameters
    ----------
    samples : int
        N.
    first_index : int, keyword-only
        Lowest sample index (≤ 0: samples of earlier steps).
    max_weight : int, keyword-only
        Highest weight kept.

    Returns
    -------
    tuple of (three ring elements)
        ``p_{first_index} … p_N``.
    """
    check_max_weight(max_weight)
    return tuple(p.total(max_weight) for p in increment_series(samples, first_index=first_index))


def algorithm_increment_series(algorithm: Algorithm, *, ring=RING, letter=omega) -> G.Graded:
    """Increment ``Δφ`` of ``algorithm`` as a graded vector series (``H = 1``).

    Every term of the data model is supported: nested cross products of any
    depth, dot-product factors, and sample indices of earlier steps.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    ring : PolyRing, keyword-only
        Ring of the letter values (default :data:`RING`).
    letter : callable, keyword-only
        ``k -> (x, y, z)``: value of ω^(k) (default the generators of RING).

    Returns
    -------
    Graded
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    first = algorithm.first_index
    p = increment_series(algorithm.samples, first_index=first, ring=ring, letter=letter)

    def sample(j):
        return p[j - first]

    def value(expr):
        if isinstance(expr, int):
            return sample(expr)
        a, b = expr
        return G.cross(value(a), value(b))

    terms = [(1, sample(j)) for j in range(1, algorithm.samples + 1)]
    for term in algorithm.terms:
        v = value(term.cross)
        for i, j in term.dots:
            v = G.times(G.dot(sample(i), sample(j)), v)
        terms.append((term.coefficient, v))
    return G.combine(terms)


@cache
def _algorithm_series(algorithm: Algorithm) -> G.Graded:
    return algorithm_increment_series(algorithm)


def algorithm_series(algorithm: Algorithm, max_weight: int = DEFAULT_MAX_WEIGHT) -> tuple:
    """Increment ``Δφ`` of ``algorithm`` as component polynomials through ``max_weight`` (``H = 1``).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    max_weight : int
        Highest weight kept.

    Returns
    -------
    tuple of three ring elements
    """
    return _algorithm_series(algorithm).total(check_max_weight(max_weight))


# ---------------------------------------------------------------------------
# Local error
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class LocalError:
    """Local error ``δφ = Δφ_exact − Δφ_algorithm`` of one step, by weight.

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm.
    parts : tuple
        ``parts[w]`` (w = 0 … max_weight) is the weight-w part as three ring
        polynomials in units of H (``H = 1``); ``parts[0]`` is zero.
    """

    algorithm: Algorithm
    parts: tuple

    @property
    def max_weight(self) -> int:
        """Highest weight held."""
        return len(self.parts) - 1

    @property
    def leading_weight(self) -> int | None:
        """Smallest weight with a nonzero part (None if zero through :attr:`max_weight`)."""
        for w, v in enumerate(self.parts):
            if any(v):
                return w
        return None

    @property
    def order(self) -> int | None:
        """Accuracy order ρ of the algorithm: local error O(h^(ρ+1)) (local-error order ρ + 1); None if zero through :attr:`max_weight`."""
        w = self.leading_weight
        return None if w is None else w - 1

    def part(self, w: int, *, unit: str = "H") -> tuple:
        """Weight-w part; ``unit="h"`` rescales it to the coefficient of ``h^w`` (``H = N h``).

        Parameters
        ----------
        w : int
            Weight, ``0 … max_weight``.
        unit : {"H", "h"}, keyword-only
            Step (H) or sample interval (h) as the unit of the coefficients.

        Returns
        -------
        tuple of three ring elements

        Raises
        ------
        ValueError
            For an unknown ``unit`` or a weight beyond :attr:`max_weight`.
        """
        if not 0 <= w <= self.max_weight:
            raise ValueError(f"Expected `w` in 0..{self.max_weight} (the weight of this series), got {w}")
        v = self.parts[w]
        if unit == "H":
            return v
        if unit == "h":
            return _scale(v, QQ(self.algorithm.samples) ** w)
        raise ValueError(f"Expected `unit` to be 'H' or 'h', got {unit!r}")


@cache
def _local_error_series(algorithm: Algorithm) -> G.Graded:
    return G.combine([(1, exact_increment_series()), (-1, _algorithm_series(algorithm))])


def local_error(algorithm: Algorithm, max_weight: int = DEFAULT_MAX_WEIGHT) -> LocalError:
    """Local-error series of ``algorithm`` through ``max_weight`` (exact minus algorithm).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    max_weight : int
        Highest weight (power of h) kept, 1 … :data:`WEIGHT_LIMIT`.

    Returns
    -------
    LocalError

    Raises
    ------
    TypeError, ValueError
        For a bad ``algorithm`` or ``max_weight``.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> local_error(get("two-sample")).order
    4
    >>> local_error(get("lebedev-panov-2")).order
    2
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    return _local_error(algorithm, check_max_weight(max_weight))


@cache
def _local_error(algorithm: Algorithm, max_weight: int) -> LocalError:
    return LocalError(algorithm, _local_error_series(algorithm).parts(max_weight))


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

    The nested products of different letter contents (the multiset of the
    ω-derivatives a product is made of) have no monomial in common, so the
    system is solved content by content.

    Parameters
    ----------
    vector : tuple of three ring polynomials
        The vector to express (elements of :data:`RING`).
    words : sequence of tuples
        The nested products allowed.  If they are linearly dependent in R³ the
        solution with the free parameters set to zero is returned.

    Returns
    -------
    dict
        ``{word: Fraction}``.

    Raises
    ------
    ValueError
        If ``vector`` is not in the span of the ``x_w`` (the residual is nonzero).
    """
    from sympy.polys.matrices import DomainMatrix

    words = [tuple(w) for w in words]
    sol = {w: Fraction(0) for w in words}
    target: dict = {}
    for key, c in _flatten(vector).items():
        target.setdefault(_monomial_content(key[1]), {})[key] = c
    by_content: dict = {}
    for w in words:
        by_content.setdefault(_word_content(w), []).append(w)
    if set(target) - set(by_content):
        raise ValueError("Expected a vector in the span of the given nested products, got a nonzero residual")
    for content, group in by_content.items():
        part = target.get(content, {})
        if not part:
            continue
        cols = [_nested_flat(w) for w in group]
        keys = sorted(set(part).union(*[set(c) for c in cols]))
        rows = [[col.get(k, QQ(0)) for col in cols] + [part.get(k, QQ(0))] for k in keys]
        m = DomainMatrix(rows, (len(rows), len(group) + 1), QQ)
        rref, pivots = m.rref()
        if len(group) in pivots:
            raise ValueError("Expected a vector in the span of the given nested products, got a nonzero residual")
        rr = rref.to_Matrix()
        for r, col in enumerate(pivots):
            val = rr[r, len(group)]
            sol[group[col]] = Fraction(int(val.p), int(val.q))
    return sol


def _monomial_content(monom) -> tuple:
    """Letter content of a monomial of :data:`RING`: how many factors of each ω^(k)."""
    return tuple(sum(monom[3 * k : 3 * k + 3]) for k in range(WEIGHT_LIMIT))


def _word_content(word) -> tuple:
    """Letter content of a nested product, as :func:`_monomial_content` counts it."""
    counts = [0] * WEIGHT_LIMIT
    for k in word:
        counts[k] += 1
    return tuple(counts)


@cache
def _nested_flat(word: tuple) -> dict:
    return _flatten(nested(word))


#: Basis of the fourth-order local error, Budennyi, Kalinovsky, Panov et al., eq. (2):
#: ``x03, x12, x002, x110, x0001``.
ORDER4_BASIS = ((0, 3), (1, 2), (0, 0, 2), (1, 1, 0), (0, 0, 0, 1))


def fourth_order_coefficients(algorithm: Algorithm) -> dict:
    """Weight-5 local error in the basis :data:`ORDER4_BASIS`, coefficients of ``h⁵``.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.

    Returns
    -------
    dict
        ``{word: Fraction}``: ``δφ = h⁵ Σ c_w x_w + O(h⁶)`` (exact minus algorithm,
        ``H = N h``); these are the products ``δ4 · k`` of Budennyi, Kalinovsky,
        Panov et al., Table 2.
    """
    return express(local_error(algorithm, max(DEFAULT_MAX_WEIGHT, 5)).part(5, unit="h"), ORDER4_BASIS)


class _Echelon:
    """Exact row echelon form over QQ of sparse vectors ``{key: coefficient}``, grown one vector at a time."""

    def __init__(self):
        self._rows: list = []  # (pivot key, row), the row normalised to 1 at its pivot

    def reduce(self, vec: dict) -> dict:
        v = {k: c for k, c in vec.items() if c}
        for pivot, row in self._rows:
            c = v.get(pivot)
            if c:
                for k, r in row.items():
                    x = v.get(k, 0) - c * r
                    if x:
                        v[k] = x
                    else:
                        v.pop(k, None)
        return v

    def add(self, vec: dict) -> bool:
        """Add ``vec``; True if it was independent of the vectors added before."""
        v = self.reduce(vec)
        if not v:
            return False
        pivot = min(v)
        inv = 1 / v[pivot]
        row = {k: c * inv for k, c in v.items()}
        # keep earlier rows reduced at the new pivot (so reduce() stays one pass)
        self._rows = [(p, _eliminate(r, pivot, row)) for p, r in self._rows]
        self._rows.append((pivot, row))
        return True


def _eliminate(row: dict, pivot, by: dict) -> dict:
    c = row.get(pivot)
    if not c:
        return row
    out = dict(row)
    for k, r in by.items():
        x = out.get(k, 0) - c * r
        if x:
            out[k] = x
        else:
            out.pop(k, None)
    return out


@cache
def canonical_basis(w: int) -> tuple:
    """Nested products of weight ``w`` independent as vector polynomials in R³.

    Candidates are right-nested words with increasing last pair, tried in the
    order (length, word) and kept when independent (by value) of those kept
    before.  Products of different letter contents share no monomial, so the
    choice is made content by content (the same words as one pass over all
    candidates).  For ``w = 5`` this is :data:`ORDER4_BASIS` up to order.

    Parameters
    ----------
    w : int
        Weight, 1 … :data:`WEIGHT_LIMIT`.

    Returns
    -------
    tuple of words
    """
    from sympy.utilities.iterables import partitions

    check_max_weight(w)
    basis = []
    for part in partitions(w):  # a content: the letters k = p − 1 of the parts p of w
        basis += _content_basis(tuple(p - 1 for p, mult in sorted(part.items()) for _ in range(mult)))
    return tuple(sorted(basis, key=lambda p: (len(p), p)))


@cache
def _content_basis(letters: tuple) -> tuple:
    """Independent nested products of one letter content (sorted letters), in the order (length, word)."""
    from sympy.utilities.iterables import multiset_permutations

    if len(letters) == 1:
        return (letters,)
    candidates = sorted(tuple(p) for p in multiset_permutations(list(letters)) if p[-2] < p[-1])
    echelon = _Echelon()
    return tuple(c for c in candidates if echelon.add(_nested_flat(c)))


@dataclass(frozen=True)
class ErrorCoefficients:
    """Leading local error in the convention of Budennyi, Kalinovsky, Panov et al., Table 2.

    ``Δφ_exact − Δφ_algorithm = δ h^(ρ+1) Σ_w k_w x_w + O(h^(ρ+2))`` with h the
    sample interval (H = N h) and ``δ = 1 / lcm`` of the denominators, so that
    the ``k_w`` are coprime-denominator integers.

    Attributes
    ----------
    order : int or None
        ρ, the accuracy order (None if the error vanishes through ``h**max_weight``);
        ρ + 1 is the local-error order.
    delta : Fraction
        δ.
    coefficients : dict
        ``{word: Fraction}`` (integers under this normalisation).
    basis : tuple of words
        The nested products of the expansion.
    max_weight : int
        Weight of the series the coefficients come from.
    """

    order: int | None
    delta: Fraction
    coefficients: dict
    basis: tuple
    max_weight: int = DEFAULT_MAX_WEIGHT

    def latex(self, *, dual: bool = False) -> str:
        """``δφ = δ h^{ρ+1}(Σ k x)`` as LaTeX.

        Parameters
        ----------
        dual : bool, keyword-only
            Give its dual part by the transfer principle instead.

        Returns
        -------
        str
        """
        if self.order is None:
            return f"\\delta\\varphi = O(h^{{{self.max_weight + 1}}})"
        return _error_latex(self.delta, self.order + 1, self.coefficients, dual=dual)


def _error_latex(delta: Fraction, power: int, coefficients: dict, *, dual: bool) -> str:
    """``δφ = δ h^power (Σ k x)`` (or its dual part) as LaTeX."""
    series = [(w, c) for w, c in coefficients.items() if c]
    d = sp.latex(sp.Rational(delta.numerator, delta.denominator))
    head = f"{d}\\, h^{{{power}}}"
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


def error_coefficients(algorithm: Algorithm, max_weight: int = DEFAULT_MAX_WEIGHT) -> ErrorCoefficients:
    """Leading local-error coefficients (Table 2 convention, see :class:`ErrorCoefficients`).

    The basis is :data:`ORDER4_BASIS` for ρ = 4 and :func:`canonical_basis`
    otherwise.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    max_weight : int
        Weight of the series searched for the leading term.

    Returns
    -------
    ErrorCoefficients

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> e = error_coefficients(get("panov-4s-3"))
    >>> e.order, e.delta, [int(e.coefficients[w]) for w in ORDER4_BASIS]
    (4, Fraction(1, 45), [0, 0, 64, 192, -64])
    """
    err = local_error(algorithm, max_weight)
    return _error_coefficients(err.algorithm, err.max_weight)


@cache
def _error_coefficients(algorithm: Algorithm, max_weight: int) -> ErrorCoefficients:
    err = _local_error(algorithm, max_weight)
    rho = err.order
    if rho is None:
        return ErrorCoefficients(None, Fraction(0), {}, (), max_weight)
    term = _error_term(algorithm, rho + 1)
    return ErrorCoefficients(rho, term.delta, term.coefficients, term.basis, max_weight)


@dataclass(frozen=True)
class ErrorTerm:
    """The local error of one weight w in the convention of Table 2: ``δ_w h^w Σ_x k_x x``.

    As :class:`ErrorCoefficients` for any weight, not only the leading one:
    ``δ_w = 1 / lcm`` of the denominators, h the sample interval (H = N h),
    exact minus algorithm.

    Attributes
    ----------
    weight : int
        w, the power of h.
    delta : Fraction
        δ_w.
    coefficients : dict
        ``{word: Fraction}`` (integers under this normalisation).
    basis : tuple of words
        The nested products of the expansion (:data:`ORDER4_BASIS` at w = 5,
        :func:`canonical_basis` otherwise).
    """

    weight: int
    delta: Fraction
    coefficients: dict
    basis: tuple

    def latex(self, *, dual: bool = False) -> str:
        """``δφ_w = δ_w h^w (Σ k x)`` as LaTeX.

        Parameters
        ----------
        dual : bool, keyword-only
            Give its dual part by the transfer principle instead.

        Returns
        -------
        str
        """
        return _error_latex(self.delta, self.weight, self.coefficients, dual=dual)


def error_series(algorithm: Algorithm, max_weight: int = DEFAULT_MAX_WEIGHT) -> tuple:
    """The local error weight by weight, every nonzero weight through ``max_weight`` (Table 2 convention).

    ``Δφ_exact − Δφ_algorithm = Σ_w δ_w h^w Σ_x k_x x + O(h^(max_weight+1))``; the
    first term is :func:`error_coefficients`.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    max_weight : int
        Highest weight kept, 1 … :data:`WEIGHT_LIMIT`.

    Returns
    -------
    tuple of ErrorTerm
        One per nonzero weight, in increasing weight.

    Raises
    ------
    TypeError, ValueError
        For a bad ``algorithm`` or ``max_weight``.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> [(t.weight, str(t.delta)) for t in error_series(get("two-sample"))]
    [(5, '1/90'), (7, '1/3780')]
    """
    err = local_error(algorithm, max_weight)
    return tuple(_error_term(err.algorithm, w) for w, part in enumerate(err.parts) if any(part))


@cache
def _error_term(algorithm: Algorithm, w: int) -> ErrorTerm:
    basis = ORDER4_BASIS if w == 5 else canonical_basis(w)
    raw = express(_local_error(algorithm, w).part(w, unit="h"), basis)
    lcm = 1
    for c in raw.values():
        lcm = lcm * c.denominator // math.gcd(lcm, c.denominator)
    delta = Fraction(1, lcm)
    return ErrorTerm(w, delta, {word: c / delta for word, c in raw.items()}, tuple(basis))


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

    Parameters
    ----------
    series : iterable of (word, coefficient)
        Nested products and their coefficients.

    Returns
    -------
    tuple of (word, Fraction)
        The same Lie element on independent words, sorted by (weight, length, word).
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

    Parameters
    ----------
    series : iterable of (word, coefficient)
        Nested products and their coefficients.

    Returns
    -------
    tuple of (word, int, Fraction)
        ``(word, marked position, coefficient)``.

    Examples
    --------
    >>> dual_words([((0, 1), Fraction(1, 12))])
    (((0, 1), 0, Fraction(1, 12)), ((0, 1), 1, Fraction(1, 12)))
    """
    return tuple((tuple(w), i, Fraction(c)) for w, c in series for i in range(len(w)))


# ---------------------------------------------------------------------------
# LaTeX
# ---------------------------------------------------------------------------
def word_latex(word, marked: int | None = None) -> str:
    r"""``x_{αβ…}`` with an optional dual mark ``°`` on one index.

    Parameters
    ----------
    word : sequence of int
        Derivative orders.
    marked : int, optional
        Position of the dual mark.

    Returns
    -------
    str

    Examples
    --------
    >>> print(word_latex((0, 1), 1))
    x_{01^\circ}
    """
    idx = "".join(f"{k}^\\circ" if i == marked else str(k) for i, k in enumerate(word))
    return f"x_{{{idx}}}"


def series_latex(series, *, power: str = "", factor: Fraction | None = None) -> str:
    """``factor · power · (Σ c_w x_w)`` as LaTeX (terms in the given order).

    Parameters
    ----------
    series : iterable of (word, coefficient)
        Nested products and their coefficients.
    power : str, keyword-only
        LaTeX put before the bracket (e.g. ``"h^5"``).
    factor : Fraction, keyword-only
        Common factor taken out of the coefficients.

    Returns
    -------
    str
    """
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
