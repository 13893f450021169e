"""Drift of rotation-vector algorithms under regular precession and under classical coning.

The body rate of the regular precession (Lebedev & Panov 1989, eq. (4.1)) is

    ω(t) = ν (ε sin ϑ sin νt,  ε sin ϑ cos νt,  1 + ε cos ϑ) = ν e_z + εν n(t),

with the precession axis ``n(t) = (sin ϑ sin νt, sin ϑ cos νt, cos ϑ)`` in E.
The motion is equivariant: shifting t rotates every ω-derivative, hence every
nested product ``x_w`` and the whole one-step error, about ``e_z`` of E by
``−νt``, while the attitude turns about the fixed precession axis of I.  The
error that one step adds in frame I is therefore the same vector turned by
``εν t`` about that axis, and its constant part — the asymptotic drift — is
its projection on the precession axis, divided by the step H.

Sign convention: errors are *exact minus algorithm* (package docstring,
"Errors").

Three levels are derived here.

* **Paper level** (Lebedev & Panov 1989, eqs. (5.2)–(5.3)): project the
  leading local error ``δφ`` itself.  Its components along ``e_z`` and along
  ``n(0) × e_x`` (the y axis) give ``A_ρ = εν^{ρ+1} sin²ϑ f_ρ(ε, ϑ)`` and
  ``B_ρ = εν^{ρ+1} sin ϑ g_ρ(ε, ϑ)`` (:func:`structure_functions`).
* **Exact to any weight** (:func:`drift_coefficients`): one step from the
  true attitude ``Λ_n``; the error rotation is
  ``Λ_n ∘ exp(Δφ_exact) ∘ exp(−Δφ_alg) ∘ Λ̄_n`` in frame I.  Seen from the
  attitude at the middle of the step, ``Λ(t_m) = Λ_n ∘ exp(Δφ_1)``
  (``Δφ_1``: exact increment over the first half step), its rotation vector
  is ``e = R(−Δφ_1) log(exp(Δφ_exact) exp(−Δφ_alg))``
  (:func:`one_step_error`), and the drift is ``n(0)·e / H`` to first order in
  e (the composition of the steps adds terms of second order in its part
  across n, from weight 2ρ + 1; see :func:`drift_coefficients`).  To first order
  in δφ, ``e = exp(−ad Δφ_1) J(Δφ) δφ`` with the left Jacobian
  ``J = (e^{ad Δφ} − 1)/ad Δφ``; where the leading term cancels (ρ = 6 under
  coning for the algorithms 3 and 5 of Budennyi, Kalinovsky, Panov et al.),
  the second-order terms of that map acting on the weight-5 error add to the
  weight-7 drift, and only the full expression matches simulation.  The series
  are built on the precession itself (letter values in ``QQ[ε, sin ϑ, cos ϑ]``),
  so a high weight costs little.
* **Classical coning in closed form** (:func:`coning_drift`): at ε = −1 and
  small half-cone angle α, only the pairwise terms reach order α², through
  their lag sums, and the drift is an exact trigonometric function of ``ωh``
  for any algorithm (cross-step terms included).

The optimal N-sample coning class (:func:`optimal_coning_algorithm`) and its
drift ``α² Ω (ΩH)^{2N} / C_N`` follow from the closed form.

Symbols are module constants: :data:`EPS`, :data:`THETA`, :data:`THETA_DUAL`,
:data:`NU`, :data:`COS`, :data:`SIN` for the precession, :data:`ALPHA` (half-cone
angle) and :data:`X` (``ω h``) for coning.

References
----------
Lebedev & Panov (1989), section 5, eqs. (5.1)–(5.6).
Budennyi, Kalinovsky, Panov et al. (Part 2), eqs. (3)–(5), Table 3.
Ignagni (1990), "Optimal strapdown attitude integration algorithms";
Ignagni (1996), "Efficient class of optimized coning compensation algorithms";
Savage (1998), "Strapdown inertial navigation integration algorithm design, part 1".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import sympy as sp
from sympy.algebras.quaternion import Quaternion
from sympy.polys.domains import QQ
from sympy.polys.rings import ring

from ..reproducible import reproducible_sympy
from . import graded as G
from . import series as S
from .algorithms import Algorithm, Term
from .magnus import rotation_series

__all__ = [
    "EPS",
    "THETA",
    "THETA_DUAL",
    "NU",
    "COS",
    "SIN",
    "ALPHA",
    "X",
    "one_step_error",
    "mapped_error",
    "precession_value",
    "drift_coefficients",
    "step_error_values",
    "coning_drift_series",
    "StructureFunctions",
    "structure_functions",
    "lag_sums",
    "lag_response",
    "exact_coning_response",
    "ConingDrift",
    "coning_drift",
    "coning_drift_closed_form",
    "optimal_coning_algorithm",
    "coning_constant",
]

EPS, THETA, THETA_DUAL, NU = sp.symbols("epsilon vartheta vartheta_dual nu", real=True)
#: Shorthands used in the polynomial results: ``COS = cos ϑ``, ``SIN = sin ϑ``.
COS, SIN = sp.cos(THETA), sp.sin(THETA)
#: Half-cone angle α of classical coning [rad].
ALPHA = sp.Symbol("alpha", positive=True)
#: ``x = ω h``: the angle the coning rate turns through in one sample interval [rad].
X = sp.Symbol("x", positive=True)

_PR, _E, _S, _C = ring("e,s,c", QQ)


# ---------------------------------------------------------------------------
# The one-step error rotation, on any ring of letter values
# ---------------------------------------------------------------------------
def one_step_error(exact: G.Graded, half: G.Graded, algorithm_increment: G.Graded) -> G.Graded:
    """Rotation vector ``R(−Δφ_1) log(exp(Δφ_exact) exp(−Δφ_alg))`` of the error one step adds.

    With the step taken from the true attitude ``Λ_n``, the computed and true
    attitudes are ``Λ_n ∘ exp(Δφ_alg)`` and ``Λ_n ∘ exp(Δφ_exact)``; the error
    rotation ``Λ_true ∘ Λ̄_computed`` (exact minus algorithm), resolved in the
    body axes at the middle of the step ``Λ_n ∘ exp(Δφ_1)``, is this vector.

    Parameters
    ----------
    exact : Graded
        Exact increment ``Δφ_exact`` over the step (vector series).
    half : Graded
        Exact increment ``Δφ_1`` over the first half of the step.
    algorithm_increment : Graded
        The algorithm's ``Δφ_alg`` on the same letters.

    Returns
    -------
    Graded
        Vector series on the ring of the arguments.
    """
    q_exact = G.rotation_quaternion(exact)
    q_alg = G.conjugate(G.rotation_quaternion(algorithm_increment))
    error = G.rotation_vector(G.quaternion_product(q_exact, q_alg))
    q_half = G.rotation_quaternion(half)
    turned = G.quaternion_product(G.quaternion_product(G.conjugate(q_half), G.pure(error)), q_half)
    return G.Graded(exact.ring, 3, lambda w: turned.part(w)[1:], low=1)


@cache
def _ring_error(algorithm: Algorithm) -> G.Graded:
    return one_step_error(S.exact_increment_series(), S.exact_increment_series(Fraction(-1, 2), Fraction(0)), S.algorithm_increment_series(algorithm))


def mapped_error(algorithm: Algorithm, max_weight: int = S.DEFAULT_MAX_WEIGHT) -> tuple:
    """One-step error :func:`one_step_error` as component polynomials through ``max_weight`` (``H = 1``).

    Exact minus algorithm, resolved in the body axes at the middle of the step;
    to first order in the local error δφ it is ``exp(−ad Δφ_1) J(Δφ) δφ``.
    The component polynomials grow fast with the weight: for the drift use
    :func:`drift_coefficients`, which works on the precession directly.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    max_weight : int
        Highest weight kept.

    Returns
    -------
    tuple of three :data:`~strapdown.derivations.coning.series.RING` elements
    """
    return _ring_error(algorithm).total(S.check_max_weight(max_weight))


# ---------------------------------------------------------------------------
# The regular precession
# ---------------------------------------------------------------------------
def _precession_letter(k: int) -> tuple:
    """ω^(k)(0)/ν^(k+1) of (4.1) in QQ[e, s, c] (e = ε, s = sin ϑ, c = cos ϑ)."""
    sin_k = [0, 1, 0, -1][k % 4]  # d^k sin(x)/dx^k at 0
    cos_k = [1, 0, -1, 0][k % 4]
    z = 1 + _E * _C if k == 0 else _PR.zero
    return (_E * _S * sin_k, _E * _S * cos_k, _PR(z))


@cache
def _precession_exact(lower: Fraction, upper: Fraction) -> G.Graded:
    return rotation_series(_PR, _precession_letter, lower, upper)


@cache
def _precession_error(algorithm: Algorithm) -> G.Graded:
    exact = _precession_exact(Fraction(-1, 2), Fraction(1, 2))
    half = _precession_exact(Fraction(-1, 2), Fraction(0))
    alg = S.algorithm_increment_series(algorithm, ring=_PR, letter=_precession_letter)
    return one_step_error(exact, half, alg)


@cache
def _precession_local_error(algorithm: Algorithm) -> G.Graded:
    alg = S.algorithm_increment_series(algorithm, ring=_PR, letter=_precession_letter)
    return G.combine([(1, _precession_exact(Fraction(-1, 2), Fraction(1, 2))), (-1, alg)])


def _substitute(poly):
    """A RING polynomial on (4.1) at t = 0, ν = 1, as an element of QQ[e, s, c]."""
    out = _PR.zero
    powers: dict = {}
    for monom, coeff in poly.items():
        term = _PR(coeff)
        for i, e in enumerate(monom):
            if e:
                key = (i, e)
                if key not in powers:
                    powers[key] = _precession_letter(i // 3)[i % 3] ** e
                term = term * powers[key]
                if not term:
                    break
        out += term
    return out


def _reduce_trig(p) -> sp.Expr:
    """Ring polynomial in (e, s, c) → SymPy expression in ε, ϑ, reduced by sin² = 1 − cos²."""
    out = _PR.zero
    one_minus_c2 = 1 - _C**2
    for (ie, is_, ic), coeff in p.items():
        out += coeff * _E**ie * _S ** (is_ % 2) * _C**ic * one_minus_c2 ** (is_ // 2)
    return sp.expand(out.as_expr(EPS, SIN, COS))


def precession_value(vector) -> tuple:
    """A weight-homogeneous series vector evaluated on (4.1) at t = 0, ν = 1.

    Parameters
    ----------
    vector : sequence of three RING elements
        Component polynomials (:mod:`strapdown.derivations.coning.series`).

    Returns
    -------
    tuple of three sympy.Expr
        The components as expressions in ε and ϑ; multiply the weight-w part by ``ν^w``.
    """
    return tuple(_reduce_trig(_substitute(c)) for c in vector)


def drift_coefficients(algorithm: Algorithm, max_weight: int = S.DEFAULT_MAX_WEIGHT) -> tuple:
    """Signed drift coefficients ``d_w(ε, ϑ)``, w = 0 … max_weight (exact minus algorithm).

    The constant drift rate of the attitude error (exact minus algorithm)
    along the precession axis n is ``Σ_w d_w ν^w H^(w−1)`` [rad/s] (``H`` the
    algorithm step), the projection on n of the error one step adds, exact
    through ``max_weight`` (see :func:`one_step_error`).  The steps compose:
    the error after K steps is ``R^K ∘ T^K`` with ``R`` the precession over a
    step and ``T = R⁻¹ ∘ exp(e)``, so the part of the step error across n adds
    ``−|e_⊥|² / (4 tan(μH/2))`` per step, second order in the error and of
    weight 2ρ + 1 and above; it is not in the ``d_w``.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    max_weight : int
        Highest weight kept.

    Returns
    -------
    tuple of sympy.Expr
        ``d_0 … d_max_weight`` in :data:`EPS`, :data:`SIN`, :data:`COS`.

    References
    ----------
    Lebedev & Panov (1989), eq. (5.3); Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3).
    """
    return _drift_coefficients(_checked(algorithm), S.check_max_weight(max_weight))


def _checked(algorithm):
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    return algorithm


@cache
@reproducible_sympy
def _drift_coefficients(algorithm: Algorithm, max_weight: int) -> tuple:
    return tuple(_reduce_trig(p) for p in _axial_parts(algorithm, max_weight))


def _axial_parts(algorithm: Algorithm, max_weight: int) -> tuple:
    """``n(0)·e_w`` in QQ[e, s, c] for w = 0 … max_weight."""
    err = _precession_error(algorithm)
    out = []
    for w in range(max_weight + 1):
        _, y, z = err.part(w)
        out.append(y * _S + z * _C)
    return tuple(out)


def step_error_values(algorithm: Algorithm, max_weight: int = S.DEFAULT_MAX_WEIGHT) -> tuple:
    """One-step error on (4.1) by weight: ``((w, (x_w, y_w, z_w)), …)``, nonzero parts only.

    The error one step adds (exact minus algorithm, :func:`one_step_error`),
    resolved in the body axes at the middle of a step centred on t = 0, is
    ``Σ_w (x_w, y_w, z_w)(ε, ϑ) (νH)^w``; at a step centred on t it is turned
    about e_z of E by −νt.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    max_weight : int
        Highest weight kept.

    Returns
    -------
    tuple of (int, tuple of three sympy.Expr)

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> [w for w, _ in step_error_values(get("lebedev-panov-4"))]
    [5, 7]
    """
    return _step_error_values(_checked(algorithm), S.check_max_weight(max_weight))


@cache
@reproducible_sympy
def _step_error_values(algorithm: Algorithm, max_weight: int) -> tuple:
    err = _precession_error(algorithm)
    out = []
    for w in range(max_weight + 1):
        part = err.part(w)
        if any(part):
            out.append((w, tuple(_reduce_trig(c) for c in part)))
    return tuple(out)


def _truncated_product(a: list, b: list) -> list:
    n = len(a)
    out = [Fraction(0)] * n
    for i, x in enumerate(a):
        if x:
            for j in range(n - i):
                if b[j]:
                    out[i + j] += x * b[j]
    return out


@cache
def _trig_powers(kind: str, power: int, order: int) -> tuple:
    """Taylor coefficients in α through α^order of sin^power α or cos^power α."""
    if power == 0:
        return (Fraction(1),) + (Fraction(0),) * order
    base = [Fraction(0)] * (order + 1)
    for k in range(order + 1):
        if kind == "sin" and k % 2 == 1:
            base[k] = Fraction((-1) ** (k // 2), math.factorial(k))
        if kind == "cos" and k % 2 == 0:
            base[k] = Fraction((-1) ** (k // 2), math.factorial(k))
    return tuple(_truncated_product(list(_trig_powers(kind, power - 1, order)), base))


def _alpha_coefficients(p, order: int) -> list:
    """Taylor coefficients in α through α^order of a polynomial in (e, s, c) at e = −1, s = sin α, c = cos α."""
    out = [Fraction(0)] * (order + 1)
    for (ie, is_, ic), coeff in p.items():
        c = Fraction(int(coeff.numerator), int(coeff.denominator)) * (-1) ** ie
        if is_ > order:
            continue
        term = _truncated_product(list(_trig_powers("sin", is_, order)), list(_trig_powers("cos", ic, order)))
        for k, t in enumerate(term):
            out[k] += c * t
    return out


def coning_drift_series(algorithm: Algorithm, max_weight: int = S.DEFAULT_MAX_WEIGHT, *, alpha_power: int = 2) -> tuple:
    """Coning drift from the general series, by weight: the terms in ``α^alpha_power``.

    Classical coning is the precession (4.1) at ε = −1 with half-cone angle
    α = ϑ.  The drift is taken along the cone axis ``a = −n``, the direction of
    the mean inertial angular velocity ``−ν(1 − cos α) n`` (exact minus
    algorithm: positive when the computed attitude lags the coning rotation),
    as in :func:`coning_drift`, which gives the α² terms in closed form.  With
    ``c_w`` returned, ``u = Σ_k α^k ν Σ_w c_w^(k) (νH)^(w−1)``; the drift has no
    α⁰ or α¹ terms (checked).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    max_weight : int
        Highest weight kept.
    alpha_power : int, keyword-only
        Power of α (even, ≥ 2): 2 is the leading coning drift, 4 its first
        correction (for pairwise algorithms it starts at (ωh)⁴ whatever their
        α² order, so it dominates at large α).

    Returns
    -------
    tuple of Fraction
        ``c_0 … c_max_weight``.

    Raises
    ------
    ValueError
        For an odd or non-positive ``alpha_power``.
    """
    if isinstance(alpha_power, bool) or not isinstance(alpha_power, int) or alpha_power < 2 or alpha_power % 2:
        raise ValueError(f"Expected `alpha_power` to be an even integer >= 2, got {alpha_power!r}")
    return _coning_drift_series(_checked(algorithm), S.check_max_weight(max_weight), alpha_power)


@cache
def _coning_drift_series(algorithm: Algorithm, max_weight: int, alpha_power: int) -> tuple:
    out = []
    for p in _axial_parts(algorithm, max_weight):
        coeffs = _alpha_coefficients(p, alpha_power)
        if coeffs[0] or coeffs[1]:
            raise ValueError(f"Expected a coning drift of order α², got terms of order α^0 or α^1 ({coeffs[0]}, {coeffs[1]})")
        out.append(-coeffs[alpha_power])
    return tuple(out)


# ---------------------------------------------------------------------------
# Structure functions of Lebedev & Panov (1989), section 5
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class StructureFunctions:
    """Leading-order drift structure of one algorithm (Lebedev & Panov 1989, (5.3)–(5.4)).

    Attributes
    ----------
    order : int
        ρ: the local error is ``δ_ρ h^(ρ+1) X`` (exact minus algorithm, h the sample interval).
    delta : Fraction
        δ_ρ, chosen so that ``g_ρ`` has coprime integer coefficients and a
        positive ε-free term (the normalisation of the printed ``f_2, g_2, f_4, g_4``).
    A, B : sympy.Expr
        ``A_ρ = εν^{ρ+1} sin²ϑ f_ρ``, ``B_ρ = εν^{ρ+1} sin ϑ g_ρ``: the e_z and
        e_y components of X on (4.1) at t = 0.
    f, g : sympy.Expr
        Structure functions of ε and ϑ.
    f_dual, g_dual : sympy.Expr
        ``f_ρ° = ϑ° ∂f_ρ/∂ϑ``, ``g_ρ° = ϑ° ∂g_ρ/∂ϑ`` (transfer principle).
    """

    order: int
    delta: Fraction
    A: sp.Expr
    B: sp.Expr
    f: sp.Expr
    g: sp.Expr
    f_dual: sp.Expr
    g_dual: sp.Expr

    @property
    def drift_factor(self) -> sp.Expr:
        """``g_ρ + f_ρ cos ϑ``: the drift is ``δ_ρ h^ρ / r · εν^{ρ+1} sin²ϑ (g_ρ + f_ρ cos ϑ)``."""
        return sp.expand(self.g + self.f * COS)


def _content(expr) -> Fraction:
    """gcd of the numerators over lcm of the denominators of the coefficients of ``expr`` in ε, cos ϑ."""
    coeffs = [sp.Rational(c) for c in sp.Poly(expr, EPS, COS).coeffs()]
    num = math.gcd(*[int(c.p) for c in coeffs]) if coeffs else 1
    den = math.lcm(*[int(c.q) for c in coeffs]) if coeffs else 1
    return Fraction(num, den)


def structure_functions(algorithm: Algorithm, max_weight: int = S.DEFAULT_MAX_WEIGHT) -> StructureFunctions:
    """``A_ρ, B_ρ, f_ρ, g_ρ, f_ρ°, g_ρ°`` of ``algorithm`` (Lebedev & Panov 1989, section 5).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    max_weight : int
        Weight of the series searched for the leading local error.

    Returns
    -------
    StructureFunctions

    Raises
    ------
    ValueError
        If the local error vanishes through ``max_weight``, or its leading part
        has no component along the precession axis on (4.1) (then f and g
        vanish, e.g. Savage's ``p_0 × p_1/12``, whose h⁴ error ``x_02`` is transverse).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> sf = structure_functions(get("lebedev-panov-2"))
    >>> sf.f, sf.g
    (-epsilon, epsilon*cos(vartheta) + 1)
    """
    return _structure_functions(_checked(algorithm), S.check_max_weight(max_weight))


@cache
@reproducible_sympy
def _structure_functions(algorithm: Algorithm, max_weight: int) -> StructureFunctions:
    rho = S.local_error(algorithm, max_weight).order
    if rho is None:
        raise ValueError(f"Expected an algorithm with a nonzero local error through h^{max_weight}, got {algorithm.name!r}")
    scale = QQ(algorithm.samples) ** (rho + 1)  # coefficient of h^(ρ+1)
    _, y, z = (_reduce_trig(c * scale) for c in _precession_local_error(algorithm).part(rho + 1))
    if y == 0 and z == 0:
        raise ValueError(
            f"Expected a leading local error with a component along the precession axis, got none for {algorithm.name!r}: "
            f"its weight-{rho + 1} error is transverse on (4.1), the structure functions vanish and the drift starts at a higher weight "
            "(see drift_coefficients)"
        )
    f_raw = sp.expand(sp.cancel(z / (EPS * (1 - COS**2))))
    g_raw = sp.expand(sp.cancel(y / (EPS * SIN)))
    delta = _content(g_raw) if g_raw != 0 else _content(f_raw)
    const = sp.expand(g_raw).subs(EPS, 0)
    if const != 0 and const < 0:
        delta = -delta
    d = sp.Rational(delta.numerator, delta.denominator)
    f = sp.expand(f_raw / d)
    g = sp.expand(g_raw / d)
    A = sp.expand(EPS * NU ** (rho + 1) * SIN**2 * f)
    B = sp.expand(EPS * NU ** (rho + 1) * SIN * g)
    return StructureFunctions(rho, delta, A, B, f, g, sp.expand(THETA_DUAL * sp.diff(f, THETA)), sp.expand(THETA_DUAL * sp.diff(g, THETA)))


# ---------------------------------------------------------------------------
# Classical coning in closed form
# ---------------------------------------------------------------------------
def lag_sums(algorithm: Algorithm) -> tuple:
    """``k_l = Σ_{j−i=l} c_ij`` of the pairwise terms, l = 1 … N − first_index.

    Sample indices ≤ 0 (earlier steps) count like any other: ``p_0 × p_1`` has lag 1.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.

    Returns
    -------
    tuple of Fraction
        One lag sum per lag (``N − 1`` of them for a within-step algorithm).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> lag_sums(get("optimal-3"))
    (Fraction(27, 20), Fraction(9, 20))
    """
    out = [Fraction(0)] * (algorithm.samples - algorithm.first_index)
    for (i, j), c in algorithm.pairwise.items():
        out[j - i - 1] += c
    return tuple(out)


def _coning_increment(t0, t1) -> sp.Matrix:
    """Increment (2.1) of (4.1) at ε = −1, ν = 1 over [t0, t1], to the order in α that matters.

    ``sin α → α`` and ``1 − cos α → α²/2``: the transverse parts are O(α) and
    the axial part O(α²), so every α²-coefficient formed from them is exact.
    """
    a = ALPHA
    return sp.Matrix([a * (sp.cos(t1) - sp.cos(t0)), -a * (sp.sin(t1) - sp.sin(t0)), a**2 / 2 * (t1 - t0)])


#: The cone axis a = −n(0) = −(0, sin α, cos α) in E at t = 0, to O(α²).
_AXIS = sp.Matrix([0, -ALPHA, -1 + ALPHA**2 / 2])


def _alpha2(expr) -> sp.Expr:
    return sp.expand(expr).coeff(ALPHA, 2)


def _sine_form(expr: sp.Expr) -> sp.Expr:
    """``expr`` rewritten as a sum of ``sin(m x)``, ``cos(m x)`` and powers of x (products to sums)."""
    from sympy.simplify.fu import TR8

    return sp.expand(TR8(sp.expand(expr)))


def lag_response(lag: int) -> sp.Expr:
    """``R_l(x)``: α²-coefficient of ``a·(p_i × p_j)`` for ``j − i = lag`` under coning (ν = 1, x = νh).

    Derived from the exact increments of (4.1) at ε = −1 with the first sample
    starting at a symbolic time s; s cancels (the response depends on the lag
    only, so a pairwise algorithm acts through its lag sums), which is checked.

    Parameters
    ----------
    lag : int
        ``j − i ≥ 1``.

    Returns
    -------
    sympy.Expr
        A sum of sines of multiples of :data:`X`.

    Raises
    ------
    ValueError
        If the lag is not a positive integer.

    Examples
    --------
    >>> lag_response(1)
    2*sin(x) - sin(2*x)
    """
    if isinstance(lag, bool) or not isinstance(lag, int) or lag < 1:
        raise ValueError(f"Expected `lag` to be a positive integer, got {lag!r}")
    return _lag_response(lag)


@cache
def _lag_response(lag: int) -> sp.Expr:
    s = sp.Symbol("s", real=True)
    pi = _coning_increment(s, s + X)
    pj = _coning_increment(s + lag * X, s + (lag + 1) * X)
    out = _sine_form(_alpha2(_AXIS.dot(pi.cross(pj))))
    if out.has(s):
        raise ValueError(f"Expected a response free of the sample time, got {out}")  # (4.1) is equivariant
    return out


def exact_coning_response(samples: int) -> sp.Expr:
    """``E(N x)``: α²-coefficient of ``a·(Δφ_exact − P)`` over the step ``H = N h`` under coning (x = νh, ν = 1).

    The exact step rotation of coning is ``Q(−H/2)⁻¹ ∘ Q(H/2)`` with Q of
    Lebedev & Panov (1989), eq. (4.4), at ε = −1.  Its rotation vector is
    ``2 asin(|v|) v/|v|`` for the vector part v, whose transverse part is O(α)
    and axial part O(α²): along the axis, 2v is exact to O(α²).

    Parameters
    ----------
    samples : int
        N ≥ 1.

    Returns
    -------
    sympy.Expr
        A function of :data:`X`.

    Raises
    ------
    TypeError, ValueError
        If ``samples`` is not a positive integer.

    Examples
    --------
    >>> exact_coning_response(1)
    x/2 - sin(x)/2
    """
    return _exact_coning_response(_positive_int(samples, "samples"))


def _positive_int(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"Expected `{name}` to be an integer, got {type(value).__name__}")
    if value < 1:
        raise ValueError(f"Expected `{name}` >= 1, got {value}")
    return value


@cache
def _exact_coning_response(samples: int) -> sp.Expr:
    a = ALPHA
    H = samples * X

    def Q(t):  # (cos α/2, sin α/2 cos νt, −sin α/2 sin νt, 0) to O(α²)
        return Quaternion(1 - a**2 / 8, a / 2 * sp.cos(t), -a / 2 * sp.sin(t), 0)

    q = Q(-H / 2).conjugate() * Q(H / 2)  # Hamilton product (sympy.algebras.Quaternion)
    phi = sp.Matrix([2 * q.b, 2 * q.c, 2 * q.d])
    return _sine_form(_alpha2(_AXIS.dot(phi - _coning_increment(-H / 2, H / 2))))


def _nonpairwise_response(algorithm: Algorithm) -> sp.Expr:
    """α²-coefficient of ``a·Σ c·term`` over the terms that are not plain pairs (nested, dot factors)."""
    N = algorithm.samples

    def sample(j):
        t0 = (j - 1) * X - N * X / 2
        return _coning_increment(t0, t0 + X)

    def value(expr):
        if isinstance(expr, int):
            return sample(expr)
        a, b = expr
        return value(a).cross(value(b))

    total = sp.Integer(0)
    for term in algorithm.terms:
        plain = not term.dots and isinstance(term.cross[0], int) and isinstance(term.cross[1], int)
        if plain:
            continue
        v = value(term.cross)
        for i, j in term.dots:
            v = v * sample(i).dot(sample(j))
        total += sp.Rational(term.coefficient.numerator, term.coefficient.denominator) * _alpha2(_AXIS.dot(v))
    return _sine_form(total)


@dataclass(frozen=True)
class ConingDrift:
    """Drift of an algorithm under classical coning, to leading order in the half-cone angle α.

    The constant drift rate along the cone axis is ``u = α² ω D(ωh) + O(α⁴)``
    [rad/s], exact minus algorithm (positive: the computed attitude lags the
    coning rotation), and ``D(x) = coefficient · x^order + O(x^(order+2))``.

    Attributes
    ----------
    samples : int
        N (samples per step H = N h).
    history : int
        Samples of earlier steps read.
    lag_sums : tuple of Fraction
        ``k_l``, l = 1 … N + history − 1.
    nonpairwise : sympy.Expr
        α²-response of the nested and dot-product terms (zero: they start at α⁴).
    function : sympy.Expr
        ``D(x)`` in closed form, x = :data:`X` = ωh.
    order : int
        Power of ωh of the leading term: the coning-drift order m.
    coefficient : Fraction
        Its exact coefficient.
    taylor : tuple of Fraction
        Taylor coefficients of D: ``D(x) = Σ_k taylor[k] x^k + O(x^len)``.
    """

    samples: int
    history: int
    lag_sums: tuple
    nonpairwise: sp.Expr
    function: sp.Expr
    order: int
    coefficient: Fraction
    taylor: tuple

    @property
    def step_coefficient(self) -> Fraction:
        """Coefficient of the leading term in the step: ``u ≈ c_H α² ω (ωH)^order``, ``c_H = coefficient / N^order``."""
        return self.coefficient / Fraction(self.samples) ** self.order

    @property
    def highest_frequency(self) -> int:
        """Largest m of the ``sin(m x)`` in D's numerator, ``N + history`` (bounds its Taylor coefficients)."""
        return self.samples + self.history

    def taylor_coefficients(self, count: int) -> tuple:
        """The first ``count`` Taylor coefficients of D (exact).

        Parameters
        ----------
        count : int
            How many (powers 0 … count − 1).

        Returns
        -------
        tuple of Fraction
        """
        if count <= len(self.taylor):
            return self.taylor[:count]
        return _drift_taylor(self.samples, self.lag_sums, self.nonpairwise, count)

    def stable_expression(self, *, tolerance: float = 1e-12) -> sp.Expr:
        """``D(x)`` for floating-point evaluation: Taylor polynomial at small x, closed form above.

        The closed form cancels: its terms are O(x) while D is O(x^order), so
        in double precision its relative accuracy is about ``ε / (2 |c| x^order)``
        (ε the machine epsilon, c the leading coefficient).  Below the x where
        that exceeds ``tolerance`` the Taylor polynomial is used, with enough
        terms that the omitted ones are below 1e-17 of D there.

        Parameters
        ----------
        tolerance : float, keyword-only
            Relative accuracy that decides the switch.

        Returns
        -------
        sympy.Expr
            A ``Piecewise`` in :data:`X`.
        """
        eps = 2.0**-52
        c = abs(float(self.coefficient))
        switch = min(2.0, (eps / (2.0 * c * tolerance)) ** (1.0 / self.order))
        value = 0.1 * c * switch**self.order
        m = self.highest_frequency
        scale = (4 * sum(abs(float(k)) for k in self.lag_sums) + 0.5) / self.samples
        k = self.order
        # |taylor[k]| ≤ scale m^(k+1)/(k+1)!; stop where that bound is negligible and terms halve
        while not (m * switch / (k + 2) < 0.5 and scale * m ** (k + 1) * switch**k / math.factorial(k + 1) < 1e-17 * value):
            k += 1
        coeffs = self.taylor_coefficients(k + 1)
        poly = sum((sp.Rational(t.numerator, t.denominator) * X**i for i, t in enumerate(coeffs) if t), sp.Integer(0))
        cut = sp.Rational(switch).limit_denominator(1000)
        return sp.Piecewise((sp.horner(poly, X), X < cut), (self.function, True))

    def latex(self) -> str:
        """``u = c α² ω (ωh)^m`` as LaTeX.

        Returns
        -------
        str
        """
        c = sp.latex(sp.Rational(self.coefficient.numerator, self.coefficient.denominator))
        return f"u = {c}\\,\\alpha^2\\,\\omega\\,(\\omega h)^{{{self.order}}}"


def _series_coefficients(expr: sp.Expr, n: int) -> list:
    """Taylor coefficients of ``expr`` (a sum of ``c sin(m x)``, ``c cos(m x)``, ``c x^k``) through x^(n−1), exact."""
    out = [Fraction(0)] * n

    def rational(c):
        r = sp.Rational(c)
        return Fraction(int(r.p), int(r.q))

    for term in sp.Add.make_args(sp.expand(expr)):
        if term == 0:
            continue
        c, rest = term.as_coeff_Mul()
        c = rational(c)
        if rest == 1:
            out[0] += c
            continue
        if rest.func in (sp.sin, sp.cos):
            m = rest.args[0] / X
            if not (m.is_Rational and not m.has(X)):
                raise ValueError(f"Expected a sine or cosine of a multiple of x, got {rest}")
            m = rational(m)
            for k in range(n):
                if (rest.func is sp.sin) == (k % 2 == 1):
                    sign = (-1) ** (k // 2)
                    out[k] += c * sign * m**k / math.factorial(k)
            continue
        power = sp.Poly(rest, X) if rest.is_polynomial(X) else None
        if power is None or len(power.terms()) != 1 or power.terms()[0][1] != 1:
            raise ValueError(f"Expected a sine, cosine or power of x, got {rest}")
        (k,), _ = power.terms()[0]
        if k < n:
            out[k] += c
    return out


@cache
def _lag_taylor(lag: int, n: int) -> tuple:
    return tuple(_series_coefficients(lag_response(lag), n))


@cache
def _exact_taylor(samples: int, n: int) -> tuple:
    return tuple(_series_coefficients(exact_coning_response(samples), n))


@cache
def _drift_taylor(samples: int, ks: tuple, nonpairwise: sp.Expr, n: int) -> tuple:
    """Taylor coefficients of D through x^(n−1): numerator ``E(Nx) − Σ k_l R_l − T`` over ``N x``."""
    num = list(_exact_taylor(samples, n + 1))
    for lag, k in enumerate(ks, start=1):
        if k:
            for i, r in enumerate(_lag_taylor(lag, n + 1)):
                num[i] -= k * r
    for i, t in enumerate(_series_coefficients(nonpairwise, n + 1)):
        num[i] -= t
    if num[0]:
        raise ValueError(f"Expected a coning response vanishing at x = 0, got {num[0]}")
    return tuple(num[i + 1] / samples for i in range(n))


@cache
@reproducible_sympy
def coning_drift(algorithm: Algorithm) -> ConingDrift:
    """Coning drift of ``algorithm`` in closed form, at leading order in the half-cone angle α.

    Classical coning with half-cone angle α and coning rate ω is the regular
    precession (4.1) with ε = −1, ϑ = α, ν = ω.  What is measured: the constant
    rate ``u`` [rad/s] of the attitude error ``Λ_true ∘ Λ̄_computed`` (exact
    minus algorithm, frame I) along the cone axis ``a``, the direction of the
    mean inertial angular velocity ``−ω(1 − cos α) n`` (``a = −n``, n the
    precession axis of (4.1)).  ``u > 0`` means the computed attitude lags the
    coning rotation about the cone axis.  The other components of the error
    do not grow.

    Derivation: to order α², a step error has a cone-axis component only from
    the pairwise terms ``c_ij p_i × p_j``, which act through their lag sums
    ``k_l`` (:func:`lag_response`; cross-step pairs included), and from the
    exact increment (:func:`exact_coning_response`); nested and dot-product
    terms are of order α⁴ and above (computed, not assumed).  With ``x = ωh``,

        D(x) = [E(N x) − Σ_l k_l R_l(x)] / (N x),    u = α² ω D(x) + O(α⁴),

    exactly in x.  The transport of the step error into frame I changes it only
    at order α⁴.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).

    Returns
    -------
    ConingDrift

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm.
    ValueError
        If the drift vanishes to every order searched (x^60).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> d = coning_drift(get("two-sample"))
    >>> d.order, d.coefficient, d.step_coefficient
    (4, Fraction(1, 60), Fraction(1, 960))
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    ks = lag_sums(algorithm)
    N = algorithm.samples
    extra = _nonpairwise_response(algorithm)
    pairs = sum((sp.Rational(k.numerator, k.denominator) * lag_response(lag) for lag, k in enumerate(ks, start=1) if k), sp.Integer(0))
    function = sp.simplify((exact_coning_response(N) - pairs - extra) / (N * X))
    n = 2 * len(ks) + 6
    while True:
        taylor = _drift_taylor(N, ks, extra, n)
        lead = next((k for k, c in enumerate(taylor) if c), None)
        if lead is not None:
            return ConingDrift(N, algorithm.history, ks, extra, function, lead, taylor[lead], taylor)
        if n >= 60:
            raise ValueError(f"Expected a coning drift of finite order, got zero through (ωh)^{n - 1} for {algorithm.name!r}")
        n = min(60, 2 * n)


@reproducible_sympy
def coning_drift_closed_form(lag_sums, samples: int) -> sp.Expr:
    """Exact α²-coefficient ``D(x)`` of the coning drift of a pairwise algorithm from its lag sums.

    Parameters
    ----------
    lag_sums : sequence of Fraction
        ``k_l = Σ_{j−i=l} c_ij`` for l = 1, 2, … (pure coning sees only these).
    samples : int
        N.

    Returns
    -------
    sympy.Expr
        ``D(x)`` with drift ``≈ α² ν D(νh)`` [rad/s], x = νh, for small cone angle α
        (sign as :func:`coning_drift`).
    """
    total = sum((sp.Rational(Fraction(k).numerator, Fraction(k).denominator) * lag_response(lag) for lag, k in enumerate(lag_sums, start=1)), sp.Integer(0))
    return sp.simplify((exact_coning_response(samples) - total) / (samples * X))


def optimal_coning_algorithm(samples: int, *, history: int = 0) -> Algorithm:
    """Optimal coning algorithm: lag sums that cancel the coning drift through the highest order.

    Under classical coning only the lag sums ``k_l`` (l = 1 … N + history − 1)
    matter (:func:`lag_sums`).  They solve the linear system that cancels the
    first N + history − 1 even Taylor coefficients of ``D(x)`` (the first one is
    the second-order condition), leaving ``D ∝ x^{2(N + history)}``.  Each lag
    sum is put on the pair ``(N − l, N)`` (``p_N`` crossed with the earlier
    samples, Ignagni's form; indices ≤ 0 are samples of earlier steps).

    Parameters
    ----------
    samples : int
        N ≥ 1.
    history : int, keyword-only
        Samples of earlier steps used (≥ 0); N + history ≥ 2.

    Returns
    -------
    Algorithm

    Raises
    ------
    ValueError
        For N < 1, history < 0 or N + history < 2.

    Examples
    --------
    >>> sorted(optimal_coning_algorithm(2).pairwise.items())
    [((1, 2), Fraction(2, 3))]
    >>> [str(k) for k in lag_sums(optimal_coning_algorithm(3))]
    ['27/20', '9/20']
    >>> optimal_coning_algorithm(1, history=1).pairwise
    {(0, 1): Fraction(1, 12)}
    """
    for name, value in (("samples", samples), ("history", history)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"Expected `{name}` to be an integer, got {type(value).__name__}")
    if samples < 1 or history < 0 or samples + history < 2:
        raise ValueError(f"Expected `samples` >= 1, `history` >= 0 and samples + history >= 2, got {samples} and {history}")
    return _optimal_coning_algorithm(samples, history)


@cache
def _optimal_coning_algorithm(samples: int, history: int) -> Algorithm:
    L = samples + history - 1
    n = 2 * L + 2
    lags = [_lag_taylor(lag, n + 1) for lag in range(1, L + 1)]
    exact = _exact_taylor(samples, n + 1)
    # Taylor coefficient of x^(2m+1) of the numerator, m = 1 … L (even powers of D are zero by symmetry)
    rows = [[QQ(r[2 * m + 1].numerator, r[2 * m + 1].denominator) for r in lags] for m in range(1, L + 1)]
    rhs = [QQ(exact[2 * m + 1].numerator, exact[2 * m + 1].denominator) for m in range(1, L + 1)]
    from sympy.polys.matrices import DomainMatrix

    A = DomainMatrix(rows, (L, L), QQ)
    if A.rank() != L:
        raise ValueError(f"Expected a unique optimal {samples}+{history} coning algorithm, got a singular system")
    b = DomainMatrix([[v] for v in rhs], (L, 1), QQ)
    sol = A.lu_solve(b).to_Matrix()
    terms = []
    for lag in range(1, L + 1):
        v = sp.Rational(sol[lag - 1])
        if v:
            terms.append(Term(Fraction(int(v.p), int(v.q)), (samples - lag, samples)))
    suffix = f"{samples}" if history == 0 else f"{samples}+{history}"
    what = f"{samples}-sample" if history == 0 else f"{samples}-sample, {history} earlier sample{'s' if history > 1 else ''}"
    return Algorithm(f"optimal-coning-{suffix}", samples, tuple(terms), f"optimal coning algorithm ({what}; lag sums)", "Ignagni (1990, 1996); derived by the package")


def coning_constant(samples: int) -> tuple:
    """``(m, C_N)``: the optimal N-sample coning drift is ``α² ν (νH)^m / C_N`` to leading order.

    H = N h is the algorithm step (Ignagni's T); m = 2N.

    Parameters
    ----------
    samples : int
        N ≥ 2.

    Returns
    -------
    tuple of int

    Raises
    ------
    ValueError
        If the leading coefficient is not the reciprocal of an integer.

    Examples
    --------
    >>> coning_constant(2)
    (4, 960)
    """
    d = coning_drift(optimal_coning_algorithm(samples))
    c = d.step_coefficient
    if c.numerator != 1:
        raise ValueError(f"Expected a leading coefficient 1/C_N, got {c}")
    return d.order, c.denominator
