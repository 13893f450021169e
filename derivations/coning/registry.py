"""The registry of published rotation-vector algorithms, each with its source.

Every entry is an :class:`~strapdown.derivations.coning.algorithms.Algorithm`
built from the coefficients its source prints (exact fractions); nothing here
is fitted.  :func:`get` looks an algorithm up by name, :func:`names` lists the
registry in a stable order.
"""

from __future__ import annotations

from fractions import Fraction

from .algorithms import Algorithm, Term

__all__ = ["REGISTRY", "get", "names", "register", "PANOV_BASIS", "PANOV_TABLE_1"]

def _cross_terms(pairs: dict) -> tuple:
    return tuple(Term(Fraction(c), (i, j)) for (i, j), c in pairs.items())


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


def register(algorithm: Algorithm) -> Algorithm:
    """Add ``algorithm`` to :data:`REGISTRY` (by its name) and return it."""
    REGISTRY[algorithm.name] = algorithm
    return algorithm


def get(name: str) -> Algorithm:
    """Registry algorithm by name; ``ValueError`` listing the names if unknown."""
    try:
        return REGISTRY[name]
    except KeyError:
        raise ValueError(f"Expected `algorithm` to be one of {', '.join(names())}, got {name!r}") from None


def names() -> list:
    """Registry names in a stable order."""
    return list(REGISTRY)


register(Algorithm("two-sample", 2, _cross_terms({(1, 2): Fraction(2, 3)}), "two-sample coning algorithm, 2/3 p1×p2", "Miller (1983); Bortz (1971) second-order condition"))
register(
    Algorithm(
        "optimal-3",
        3,
        _cross_terms({(1, 3): Fraction(9, 20), (2, 3): Fraction(27, 40), (1, 2): Fraction(27, 40)}),
        "coning-optimal three-sample algorithm, 9/20 p1×p3 + 27/40 p2×(p3−p1)",
        "Ignagni (1990), Algorithm 7",
    )
)
for _order in (2, 4, 6):
    register(_lebedev_panov(_order))


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
    register(_panov(_number))
