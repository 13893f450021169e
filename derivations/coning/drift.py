"""Asymptotic drift of rotation-vector algorithms under regular precession.

The body rate of the regular precession (Lebedev & Panov 1989, eq. (4.1)) is

    ω(t) = ν (ε sin ϑ sin νt,  ε sin ϑ cos νt,  1 + ε cos ϑ) = ν e_z + εν n(t),

with the precession axis ``n(t) = (sin ϑ sin νt, sin ϑ cos νt, cos ϑ)`` in E.
The motion is equivariant: shifting t rotates every ω-derivative, hence every
nested product ``x_w`` and the whole local error, about ``e_z`` of E by
``−νt``, while the attitude turns about the fixed precession axis of I.  The
error that one step adds in frame I is therefore the same vector turned by
``εν t`` about that axis, and its constant part — the asymptotic drift — is
its projection on the precession axis, divided by the step H.

Two levels of rigour are derived here.

* **Paper level** (Lebedev & Panov 1989, eqs. (5.2)–(5.3)): project the
  leading local error ``δφ`` itself.  Its components along ``e_z`` and along
  ``n(0) × e_x`` (the y axis) give ``A_ρ = εν^{ρ+1} sin²ϑ f_ρ(ε, ϑ)`` and
  ``B_ρ = εν^{ρ+1} sin ϑ g_ρ(ε, ϑ)``; the drift is
  ``δ_ρ h^ρ / r · (B_ρ sin ϑ + A_ρ cos ϑ)``.
* **Exact to weight 7**: one step of the algorithm from the true attitude
  ``Λ_n`` gives ``Λ_n ∘ exp(Δφ + δφ) = exp(J δφ)_I ∘ Λ_n ∘ exp(Δφ)`` with the
  left Jacobian ``J = (e^{ad Δφ} − 1)/ad Δφ``; seen from the attitude at the
  middle of the step, ``Λ(t_m) = Λ_n ∘ exp(Δφ_1)`` (``Δφ_1``: exact increment
  over the first half step), the error vector is
  ``δφ_I = exp(−ad Δφ_1) J(Δφ) δφ``.  The drift series is
  ``n(0)·δφ_I / H`` through weight 7.  It agrees with the paper level in the
  leading term; where the leading term cancels (ρ = 6 under coning for the
  algorithms 3 and 5 of Budennyi, Kalinovsky, Panov et al.), the second-order
  terms of ``exp(−ad Δφ_1) J`` acting on the weight-5 error add to the weight-7
  drift, and only the full expression matches simulation.

The optimal N-sample coning class (lag-sum coefficients of the pairwise
terms) and its closed-form drift ``α² Ω (ΩH)^{2N} / C_N`` are derived exactly
for pure coning (ε = −1) and small cone angle α.

References
----------
Lebedev & Panov (1989), section 5, eqs. (5.1)–(5.6).
Budennyi, Kalinovsky, Panov et al. (Part 2), eqs. (3)–(5), Table 3.
Ignagni (1990), "Optimal strapdown attitude integration algorithms".
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import factorial

import sympy as sp
from sympy.algebras.quaternion import Quaternion
from sympy.polys.domains import QQ
from sympy.polys.rings import ring

from ..reproducible import reproducible_sympy
from . import series as S
from .algorithms import Algorithm, Term

__all__ = [
    "EPS",
    "THETA",
    "THETA_DUAL",
    "NU",
    "COS",
    "SIN",
    "mapped_error",
    "precession_value",
    "drift_coefficients",
    "step_error_values",
    "StructureFunctions",
    "structure_functions",
    "optimal_coning_algorithm",
    "coning_drift_closed_form",
    "coning_constant",
]

EPS, THETA, THETA_DUAL, NU = sp.symbols("epsilon vartheta vartheta_dual nu", real=True)
#: Shorthands used in the polynomial results: ``COS = cos ϑ``, ``SIN = sin ϑ``.
COS, SIN = sp.cos(THETA), sp.sin(THETA)

_PR, _E, _S, _C = ring("e,s,c", QQ)


# ---------------------------------------------------------------------------
# Error as seen in frame I
# ---------------------------------------------------------------------------
def _ad_series(a, v, coeff, max_terms: int):
    """``Σ_n coeff(n) ad_a^n v`` truncated at weight 7 (vectors of ring polynomials)."""
    total = v
    term = v
    for n in range(1, max_terms + 1):
        term = S._cross(a, term)
        if not any(term):
            break
        total = S._add(total, S._scale(term, coeff(n)))
    return total


@cache
def mapped_error(algorithm: Algorithm) -> tuple:
    """``δφ_I = exp(−ad Δφ_1) J(Δφ) δφ`` through weight 7 (``H = 1``), algorithm minus exact.

    See the module docstring: this is the error one step adds to the attitude,
    resolved in the body axes at the middle of the step.
    """
    err = S.local_error(algorithm)
    delta = (S.RING.zero,) * 3
    for part in err.parts:
        delta = S._add(delta, part)
    full = S.exact_increment()
    half = S.exact_increment(Fraction(-1, 2), Fraction(0))
    j = _ad_series(full, delta, lambda n: QQ(1, factorial(n + 1)), 6)
    return _ad_series(half, j, lambda n: QQ((-1) ** n, factorial(n)), 6)


# ---------------------------------------------------------------------------
# Substituting the regular precession
# ---------------------------------------------------------------------------
@cache
def _omega_values() -> tuple:
    """ω^(k)(0)/ν^(k+1) of (4.1) in QQ[ε, sinϑ, cosϑ]."""
    vals = []
    for k in range(S.MAX_WEIGHT):
        sin_k = [0, 1, 0, -1][k % 4]  # d^k sin(x)/dx^k at 0
        cos_k = [1, 0, -1, 0][k % 4]
        z = 1 + _E * _C if k == 0 else _PR.zero
        vals.append((_E * _S * sin_k, _E * _S * cos_k, z))
    return tuple(v for vec in vals for v in vec)


def _substitute(poly):
    vals = _omega_values()
    out = _PR.zero
    cache: dict = {}
    for monom, coeff in poly.items():
        term = _PR(coeff)
        for i, e in enumerate(monom):
            if e:
                key = (i, e)
                if key not in cache:
                    cache[key] = vals[i] ** e
                term = term * cache[key]
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

    Returns the three components as SymPy expressions in ε and ϑ; multiply
    the weight-w part by ``ν^w``.
    """
    return tuple(_reduce_trig(_substitute(c)) for c in vector)


