"""The tilt quaternion (1.9)–(1.10) of Plotnikov (1999), derived from (1.7)–(1.8).

With ψ = 0, the load factors ``n = W/g`` of (1.8),
``n₁ = sin θ``, ``n₂ = cos θ cos γ``, ``n₃ = −cos θ sin γ`` (for ``|n|`` = 1; in
general divided by ``n = |n|``), give

    sin θ = n₁/n,  cos θ = h/n,  sin γ = −n₃/h,  cos γ = n₂/h,   h = √(n₂² + n₃²),

and (1.10) takes the quaternion from the direction-cosine matrix A of (1.7):
``μ₀ = ½√(1 + a₁₁ + a₂₂ + a₃₃)``, ``μ₁ = (a₂₃ − a₃₂)/4μ₀``,
``μ₂ = −(a₁₃ − a₃₁)/4μ₀``, ``μ₃ = (a₁₂ − a₂₁)/4μ₀``.  This module does the
substitution and compares the result with the formulas as printed
(:mod:`strapdown.derivations.multistage.published`).

Examples
--------
>>> d = derive()
>>> d.matches_printed
(False, True, True, False)
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from ..reproducible import reproducible_sympy

__all__ = ["TiltQuaternionDerivation", "derive"]


@dataclass(frozen=True)
class TiltQuaternionDerivation:
    """Results of :func:`derive`.

    Attributes
    ----------
    components : tuple of sympy.Expr
        (μ₀, μ₁, μ₂, μ₃) in ``n1, n2, n3, h, n`` of
        :data:`strapdown.derivations.multistage.published.SYMBOLS`.
    cos_gamma : sympy.Expr
        cos γ from (1.8): ``n₂/h``.
    matches_printed : tuple of bool
        Whether μ₀, and 4μ₀μ₁, 4μ₀μ₂, 4μ₀μ₃ (the printed recipe applied to its
        own μ₀), equal the printed ones (with ``h² = n₂² + n₃²``, ``n² = n₁² + h²``).
    cos_gamma_matches_printed : bool
        Whether cos γ equals the printed ``−n₂/h``.
    """

    components: tuple
    cos_gamma: sp.Expr
    matches_printed: tuple
    cos_gamma_matches_printed: bool


def _equal(a, b, n1, n2, n3, h, n) -> bool:
    """Equality on the load factors, at exact points evaluated to 50 digits (h, n substituted)."""
    sub = {h: sp.sqrt(n2**2 + n3**2), n: sp.sqrt(n1**2 + n2**2 + n3**2)}
    diff = (a - b).subs(sub)
    points = ((sp.Rational(1, 3), sp.Rational(2, 3), sp.Rational(-2, 3)), (sp.Rational(-1, 5), sp.Rational(4, 5), sp.Rational(1, 7)), (sp.Rational(3, 10), sp.Rational(9, 10), sp.Rational(2, 5)))
    return all(abs(sp.N(diff.subs(dict(zip((n1, n2, n3), p))), 50)) < sp.Float("1e-40") for p in points)


@lru_cache(maxsize=1)
@reproducible_sympy
def derive() -> TiltQuaternionDerivation:
    """Substitute (1.9) into (1.7) with ψ = 0 and form (1.10).

    Returns
    -------
    TiltQuaternionDerivation

    References
    ----------
    Plotnikov (1999), eqs. (1.7)–(1.10).
    """
    from . import published

    s = published.SYMBOLS
    n1, n2, n3, h, n = s.n1, s.n2, s.n3, s.h, s.n
    theta, gamma = sp.symbols("theta gamma", real=True)
    psi = sp.Integer(0)
    # (1.7), the Krylov-angle form of A (x = A η).
    a = sp.Matrix(
        [
            [sp.cos(psi) * sp.cos(theta), sp.sin(theta), -sp.sin(psi) * sp.cos(theta)],
            [-sp.cos(psi) * sp.sin(theta) * sp.cos(gamma) + sp.sin(psi) * sp.sin(gamma), sp.cos(theta) * sp.cos(gamma), sp.sin(psi) * sp.sin(theta) * sp.cos(gamma) + sp.cos(psi) * sp.sin(gamma)],
            [sp.sin(psi) * sp.cos(gamma) + sp.sin(gamma) * sp.sin(theta) * sp.cos(psi), -sp.cos(theta) * sp.sin(gamma), sp.cos(psi) * sp.cos(gamma) - sp.sin(psi) * sp.sin(theta) * sp.sin(gamma)],
        ]
    )
    # (1.8): W = g (sin θ, cos θ cos γ, −cos θ sin γ); so with h = √(n₂² + n₃²) = n cos θ:
    angles = {sp.sin(theta): n1 / n, sp.cos(theta): h / n, sp.sin(gamma): -n3 / h, sp.cos(gamma): n2 / h}
    a = a.subs(angles)
    mu0 = sp.sqrt(1 + a[0, 0] + a[1, 1] + a[2, 2]) / 2
    comps = (
        sp.simplify(mu0),
        sp.simplify((a[1, 2] - a[2, 1]) / (4 * mu0)),
        sp.simplify(-(a[0, 2] - a[2, 0]) / (4 * mu0)),
        sp.simplify((a[0, 1] - a[1, 0]) / (4 * mu0)),
    )
    printed = published.PRINTED_TILT_QUATERNION_1_10
    # μ₀ as it stands; μ₁…μ₃ through 4μ₀μᵢ (the printed recipe applied to its own μ₀).
    matches = (_equal(comps[0], printed[0], n1, n2, n3, h, n),) + tuple(_equal(c * comps[0], p * printed[0], n1, n2, n3, h, n) for c, p in zip(comps[1:], printed[1:]))
    cos_gamma = angles[sp.cos(gamma)]
    return TiltQuaternionDerivation(comps, cos_gamma, matches, _equal(cos_gamma, published.PRINTED_COS_GAMMA_1_9, n1, n2, n3, h, n))
