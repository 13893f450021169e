"""The registry of published rotation-vector algorithms, each with its source.

Every entry is an :class:`~strapdown.derivations.coning.algorithms.Algorithm`
built from the coefficients its source prints (exact fractions); nothing here
is fitted.  :func:`get` looks an algorithm up by name, :func:`names` lists the
registry in a stable order.

Families
--------
``one-sample``, ``savage-1+1``
    No coning term; Savage's "1 + previous sample" ``(1/12) p₀ × p₁``.
``two-sample``, ``miller-3``, ``optimal-3``, ``polynomial-N``
    Uncompressed forms (every pair ``p_i × p_j`` of the step): Miller's
    coning-optimal three-sample algorithm and the polynomial fits (N = 3 is
    Ignagni's Algorithm D; N = 4 coincides with ``panov-4s-5``).
``compressed-N`` (N = 2 … 6)
    Optimal coning algorithms in the compressed form ``(Σ_{i<N} k_i p_i) × p_N``.
``ignagni-1996-K`` (K = 1 … 7)
    Ignagni's (1996) "N + previous interval" class; 1, 2, 4, 5, 6 reach into
    the previous step (indices ≤ 0), 3 and 7 are ``compressed-3`` and
    ``compressed-4``.
``lebedev-panov-*``, ``panov-4s-*``
    The algorithms of the source papers (Lebedev & Panov 1989; Budennyi,
    Kalinovsky, Panov et al.).
"""

from __future__ import annotations

from fractions import Fraction

from .algorithms import Algorithm, Term
from .polynomial_fit import polynomial_fit_algorithm

__all__ = ["REGISTRY", "get", "names", "register", "PANOV_BASIS", "PANOV_TABLE_1", "COMPRESSED_TABLE", "IGNAGNI_1996"]

def _cross_terms(pairs: dict) -> tuple:
    return tuple(Term(Fraction(c), (i, j)) for (i, j), c in pairs.items())


def _compressed_terms(samples: int, ks) -> list:
    """Terms of ``(Σ k_i p_i) × p_N``, ``ks`` for the indices ``N − len(ks) … N − 1`` (≤ 0: earlier steps)."""
    first = samples - len(ks)
    return [Term(Fraction(k), (first + m, samples)) for m, k in enumerate(ks) if Fraction(k)]


def _interval_terms(samples: int, c) -> list:
    """Terms of ``c P_prev × P``: the previous step's increment sum crossed with the current one."""
    return _expand_sum_cross(range(1 - samples, 1), range(1, samples + 1), c)


def _expand_sum_cross(left, right, c) -> list:
    """Terms of ``c (Σ_{i∈left} p_i) × (Σ_{j∈right} p_j)`` by bilinearity."""
    return [Term(Fraction(c), (i, j)) for i in left for j in right]


def _lebedev_panov(order: int) -> Algorithm:
    """Nested four-sample algorithm of Lebedev & Panov (1989), eq. (2.2), as printed."""
    terms: list = []
    if order >= 4:
        terms += _expand_sum_cross((1, 2), (3, 4), Fraction(2, 3))
    if order >= 6:
        terms += [Term(Fraction(32, 15), (1, 3)), Term(Fraction(32, 15), (2, 4))]
        terms += _expand_sum_cross((1, 2), (3, 4), Fraction(-8, 9))
        terms += [Term(Fraction(32, 45), (1, (2, 4))), Term(Fraction(-32, 45), (4, (1, 3)))]
        terms += [Term(Fraction(-64, 45), (2, 3)), Term(Fraction(64, 45), (2, 3), ((2, 3),))]
    return Algorithm(
        f"lebedev-panov-{order}",
        4,
        tuple(terms),
        description=f"nested four-sample algorithm (2.2) truncated to order {order}",
        reference="Lebedev & Panov (1989), eq. (2.2)",
    )


REGISTRY: dict = {}
#: Names of the algorithms analysed in the source papers' tables (the default of :func:`names`).
_PAPER: list = []


def register(algorithm: Algorithm, *, paper: bool = False) -> Algorithm:
    """Add ``algorithm`` to :data:`REGISTRY` (by its name) and return it.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm; its name is the key.
    paper : bool, keyword-only
        Also list it among the source papers' algorithms (:func:`names` default).

    Raises
    ------
    ValueError
        If the name is already registered.
    """
    if algorithm.name in REGISTRY:
        raise ValueError(f"Expected a new algorithm name, got {algorithm.name!r} (already registered)")
    REGISTRY[algorithm.name] = algorithm
    if paper:
        _PAPER.append(algorithm.name)
    return algorithm


