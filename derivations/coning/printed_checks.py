"""Printed formulas of the coning papers against the derivations, exactly.

* Table 2 of Budennyi, Kalinovsky, Panov et al.: the derived local-error
  coefficients of the five algorithms, rescaled to the printed δ4, cell by cell.
* Eq. (2.4) of Lebedev & Panov (1989): the printed h⁷ error of (2.2) against the
  derived one, as vector polynomials in the ω-derivatives (by value: the 20
  printed nested products are linearly dependent, so their coefficients are not
  unique).
* The structure functions of Lebedev & Panov (1989), section 5, printed for
  ρ = 2 and 4, against those derived for (2.2) truncated to that order.

The printed data come from :mod:`strapdown.derivations.coning.published`.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (2), Table 2.
Lebedev & Panov (1989), eqs. (2.2), (2.4), (5.3).
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from typing import NamedTuple

import sympy as sp

from . import drift as D
from . import published as P
from . import series as S
from .registry import get

__all__ = [
    "Table2Check",
    "table2_checks",
    "Eq24Check",
    "eq_2_4_check",
    "StructureFunctionCheck",
    "structure_function_checks",
]


class Table2Check(NamedTuple):
    """One column of Table 2, printed and derived.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5.
    delta : Fraction
        δ4 as printed.
    printed : tuple of int
        k03, k12, k002, k110, k0001 as printed.
    derived : tuple of Fraction
        The same coefficients derived (exact minus algorithm, coefficient of h⁵),
        rescaled to the printed δ4.
    """

    algorithm: int
    delta: Fraction
    printed: tuple
    derived: tuple

    @property
    def differs(self) -> tuple:
        """For each coefficient, True where the derivation contradicts the print."""
        return tuple(d != p for d, p in zip(self.derived, self.printed))

    @property
    def products(self) -> tuple:
        """δ4 · k of the derived coefficients: the invariant of the local error (the coefficients of h⁵)."""
        return tuple(self.delta * d for d in self.derived)

    @property
    def printed_products(self) -> tuple:
        """δ4 · k of the printed coefficients."""
        return tuple(self.delta * Fraction(k) for k in self.printed)


def table2_checks() -> tuple:
    """Table 2 of Budennyi, Kalinovsky, Panov et al., derived cell by cell.

    Returns
    -------
    tuple of Table2Check
        One per algorithm, in the order of the table.

    References
    ----------
    Budennyi, Kalinovsky, Panov et al. (Part 2), Table 2.

    Examples
    --------
    >>> [i for i, bad in enumerate(table2_checks()[3].differs) if bad]   # algorithm 4: k002, k0001
    [2, 4]
    """
    out = []
    for column in P.BUDENNYI_TABLE_2:
        c = S.error_coefficients(get(f"panov-4s-{column.algorithm}"))
        scale = c.delta / column.delta
        derived = tuple(c.coefficients[w] * scale for w in S.ORDER4_BASIS)
        out.append(Table2Check(column.algorithm, column.delta, column.k, derived))
    return tuple(out)


class Eq24Check(NamedTuple):
    """Eq. (2.4) against the derived h⁷ error of the sixth-order algorithm (2.2).

    Attributes
    ----------
    identical : bool
        True if the printed and the derived h⁷ terms are the same vector polynomial.
    lower_weights : tuple of int
        Weights below 7 with a nonzero local error (empty for a sixth-order algorithm).
    """

    identical: bool
    lower_weights: tuple


@cache
def eq_2_4_check(printed: tuple | None = None) -> Eq24Check:
    """Compare eq. (2.4), as printed, with the h⁷ local error of ``lebedev-panov-6``.

    Parameters
    ----------
    printed : tuple of (str, int), optional
        ``((word, coefficient), …)`` of the bracket of (2.4), times 8/945 h⁷; default
        the printed :data:`strapdown.derivations.coning.published.EQ_2_4` (a changed
        coefficient is how a test shows that the comparison can fail).

    Returns
    -------
    Eq24Check

    References
    ----------
    Lebedev & Panov (1989), eqs. (2.2), (2.4).

    Examples
    --------
    >>> eq_2_4_check().identical
    True
    """
    words = tuple(P.EQ_2_4.items()) if printed is None else printed
    err = S.local_error(get("lebedev-panov-6"))
    # (2.4) and the series are both exact minus algorithm.
    printed_error = S.lie_vector([(tuple(int(ch) for ch in w), P.EQ_2_4_FACTOR * c) for w, c in words])
    same = all(a == b for a, b in zip(err.part(7, unit="h"), printed_error))
    lower = tuple(w for w in range(7) if any(err.parts[w]))
    return Eq24Check(same, lower)


class StructureFunctionCheck(NamedTuple):
    """One printed structure function of Lebedev & Panov (1989), section 5, against the derivation.

    Attributes
    ----------
    order : int
        ρ (2 or 4).
    name : str
        ``"f"``, ``"g"``, ``"f_dual"`` or ``"g_dual"``.
    printed : sympy.Expr
        As printed.
    derived : sympy.Expr
        Derived for (2.2) truncated to order ρ.
    """

    order: int
    name: str
    printed: sp.Expr
    derived: sp.Expr

    @property
    def equal(self) -> bool:
        """True if printed and derived are the same expression (after expansion)."""
        return sp.expand(self.derived - self.printed) == 0


def structure_function_checks() -> tuple:
    """Every printed structure function against the derived one.

    Returns
    -------
    tuple of StructureFunctionCheck
        For ρ = 2 then 4: f, g, f°, g°.

    References
    ----------
    Lebedev & Panov (1989), section 5.

    Examples
    --------
    >>> all(c.equal for c in structure_function_checks())
    True
    """
    out = []
    for rho, printed in P.STRUCTURE_FUNCTIONS.items():
        sf = D.structure_functions(get(f"lebedev-panov-{rho}"))
        out += [StructureFunctionCheck(rho, name, expr, getattr(sf, name)) for name, expr in printed.items()]
    return tuple(out)