@cache
@reproducible_sympy
def drift_coefficients(algorithm: Algorithm) -> tuple:
    """Signed drift coefficients ``d_w(ε, ϑ)``, w = 0 … 7 (algorithm minus exact).

    The constant drift rate along the precession axis is
    ``Σ_w d_w ν^w H^(w−1)`` [rad/s] (``H`` the algorithm step), exact through
    weight 7 (see :func:`mapped_error`).
    """
    mapped = S._truncate(mapped_error(algorithm), S.MAX_WEIGHT)
    out = []
    for w in range(S.MAX_WEIGHT + 1):
        part = S._weight_part(mapped, w)
        if not any(part):
            out.append(sp.Integer(0))
            continue
        y = _substitute(part[1])
        z = _substitute(part[2])
        out.append(_reduce_trig(y * _S + z * _C))
    return tuple(out)


@cache
def step_error_values(algorithm: Algorithm) -> tuple:
    """One-step error on (4.1) by weight: ``((w, (x_w, y_w, z_w)), …)``, w ≤ 7, nonzero parts only.

    The error one step adds (algorithm minus exact, :func:`mapped_error`),
    resolved in the body axes at the middle of a step centred on t = 0, is
    ``Σ_w (x_w, y_w, z_w)(ε, ϑ) (νH)^w``; at a step centred on t it is turned
    about e_z of E by −νt.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> [w for w, _ in step_error_values(get("lebedev-panov-4"))]
    [5, 7]
    """
    mapped = S._truncate(mapped_error(algorithm), S.MAX_WEIGHT)
    out = []
    for w in range(S.MAX_WEIGHT + 1):
        part = S._weight_part(mapped, w)
        if any(part):
            out.append((w, precession_value(part)))
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
    poly = sp.Poly(expr, EPS, COS)
    coeffs = [sp.Rational(c) for c in poly.coeffs()]
    num = sp.igcd(*[c.p for c in coeffs]) if coeffs else 1
    den = sp.ilcm(*[c.q for c in coeffs]) if coeffs else 1
    return Fraction(int(num), int(den))


