"""The two-sample algorithm tuned to one coning line: its coefficient in closed form.

In a vibration environment (``strapdown.analysis.vibration.drift``) a
line of coning vector q reaches the algorithm as ``q̃ = ρ q``, where ρ is the
fraction of its coning the sensors pass (``ρ = |H(iω)|²`` for identical
filters).  The mean drift, to second order in the amplitude and exactly in
``x = ωh``, is

    u = (q/ω) [ (1 − ρ)/2 + ρ D(x) ],      D(x) = [E(2x) − k R₁(x)] / (2x)

for a two-sample algorithm with coefficient k (``E`` and ``R₁`` from
:func:`strapdown.derivations.coning.drift.exact_coning_response` and
:func:`~strapdown.derivations.coning.drift.lag_response`).  It vanishes for

    k(x, ρ) = [x/ρ − sin(2x)/2] / (2 sin x − sin 2x),

which :func:`two_sample_null_coefficient` solves for (not typed in).  With
ideal sensors (ρ = 1) ``k → 2/3`` as x → 0, the classical coefficient; a
first-order low-pass of cut-off ω_c (``ρ = 1/(1 + (ω/ω_c)²)``, with
``c = ω_c h``) gives ``k → 2/3 + 1/c²``: the algorithm then also compensates
the filter's pseudo-coning (Mark & Tazartes 1996).

Public API
----------
.. autosummary::

   RHO
   CUTOFF
   two_sample_null_coefficient
   lowpass_null_coefficient

References
----------
Ignagni (1990); Mark & Tazartes (1996), "Tuning of coning algorithms to gyro
data frequency response characteristics".
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from ..reproducible import reproducible_sympy
from .drift import X, exact_coning_response, lag_response

__all__ = ["RHO", "CUTOFF", "two_sample_null_coefficient", "lowpass_null_coefficient"]

#: Fraction ρ = q̃/q of a line's coning vector that the sensors pass [-].
RHO = sp.Symbol("rho", positive=True)
#: ``c = ω_c h``: a first-order filter's cut-off in units of the sample rate [rad].
CUTOFF = sp.Symbol("c", positive=True)


@cache
@reproducible_sympy
def two_sample_null_coefficient() -> sp.Expr:
    """``k(x, ρ)`` that nulls the mean drift of a two-sample algorithm on one line (module docstring).

    Returns
    -------
    sympy.Expr
        In :data:`strapdown.derivations.coning.drift.X` (= ωh) and :data:`RHO`.

    Examples
    --------
    >>> k = two_sample_null_coefficient()
    >>> sp.limit(k.subs(RHO, 1), X, 0)
    2/3
    """
    k = sp.Symbol("k")
    drift = (1 - RHO) / 2 + RHO * (exact_coning_response(2) - k * lag_response(1)) / (2 * X)
    (solution,) = sp.solve(sp.Eq(drift, 0), k)
    return sp.simplify(solution)


@cache
@reproducible_sympy
def lowpass_null_coefficient() -> sp.Expr:
    """``k(x, c)`` of :func:`two_sample_null_coefficient` behind a first-order low-pass, ``ρ = 1/(1 + x²/c²)``.

    Returns
    -------
    sympy.Expr
        In :data:`~strapdown.derivations.coning.drift.X` (= ωh) and :data:`CUTOFF` (= ω_c h).

    Examples
    --------
    >>> sp.expand(sp.limit(lowpass_null_coefficient(), X, 0))
    2/3 + c**(-2)
    """
    return sp.simplify(two_sample_null_coefficient().subs(RHO, 1 / (1 + X**2 / CUTOFF**2)))
