"""The exact rotation-vector increment as a Lie series in the ω-derivatives (Magnus expansion).

Expand the body rate about an instant ``t_m``, ``ω(t_m + τ) = Σ_k ω^(k) τ^k/k!``,
and give the letter ``ω^(k)`` the weight ``k + 1``.  The attitude obeys
``2Λ' = Λ ∘ ω``, so the rotation over ``[t_m + lower·H, t_m + upper·H]`` is
the time-ordered exponential ``U = Σ_w I_w X_{w_1} … X_{w_n}`` with
``X_k = ω^(k)/2`` as pure quaternions and iterated integrals of monomials

    I_{(k_1 … k_n)} = ∫_{lower < t_1 < … < t_n < upper} Π t_i^{k_i}/k_i!   (H = 1),

the earliest letter on the left (``U' = U X``).  ``log U = φ/2`` (Magnus
1954), and the Dynkin–Specht–Wever map turns that Lie element into
right-nested brackets: with ``[u, v] = 2 u × v`` for pure quaternions, a Lie
element ``Σ c_w w`` of word length ``n`` is ``φ = Σ (c_w / n) x_w``, where
``x_{αβ…γδ} = ω^(α) × (ω^(β) × … × (ω^(γ) × ω^(δ)))`` (Lebedev & Panov 1989,
eq. (2.4)).  Words are tuples and coefficients :class:`fractions.Fraction`;
no symbolic ``expand`` is involved.

Everything is computed weight by weight and kept: the iterated integrals of
the words of weight ``w`` come from those of lower weight, the weight-``w``
part of ``(U − 1)^n`` from lower powers, so asking for weight 13 after weight
7 adds only the weights 8 to 13.

:func:`evaluate` turns a Lie series into a vector of any ring, given the value
of each letter: the component polynomials of the local-error series
(:mod:`strapdown.derivations.coning.series`) and the values on a regular
precession (:mod:`strapdown.derivations.coning.drift`) come from the same words.

References
----------
Magnus (1954), "On the exponential solution of differential equations for a linear operator".
Bortz (1971), "A new mathematical formulation for strapdown inertial navigation".
Lebedev & Panov (1989), eqs. (2.3)–(2.4).
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from math import factorial

from .graded import Graded, coefficient

__all__ = ["weight", "words", "exact_words", "evaluate", "rotation_series"]


def weight(word) -> int:
    """Weight ``Σ (k + 1)`` of a word of derivative orders.

    Parameters
    ----------
    word : sequence of int
        Derivative orders ``k`` of the letters ``ω^(k)``.

    Returns
    -------
    int

    Examples
    --------
    >>> weight((0, 3))
    5
    """
    return sum(k + 1 for k in word)


def _integrate(poly: dict, k: int, lower: Fraction) -> dict:
    """``∫_lower^t f(τ) τ^k/k! dτ`` for ``f = {power: coefficient}``."""
    fk = factorial(k)
    out: dict = {}
    for n, c in poly.items():
        out[n + k + 1] = out.get(n + k + 1, 0) + c / (fk * (n + k + 1))
    const = -sum(c * lower**n for n, c in out.items())
    if const:
        out[0] = out.get(0, 0) + const
    return out


def _value(poly: dict, t: Fraction) -> Fraction:
    return sum((c * t**n for n, c in poly.items()), Fraction(0))


class _Expansion:
    """Time-ordered exponential and its logarithm over one interval, kept by weight."""

    def __init__(self, lower: Fraction, upper: Fraction):
        self.lower, self.upper = lower, upper
        self._integrals = {0: {(): {0: Fraction(1)}}}  # weight -> {word: F_word(t)}
        self._coefficients: dict = {}  # weight -> {word: I_word}
        self._powers: dict = {}  # (n, weight) -> {word: coefficient of (U − 1)^n}
        self._lie: dict = {}  # weight -> ((word, c), ...) right-nested, last pair increasing

    def integrals(self, w: int) -> dict:
        if w not in self._integrals:
            out = {}
            for k in range(w):
                for word, f in self.integrals(w - k - 1).items():
                    out[word + (k,)] = _integrate(f, k, self.lower)
            self._integrals[w] = out
        return self._integrals[w]

    def coefficients(self, w: int) -> dict:
        """``I_word`` for the words of weight w (the part of U − 1 of weight w)."""
        if w not in self._coefficients:
            self._coefficients[w] = {word: c for word, f in self.integrals(w).items() if (c := _value(f, self.upper))}
        return self._coefficients[w]

    def power(self, n: int, w: int) -> dict:
        """Weight-w part of ``(U − 1)^n`` (every word of U − 1 has weight ≥ 1)."""
        if w < n:
            return {}
        if n == 1:
            return self.coefficients(w)
        key = (n, w)
        if key not in self._powers:
            out: dict = {}
            for a in range(n - 1, w):
                left = self.power(n - 1, a)
                if not left:
                    continue
                right = self.coefficients(w - a)
                for x, cx in left.items():
                    for y, cy in right.items():
                        word = x + y
                        out[word] = out.get(word, 0) + cx * cy
            self._powers[key] = {k: v for k, v in out.items() if v}
        return self._powers[key]

    def lie(self, w: int) -> tuple:
        """Weight-w part of φ as right-nested words (Dynkin–Specht–Wever), sorted."""
        if w not in self._lie:
            log: dict = {}
            for n in range(1, w + 1):
                f = Fraction((-1) ** (n + 1), n)
                for word, c in self.power(n, w).items():
                    log[word] = log.get(word, 0) + f * c
            out: dict = {}
            for word, c in log.items():
                if not c:
                    continue
                if len(word) >= 2:
                    a, b = word[-2], word[-1]
                    if a == b:
                        continue  # x_{…aa} = 0
                    if a > b:
                        word, c = word[:-2] + (b, a), -c
                out[word] = out.get(word, 0) + c / len(word)
            self._lie[w] = tuple(sorted(((k, v) for k, v in out.items() if v), key=lambda kv: (len(kv[0]), kv[0])))
        return self._lie[w]


@cache
def _expansion(lower: Fraction, upper: Fraction) -> _Expansion:
    return _Expansion(lower, upper)


def words(w: int, lower=Fraction(-1, 2), upper=Fraction(1, 2)) -> tuple:
    """Weight-``w`` part of the exact rotation vector over ``[lower, upper]`` as nested products.

    Parameters
    ----------
    w : int
        Weight (≥ 1).
    lower, upper : Fraction
        Interval ends in units of ``H`` relative to the expansion point ``t_m``.

    Returns
    -------
    tuple of (word, Fraction)
        ``φ_w = Σ c_w x_w`` (H = 1), right-nested words whose last two letters
        increase, sorted by (length, word).

    Raises
    ------
    ValueError
        If ``w`` is not a positive integer.

    Examples
    --------
    >>> words(3)
    (((2,), Fraction(1, 24)), ((0, 1), Fraction(1, 12)))
    """
    if isinstance(w, bool) or not isinstance(w, int) or w < 1:
        raise ValueError(f"Expected `w` to be a positive integer, got {w!r}")
    return _expansion(Fraction(lower), Fraction(upper)).lie(w)


def exact_words(lower=Fraction(-1, 2), upper=Fraction(1, 2), max_weight: int = 7) -> tuple:
    """Exact rotation-vector increment over ``[t_m + lower·H, t_m + upper·H]`` through ``max_weight``.

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
    return tuple(item for w in range(1, max_weight + 1) for item in words(w, lower, upper))