def get(name: str) -> Algorithm:
    """Registry algorithm by name.

    Parameters
    ----------
    name : str
        A name of :func:`names` (``library=True``).

    Raises
    ------
    ValueError
        If the name is unknown (the message lists the names).
    """
    try:
        return REGISTRY[name]
    except KeyError:
        raise ValueError(f"Expected `algorithm` to be one of {', '.join(names(library=True))}, got {name!r}") from None


def names(*, library: bool = False) -> list:
    """Registry names in a stable order.

    Parameters
    ----------
    library : bool, keyword-only
        False (default): the algorithms of the source papers' tables (two-sample,
        optimal-3, lebedev-panov-*, panov-4s-*), which every report section and
        the symbolic drift theory cover.  True: the whole registry, including the
        library of published algorithms (cross-step ones among them).

    Returns
    -------
    list of str
    """
    return list(REGISTRY) if library else list(_PAPER)


register(Algorithm("one-sample", 1, (), "no coning term, Δφ = p1 (first order)", "Ignagni (1990), Algorithm A; residual coning coefficient ρ_1 of the optimal-algorithm tables"))
register(
    Algorithm(
        "savage-1+1",
        1,
        (Term(Fraction(1, 12), (0, 1)),),
        "one sample + previous sample, (1/12) p0×p1",
        "Savage (1998), 'Strapdown inertial navigation integration algorithm design part 1: attitude algorithms', "
        "the (1/12) α_{l−1} × α_l coning term",
    )
)
register(Algorithm("two-sample", 2, _cross_terms({(1, 2): Fraction(2, 3)}), "two-sample coning algorithm, 2/3 p1×p2", "Miller (1983); Bortz (1971) second-order condition"), paper=True)
register(
    Algorithm(
        "miller-3",
        3,
        _cross_terms({(1, 3): Fraction(9, 20), (2, 3): Fraction(27, 40), (1, 2): Fraction(27, 40)}),
        "Miller's coning-optimal three-sample algorithm, 9/20 p1×p3 + 27/40 p2×(p3−p1) (uncompressed)",
        "Miller (1983), 'A new strapdown attitude algorithm'; Ignagni (1990), Algorithm E",
    )
)
register(
    Algorithm(
        "optimal-3",
        3,
        _cross_terms({(1, 3): Fraction(9, 20), (2, 3): Fraction(27, 40), (1, 2): Fraction(27, 40)}),
        "coning-optimal three-sample algorithm, 9/20 p1×p3 + 27/40 p2×(p3−p1)",
        "Ignagni (1990), Algorithm 7",
    ),
    paper=True,
)
register(
    Algorithm(
        "polynomial-3",
        3,
        _cross_terms({(1, 3): Fraction(33, 80), (2, 3): Fraction(57, 80), (1, 2): Fraction(57, 80)}),
        "quadratic fit of ω through three samples, 33/80 p1×p3 + 57/80 p2×(p3−p1)",
        "Ignagni (1990), Algorithm D (quadratic approximation through three samples)",
    )
)
for _n in (4, 5):
    register(polynomial_fit_algorithm(_n))

#: Optimal coning algorithms in the compressed form ``(Σ k_i p_i) × p_N``, k_1 … k_{N−1}
#: (PSINS coefficient table ``glv.cs``, Yan Gongmin; N = 2 … 4 are Ignagni's
#: (1990, 1996) algorithms).  N = 6, k_1 is 2315/4620 as in the ``glv.cs`` table; the
#: PSINS manual's Tab. 10-1 prints 2135/4620 (see derivations.coning.published).
COMPRESSED_TABLE = {
    2: ("2/3",),
    3: ("9/20", "27/20"),
    4: ("54/105", "92/105", "214/105"),
    5: ("250/504", "525/504", "650/504", "1375/504"),
    6: ("2315/4620", "4558/4620", "7296/4620", "7834/4620", "15797/4620"),
}
_COMPRESSED_SOURCES = {
    2: "Ignagni (1990); PSINS coefficient table (Yan Gongmin), N = 2",
    3: "Ignagni (1990), Algorithm F = Ignagni (1996), Algorithm 3; PSINS table, N = 3",
    4: "Ignagni (1996), Algorithm 7; PSINS table, N = 4",
    5: "PSINS coning/sculling coefficient table (Yan Gongmin), N = 5",
    6: "PSINS coning/sculling coefficient table (Yan Gongmin), N = 6 (glv.cs; Tab. 10-1 misprints k_1)",
}
for _n, _ks in COMPRESSED_TABLE.items():
    register(
        Algorithm(
            f"compressed-{_n}",
            _n,
            tuple(_compressed_terms(_n, _ks)),
            f"optimal {_n}-sample coning algorithm, compressed form ({' + '.join(f'{k} p{i + 1}' for i, k in enumerate(_ks))}) × p{_n}",
            _COMPRESSED_SOURCES[_n],
        )
    )