@cache
@reproducible_sympy
def structure_functions(algorithm: Algorithm) -> StructureFunctions:
    """``A_ρ, B_ρ, f_ρ, g_ρ, f_ρ°, g_ρ°`` of ``algorithm`` (Lebedev & Panov 1989, section 5).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> sf = structure_functions(get("lebedev-panov-2"))
    >>> sf.f, sf.g
    (-epsilon, epsilon*cos(vartheta) + 1)
    """
    err = S.local_error(algorithm)
    rho = err.order
    if rho is None:
        raise ValueError(f"Expected an algorithm with a nonzero local error through h^{S.MAX_WEIGHT}, got {algorithm.name!r}")
    x = S._scale(err.part(rho + 1, unit="h"), QQ(-1))  # exact − algorithm
    _, y, z = precession_value(x)
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
# Optimal N-sample coning algorithms and their closed-form drift
# ---------------------------------------------------------------------------
_X, _ALPHA = sp.symbols("x alpha", positive=True)


def _coning_lag_response(samples: int) -> list:
    """For pure coning, ``n·(p_i × p_j)`` depends on the lag ``l = j − i`` only.

    Returns ``[R_1, …, R_{N−1}]`` with the exact ``α²``-coefficient of
    ``n(t_m)·(p_i × p_j)`` as a function of ``x = νh`` (ν = 1), derived from
    the exact increments of (4.1) at ε = −1.
    """
    e = -1
    a = _ALPHA

    def p(t0, t1):
        return sp.Matrix([
            -e * sp.sin(a) * (sp.cos(t1) - sp.cos(t0)),
            e * sp.sin(a) * (sp.sin(t1) - sp.sin(t0)),
            (1 + e * sp.cos(a)) * (t1 - t0),
        ])

    n = sp.Matrix([0, sp.sin(a), sp.cos(a)])
    half = sp.Rational(samples, 2)
    out = []
    for lag in range(1, samples):
        pi = p((0 - half) * _X, (1 - half) * _X)
        pj = p((lag - half) * _X, (lag + 1 - half) * _X)
        val = n.dot(pi.cross(pj))
        coeff = sp.series(val, a, 0, 3).removeO().coeff(a, 2)
        out.append(sp.simplify(sp.expand_trig(coeff)))
    return out


@cache
@reproducible_sympy
def _coning_exact(samples: int) -> sp.Expr:
    """``α²``-coefficient of ``n·(Δφ_exact − P)`` for pure coning over ``H = N h`` (x = νh, ν = 1).

    The exact step rotation of coning is ``Q(−H/2)⁻¹ Q(H/2)`` with Q of
    Lebedev & Panov (1989), eq. (4.4), at ε = −1.
    """
    a = _ALPHA
    H = samples * _X

    def Q(t):
        c, s = sp.cos(a / 2), sp.sin(a / 2)
        return Quaternion(c * sp.cos(0 * t), s * sp.cos(t), -s * sp.sin(t), c * sp.sin(0 * t))

    q = Q(-H / 2).conjugate() * Q(H / 2)  # Hamilton product (sympy.algebras.Quaternion)
    rel = (q.a, q.b, q.c, q.d)
    # rotation vector = 2 asin(|v|)/|v| v; to O(α²) along n = (0, sin α, cos α):
    # v = O(α) in x,y and O(α²) in z, so 2 v is exact to O(α²) in n·φ.
    phi = [2 * rel[1], 2 * rel[2], 2 * rel[3]]
    n_phi = sp.sin(a) * phi[1] + sp.cos(a) * phi[2]
    P = [sp.sin(a) * (sp.cos(H / 2) - sp.cos(-H / 2)), -sp.sin(a) * (sp.sin(H / 2) - sp.sin(-H / 2)), (1 - sp.cos(a)) * H]
    n_P = sp.sin(a) * P[1] + sp.cos(a) * P[2]
    val = sp.series(n_phi - n_P, a, 0, 3).removeO().coeff(a, 2)
    return sp.simplify(sp.expand_trig(val))


