"""Azimuth error of analytical gyrocompassing on a rocking base (SymPy).

Hrechka & Koroliov write the azimuth from two horizontal gyros as
``α = −arctan(f2/f1) + σ`` with the tilt correction (their eq. (2) and the
unnumbered lines after it)

    σ = arctan(B/A),   A = cos φ cos γ + sin φ cos β sin γ,   B = sin φ sin β,

φ the latitude and β, γ the tilts measured by the accelerometers.  On a rocking
base ``β = β0 + ξ``, ``γ = γ0 + η`` with zero-mean random ξ, η (4), and the
first-order estimate uses the stable tilts: ``σ* = arctan(B*/A*)`` (11).

This module derives, from the definition alone,

* the Taylor parts ``A = A* + ζ1``, ``B = B* + ζ2`` of (5)–(10);
* bound (14) and its simplification (15);
* the series of the error ``σ − σ*`` to third order in (ξ, η), from which the
  second-order bias ``E(σ − σ*)`` and the mean-square error to fourth order
  follow (neither is in the paper).

The error series uses the angle form ``σ − σ* = Im log(1 + w)``,
``w = ((A − A*) + i(B − B*)) / (A* + iB*)``, which equals the difference of the
two arctangents whenever ``A, A* > 0`` and is the wrapped angle difference
otherwise.

Moments: ξ and η are independent and symmetric, with variances ``Dξ, Dη`` and
fourth moments ``κξ Dξ²``, ``κη Dη²`` (κ = 3 for a Gaussian, 3/2 for a
sinusoid with random phase).

References
----------
Hrechka & Koroliov, "Estimation of the azimuth error of a self-orienting SINS
under random rocking", eqs. (2), (4)–(15).
"""

from __future__ import annotations

from functools import cache
from typing import NamedTuple

import sympy as sp

from ..reproducible import reproducible_sympy

__all__ = [
    "AzimuthSymbols",
    "SYMBOLS",
    "TaylorComponents",
    "LinearParts",
    "CoefficientSymbols",
    "MomentExpressions",
    "components",
    "taylor_components",
    "linear_parts",
    "coefficient_symbols",
    "coefficient_values",
    "generic_error_series",
    "error_series",
    "expectation",
    "first_order_mse",
    "bias_second_order",
    "mse_fourth_order",
    "bound13_series",
    "bound14",
    "bound14_rocking",
    "bound15",
    "coefficient_expressions",
    "moment_expressions",
    "mse_at_zero_tilt",
    "bound14_reduces_to_15",
]


class AzimuthSymbols(NamedTuple):
    """The symbols of the derivation (the one way they are exposed).

    Attributes
    ----------
    phi : sympy.Symbol
        Latitude φ [rad].
    beta0, gamma0 : sympy.Symbol
        Stable tilts β0, γ0 [rad].
    xi, eta : sympy.Symbol
        Rocking ξ, η [rad].
    D_xi, D_eta : sympy.Symbol
        Variances Dξ, Dη [rad²].
    kappa_xi, kappa_eta : sympy.Symbol
        Normalised fourth moments ``E ξ⁴ / (E ξ²)²`` and likewise for η.
    D_zeta1, D_zeta2 : sympy.Symbol
        Variances of ζ1, ζ2 of (7), (10) [rad²].
    """

    phi: sp.Symbol
    beta0: sp.Symbol
    gamma0: sp.Symbol
    xi: sp.Symbol
    eta: sp.Symbol
    D_xi: sp.Symbol
    D_eta: sp.Symbol
    kappa_xi: sp.Symbol
    kappa_eta: sp.Symbol
    D_zeta1: sp.Symbol
    D_zeta2: sp.Symbol


SYMBOLS = AzimuthSymbols(
    *sp.symbols("varphi beta_0 gamma_0 xi eta", real=True),
    *sp.symbols("D_xi D_eta", nonnegative=True),
    *sp.symbols("kappa_xi kappa_eta", positive=True),
    *sp.symbols("D_zeta1 D_zeta2", nonnegative=True),
)
_S = SYMBOLS


class TaylorComponents(NamedTuple):
    """Taylor polynomials of A and B in (ξ, η): ``{(i, j): coefficient of ξ^i η^j}``.

    Attributes
    ----------
    A, B : dict
        The ``(0, 0)`` entries are A*, B*.
    """

    A: dict
    B: dict


