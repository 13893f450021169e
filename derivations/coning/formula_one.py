"""Formula (1) of Budennyi, Kalinovsky, Panov et al.: which Table 1 constant multiplies which cross product.

The generalised four-sample algorithm (1) of the paper, ``Δφ = P + Σ_v a_v B_v``,
was lost in conversion: the text keeps the constants a1 … a4 of Table 1 but
not the combinations ``B_v`` of cross products they multiply.  The registry
reconstructs it with the time-symmetric combinations
``p2×p3, p1×p4, p1×p3 + p2×p4, p1×p2 + p3×p4``
(:data:`strapdown.derivations.coning.registry.PANOV_BASIS`).  This module
states the alternatives: every assignment of a1 … a4 to those four
combinations (:func:`basis_assignments`), and the algorithm that a column of
constants gives under an assignment (:func:`algorithm_from_constants`).  The
numeric side scores them against Table 3
(:mod:`strapdown.analysis.coning.papers.formula_one`).

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), formula (1), Tables 1–3.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from fractions import Fraction

from .algorithms import Algorithm, Term
from .registry import PANOV_BASIS

__all__ = ["CONSTANTS", "BasisAssignment", "basis_assignments", "algorithm_from_constants"]

#: Names of the Table 1 constants, in the order of a column.
CONSTANTS = ("a1", "a2", "a3", "a4")


@dataclass(frozen=True)
class BasisAssignment:
    """An assignment of the constants a1 … a4 to combinations of cross products.

    Parameters
    ----------
    combinations : tuple
        For a1 … a4 in turn, the pairs ``(i, j)`` whose products ``p_i × p_j``
        the constant multiplies, e.g. ``((2, 3),)`` or ``((1, 3), (2, 4))``.

    Examples
    --------
    >>> BasisAssignment(tuple(PANOV_BASIS[k] for k in CONSTANTS)).is_registry
    True
    """

    combinations: tuple

    def __post_init__(self):
        if len(self.combinations) != len(CONSTANTS):
            raise ValueError(f"Expected `combinations` for {len(CONSTANTS)} constants, got {len(self.combinations)}")

    @property
    def mapping(self) -> dict:
        """``{"a1": pairs, …}``."""
        return dict(zip(CONSTANTS, self.combinations))

    @property
    def is_registry(self) -> bool:
        """True for the registry's reconstruction (:data:`~strapdown.derivations.coning.registry.PANOV_BASIS`)."""
        return self.mapping == dict(PANOV_BASIS)

    @property
    def label(self) -> str:
        """``"a1→p2×p3, a2→p1×p4, …"``."""
        return ", ".join(f"{key}→{'+'.join(f'p{i}×p{j}' for i, j in pairs)}" for key, pairs in self.mapping.items())


def basis_assignments() -> tuple:
    """All 24 assignments of a1 … a4 to the four combinations of the registry basis.

    Returns
    -------
    tuple of BasisAssignment
        In the order of :func:`itertools.permutations`; the first is the registry's.

    Examples
    --------
    >>> found = basis_assignments()
    >>> len(found), found[0].is_registry
    (24, True)
    """
    combos = [PANOV_BASIS[key] for key in CONSTANTS]
    return tuple(BasisAssignment(tuple(combos[i] for i in perm)) for perm in itertools.permutations(range(len(CONSTANTS))))


def algorithm_from_constants(constants, assignment: BasisAssignment | None = None, *, name: str = "candidate") -> Algorithm:
    """The four-sample algorithm ``P + Σ_v a_v B_v`` of one column of Table 1.

    Parameters
    ----------
    constants : sequence of 4 str, Fraction or int
        a1 … a4, exact (strings such as ``"22/45"`` are read as fractions).
    assignment : BasisAssignment, optional
        Which combination each constant multiplies; default the registry's.
    name : str, keyword-only
        Name of the resulting algorithm.

    Returns
    -------
    Algorithm

    Raises
    ------
    ValueError
        If ``constants`` does not hold four exact numbers.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), formula (1), Table 1.

    Examples
    --------
    >>> alg = algorithm_from_constants(("0", "0", "4/3", "0"))
    >>> sorted(alg.pairwise.items())
    [((1, 3), Fraction(4, 3)), ((2, 4), Fraction(4, 3))]
    """
    constants = tuple(constants)
    if len(constants) != len(CONSTANTS):
        raise ValueError(f"Expected `constants` to hold {len(CONSTANTS)} values a1…a4, got {len(constants)}")
    try:
        values = [Fraction(c) for c in constants]
    except (TypeError, ValueError):
        raise ValueError(f"Expected `constants` as exact numbers such as '22/45', got {constants!r}") from None
    mapping = (assignment or BasisAssignment(tuple(PANOV_BASIS[k] for k in CONSTANTS))).mapping
    terms = []
    for key, value in zip(CONSTANTS, values):
        if value:
            terms += [Term(value, pair) for pair in mapping[key]]
    return Algorithm(name, 4, tuple(terms))
