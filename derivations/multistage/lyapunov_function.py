"""Lyapunov analysis of the first-variant stage, Plotnikov (1999), eqs. (3.1)–(3.4).

With an exact external reference (c = 1, μ⁺ = μ) the perturbation ``z = ν − μ``
of (1.5) and the integral correction ``y = l ∫ z dτ`` obey (3.1):

    2z' = z∘ω − k z − y,        y' = l z,

with ω the (pure) body-rate quaternion.  This module derives, with quaternion
algebra in SymPy (:class:`sympy.algebras.quaternion.Quaternion`):

* ``V = l z∘z̄ + ½ y∘ȳ`` (3.2) and its derivative along (3.1),
  ``V' = −l k z∘z̄`` (3.4) — exactly, for any body rate ω(t);
* the LaSalle step: on the set ``V' = 0`` (z ≡ 0) the equations force y = 0;
* a *strict* Lyapunov function ``W = V + ε z·y`` with its exact derivative,
  which gives uniform exponential stability for a bounded body rate
  ``|ω| ≤ ϖ`` and an explicit rate;
* the characteristic polynomial for ω = 0, ``(2s² + ks + l)⁴``, whose roots
  give the exponential rate in terms of k and l.

``V'`` is only negative semidefinite (it does not contain y), so the
Lyapunov theorem gives stability, not asymptotic stability: the paper's
conclusion (3.4) needs the LaSalle step (autonomous case, ω constant) or the
strict function W (time-varying ω).

Examples
--------
>>> d = derive()
>>> d.vdot_matches
True
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import NamedTuple

import sympy as sp
from sympy.algebras.quaternion import Quaternion

from ..reproducible import reproducible_sympy

__all__ = ["LyapunovSymbols", "SYMBOLS", "LyapunovDerivation", "derive", "perturbation_rhs", "strict_bound_matrices"]


class LyapunovSymbols(NamedTuple):
    """Symbols of the Lyapunov analysis (:data:`SYMBOLS`).

    Attributes
    ----------
    k, l : sympy.Symbol
        Position and integral gains (positive).
    z : tuple of sympy.Symbol
        Components of the perturbation z.
    y : tuple of sympy.Symbol
        Components of the integral correction y.
    omega : tuple of sympy.Symbol
        Components of the body rate ω.
    epsilon : sympy.Symbol
        Weight ε of the cross term of the strict Lyapunov function.
    varpi : sympy.Symbol
        Bound ϖ on ``|ω|``.
    s : sympy.Symbol
        Laplace variable.
    """

    k: sp.Symbol
    l: sp.Symbol
    z: tuple
    y: tuple
    omega: tuple
    epsilon: sp.Symbol
    varpi: sp.Symbol
    s: sp.Symbol


#: The symbols of the Lyapunov analysis.
SYMBOLS = LyapunovSymbols(
    *sp.symbols("k l", positive=True),
    sp.symbols("z0:4", real=True),
    sp.symbols("y0:4", real=True),
    sp.symbols("omega1:4", real=True),
    *sp.symbols("epsilon varpi", positive=True),
    sp.Symbol("s"),
)


def _q(c):
    return Quaternion(*c)


def _comps(q):
    return [q.a, q.b, q.c, q.d]


def perturbation_rhs(k, l, z, y, w):
    """Right-hand sides ``(z', y')`` of (3.1) as lists of components.

    Parameters
    ----------
    k, l : sympy.Expr
        Gains.
    z, y : sequence of 4 sympy.Expr
        Perturbation and integral correction.
    w : sequence of 3 sympy.Expr
        Body rate ω.

    Returns
    -------
    zdot, ydot : list of sympy.Expr
    """
    zq, yq, wq = _q(z), _q(y), Quaternion(0, *w)
    zdot = (zq * wq - k * zq - yq) * sp.Rational(1, 2)
    ydot = l * zq
    return [sp.expand(c) for c in _comps(zdot)], [sp.expand(c) for c in _comps(ydot)]


def _along(f, states, rates):
    """Derivative of ``f`` along a vector field (chain rule)."""
    return sp.expand(sum(sp.diff(f, s) * r for s, r in zip(states, rates)))


def strict_bound_matrices(k, l, eps, wbar):
    """Quadratic-form bounds of the strict Lyapunov function in (``|z|``, ``|y|``).

    With ``|ω| ≤ ϖ`` and Cauchy–Schwarz, ``−W' ≥ [a b] M [a b]ᵀ`` and
    ``[a b] P₋ [a b]ᵀ ≤ W ≤ [a b] P₊ [a b]ᵀ`` for ``a = |z|``, ``b = |y|``.

    Parameters
    ----------
    k, l : sympy.Expr
        Gains.
    eps : sympy.Expr
        Weight ε of the cross term.
    wbar : sympy.Expr
        Bound ϖ on ``|ω|``.

    Returns
    -------
    M, P_plus, P_minus : sympy.Matrix
    """
    m = sp.Matrix([[l * (k - eps), -eps * (k + wbar) / 4], [-eps * (k + wbar) / 4, eps / 2]])
    p_plus = sp.Matrix([[l, eps / 2], [eps / 2, sp.Rational(1, 2)]])
    p_minus = sp.Matrix([[l, -eps / 2], [-eps / 2, sp.Rational(1, 2)]])
    return m, p_plus, p_minus


@dataclass(frozen=True)
class LyapunovDerivation:
    """Results of :func:`derive` (SymPy expressions).

    Attributes
    ----------
    V : sympy.Expr
        ``l z∘z̄ + ½ y∘ȳ`` (scalar part; the vector part is identically 0).
    Vdot : sympy.Expr
        Derivative of V along (3.1), simplified.
    Vdot_expected : sympy.Expr
        ``−l k z∘z̄`` of (3.4).
    vdot_matches : bool
        ``Vdot − Vdot_expected`` expands to exactly 0.
    vector_part_zero : bool
        ``z∘z̄`` and ``y∘ȳ`` have zero vector parts.
    lasalle_zdot : list
        ``z'`` on the set ``z = 0``: ``−y/2``; it vanishes only for y = 0.
    W : sympy.Expr
        Strict Lyapunov function ``V + ε z·y``.
    Wdot : sympy.Expr
        Its derivative along (3.1).
    Wdot_structure : sympy.Expr
        ``−lk|z|² + ε(l|z|² − ½|y|² − (k/2) z·y + ½ y·(z∘ω))``.
    wdot_matches : bool
        ``Wdot − Wdot_structure`` expands to exactly 0.
    eps_max : sympy.Expr
        Upper limit of ε for ``M > 0``: ``8lk/(8l + (k + ϖ)²)`` (also ε² < 2l for W > 0).
    charpoly_rest : sympy.Expr
        Characteristic polynomial of (3.1) for ω = 0, factored.
    rate_roots : list
        Roots of ``2s² + ks + l``.
    """

    V: sp.Expr
    Vdot: sp.Expr
    Vdot_expected: sp.Expr
    vdot_matches: bool
    vector_part_zero: bool
    lasalle_zdot: list
    W: sp.Expr
    Wdot: sp.Expr
    Wdot_structure: sp.Expr
    wdot_matches: bool
    eps_max: sp.Expr
    charpoly_rest: sp.Expr
    rate_roots: list


@lru_cache(maxsize=1)
@reproducible_sympy
def derive() -> LyapunovDerivation:
    """Derive V, V', the LaSalle step, the strict function W and the rest rates.

    References
    ----------
    Plotnikov (1999), eqs. (3.1)–(3.4).
    """
    k, l, z, y, w = SYMBOLS.k, SYMBOLS.l, SYMBOLS.z, SYMBOLS.y, SYMBOLS.omega
    zdot, ydot = perturbation_rhs(k, l, z, y, w)
    zq, yq = _q(z), _q(y)
    zz, yy = zq * zq.conjugate(), yq * yq.conjugate()
    vector_zero = all(sp.expand(c) == 0 for c in _comps(zz)[1:] + _comps(yy)[1:])
    V = sp.expand(l * zz.a + sp.Rational(1, 2) * yy.a)
    states, rates = list(z) + list(y), zdot + ydot
    Vdot = sp.factor(_along(V, states, rates))
    Vdot_expected = -l * k * sp.expand(zz.a)
    vdot_matches = sp.expand(Vdot - Vdot_expected) == 0

    # LaSalle: on {V' = 0} = {z = 0}, z' = −y/2, so invariance forces y = 0.
    lasalle = [sp.simplify(c.subs({zi: 0 for zi in z})) for c in zdot]

    eps, wbar = SYMBOLS.epsilon, SYMBOLS.varpi
    zy = sum(a * b for a, b in zip(z, y))
    W = V + eps * zy
    Wdot = _along(W, states, rates)
    zw = zq * Quaternion(0, *w)
    y_dot_zw = sum(a * b for a, b in zip(y, _comps(zw)))
    z2, y2 = sum(c * c for c in z), sum(c * c for c in y)
    structure = -l * k * z2 + eps * (l * z2 - y2 / 2 - k * zy / 2 + y_dot_zw / 2)
    wdot_matches = sp.expand(Wdot - structure) == 0
    m, _, _ = strict_bound_matrices(k, l, eps, wbar)
    eps_max = sp.simplify(sp.solve(sp.Eq(m.det(), 0), eps)[-1])

    # Rates at rest (ω = 0): det(sI − A) for the 8-dimensional linear system.
    s = SYMBOLS.s
    zero_w = {wi: 0 for wi in w}
    jac = sp.Matrix(rates).subs(zero_w).jacobian(states)
    charpoly = sp.factor(jac.charpoly(s).as_expr())
    roots = sp.solve(2 * s**2 + k * s + l, s)
    return LyapunovDerivation(
        V=V,
        Vdot=Vdot,
        Vdot_expected=Vdot_expected,
        vdot_matches=bool(vdot_matches),
        vector_part_zero=bool(vector_zero),
        lasalle_zdot=lasalle,
        W=W,
        Wdot=Wdot,
        Wdot_structure=structure,
        wdot_matches=bool(wdot_matches),
        eps_max=eps_max,
        charpoly_rest=charpoly,
        rate_roots=roots,
    )