class LinearParts(NamedTuple):
    """A*, B* and the first-order parts ζ1, ζ2 of (5)–(10).

    Attributes
    ----------
    A_star : sympy.Expr
        A* of (6).
    B_star : sympy.Expr
        B* of (9).
    zeta1 : sympy.Expr
        ζ1 of (7), linear in ξ, η.
    zeta2 : sympy.Expr
        ζ2 of (10), linear in ξ.
    """

    A_star: sp.Expr
    B_star: sp.Expr
    zeta1: sp.Expr
    zeta2: sp.Expr


class CoefficientSymbols(NamedTuple):
    """Symbols of the generic error series: ``A = A* + Σ a_ij ξ^i η^j``, ``B = B* + Σ b_ij ξ^i η^j``.

    Attributes
    ----------
    A_star, B_star : sympy.Symbol
        Values at the stable tilts.
    a, b : dict
        ``{(i, j): symbol}`` for 1 ≤ i + j ≤ order.
    """

    A_star: sp.Symbol
    B_star: sp.Symbol
    a: dict
    b: dict


class MomentExpressions(NamedTuple):
    """Moments of the azimuth error, generic in the coefficient symbols.

    Attributes
    ----------
    mse_first_order : sympy.Expr
        ``E L²`` of the linear error.
    bias : sympy.Expr
        ``E(σ − σ*)`` to second order.
    mse : sympy.Expr
        ``E(σ − σ*)²`` to fourth order.
    """

    mse_first_order: sp.Expr
    bias: sp.Expr
    mse: sp.Expr


# A polynomial in (ξ, η) is a dict {(i, j): coefficient of ξ^i η^j}.
Poly2 = dict


def components(beta, gamma, latitude=_S.phi):
    """``(A, B)`` of the tilt correction ``σ = arctan(B/A)``.

    Parameters
    ----------
    beta, gamma : sympy expressions
        Tilts β, γ [rad].
    latitude : sympy expression
        Latitude φ [rad].

    Returns
    -------
    (A, B) : tuple of sympy expressions

    References
    ----------
    Hrechka & Koroliov, the lines after eq. (2), with ``cos γ`` in the first
    term of A (the printed ``sin γ`` is a misprint: see
    :mod:`strapdown.derivations.gyrocompass.published`).

    >>> components(0, 0)
    (cos(varphi), 0)
    """
    A = sp.cos(latitude) * sp.cos(gamma) + sp.sin(latitude) * sp.cos(beta) * sp.sin(gamma)
    B = sp.sin(latitude) * sp.sin(beta)
    return A, B


def _mul(p: Poly2, q: Poly2, order: int) -> Poly2:
    out: Poly2 = {}
    for (i, j), a in p.items():
        for (k, m), b in q.items():
            if i + j + k + m <= order:
                key = (i + k, j + m)
                out[key] = out.get(key, 0) + a * b
    return out


def _add(*polys: Poly2, scale=None) -> Poly2:
    out: Poly2 = {}
    for n, p in enumerate(polys):
        c = 1 if scale is None else scale[n]
        for key, a in p.items():
            out[key] = out.get(key, 0) + c * a
    return out


@reproducible_sympy
def _clean(p: Poly2) -> Poly2:
    out = {}
    for key in sorted(p):
        value = sp.simplify(sp.expand(p[key]))
        if value != 0:
            out[key] = value
    return out


def _trig_series(angle0, var, order: int):
    """``(cos(angle0 + var), sin(angle0 + var))`` as polynomials in ``var`` to ``order``."""
    c0, s0 = sp.cos(angle0), sp.sin(angle0)
    cos_p, sin_p = {}, {}
    for n in range(order + 1):
        # d^n/dx^n cos(x) at angle0 and likewise for sin
        dcos = [c0, -s0, -c0, s0][n % 4] / sp.factorial(n)
        dsin = [s0, c0, -s0, -c0][n % 4] / sp.factorial(n)
        key = (n, 0) if var is _S.xi else (0, n)
        cos_p[key], sin_p[key] = dcos, dsin
    return cos_p, sin_p


