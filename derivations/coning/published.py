"""Published numbers of the coning domain, quoted as reference data with their source.

Nothing in the library computes from these: tests, the CLI and the reports
compare what the library computes with them.

Sections
--------
``PUBLISHED_ALGORITHM_ERRORS`` and ``PUBLISHED_ALGORITHM_COEFFICIENTS``
    Error figures and coefficient tables of published coning algorithms
    (Ignagni 1990, 1996; Savage 1998; the PSINS coefficient table).
"""

from __future__ import annotations

from fractions import Fraction
from typing import NamedTuple

__all__ = ["PublishedFigure", "PUBLISHED_ALGORITHM_ERRORS", "PUBLISHED_ALGORITHM_COEFFICIENTS", "PSINS_TABLE_10_1_N6"]


class PublishedFigure(NamedTuple):
    """One published number about an algorithm.

    Attributes
    ----------
    key : str
        Short identifier, unique in its table.
    algorithm : str
        Registry name of the algorithm it is about.
    quantity : str
        What it is: ``"coning_coefficient"`` (ρ_N in the residual coning drift
        ``ρ_N α² Ω (ΩT)^{2N}``, T the algorithm step), ``"coefficient"`` (a
        printed algorithm coefficient).
    value : Fraction
        The printed number, exactly.
    source : str
        Author, year, table or equation.
    note : str
        How it is printed, where that matters.
    """

    key: str
    algorithm: str
    quantity: str
    value: Fraction
    source: str
    note: str = ""


# ===========================================================================
# PUBLISHED_ALGORITHM_ERRORS: published error figures of coning algorithms.
# (This block is self-contained: other tables of the domain go in blocks of
# their own.)
# ===========================================================================
_PSINS = "PSINS toolbox (Yan Gongmin), coning/sculling coefficient table glv.cs with the residual coefficient ρ_N"
#: Residual coning drift of the optimal N-sample compressed algorithm under classical coning
#: (half-cone angle α, coning rate Ω, step T = N h): drift ≈ ρ_N α² Ω (ΩT)^{2N}.  N = 1 is the
#: uncompensated one-sample update.  N = 2, 3 are also printed by Ignagni (1990).
PUBLISHED_ALGORITHM_ERRORS = (
    PublishedFigure("rho-1", "one-sample", "coning_coefficient", Fraction(1, 12), _PSINS, "row N = 1, no coning term"),
    PublishedFigure("rho-2", "compressed-2", "coning_coefficient", Fraction(1, 960), _PSINS),
    PublishedFigure("rho-3", "compressed-3", "coning_coefficient", Fraction(1, 204120), _PSINS),
    PublishedFigure("rho-4", "compressed-4", "coning_coefficient", Fraction(1, 82575360), _PSINS),
    PublishedFigure("rho-5", "compressed-5", "coning_coefficient", Fraction(1, 54140625000), _PSINS),
    PublishedFigure("rho-6", "compressed-6", "coning_coefficient", Fraction(1, 52295018840064), _PSINS),
)

#: Printed coefficients k_1 … k_{N−1} of the compressed optimal algorithms ``(Σ k_i p_i) × p_N``
#: (the registry holds the same numbers as its data; kept here as the quotation the tests
#: compare the derived optimal coefficients with).
PUBLISHED_ALGORITHM_COEFFICIENTS = {
    2: ((Fraction(2, 3),), _PSINS),
    3: ((Fraction(9, 20), Fraction(27, 20)), _PSINS + "; Ignagni (1996), Algorithm 3"),
    4: ((Fraction(54, 105), Fraction(92, 105), Fraction(214, 105)), _PSINS + "; Ignagni (1996), Algorithm 7"),
    5: ((Fraction(250, 504), Fraction(525, 504), Fraction(650, 504), Fraction(1375, 504)), _PSINS),
    6: ((Fraction(2315, 4620), Fraction(4558, 4620), Fraction(7296, 4620), Fraction(7834, 4620), Fraction(15797, 4620)), _PSINS),
}

#: The N = 6 row as the PSINS manual prints it in Tab. 10-1 ("Coning error compensation
#: coefficients"): k_1 = 2135/4620, where the glv.cs table has 2315/4620.
PSINS_TABLE_10_1_N6 = (
    (Fraction(2135, 4620), Fraction(4558, 4620), Fraction(7296, 4620), Fraction(7834, 4620), Fraction(15797, 4620)),
    "PSINS manual (Yan Gongmin), section 10.7, Tab. 10-1, row N = 6",
)
# ============================================================== end of block
