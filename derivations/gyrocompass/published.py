"""What Hrechka & Koroliov print, typed from the paper: reference data, never an input.

The paper's formulas are kept here once, as SymPy expressions in the symbols of
:data:`strapdown.derivations.gyrocompass.azimuth_error.SYMBOLS`, each with the
place it comes from.  Tests, the report and the errata compare them with what
the package derives; nothing in the library computes with them.

A printed formula that the derivation contradicts stays here as printed (it is
the evidence of the erratum).

References
----------
Hrechka & Koroliov, "Estimation of the azimuth error of a self-orienting SINS
under random rocking": eq. (2) and the lines after it, (5)–(10), (14), (15),
(16), conclusions 2 and 4.
"""

from __future__ import annotations

from functools import cache
from typing import NamedTuple

import sympy as sp

from .azimuth_error import SYMBOLS

__all__ = ["PrintedFormula", "PrintedStatement", "printed_formulas", "printed_formula", "STATEMENTS", "SOURCE"]

#: The paper, as cited in the project.
SOURCE = "Hrechka & Koroliov"


class PrintedFormula(NamedTuple):
    """One formula as printed.

    Attributes
    ----------
    label : str
        The paper's label, e.g. ``"(7)"``, or a description for unnumbered lines.
    expression : sympy.Expr
        The printed right-hand side, in the symbols of ``SYMBOLS`` (β = β0 + ξ,
        γ = γ0 + η substituted where the paper writes β, γ).
    source : str
        Where it is printed.
    order : int or None
        Total degree in (ξ, η) to which the printed formula is stated (its
        ``O(ξ² + η²)`` remainder dropped); None for an exact formula.
    """

    label: str
    expression: sp.Expr
    source: str
    order: int | None


class PrintedStatement(NamedTuple):
    """A claim in words, quoted in translation.

    Attributes
    ----------
    label : str
        Short name.
    text : str
        The claim (translated from Ukrainian).
    source : str
        Where it is printed.
    """

    label: str
    text: str
    source: str


@cache
def printed_formulas() -> tuple:
    """The printed formulas of the tilt correction and its expansion, in print order.

    Returns
    -------
    tuple of PrintedFormula

    References
    ----------
    Hrechka & Koroliov, the definition of A, B after eq. (2) and eqs. (5)–(10).
    """
    s = SYMBOLS
    phi, b0, g0, xi, eta = s.phi, s.beta0, s.gamma0, s.xi, s.eta
    cos, sin = sp.cos, sp.sin
    beta, gamma = b0 + xi, g0 + eta
    src = f"{SOURCE}, "
    return (
        PrintedFormula("A (after (2))", cos(phi) * sin(gamma) + sin(phi) * cos(beta) * sin(gamma), src + "definition of A after eq. (2)", None),
        PrintedFormula("B (after (2))", sin(phi) * sin(beta), src + "definition of B after eq. (2)", None),
        PrintedFormula(
            "(5)",
            cos(phi) * cos(g0) + sin(phi) * cos(b0) * sin(g0) - eta * cos(phi) * sin(g0) + sin(phi) * (eta * cos(b0) * cos(g0) - xi * sin(b0) * sin(g0)),
            src + "eq. (5)",
            1,
        ),
        PrintedFormula("(6)", cos(phi) * cos(g0) + sin(phi) * cos(b0) * sin(g0), src + "eq. (6)", None),
        PrintedFormula("(7)", eta * (sin(phi) * cos(b0) * cos(g0) - cos(phi) * sin(g0)) - xi * sin(phi) * cos(b0) * sin(g0), src + "eq. (7)", 1),
        PrintedFormula("(8)", sin(phi) * sin(b0) + xi * sin(phi) * cos(b0), src + "eq. (8)", 1),
        PrintedFormula("(9)", sin(phi) * sin(b0), src + "eq. (9)", None),
        PrintedFormula("(10)", xi * sin(phi) * cos(b0), src + "eq. (10)", 1),
    )


def printed_formula(label: str) -> PrintedFormula:
    """The printed formula with the given label.

    Parameters
    ----------
    label : str
        E.g. ``"(7)"`` or ``"A (after (2))"``.

    Returns
    -------
    PrintedFormula

    Raises
    ------
    ValueError
        For an unknown label.

    >>> printed_formula("(9)").expression
    sin(beta_0)*sin(varphi)
    """
    for f in printed_formulas():
        if f.label == label:
            return f
    raise ValueError(f"Expected `label` among {', '.join(f.label for f in printed_formulas())}, got {label!r}")


#: Printed claims the report tests (quoted in translation).
STATEMENTS = (
    PrintedStatement("(15)", "δ ≤ tg φ √Dξ, obtained from (14) after discarding the first-order terms in β0, γ0", f"{SOURCE}, eq. (15)"),
    PrintedStatement(
        "conclusion 2",
        "the rms azimuth error is proportional to tg φ and to the square root of the variance of the rocking about the gyro's sensitive axis, "
        "and practically does not depend on the oscillations in other planes",
        f"{SOURCE}, conclusion 2",
    ),
    PrintedStatement(
        "(2)",
        "α = −arctg(f2/f1) + σ with σ = arctg(B/A): the azimuth from two horizontal gyros, σ the levelling error of their axes",
        f"{SOURCE}, eq. (2) and the lines after it",
    ),
    PrintedStatement(
        "conclusion 4",
        "the admissible rocking parameters (amplitude and frequency) for a given azimuth error are left to further research",
        f"{SOURCE}, conclusion 4",
    ),
)