@cache
def taylor_components(order: int = 3) -> TaylorComponents:
    """Taylor polynomials of A and B in (ξ, η) about (β0, γ0), to total degree ``order``.

    Parameters
    ----------
    order : int
        Total degree kept.

    Returns
    -------
    TaylorComponents

    References
    ----------
    Hrechka & Koroliov, eqs. (5), (8) (there to first order).
    """
    cb, sb = _trig_series(_S.beta0, _S.xi, order)
    cg, sg = _trig_series(_S.gamma0, _S.eta, order)
    A = _add({(0, 0): 0}, _mul(cg, {(0, 0): sp.cos(_S.phi)}, order), _mul(_mul(cb, sg, order), {(0, 0): sp.sin(_S.phi)}, order))
    B = _mul(sb, {(0, 0): sp.sin(_S.phi)}, order)
    return TaylorComponents(_clean(A), _clean(B))


@cache
def linear_parts() -> LinearParts:
    """A*, B* and the first-order parts ζ1, ζ2 of (5)–(10), derived.

    Returns
    -------
    LinearParts
        Sympy expressions in φ, β0, γ0, ξ, η.

    References
    ----------
    Hrechka & Koroliov, eqs. (5)–(10).

    >>> linear_parts().zeta2
    xi*sin(varphi)*cos(beta_0)
    """
    A, B = taylor_components(1)
    zeta1 = A.get((1, 0), 0) * _S.xi + A.get((0, 1), 0) * _S.eta
    zeta2 = B.get((1, 0), 0) * _S.xi + B.get((0, 1), 0) * _S.eta
    return LinearParts(A[(0, 0)], B.get((0, 0), sp.Integer(0)), sp.expand(zeta1), sp.expand(zeta2))


def coefficient_symbols(order: int = 3) -> CoefficientSymbols:
    """Symbols ``A*, B*`` and the Taylor coefficients ``a_ij, b_ij`` (1 ≤ i + j ≤ order).

    Parameters
    ----------
    order : int
        Highest total degree.

    Returns
    -------
    CoefficientSymbols
    """
    keys = [(i, n - i) for n in range(1, order + 1) for i in range(n, -1, -1)]
    a = {k: sp.Symbol(f"a_{k[0]}{k[1]}", real=True) for k in keys}
    b = {k: sp.Symbol(f"b_{k[0]}{k[1]}", real=True) for k in keys}
    return CoefficientSymbols(sp.Symbol("A_s", real=True), sp.Symbol("B_s", real=True), a, b)


@cache
def coefficient_values(order: int = 3) -> dict:
    """Values of the symbols of :func:`coefficient_symbols` for the gyrocompass A, B.

    Parameters
    ----------
    order : int
        Highest total degree.

    Returns
    -------
    dict
        ``{symbol: expression in φ, β0, γ0}``.
    """
    As, Bs, a, b = coefficient_symbols(order)
    A, B = taylor_components(order)
    values = {As: A[(0, 0)], Bs: B.get((0, 0), sp.Integer(0))}
    for k in a:
        values[a[k]] = A.get(k, sp.Integer(0))
        values[b[k]] = B.get(k, sp.Integer(0))
    return values


@cache
@reproducible_sympy
def generic_error_series(order: int = 3) -> dict:
    """Series of ``σ − σ* = arg(A + iB) − arg(A* + iB*)`` in (ξ, η) to total degree ``order``.

    Generic in A*, B* and the Taylor coefficients (:func:`coefficient_symbols`).
    Uses ``σ − σ* = Im log(1 + w) = v − uv + u²v − v³/3 + O(4)`` with
    ``u + iv = w = (a + ib)/(A* + iB*)``, ``a = A − A*``, ``b = B − B*``.

    Parameters
    ----------
    order : int
        1, 2 or 3.

    Returns
    -------
    dict
        ``{(i, j): coefficient of ξ^i η^j}`` (no constant term).

    Raises
    ------
    ValueError
        For an order outside 1–3.
    """
    if order not in (1, 2, 3):
        raise ValueError(f"Expected `order` in {{1, 2, 3}}, got {order}")
    As, Bs, ca, cb = coefficient_symbols(order)
    R2 = As**2 + Bs**2
    u = _add(ca, cb, scale=[As / R2, Bs / R2])
    v = _add(cb, ca, scale=[As / R2, -Bs / R2])
    uv = _mul(u, v, order)
    u2v = _mul(u, uv, order)
    v3 = _mul(v, _mul(v, v, order), order)
    series = _add(v, uv, u2v, v3, scale=[1, -1, 1, sp.Rational(-1, 3)])
    return {k: sp.factor(sp.expand(c)) for k, c in sorted(series.items())}


