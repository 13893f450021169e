"""Linearised error of analytic self-alignment: gains of the heading estimate (SymPy).

The analytic method averages the sensor outputs over the alignment time T and
computes the heading from the mean gyro rate ``ω̄`` and the tilt estimates
``(β̂, γ̂)`` of (16).  Two heading formulas are derived:

``"paper"``
    eq. (2) of Hrechka & Koroliov with the tilt correction:
    ``ψ̂ = −atan2(ω̄2, ω̄1) + atan2(B(β̂, γ̂), A(β̂, γ̂))`` (two horizontal gyros);
``"levelled"``
    the mean rate turned to the level frame by the tilt estimates,
    ``ω_h = R_x(−β̂) R_y(γ̂) ω̄``, and ``ψ̂ = atan2(−ω_h,y, ω_h,x)`` (three gyros);
    exact for any heading, where (2) is exact at ψ = 0 only.

The attitude is ``C_b^n = R_z(ψ) R_x(−β) R_y(γ)`` (NED), as in
:mod:`strapdown.analysis.alignment.tilt_attitude`, so that at ψ = 0 the two
horizontal gyros read ``Ω (A, B)``.  Everything is differentiated at the
stable state ``(ψ0, β0, γ0)`` with ideal sensors:

* ``G_ω = ∂ψ̂/∂ω̄`` and ``G_t = ∂ψ̂/∂(β̂, γ̂)``: the gains of the heading;
* ``T_f = ∂(β, γ)/∂f`` with ``β = atan2(f_y, √(f_x² + f_z²))``, ``γ = atan2(f_x, −f_z)``:
  the tilt from the specific force;
* ``D = ∂(C_n^b ω_ie^n)/∂θ``: the Earth rate seen by a rocked body;
* ``J``: the body rate of the angle rates, ``ω_nb^b = J θ'``, derived here
  from ``vee(Cᵀ ∂C/∂θ_i)``, independently of the numerical kinematics.

With these, to first order, a gyro bias b gives ``G_ω b`` (at ψ0 = β0 = γ0 = 0:
``−b_E/(Ω cos φ)``, the gyro-bias floor), an accelerometer bias a gives
``G_t T_f a`` (``tan φ · a_E/g``), and a rocking ``θ_r(t)`` gives
``G_ω [J Δθ_r/T + D θ̄_r] + G_t [E θ̄_r + T_f ((J Δθ'_r/T) × r)]``, E selecting
β, γ: the mean tilt enters through the accelerometers (the paper's tilt
channel) and through the gyros (``G_ω D``), and the two cancel for the tilts;
what remains is the rate term ``J Δθ_r/T``, the rocking's angle gained over
the window divided by T.
"""

from __future__ import annotations

from functools import cache
from typing import NamedTuple

import sympy as sp

from ..reproducible import reproducible_sympy

__all__ = ["AlignmentSymbols", "SYMBOLS", "AnalyticGains", "attitude_matrix", "heading_estimate", "tilt_estimate", "analytic_gains", "gain_expressions", "FORMULAS"]

FORMULAS = ("levelled", "paper")


class AlignmentSymbols(NamedTuple):
    """The symbols of the alignment derivation (the one way they are exposed).

    Attributes
    ----------
    phi : sympy.Symbol
        Latitude φ [rad].
    psi0, beta0, gamma0 : sympy.Symbol
        Stable heading and tilts [rad].
    Omega : sympy.Symbol
        Earth rate Ω [rad/s].
    g : sympy.Symbol
        Gravity [m/s²].
    omega : tuple of sympy.Symbol
        Mean gyro rates ω̄1, ω̄2, ω̄3 [rad/s].
    beta_hat, gamma_hat : sympy.Symbol
        Tilt estimates [rad].
    f : tuple of sympy.Symbol
        Specific force components [m/s²].
    """

    phi: sp.Symbol
    psi0: sp.Symbol
    beta0: sp.Symbol
    gamma0: sp.Symbol
    Omega: sp.Symbol
    g: sp.Symbol
    omega: tuple
    beta_hat: sp.Symbol
    gamma_hat: sp.Symbol
    f: tuple


SYMBOLS = AlignmentSymbols(
    *sp.symbols("varphi psi_0 beta_0 gamma_0", real=True),
    *sp.symbols("Omega g", positive=True),
    sp.symbols("omega1:4", real=True),
    *sp.symbols("hat{beta} hat{gamma}", real=True),
    sp.symbols("f_x f_y f_z", real=True),
)
_S = SYMBOLS


def _rx(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def _ry(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a)], [0, 1, 0], [-sp.sin(a), 0, sp.cos(a)]])