#: Ignagni (1996), "Efficient class of optimized coning compensation algorithms":
#: {K: (N, compressed coefficients of p_{N−m} … p_{N−1}, coefficient of P_prev × P)}.
#: Indices ≤ 0 are samples of the previous step; ``P_prev × P`` crosses the sums
#: of the previous and the current step.
IGNAGNI_1996 = {
    1: (2, ("0", "32/45"), "-1/180"),
    2: (2, ("-1/30", "11/15"), "0"),
    3: (3, ("9/20", "27/20"), "0"),
    4: (3, ("243/560", "1539/1120"), "1/3360"),
    5: (3, ("3/280", "57/140", "393/280"), "0"),
    6: (3, ("-1/420", "1/40", "157/420", "1207/840"), "0"),
    7: (4, ("54/105", "92/105", "214/105"), "0"),
}


def _ignagni_1996(number: int) -> Algorithm:
    n, ks, c_prev = IGNAGNI_1996[number]
    terms = _compressed_terms(n, ks) + (_interval_terms(n, c_prev) if Fraction(c_prev) else [])
    pieces = [f"({' + '.join(f'{k} p{n - len(ks) + m}' for m, k in enumerate(ks) if Fraction(k))}) × p{n}"]
    if Fraction(c_prev):
        pieces.append(f"({c_prev}) P_prev × P")
    history = max(0, 1 - min(n - len(ks), 1 - n if Fraction(c_prev) else 1))
    kind = f"{n} samples + {history} previous" if history else f"{n} samples"
    return Algorithm(
        f"ignagni-1996-{number}",
        n,
        tuple(terms),
        f"{kind}: " + " + ".join(pieces),
        f"Ignagni (1996), 'Efficient class of optimized coning compensation algorithms', Algorithm {number}",
    )


for _number in IGNAGNI_1996:
    register(_ignagni_1996(_number))

for _order in (2, 4, 6):
    register(_lebedev_panov(_order), paper=True)


# Budennyi, Kalinovsky, Panov et al. (Part 2), Table 1.  Their formula (1), which
# says which constant multiplies which cross product, was lost in print.  The
# reconstruction below uses the time-symmetric basis of four-sample pairwise
# terms; it is the only assignment of a1..a4 to that basis for which all five
# algorithms satisfy the second-order condition (weights j − i = 1, 3, 4, 2),
# and Tables 2 and 3 confirm it (see reports/algorithms.md and derivations.md).
# Table 1 is quoted as printed except the column of algorithm 2 (see below).
PANOV_BASIS = {
    "a1": ((2, 3),),
    "a2": ((1, 4),),
    "a3": ((1, 3), (2, 4)),
    "a4": ((1, 2), (3, 4)),
}
PANOV_TABLE_1 = {
    1: ("0", "16/9", "0", "0"),
    # Printed (0, 0, 4/3, 0); Tables 2 and 3 both require a1 = a2 = 4/3, i.e.
    # 4/3 (p1×p4 + p2×p3) (erratum, evidence in reports/algorithms.md).
    2: ("4/3", "4/3", "0", "0"),
    3: ("22/45", "22/45", "22/45", "32/45"),
    4: ("184/315", "112/315", "212/315", "52/105"),
    5: ("654/945", "526/945", "334/945", "736/945"),
}


def _panov(number: int) -> Algorithm:
    terms = []
    for key, value in zip(("a1", "a2", "a3", "a4"), PANOV_TABLE_1[number]):
        c = Fraction(value)
        if c:
            terms += [Term(c, pair) for pair in PANOV_BASIS[key]]
    return Algorithm(
        f"panov-4s-{number}",
        4,
        tuple(terms),
        description=f"four-sample fourth-order algorithm {number}: "
        + ", ".join(f"{k}={v}" for k, v in zip(("a1", "a2", "a3", "a4"), PANOV_TABLE_1[number])),
        reference="Budennyi, Kalinovsky, Panov et al. (Part 2), Table 1; formula (1) reconstructed",
    )


for _number in range(1, 6):
    register(_panov(_number), paper=True)