@reproducible_sympy
def error_series(order: int = 3) -> dict:
    """Series of ``σ − σ*`` for the gyrocompass A, B, in φ, β0, γ0 (unsimplified).

    Parameters
    ----------
    order : int
        1, 2 or 3.

    Returns
    -------
    dict
        ``{(i, j): coefficient of ξ^i η^j}``.

    >>> s = error_series(1)
    >>> sp.simplify(s[(1, 0)].subs({SYMBOLS.beta0: 0, SYMBOLS.gamma0: 0}))
    tan(varphi)
    """
    values = coefficient_values(order)
    return {k: c.subs(values) for k, c in generic_error_series(order).items()}


def _moment(i: int, j: int):
    """``E ξ^i η^j`` for independent, symmetric ξ, η (to fourth order)."""

    def one(n, D, kappa):
        if n % 2:
            return 0
        return {0: 1, 2: D, 4: kappa * D**2}.get(n, None)

    mi, mj = one(i, _S.D_xi, _S.kappa_xi), one(j, _S.D_eta, _S.kappa_eta)
    if mi is None or mj is None:
        raise ValueError(f"moment E ξ^{i} η^{j} is beyond fourth order")
    return mi * mj


def expectation(poly: Poly2):
    """Expectation of a polynomial in (ξ, η) of total degree ≤ 4, in Dξ, Dη, κξ, κη.

    Parameters
    ----------
    poly : dict
        ``{(i, j): coefficient of ξ^i η^j}``.

    Returns
    -------
    sympy.Expr

    Raises
    ------
    ValueError
        For a monomial beyond fourth order.

    >>> expectation({(2, 0): 1, (1, 1): 5, (0, 4): 1})
    D_eta**2*kappa_eta + D_xi
    """
    return sp.expand(sum((c * _moment(i, j) for (i, j), c in poly.items()), sp.Integer(0)))


def _degree(poly: Poly2, n: int) -> Poly2:
    return {k: v for k, v in poly.items() if sum(k) == n}


def _specialise(expr, generic: bool, order: int):
    return expr if generic else expr.subs(coefficient_values(order))


@cache
@reproducible_sympy
def first_order_mse(*, generic: bool = False):
    """``E L²`` of the linear error ``L = (A* ζ2 − B* ζ1)/(A*² + B*²)``.

    This is the exact mean-square error to second order in the rocking.

    Parameters
    ----------
    generic : bool
        Keep the result in the symbols of :func:`coefficient_symbols`.

    Returns
    -------
    sympy.Expr
    """
    L = _degree(generic_error_series(1), 1)
    return _specialise(sp.factor(expectation(_mul(L, L, 2))), generic, 1)


@cache
@reproducible_sympy
def bias_second_order(*, generic: bool = False):
    """Second-order bias ``E(σ − σ*) = ½ (σ_ββ Dξ + σ_γγ Dη) + O(4)``.

    Not in the paper.  Vanishes for β0 = 0 (σ is odd in β there).

    Parameters
    ----------
    generic : bool
        Keep the result in the symbols of :func:`coefficient_symbols`.

    Returns
    -------
    sympy.Expr
    """
    Q = _degree(generic_error_series(2), 2)
    return _specialise(sp.factor(expectation(Q)), generic, 2)


@cache
@reproducible_sympy
def mse_fourth_order(*, generic: bool = False):
    """Mean-square error ``E(σ − σ*)²`` to fourth order: ``E L² + E Q² + 2 E L C``.

    L, Q, C are the first-, second- and third-degree parts of the error series;
    the odd third-order moments vanish.  Not in the paper.

    Parameters
    ----------
    generic : bool
        Keep the result in the symbols of :func:`coefficient_symbols`.

    Returns
    -------
    sympy.Expr
    """
    s = generic_error_series(3)
    L, Q, C = _degree(s, 1), _degree(s, 2), _degree(s, 3)
    fourth = _add(_mul(L, L, 2), _mul(Q, Q, 4), _mul(L, C, 4), scale=[1, 1, 2])
    return _specialise(expectation(fourth), generic, 3)


def bound13_series():
    """First-order part of ``B/A − B*/A*`` (Taylor of x/y about (B*, A*)), as printed before (14).

    Returns
    -------
    sympy.Expr
    """
    p = linear_parts()
    return sp.expand(-p.B_star / p.A_star**2 * p.zeta1 + p.zeta2 / p.A_star)