def _rz(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def attitude_matrix(psi, beta, gamma) -> sp.Matrix:
    """``C_b^n = R_z(ψ) R_x(−β) R_y(γ)``.

    Parameters
    ----------
    psi, beta, gamma : sympy expressions
        Heading and tilts [rad].

    Returns
    -------
    sympy.Matrix
    """
    return _rz(psi) * _rx(-beta) * _ry(gamma)


def _earth_rate():
    return _S.Omega * sp.Matrix([sp.cos(_S.phi), 0, -sp.sin(_S.phi)])


def heading_estimate(formula: str = "levelled"):
    """The heading ψ̂ as a function of the mean gyro rate and the tilt estimates.

    Parameters
    ----------
    formula : str
        ``"levelled"`` or ``"paper"``.

    Returns
    -------
    sympy.Expr
        In ``SYMBOLS.omega``, ``beta_hat``, ``gamma_hat`` (and φ for the paper's σ).

    Raises
    ------
    ValueError
        For an unknown formula.

    References
    ----------
    Hrechka & Koroliov, eq. (2) and the lines after it (``"paper"``).
    """
    w = sp.Matrix(_S.omega)
    b, c = _S.beta_hat, _S.gamma_hat
    if formula == "levelled":
        h = _rx(-b) * _ry(c) * w
        return sp.atan2(-h[1], h[0])
    if formula == "paper":
        A = sp.cos(_S.phi) * sp.cos(c) + sp.sin(_S.phi) * sp.cos(b) * sp.sin(c)
        B = sp.sin(_S.phi) * sp.sin(b)
        return -sp.atan2(w[1], w[0]) + sp.atan2(B, A)
    raise ValueError(f"Expected `formula` in {FORMULAS}, got {formula!r}")


def tilt_estimate():
    """Tilts from the specific force at rest: ``(atan2(f_y, √(f_x² + f_z²)), atan2(f_x, −f_z))``.

    Returns
    -------
    sympy.Matrix
        2 × 1.
    """
    fx, fy, fz = _S.f
    return sp.Matrix([sp.atan2(fy, sp.sqrt(fx**2 + fz**2)), sp.atan2(fx, -fz)])


class AnalyticGains(NamedTuple):
    """Gains of the linearised analytic alignment at the stable state.

    Attributes
    ----------
    G_omega : sympy.Matrix
        1 × 3, ``∂ψ̂/∂ω̄`` [s].
    G_tilt : sympy.Matrix
        1 × 2, ``∂ψ̂/∂(β̂, γ̂)``.
    T_f : sympy.Matrix
        2 × 3, ``∂(β, γ)/∂f`` [s²/m].
    D : sympy.Matrix
        3 × 3, ``∂(C_n^b ω_ie^n)/∂(ψ, β, γ)`` [rad/s].
    J : sympy.Matrix
        3 × 3, ``ω_nb^b = J (ψ', β', γ')``.
    omega0 : sympy.Matrix
        3 × 1, the Earth rate in body axes at the stable state [rad/s].
    f0 : sympy.Matrix
        3 × 1, the specific force at the stable state [m/s²].
    """

    G_omega: sp.Matrix
    G_tilt: sp.Matrix
    T_f: sp.Matrix
    D: sp.Matrix
    J: sp.Matrix
    omega0: sp.Matrix
    f0: sp.Matrix


@cache
@reproducible_sympy
def analytic_gains(formula: str = "levelled") -> AnalyticGains:
    """Derive the gains of the analytic alignment at ``(ψ0, β0, γ0)``.

    Parameters
    ----------
    formula : str
        ``"levelled"`` or ``"paper"``.

    Returns
    -------
    AnalyticGains
        Expressions in φ, ψ0, β0, γ0, Ω, g.

    Examples
    --------
    At zero heading and tilt the heading reacts to the east gyro only, by the
    gyro-bias floor, and to the east tilt by tan φ:

    >>> G = analytic_gains("levelled")
    >>> S = SYMBOLS
    >>> at0 = {S.psi0: 0, S.beta0: 0, S.gamma0: 0}
    >>> sp.simplify(G.G_omega.subs(at0))
    Matrix([[0, -1/(Omega*cos(varphi)), 0]])
    >>> sp.simplify(G.G_tilt.subs(at0))
    Matrix([[tan(varphi), 0]])
    """
    s = _S
    C0 = attitude_matrix(s.psi0, s.beta0, s.gamma0)
    W = _earth_rate()
    w0 = C0.T * W
    grav = sp.Matrix([0, 0, s.g])
    f0 = -C0.T * grav
    psi_hat = heading_estimate(formula)
    point = {**dict(zip(s.omega, w0)), s.beta_hat: s.beta0, s.gamma_hat: s.gamma0}
    G_omega = sp.Matrix([[sp.diff(psi_hat, wi).subs(point) for wi in s.omega]])
    G_tilt = sp.Matrix([[sp.diff(psi_hat, t).subs(point) for t in (s.beta_hat, s.gamma_hat)]])
    tilt = tilt_estimate()
    fpoint = dict(zip(s.f, f0))
    T_f = sp.Matrix(2, 3, lambda i, j: sp.diff(tilt[i], s.f[j]).subs(fpoint))
    th = sp.symbols("theta_psi theta_beta theta_gamma", real=True)
    C = attitude_matrix(*th)
    at = dict(zip(th, (s.psi0, s.beta0, s.gamma0)))
    Cw = C.T * W
    D = sp.Matrix(3, 3, lambda i, j: sp.diff(Cw[i], th[j]).subs(at))
    cols = []
    for t in th:
        Wm = (C.T * sp.diff(C, t)).subs(at)
        cols.append([Wm[2, 1], Wm[0, 2], Wm[1, 0]])
    J = sp.Matrix(3, 3, lambda i, j: cols[j][i])
    return AnalyticGains(G_omega, G_tilt, T_f, D, J, w0, f0)


def gain_expressions(formula: str = "levelled") -> tuple:
    """``(arguments, expressions)`` of :func:`analytic_gains`, flattened, for numerical code generation.

    Parameters
    ----------
    formula : str
        ``"levelled"`` or ``"paper"``.

    Returns
    -------
    tuple
        ``((φ, ψ0, β0, γ0, Ω, g), [3 + 2 + 6 + 9 + 9 + 3 + 3 expressions])`` in the
        order of the fields of :class:`AnalyticGains`, each matrix row-major.
    """
    s = _S
    G = analytic_gains(formula)
    exprs = [e for m in G for e in m]
    return (s.phi, s.psi0, s.beta0, s.gamma0, s.Omega, s.g), exprs
