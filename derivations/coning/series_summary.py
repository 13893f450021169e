"""What the error series say about each algorithm, ready to print.

Small typed summaries of :mod:`strapdown.derivations.coning.series` and
:mod:`strapdown.derivations.coning.drift`: the exact rotation-vector increment
reduced to an independent basis of nested products, the local error of an
algorithm (order, nonzero weights, leading coefficients), its drift
coefficients and structure functions in factored form.  Nothing here is new
mathematics; it is the derivations in the shape a report or a user reads.

References
----------
Lebedev & Panov (1989), eqs. (2.4), (5.3); Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (2), Table 2.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from typing import NamedTuple

import sympy as sp

from . import drift as D
from . import series as S
from .algorithms import Algorithm

__all__ = [
    "ExactIncrement",
    "exact_increment",
    "LocalErrorSummary",
    "local_error_summary",
    "DriftCoefficients",
    "drift_coefficients",
    "StructureSummary",
    "structure_summary",
]


class ExactIncrement(NamedTuple):
    """The exact rotation-vector increment as a series of nested products (``H = 1``).

    Attributes
    ----------
    step : tuple
        Over the whole step ``[t_m − H/2, t_m + H/2]``, as ``((word, Fraction), …)``.
    first_half : tuple
        Over the first half step ``[t_m − H/2, t_m]``.
    """

    step: tuple
    first_half: tuple


@cache
def exact_increment() -> ExactIncrement:
    """The exact increment over the step and over its first half, in an independent Lie basis.

    Returns
    -------
    ExactIncrement

    Examples
    --------
    >>> exact_increment().step[0]
    ((0,), Fraction(1, 1))
    """
    return ExactIncrement(S.lie_basis_reduce(S.exact_words()), S.lie_basis_reduce(S.exact_words(Fraction(-1, 2), Fraction(0))))


class LocalErrorSummary(NamedTuple):
    """Local error of one algorithm through weight 7.

    Attributes
    ----------
    name : str
        Algorithm name.
    samples : int
        N.
    order : int or None
        ρ (None if the error vanishes through weight 7).
    nonzero_weights : tuple of int
        Weights with a nonzero error part.
    leading : strapdown.derivations.coning.series.ErrorCoefficients
        Leading term in the convention of Table 2 (exact minus algorithm, ``h`` the sample interval).
    """

    name: str
    samples: int
    order: int | None
    nonzero_weights: tuple
    leading: S.ErrorCoefficients


def local_error_summary(algorithm: Algorithm) -> LocalErrorSummary:
    """Order, nonzero weights and leading coefficients of the local error of ``algorithm``.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.

    Returns
    -------
    LocalErrorSummary

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> local_error_summary(get("lebedev-panov-6")).nonzero_weights
    (7,)
    """
    err = S.local_error(algorithm)
    weights = tuple(w for w, part in enumerate(err.parts) if any(part))
    return LocalErrorSummary(algorithm.name, algorithm.samples, err.order, weights, S.error_coefficients(algorithm))


class DriftCoefficients(NamedTuple):
    """The drift coefficients of weights 5 and 7 of one algorithm, factored.

    Attributes
    ----------
    name : str
        Algorithm name.
    d5, d7 : sympy.Expr
        ``d_5(ε, ϑ)``, ``d_7(ε, ϑ)``: the drift is ``Σ d_w ν^w H^(w−1)`` [rad/s].
    """

    name: str
    d5: sp.Expr
    d7: sp.Expr


def drift_coefficients(algorithm: Algorithm) -> DriftCoefficients:
    """``d_5`` and ``d_7`` of ``algorithm`` in factored form.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.

    Returns
    -------
    DriftCoefficients

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> drift_coefficients(get("lebedev-panov-6")).d5
    0
    """
    d = D.drift_coefficients(algorithm)
    return DriftCoefficients(algorithm.name, sp.factor(d[5]), sp.factor(d[7]))


class StructureSummary(NamedTuple):
    """Structure functions of one algorithm (Lebedev & Panov 1989, (5.3)).

    Attributes
    ----------
    name : str
        Algorithm name.
    delta : Fraction
        δ_ρ.
    f, g : sympy.Expr
        ``f_ρ(ε, ϑ)``, ``g_ρ(ε, ϑ)``.
    drift_factor : sympy.Expr
        ``g_ρ + f_ρ cos ϑ``, factored: the drift is ``δ_ρ h^ρ / r · εν^{ρ+1} sin²ϑ (g_ρ + f_ρ cos ϑ)``.
    """

    name: str
    delta: Fraction
    f: sp.Expr
    g: sp.Expr
    drift_factor: sp.Expr


def structure_summary(algorithm: Algorithm) -> StructureSummary:
    """δ_ρ, f_ρ, g_ρ and the factored drift factor of ``algorithm``.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.

    Returns
    -------
    StructureSummary

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> structure_summary(get("panov-4s-3")).drift_factor
    -2*(epsilon - 1)*(epsilon + 1)
    """
    sf = D.structure_functions(algorithm)
    return StructureSummary(algorithm.name, sf.delta, sf.f, sf.g, sp.factor(sf.drift_factor))