def bound14(Dz1=_S.D_zeta1, Dz2=_S.D_zeta2):
    """Right-hand side of bound (14) on δ², in terms of Dζ1, Dζ2.

    ``δ² ≤ (B*/A*²)² Dζ1 + 2 |B*/A*³| √Dζ1 √Dζ2 + Dζ2 / A*²``.

    Parameters
    ----------
    Dz1, Dz2 : sympy expressions
        Variances of ζ1, ζ2 (default the symbols ``D_zeta1``, ``D_zeta2``).

    Returns
    -------
    sympy.Expr

    References
    ----------
    Hrechka & Koroliov, eq. (14).
    """
    p = linear_parts()
    As, Bs = p.A_star, p.B_star
    return (Bs / As**2) ** 2 * Dz1 + 2 * sp.Abs(Bs / As**3) * sp.sqrt(Dz1) * sp.sqrt(Dz2) + Dz2 / As**2


@cache
def bound14_rocking():
    """Bound (14) on δ² with ``Dζ1, Dζ2`` expressed through Dξ, Dη (ξ, η independent).

    ``Dζ = c_ξ² Dξ + c_η² Dη`` is kept as a sum of squares, so that it is never
    negative in floating point.

    Returns
    -------
    sympy.Expr
    """
    p = linear_parts()

    def variance(zeta):
        return sp.diff(zeta, _S.xi) ** 2 * _S.D_xi + sp.diff(zeta, _S.eta) ** 2 * _S.D_eta

    return bound14(variance(p.zeta1), variance(p.zeta2))


def bound15():
    """Bound (15): ``δ ≤ tan φ √Dξ`` (returned as the bound on δ).

    Obtained from (14) by setting β0 = γ0 = 0 (the paper's "discard the first
    order terms"); :func:`bound14_rocking` reduces to its square there.

    Returns
    -------
    sympy.Expr
    """
    return sp.tan(_S.phi) * sp.sqrt(_S.D_xi)


def coefficient_expressions(order: int = 3) -> tuple:
    """``(arguments, expressions)`` of the Taylor coefficients as functions of (φ, β0, γ0).

    The expressions are, in order, A*, B*, the ``a_ij`` and the ``b_ij`` of
    :func:`coefficient_symbols`; this is the input of
    :func:`strapdown.analysis.core.cache.compiled`.

    Parameters
    ----------
    order : int
        Highest total degree.

    Returns
    -------
    tuple
        ``((φ, β0, γ0), [expressions])``.
    """
    As, Bs, a, b = coefficient_symbols(order)
    values = coefficient_values(order)
    return (_S.phi, _S.beta0, _S.gamma0), [values[s] for s in (As, Bs, *a.values(), *b.values())]


def moment_expressions() -> tuple:
    """``(arguments, MomentExpressions)`` generic in the third-order coefficients and the moments.

    Arguments are A*, B*, the ``a_ij``, the ``b_ij`` (order 3), then Dξ, Dη,
    κξ, κη: the input of :func:`strapdown.analysis.core.cache.compiled`.

    Returns
    -------
    tuple
        ``(arguments, MomentExpressions)``.
    """
    As, Bs, a, b = coefficient_symbols(3)
    args = (As, Bs, *a.values(), *b.values(), _S.D_xi, _S.D_eta, _S.kappa_xi, _S.kappa_eta)
    return args, MomentExpressions(first_order_mse(generic=True), bias_second_order(generic=True), mse_fourth_order(generic=True))


@cache
@reproducible_sympy
def mse_at_zero_tilt():
    """``E(σ − σ*)²`` to fourth order at zero stable tilt, factored.

    Equals ``tan²φ Dξ [1 + Dη(1 + 3 tan²φ) − κξ Dξ (1 + 2 tan²φ)/3]``: the rocking
    η about the other axis enters at second order.  Not in the paper.

    Returns
    -------
    sympy.Expr
    """
    return sp.factor(sp.simplify(mse_fourth_order().subs({_S.beta0: 0, _S.gamma0: 0})))


@reproducible_sympy
def bound14_reduces_to_15() -> bool:
    """Whether (14) at β0 = γ0 = 0 equals the square of (15) (``sympy.simplify`` of the difference).

    Returns
    -------
    bool

    References
    ----------
    Hrechka & Koroliov, eqs. (14), (15).

    >>> bound14_reduces_to_15()
    True
    """
    return bool(sp.simplify(bound14_rocking().subs({_S.beta0: 0, _S.gamma0: 0}) - bound15() ** 2) == 0)
