"""The printed formulas of Hrechka & Koroliov against the derivation: symbolic and numeric.

Each printed formula (:mod:`strapdown.derivations.gyrocompass.published`) is
compared with what :mod:`strapdown.derivations.gyrocompass.azimuth_error`
derives from the definition of σ: the simplified symbolic difference, and, as
an independent check of that simplification, the largest numeric residual on
random points (latitude in (0.1, 1.4) rad, tilts and rocking in ±0.5 rad).
Formulas stated to first order are compared with the first-order Taylor part.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import budget
from ..core.validation import as_int

__all__ = ["FormulaCheck", "check_printed_formulas"]


@dataclass(frozen=True)
class FormulaCheck:
    """One printed formula against the derivation.

    Attributes
    ----------
    label : str
        The paper's label.
    printed : sympy.Expr
        As printed.
    derived : sympy.Expr
        As derived (to the order the formula is stated).
    difference : sympy.Expr
        ``simplify(printed − derived)``.
    residual : float
        Largest ``|printed − derived|`` on the random points.
    source : str
        Where the formula is printed.
    """

    label: str
    printed: object
    derived: object
    difference: object
    residual: float
    source: str

    @property
    def agrees(self) -> bool:
        """True when the symbolic difference is zero."""
        return self.difference == 0


def _derived(label: str):
    from ...derivations.gyrocompass import azimuth_error as g

    s = g.SYMBOLS
    p = g.linear_parts()
    A1, B1 = g.taylor_components(1)
    A_full, B_full = g.components(s.beta0 + s.xi, s.gamma0 + s.eta)
    return {
        "A (after (2))": A_full,
        "B (after (2))": B_full,
        "(5)": sum(c * s.xi**i * s.eta**j for (i, j), c in A1.items()),
        "(6)": p.A_star,
        "(7)": p.zeta1,
        "(8)": sum(c * s.xi**i * s.eta**j for (i, j), c in B1.items()),
        "(9)": p.B_star,
        "(10)": p.zeta2,
    }[label]


def check_printed_formulas(*, n_points: int = 200, rng=None, limits: budget.Limits | None = None) -> tuple:
    """Compare every printed formula of (2), (5)–(10) with its derivation.

    Parameters
    ----------
    n_points : int
        Random points of the numeric residual.
    rng : Generator | int | None
        Random stream of the points (default seed 0, so the residuals are reproducible).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    tuple of FormulaCheck

    Raises
    ------
    ValueError
        For ``n_points`` below 1 or beyond ``limits``.

    References
    ----------
    Hrechka & Koroliov, eq. (2) and the lines after it, eqs. (5)–(10).
    """
    import sympy as sp

    from ...derivations.gyrocompass import azimuth_error as g
    from ...derivations.gyrocompass.published import printed_formulas
    from ...derivations.reproducible import reproducible

    n = as_int(n_points, "n_points", minimum=1)
    budget.check(budget.arrays(n, what=f"`n_points` = {n:.3g} points", copies=100.0), limits)
    gen = np.random.default_rng(0 if rng is None else rng)
    s = g.SYMBOLS
    args = (s.phi, s.beta0, s.gamma0, s.xi, s.eta)
    pts = gen.uniform(-0.5, 0.5, size=(5, n))
    pts[0] = gen.uniform(0.1, 1.4, size=n)
    out = []
    with reproducible():
        for f in printed_formulas():
            derived = _derived(f.label)
            diff = sp.simplify(sp.expand(f.expression - derived))
            fn = sp.lambdify(args, f.expression - derived, modules="numpy")
            resid = float(np.max(np.abs(np.broadcast_to(fn(*pts), (n,)))))
            out.append(FormulaCheck(f.label, f.expression, derived, diff, resid, f.source))
    return tuple(out)
