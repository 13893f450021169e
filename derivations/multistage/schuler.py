"""Small-angle linearisation of a corrected stage and its Schuler tuning.

Plotnikov (1999), eqs. (3.5)–(3.12).  The second stage (2.1) with ρ⁽¹⁾ = 0
estimates the attitude ν₁ of the frame η⁽¹⁾ (modelled by stage 1) relative to
its own horizon η⁽²⁾, from

* the absolute rate of η⁽¹⁾ in its axes, ``ω_η(1) = Δ̄∘ω_η∘Δ + 2Δ̄∘Δ'``,
* the specific force re-projected on η⁽¹⁾, ``W⁽¹⁾ = Δ̄∘W∘Δ``, entering through
  the pure quaternion (1.4) ``M₁ = (0, −W₃⁽¹⁾/g, 0, W₁⁽¹⁾/g)``,

where Δ is the rotation η⁽¹⁾ → η by the small stage-1 error angles
(α, β, χ) about the axes 1, 2, 3 of η, ``ω_η = (ω₁, 0, ω₃)`` is the absolute
rate of the azimuth-free horizon η and ``W = (W₁, g, W₃)`` the specific force
in η.  The stage estimate is written with Krylov angles (3.6),
``ν₁ = q₂(ψ₁⁺)∘q₃(θ₁⁺)∘q₁(γ₁⁺)``, and the integral as the state
``y = l ∫(M₁ − 2ν₁) dτ`` on the components 1 and 3.

Nothing is typed in: the scalar equations (3.8) come out of a first-order
Taylor expansion of the quaternion equation in the small quantities (angles,
their rates, the frame rate ω and y), the load factors ``n = W/g`` being
kept as they are (they need not be small).  Then, with ``V̇ = W``,
``ω₃ = −V₁/R``, ``ω₁ = V₃/R`` (a non-rotating Earth, as in the paper), the
Laplace transform of the error ``θ₁⁺ − χ`` gives the transfer function from the
horizontal acceleration to the stage's tilt error,

    E(s)/A(s) = (k s + l − g/R) / (g (s² + k s + l)),

which vanishes identically exactly when k = 0 and l = g/R (3.11)–(3.12).
The same equations with α = β = χ = 0 describe stage 1 of the second variant
(input frame x level), so the formula also gives stage 1's error.

Examples
--------
>>> d = derive()
>>> d.schuler_residual
0
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import NamedTuple

import sympy as sp
from sympy.algebras.quaternion import Quaternion

from ..reproducible import reproducible_sympy

__all__ = ["SchulerSymbols", "SYMBOLS", "SchulerDerivation", "derive", "krylov_quaternion", "accel_to_tilt_tf"]


class SchulerSymbols(NamedTuple):
    """Symbols of the linearisation (:data:`SYMBOLS`).

    Attributes
    ----------
    k, l : sympy.Symbol
        Position and integral gains.
    g, R : sympy.Symbol
        Gravity and Earth radius.
    t, s : sympy.Symbol
        Time and the Laplace variable.
    alpha, beta, chi : sympy.Function
        Small stage-1 error angles about the axes 1, 2, 3 of η (functions of t).
    psi1, theta1, gamma1 : sympy.Function
        Krylov angles of ν₁ (3.6).
    omega1, omega3 : sympy.Function
        Horizontal absolute rate of η.
    y1, y3 : sympy.Function
        Integral states of the components 1 and 3.
    n1, n3 : sympy.Function
        Horizontal load factors W/g in η.
    """

    k: sp.Symbol
    l: sp.Symbol
    g: sp.Symbol
    R: sp.Symbol
    t: sp.Symbol
    s: sp.Symbol
    alpha: sp.Expr
    beta: sp.Expr
    chi: sp.Expr
    psi1: sp.Expr
    theta1: sp.Expr
    gamma1: sp.Expr
    omega1: sp.Expr
    omega3: sp.Expr
    y1: sp.Expr
    y3: sp.Expr
    n1: sp.Expr
    n3: sp.Expr


def _make_symbols() -> SchulerSymbols:
    t = sp.Symbol("t", real=True)
    names = ["alpha", "beta", "chi", "psi1", "theta1", "gamma1", "omega1", "omega3", "y1", "y3", "n1", "n3"]
    return SchulerSymbols(*sp.symbols("k l g R", positive=True), t, sp.Symbol("s"), *(sp.Function(n, real=True)(t) for n in names))


#: The symbols of the linearisation.
SYMBOLS = _make_symbols()


def krylov_quaternion(psi, theta, gamma) -> Quaternion:
    """``q₂(ψ)∘q₃(θ)∘q₁(γ)``: eq. (3.6) as a SymPy quaternion.

    Parameters
    ----------
    psi, theta, gamma : sympy.Expr
        Yaw, pitch and roll.

    Returns
    -------
    sympy.algebras.quaternion.Quaternion
    """
    q2 = Quaternion(sp.cos(psi / 2), 0, sp.sin(psi / 2), 0)
    q3 = Quaternion(sp.cos(theta / 2), 0, 0, sp.sin(theta / 2))
    q1 = Quaternion(sp.cos(gamma / 2), sp.sin(gamma / 2), 0, 0)
    return q2 * q3 * q1


def _comps(q):
    return [q.a, q.b, q.c, q.d]


@dataclass(frozen=True)
class SchulerDerivation:
    """Results of :func:`derive` (SymPy objects).

    Attributes
    ----------
    W1 : list of sympy.Expr
        Specific force in η⁽¹⁾ to first order in (α, β, χ): ``[W₁⁽¹⁾, W₂⁽¹⁾, W₃⁽¹⁾]``.
    M1 : list of sympy.Expr
        Components 1 and 3 of the pure quaternion (1.4) built from ``W⁽¹⁾``.
    frame_rate : list of sympy.Expr
        ``ω_η(1)`` to first order: ``[ω₁ + α', β', ω₃ + χ']``.
    rates : dict
        ``{ψ₁⁺': …, θ₁⁺': …, γ₁⁺': …, y₁': …, y₃': …}``: the linearised stage (3.8).
    tf_accel : sympy.Expr
        ``E(s)/A(s)`` from the horizontal acceleration to the tilt error [rad per m/s²].
    tf_velocity : sympy.Expr
        ``E(s)/V(s)`` from the horizontal velocity to the tilt error [rad per m/s].
    tf_accel_roll : sympy.Expr
        The same for the roll channel (acceleration along η3).
    schuler_residual : sympy.Expr
        ``tf_accel`` at k = 0, l = g/R, simplified (0 exactly).
    characteristic : sympy.Expr
        ``s² + k s + l``.
    """

    W1: list
    M1: list
    frame_rate: list
    rates: dict
    tf_accel: sp.Expr
    tf_velocity: sp.Expr
    tf_accel_roll: sp.Expr
    schuler_residual: sp.Expr
    characteristic: sp.Expr


@lru_cache(maxsize=1)
@reproducible_sympy
def derive() -> SchulerDerivation:
    """Linearise the stage equation (2.1)/(3.5) and derive the Schuler transfer function.

    References
    ----------
    Plotnikov (1999), eqs. (3.5)–(3.12).
    """
    sym = SYMBOLS
    k, l, g, R, t, s = sym.k, sym.l, sym.g, sym.R, sym.t, sym.s
    eps = sp.Symbol("epsilon")
    names = ["alpha", "beta", "chi", "psi1", "theta1", "gamma1", "omega1", "omega3", "y1", "y3", "n1", "n3"]
    f = {n: getattr(sym, n) for n in names}
    small = ["alpha", "beta", "chi", "psi1", "theta1", "gamma1", "omega1", "omega3", "y1", "y3"]
    sc = {n: eps * f[n] if n in small else f[n] for n in names}

    # Rotation η(1) → η by the small stage-1 error angles (first order in ε is all we keep).
    delta = (
        Quaternion(sp.cos(sc["alpha"] / 2), sp.sin(sc["alpha"] / 2), 0, 0)
        * Quaternion(sp.cos(sc["beta"] / 2), 0, sp.sin(sc["beta"] / 2), 0)
        * Quaternion(sp.cos(sc["chi"] / 2), 0, 0, sp.sin(sc["chi"] / 2))
    )
    dbar = delta.conjugate()
    omega_eta = Quaternion(0, sc["omega1"], 0, sc["omega3"])
    rate_q = dbar * omega_eta * delta + 2 * dbar * Quaternion(*[sp.diff(c, t) for c in _comps(delta)])
    force = Quaternion(0, g * sc["n1"], g, g * sc["n3"])
    force1 = dbar * force * delta

    def first_order(expr):
        e0 = expr.subs(eps, 0)
        e1 = sp.diff(expr, eps).subs(eps, 0)
        return sp.simplify(sp.expand(e0 + e1))

    w1 = [first_order(c).subs(eps, 1) for c in _comps(force1)[1:]]
    m11 = -_comps(force1)[3] / g
    m13 = _comps(force1)[1] / g
    frame_rate = [first_order(c) for c in _comps(rate_q)[1:]]

    nu = krylov_quaternion(sc["psi1"], sc["theta1"], sc["gamma1"])
    nud = [sp.diff(c, t) for c in _comps(nu)]
    kin = nu * rate_q
    y = [0, sc["y1"], 0, sc["y3"]]
    m = [0, m11, 0, m13]
    corr = [0, k * (m[1] - 2 * nu.b) + y[1], 0, k * (m[3] - 2 * nu.d) + y[3]]
    residual = [2 * nud[i] - _comps(kin)[i] - corr[i] for i in range(4)]
    lin = [first_order(r) for r in residual]
    # Components 1, 2, 3 give γ', ψ', θ' (component 0 is second order).
    dpsi, dtheta, dgamma = (sp.diff(f[n], t) for n in ("psi1", "theta1", "gamma1"))
    sol = sp.solve([lin[1].subs(eps, 1), lin[2].subs(eps, 1), lin[3].subs(eps, 1)], [dgamma, dpsi, dtheta], dict=True)[0]
    ydot1 = first_order(l * (m[1] - 2 * nu.b)).subs(eps, 1)
    ydot3 = first_order(l * (m[3] - 2 * nu.d)).subs(eps, 1)
    rates = {
        "psi1": sp.expand(sol[dpsi]),
        "theta1": sp.expand(sol[dtheta]),
        "gamma1": sp.expand(sol[dgamma]),
        "y1": sp.expand(ydot1),
        "y3": sp.expand(ydot3),
    }

    # Laplace transform of the pitch channel for e = θ₁⁺ − χ, with β = 0 (no yaw error),
    # ω₃ = −V₁/R, n₁ = sV₁/g, zero initial conditions.
    E, Y, X, V = sp.symbols("E Y X V")

    def laplace(expr, mapping):
        expr = expr.subs({f["beta"]: 0, f["n3"]: 0, f["omega1"]: 0, f["alpha"]: 0, f["gamma1"]: 0, f["y1"]: 0})
        expr = expr.subs({sp.Derivative(f["chi"], t): s * X})
        return expr.subs(mapping)

    pitch_map = {f["theta1"]: E + X, f["chi"]: X, f["y3"]: Y, f["omega3"]: -V / R, f["n1"]: s * V / g}
    eq1 = sp.Eq(s * (E + X), laplace(rates["theta1"], pitch_map))
    eq2 = sp.Eq(s * Y, laplace(rates["y3"], pitch_map))
    sol_p = sp.solve([eq1, eq2], [E, Y], dict=True)[0]
    tf_velocity = sp.factor(sp.simplify(sol_p[E] / V))
    tf_accel = sp.factor(sp.simplify(tf_velocity / s))

    # Roll channel: e = γ₁⁺ − α, ω₁ = V₃/R, n₃ = sV₃/g.
    def laplace_roll(expr, mapping):
        expr = expr.subs({f["beta"]: 0, f["n1"]: 0, f["omega3"]: 0, f["chi"]: 0, f["theta1"]: 0, f["y3"]: 0})
        expr = expr.subs({sp.Derivative(f["alpha"], t): s * X})
        return expr.subs(mapping)

    roll_map = {f["gamma1"]: E + X, f["alpha"]: X, f["y1"]: Y, f["omega1"]: V / R, f["n3"]: s * V / g}
    eq1r = sp.Eq(s * (E + X), laplace_roll(rates["gamma1"], roll_map))
    eq2r = sp.Eq(s * Y, laplace_roll(rates["y1"], roll_map))
    sol_r = sp.solve([eq1r, eq2r], [E, Y], dict=True)[0]
    tf_accel_roll = sp.factor(sp.simplify(sol_r[E] / V / s))

    residual_schuler = sp.simplify(tf_accel.subs({k: 0, l: g / R}))
    return SchulerDerivation(
        W1=w1,
        M1=[first_order(m11).subs(eps, 1), first_order(m13).subs(eps, 1)],
        frame_rate=[sp.expand(c.subs(eps, 1)) for c in frame_rate],
        rates=rates,
        tf_accel=tf_accel,
        tf_velocity=tf_velocity,
        tf_accel_roll=tf_accel_roll,
        schuler_residual=residual_schuler,
        characteristic=s**2 + k * s + l,
    )


@reproducible_sympy
def accel_to_tilt_tf():
    """Numerator and denominator coefficients (in descending powers of s) of ``E(s)/A(s)``.

    Returns
    -------
    num, den : list of sympy.Expr
        Functions of the symbols k, l, g, R of :data:`SYMBOLS`.
    """
    d = derive()
    num, den = sp.fraction(sp.together(d.tf_accel))
    num_p, den_p = sp.Poly(sp.expand(num), SYMBOLS.s), sp.Poly(sp.expand(den), SYMBOLS.s)
    lead = den_p.LC()
    return [sp.simplify(c / lead) for c in num_p.all_coeffs()], [sp.simplify(c / lead) for c in den_p.all_coeffs()]
