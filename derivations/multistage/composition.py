"""The composite of two stages: every correction of stage 1 cancels, Plotnikov (1999), (2.1)–(2.6).

Stage 1 obeys ``2ν' = ν∘ω + C`` with C its whole correction (position,
integral and norm terms, on any components).  Stage 2 is driven by the rate of
the frame modelled by stage 1, (2.2),

    ω_η(1) = ν∘(ω − ω⁽¹⁾)∘ν̄,    ω⁽¹⁾ = 2 ν̄∘ν',

and obeys ``2ν₁' = ν₁∘ω_η(1) + C₁``.  For the composite ``P = ν₁∘ν`` of (2.6)
this module derives, with SymPy quaternions::

    2P' = P∘ω + C₁∘ν + (|ν|² − 1) P∘ω + 2(1 − |ν|⁴) ν₁∘ν',

so that for a unit ν (which the norm-keeping term maintains, and which the
numerical cascade enforces) ``2P' = P∘ω + C₁∘ν``: C has cancelled.  With the
inverse ``ν⁻¹ = ν̄/|ν|²`` in place of ν̄ in (2.2) the cancellation is exact for
any norm.  The composite is therefore the gyro-integrated attitude corrected
only by stage 2: whatever stage 1 does to the yaw, the composite's yaw follows
the gyros.

Examples
--------
>>> d = derive()
>>> d.cancels_unit_norm, d.cancels_any_norm_with_inverse
(True, True)
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import NamedTuple

import sympy as sp
from sympy.algebras.quaternion import Quaternion

from ..reproducible import reproducible_sympy

__all__ = ["CompositionSymbols", "SYMBOLS", "CompositionDerivation", "derive"]


class CompositionSymbols(NamedTuple):
    """Symbols of the derivation (functions of the time ``t``).

    Attributes
    ----------
    t : sympy.Symbol
        Time.
    nu : tuple
        Components of the stage-1 estimate ν.
    nu1 : tuple
        Components of the stage-2 estimate ν₁.
    omega : tuple
        Body rate ω (pure quaternion, three components).
    C : tuple
        Components of the stage-1 correction.
    C1 : tuple
        Components of the stage-2 correction.
    """

    t: sp.Symbol
    nu: tuple
    nu1: tuple
    omega: tuple
    C: tuple
    C1: tuple


def _functions(name, count, t):
    return tuple(sp.Function(f"{name}{i}", real=True)(t) for i in range(count))


_t = sp.Symbol("t", real=True)
#: The symbols of :func:`derive`.
SYMBOLS = CompositionSymbols(_t, _functions("nu", 4, _t), _functions("nuI", 4, _t), _functions("omega", 3, _t), _functions("C", 4, _t), _functions("CI", 4, _t))


def _comps(q):
    return [q.a, q.b, q.c, q.d]


@dataclass(frozen=True)
class CompositionDerivation:
    """Results of :func:`derive` (SymPy expressions, components 0…3).

    Attributes
    ----------
    composite_rate : list
        ``2P'`` with (1.5) and (2.1) substituted, ν̄ as printed in (2.2).
    expected : list
        ``P∘ω + C₁∘ν``.
    residual : list
        ``composite_rate − expected``, expanded.
    residual_structure : list
        ``(|ν|² − 1) P∘ω + 2(1 − |ν|⁴) ν₁∘ν'`` (ν' from (1.5)).
    cancels_unit_norm : bool
        ``residual − residual_structure`` expands to 0 (so the residual vanishes for ``|ν|`` = 1).
    stage1_correction_free : bool
        No component of C appears in ``composite_rate`` once ``|ν|`` = 1 is used,
        i.e. in ``composite_rate − residual_structure``.
    cancels_any_norm_with_inverse : bool
        With ν⁻¹ for ν̄ in (2.2), ``2P' − P∘ω − C₁∘ν`` expands to exactly 0.
    """

    composite_rate: list
    expected: list
    residual: list
    residual_structure: list
    cancels_unit_norm: bool
    stage1_correction_free: bool
    cancels_any_norm_with_inverse: bool


@lru_cache(maxsize=1)
@reproducible_sympy
def derive() -> CompositionDerivation:
    """Derive the equation of the composite ``P = ν₁∘ν`` of two stages.

    Returns
    -------
    CompositionDerivation

    References
    ----------
    Plotnikov (1999), eqs. (1.5), (2.1), (2.2), (2.6), (3.13).
    """
    s = SYMBOLS
    nu, nu1 = Quaternion(*s.nu), Quaternion(*s.nu1)
    omega = Quaternion(0, *s.omega)
    corr, corr1 = Quaternion(*s.C), Quaternion(*s.C1)
    nudot = (nu * omega + corr) * sp.Rational(1, 2)  # (1.5), whatever C holds
    norm2 = sum(c * c for c in s.nu)
    # (2.2) with ν̄ r on the right: r = 1 as printed, r = 1/|ν|² for the inverse.
    r = sp.Symbol("r", positive=True)
    right = nu.conjugate() * r
    rate1 = right * nudot * 2  # ω⁽¹⁾
    frame_rate = nu * (omega - rate1) * right  # ω_η(1)
    nu1dot = (nu1 * frame_rate + corr1) * sp.Rational(1, 2)  # (2.1)
    p = nu1 * nu
    expected = _comps(p * omega + corr1 * nu)
    general = [sp.expand(2 * a - b) for a, b in zip(_comps(nu1dot * nu + nu1 * nudot), expected)]  # 2P' − P∘ω − C₁∘ν
    residual = [c.subs(r, 1) for c in general]
    structure = [sp.expand(c) for c in _comps(p * omega * (norm2 - 1) + nu1 * nudot * (2 * (1 - norm2**2)))]
    cancels = all(sp.expand(a - b) == 0 for a, b in zip(residual, structure))
    expected = [sp.expand(c) for c in expected]
    rate = [sp.expand(a + b) for a, b in zip(residual, expected)]
    free = not any(sp.expand(a - b).has(c) for a, b in zip(rate, structure) for c in s.C)

    def with_inverse(expr):
        # Replace r^k by |ν|^(-2k): multiply through by |ν|^(2·degree).
        poly = sp.Poly(expr, r)
        deg = poly.degree()
        return sp.expand(sum(c * norm2 ** (deg - k) for (k,), c in poly.terms()))

    exact = all(with_inverse(c) == 0 for c in general)
    return CompositionDerivation(
        composite_rate=rate,
        expected=expected,
        residual=residual,
        residual_structure=structure,
        cancels_unit_norm=bool(cancels),
        stage1_correction_free=bool(free),
        cancels_any_norm_with_inverse=bool(exact),
    )