@reproducible_sympy
def coning_drift_closed_form(lag_sums, samples: int) -> sp.Expr:
    """Exact ``α²``-coefficient of the coning drift ``n·(Δφ_alg − Δφ_exact)/H`` of a pairwise algorithm.

    Parameters
    ----------
    lag_sums : sequence of Fraction
        ``k_l = Σ_{j−i=l} c_ij`` for l = 1 … N−1 (pure coning sees only these).
    samples : int
        N.

    Returns
    -------
    sympy.Expr
        ``D(x)`` with drift ``≈ α² ν D(νh)`` [rad/s], x = νh, for small cone angle α.
    """
    resp = _coning_lag_response(samples)
    total = sum((sp.Rational(k.numerator, k.denominator) * r for k, r in zip(lag_sums, resp)), sp.Integer(0))
    return sp.simplify((total - _coning_exact(samples)) / (samples * _X))


@cache
@reproducible_sympy
def optimal_coning_algorithm(samples: int) -> Algorithm:
    """Optimal N-sample coning algorithm: lag sums that cancel the coning drift through ``(νh)^{2N−1}``.

    Under pure coning only the lag sums ``k_l = Σ_{j−i=l} c_ij`` matter
    (:func:`lag_sums`).  They solve the linear system that cancels the first
    N − 1 terms of the drift series in ``x = νh`` (the first one is the
    second-order condition).  Each lag sum is put on the pair ``(N − l, N)``
    (``p_N`` crossed with the earlier samples, Ignagni's form).

    Examples
    --------
    >>> sorted(optimal_coning_algorithm(2).pairwise.items())
    [((1, 2), Fraction(2, 3))]
    >>> [str(k) for k in lag_sums(optimal_coning_algorithm(3))]
    ['27/20', '9/20']
    """
    if samples < 2:
        raise ValueError(f"Expected `samples` >= 2, got {samples}")
    resp = _coning_lag_response(samples)
    exact = _coning_exact(samples)
    ks = sp.symbols(f"k1:{samples}")
    total = sum(k * r for k, r in zip(ks, resp)) - exact
    ser = sp.expand(sp.series(total, _X, 0, 2 * samples + 1).removeO())
    eqs = [ser.coeff(_X, m) for m in range(1, 2 * samples)]
    eqs = [e for e in eqs if e != 0]
    sol = sp.solve(eqs, ks, dict=True)
    if len(sol) != 1:
        raise ValueError(f"Expected a unique optimal {samples}-sample coning algorithm, got {len(sol)} solutions")
    sol = sol[0]
    terms = tuple(Term(Fraction(int(sp.fraction(sol[k])[0]), int(sp.fraction(sol[k])[1])), (samples - l, samples)) for l, k in enumerate(ks, start=1) if sol[k] != 0)
    return Algorithm(f"optimal-coning-{samples}", samples, terms, f"optimal {samples}-sample coning algorithm (lag sums)", "Ignagni (1990); derived by the package")


def lag_sums(algorithm: Algorithm) -> tuple:
    """``k_l = Σ_{j−i=l} c_ij`` of the pairwise terms (l = 1 … N−1)."""
    out = [Fraction(0)] * (algorithm.samples - 1)
    for (i, j), c in algorithm.pairwise.items():
        out[j - i - 1] += c
    return tuple(out)


@cache
def coning_constant(samples: int) -> tuple:
    """``(m, C_N)``: the optimal N-sample coning drift is ``α² ν (νH)^m / C_N`` to leading order.

    H = N h is the algorithm step (Ignagni's T); m = 2N.

    Examples
    --------
    >>> coning_constant(2)
    (4, 960)
    """
    alg = optimal_coning_algorithm(samples)
    d = coning_drift_closed_form(lag_sums(alg), samples)
    # d(x) with x = νh; rewrite in X = νH = N x
    X = sp.Symbol("X", positive=True)
    dd = sp.expand(sp.series(d.subs(_X, X / samples), X, 0, 2 * samples + 2).removeO())
    lead = sp.Poly(dd, X).terms()[-1]
    (m,), c = lead
    c = sp.Rational(c)
    if c.p != 1:
        raise ValueError(f"Expected a leading coefficient 1/C_N, got {c}")
    return int(m), int(c.q)