def evaluate(series, letter) -> tuple:
    """``Σ c_w x_w`` with the letter ``ω^(k)`` replaced by the vector ``letter(k)``.

    The words are arranged in a prefix tree, so that words sharing their first
    letters share the inner products: ``Σ_w c_w x_w = Σ_a ω^(a) × T_a + …`` with
    ``T_a`` the sum over the words that start with ``a`` (Horner's scheme for
    right-nested products).

    Parameters
    ----------
    series : iterable of (word, coefficient)
        A Lie series, as :func:`words` returns it.
    letter : callable
        ``k -> (x, y, z)``: the value of ``ω^(k)`` as three elements of one ring.

    Returns
    -------
    tuple of three ring elements

    Examples
    --------
    >>> from sympy.polys.domains import QQ
    >>> from sympy.polys.rings import ring
    >>> R, *g = ring("a0:3 b0:3", QQ)
    >>> evaluate([((0, 1), Fraction(1, 2))], lambda k: tuple(g[3 * k : 3 * k + 3]))[2]
    1/2*a0*b1 - 1/2*a1*b0
    """
    trie: dict = {}
    for word, c in series:
        node = trie
        for a in word:
            node = node.setdefault(a, {})
        node[None] = node.get(None, 0) + c
    values: dict = {}
    ring = None

    def value(k):
        nonlocal ring
        if k not in values:
            values[k] = tuple(letter(k))
            if ring is None:
                ring = values[k][0].ring
        return values[k]

    def horner(node):
        total = None
        for a, child in node.items():
            if a is None:
                continue
            v = value(a)
            inner = horner(child)
            term = None
            if inner is not None and any(inner):
                term = [v[1] * inner[2] - v[2] * inner[1], v[2] * inner[0] - v[0] * inner[2], v[0] * inner[1] - v[1] * inner[0]]
            c = child.get(None)
            if c:
                q = coefficient(ring, c)
                lin = [x * q for x in v]
                term = lin if term is None else [x + y for x, y in zip(term, lin)]
            if term is not None:
                total = term if total is None else [x + y for x, y in zip(total, term)]
        return total

    out = horner(trie)
    if out is None:
        raise ValueError("Expected a non-empty Lie series, got no words")
    return tuple(out)


def rotation_series(ring, letter, lower=Fraction(-1, 2), upper=Fraction(1, 2)) -> Graded:
    """The exact rotation vector over ``[lower, upper]`` (units of H) as a :class:`Graded` vector series.

    Parameters
    ----------
    ring : sympy.polys.rings.PolyRing
        Ring of the letter values.
    letter : callable
        ``k -> (x, y, z)`` in ``ring``: the value of ``ω^(k)`` (for a weight-w
        part, the letters up to ``k = w − 1`` are used).
    lower, upper : Fraction
        Interval ends relative to the expansion point, in units of H.

    Returns
    -------
    Graded
        Part w is ``Σ_{weight(w)=w} c_w x_w(letter)``.
    """
    lower, upper = Fraction(lower), Fraction(upper)
    zero = (ring.zero,) * 3

    def rule(w):
        items = words(w, lower, upper)
        return evaluate(items, letter) if items else zero

    return Graded(ring, 3, rule, low=1)
