"""The N-sample position (scrolling) algorithm as exact fractions, and its scrolling error in closed form.

Position over one step
----------------------
Over a step ``t ∈ [0, H]``, ``H = N h``, let ``α(t) = ∫₀ᵗ ω`` and
``υ(t) = ∫₀ᵗ f`` be the integrated body rate and specific force, resolved in
the body axes at the start of the step (frame I of the step).  The apparent
velocity and the position gained over the step are ::

    W(t) = ∫₀ᵗ C(τ) f(τ) dτ,        ΔR = ∫₀ᴴ W(t) dt = ∫₀ᴴ (H − τ) C(τ) f(τ) dτ,

with C the rotation from the body at τ to the body at 0.  To second order in
the motion, ``C ≈ I + [α×]``, so that ::

    ΔR ≈ S + ∫₀ᴴ (H − τ) α(τ) × f(τ) dτ,       S = ∫₀ᴴ υ dt = ∫₀ᴴ (H − τ) f dτ.

For constant ω and f the sum over every order is ``ΔR = H² Σ_k [φ×]^k f /(k+2)!
= 2 Γ₂(φ) S`` with ``φ = ωH`` and the second Jacobian of SO(3)
``Γ₂(φ) = Σ_k [φ×]^k/(k+2)!`` (its second-order part is ``⅓ φ × S``).  The
algorithm keeps that exact rotation compensation and adds, from the N gyro
increments ``p_i`` and N velocity increments ``b_j`` of the step, what the
rates' variation within the step adds at second order::

    ΔR = 2 Γ₂(φ) S + h Σ_ij d_ij p_i × b_j,        S = h Σ_j s_j b_j,

where φ is the step's rotation vector (from the coning algorithm) and the
exact fractions ``s_j``, ``d_ij`` make both parts exact when ω and f are
polynomials of degree N − 1 in time (the model behind the N-sample coning
algorithms): with the dual basis ``L_i(u)`` (degree N − 1, ``∫_{j−1}^{j} L_i du = δ_ij``)
and ``A_i(u) = ∫₀ᵘ L_i``, ::

    s_j = ∫₀ᴺ A_j du,     e_ij = ∫₀ᴺ (N − u) A_i(u) L_j(u) du,     d_ij = e_ij − s_j/3.

This is the structure of Savage (1998), part 2: an exact moderate-speed
update (here ``2 Γ₂(φ) S``, the analogue of the velocity's ``J(φ) ΔV``) with a
high-speed term that measures the rectified motion within the step, the
*scrolling* term ``h Σ d_ij p_i × b_j`` (Savage's name).  For N = 1 the
scrolling term vanishes (``d = 0``).

Scrolling error under sculling, in closed form
----------------------------------------------
Under a line of sculling, ``ω = Re(Â e^{iνt})``, ``f = Re(B̂ e^{iνt})`` (rate
and specific-force amplitude vectors), the errors of the velocity and position
algorithms rectify.  Exact minus algorithm (package docstring, "Errors"), one
step started from the exact state adds on average ``e_v H`` to the velocity
error (the rectification, or sculling, error ``e_v``) and ``e_r H`` to the
position error: ``e_r`` is the *scrolling error*, the rate at which the
position algorithm alone loses position.  Averaged over the phase of the
steps, every second-order quantity of a step is ``½ Re((Â × conj B̂) K)`` with
a scalar kernel K of ``x = νh``, so that, with the step increments ``p_i``,
``b_j`` over the sample intervals ``[(i − 1)h, ih]`` (indices ≤ 0 read the
steps before), ::

    e_v = (h/(2N)) Re((Â × conj B̂) (K_v − K_v,alg)),
    e_r = (h²/2) Re((Â × conj B̂) Z(x)),
    Z(x) = [K_r − Σ_ij e_ij k_ij + conj σ(x)/(ix)]/N,

    k_ij = ∫_{i−1}^{i} e^{ixσ} dσ · conj ∫_{j−1}^{j} e^{ixτ} dτ,
    K_v = ∫₀ᴺ ∫₀^τ e^{ix(σ−τ)} dσ dτ,     K_r = ∫₀ᴺ (N − τ) ∫₀^τ e^{ix(σ−τ)} dσ dτ,
    σ(x) = ∫₀ᴺ (N − u) e^{ixu} du − Σ_j s_j ∫_{j−1}^{j} e^{ixu} du,
    K_v,alg = Σ_{i<j} c_ij (k_ij − k_ji) + ½ Σ_{i,j=1}^{N} k_ij

(``c_ij`` the pairwise coefficients of the coning algorithm, whose dual
extension is the velocity algorithm, ``ΔV = J(φ) φ°``; ``½ P × B`` is the
second-order part of J).  The last term of Z is the linear error of the
position algorithm, ``h² Re(B̂ e^{iνt} σ)`` (zero for f polynomial of degree
N − 1, but not for a sinusoid), turned into frame I by the vibration angle at
the start of the step, ``Re(Â e^{iνt}/(iν))``: the two are correlated and
their product rectifies.  The velocity algorithm has no such term, its linear
part ``Σ b_j`` being exact.  Over a run the
position error then grows as ``½ e_v t² + (e_r − ½ e_v H) t`` plus a term that
depends on the phase at the start: the position update uses the velocity at
the start of each step, which lags the velocity error by half a step.
Classical sculling (angle ``θ₀ sin(νt + φ_θ)`` about ``e_r``, specific force
``A sin(νt + φ_a)`` along ``e_a``) has
``Â × conj B̂ = i θ₀ ν A e^{−i(φ_a − φ_θ)} e_r × e_a``.

References
----------
Savage, P. G., "Strapdown inertial navigation integration algorithm design
part 2: velocity and position algorithms", *J. Guidance, Control, and
Dynamics* 21(2), 1998 (two-speed structure; sculling and scrolling).
Lebedev & Panov (1989), eq. (2.5) (the velocity algorithm as the dual
extension of the coning algorithm).

Public API
----------
.. autosummary::

   PositionAlgorithm
   position_algorithm
   ScrollingKernel
   scrolling_kernel
   X
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from fractions import Fraction

import sympy as sp

from ..coning.algorithms import Algorithm

__all__ = ["PositionAlgorithm", "position_algorithm", "ScrollingKernel", "scrolling_kernel", "X", "MAX_SAMPLES"]

#: ``x = νh``, the vibration's phase advance over one sample [rad].
X = sp.Symbol("x", positive=True)
#: Largest number of samples per step of a position algorithm [count].
MAX_SAMPLES = 8

_U, _S = sp.symbols("u s", real=True)


@dataclass(frozen=True)
class PositionAlgorithm:
    """The N-sample position algorithm ``ΔR = 2 Γ₂(φ) S + h Σ d_ij p_i × b_j``, ``S = h Σ s_j b_j`` (module docstring).

    Attributes
    ----------
    samples : int
        N, samples per step.
    weights : tuple of Fraction
        ``s_j``, j = 1 … N [dimensionless].
    scrolling : tuple of tuple of Fraction
        ``d_ij`` (N × N) [dimensionless], row i for the gyro increment.
    """

    samples: int
    weights: tuple
    scrolling: tuple


def _check_samples(samples) -> int:
    if not isinstance(samples, int) or isinstance(samples, bool) or not 1 <= samples <= MAX_SAMPLES:
        raise ValueError(f"Expected `samples` as an integer in 1 … {MAX_SAMPLES}, got {samples!r}")
    return samples


@functools.cache
def _basis(samples: int) -> tuple:
    """``(L_i, A_i)``: the dual basis of degree N − 1 and its integrals from 0, polynomials in u."""
    n = samples
    M = sp.Matrix(n, n, lambda j, k: sp.Rational((j + 1) ** (k + 1) - j ** (k + 1), k + 1))
    C = M.inv()
    L = [sp.expand(sum(C[k, i] * _U**k for k in range(n))) for i in range(n)]
    A = [sp.expand(sp.integrate(Li.subs(_U, _S), (_S, 0, _U))) for Li in L]
    return tuple(L), tuple(A)


def _fraction(r) -> Fraction:
    r = sp.Rational(r)
    return Fraction(int(r.p), int(r.q))


@functools.cache
def _exact_weights(samples: int) -> tuple:
    """``(s_j, e_ij)`` as SymPy rationals."""
    n = samples
    L, A = _basis(n)

    def definite(expr):  # ∫_0^n of a polynomial in u, exactly (as sp.integrate, without its general machinery)
        antiderivative = sp.Poly(expr, _U).integrate()
        return antiderivative.eval(n) - antiderivative.eval(0)

    s = tuple(definite(Aj) for Aj in A)
    e = tuple(tuple(definite(sp.expand((n - _U) * A[i] * L[j])) for j in range(n)) for i in range(n))
    return s, e


def position_algorithm(samples: int) -> PositionAlgorithm:
    """The N-sample position algorithm (module docstring), derived once per N.

    Parameters
    ----------
    samples : int
        N, samples per step, 1 … :data:`MAX_SAMPLES`.

    Returns
    -------
    PositionAlgorithm

    Raises
    ------
    ValueError
        For N outside 1 … :data:`MAX_SAMPLES`.

    References
    ----------
    Savage (1998), part 2 (the scrolling term).

    Examples
    --------
    One sample: the rotation compensation is all there is.

    >>> a = position_algorithm(1)
    >>> a.weights, a.scrolling
    ((Fraction(1, 2),), ((Fraction(0, 1),),))
    >>> [str(w) for w in position_algorithm(2).weights]      # S = h (5/3 b1 + 1/3 b2)
    ['5/3', '1/3']
    """
    n = _check_samples(samples)
    s, e = _exact_weights(n)
    d = tuple(tuple(_fraction(e[i][j] - s[j] / 3) for j in range(n)) for i in range(n))
    return PositionAlgorithm(n, tuple(_fraction(w) for w in s), d)


# --------------------------------------------------------------------------- scrolling error
def _interval(a: int, b: int):
    """``∫_a^b e^{ixσ} dσ`` (closed form)."""
    return (sp.exp(sp.I * X * b) - sp.exp(sp.I * X * a)) / (sp.I * X)


def _conj_interval(a: int, b: int):
    """``conj ∫_a^b e^{ixσ} dσ`` for real x."""
    return (sp.exp(-sp.I * X * b) - sp.exp(-sp.I * X * a)) / (-sp.I * X)


def _closed_form(algorithm: Algorithm) -> sp.Expr:
    """Z(x) built from the integrals of the exponentials (each kernel in closed form, no symbolic integration)."""
    n = algorithm.samples
    a = sp.I * X
    E = sp.exp(-a * n)
    K_r = (sp.Rational(n * n, 2) - (n / a - (1 - E) / a**2)) / a  # ∫₀ᴺ (N − τ)(1 − e^{−ixτ})/(ix) dτ
    sw, e = _exact_weights(n)

    def k(i, j):
        return _interval(i - 1, i) * _conj_interval(j - 1, j)

    K_ralg = sum(e[i][j] * k(i + 1, j + 1) for i in range(n) for j in range(n))
    b = -sp.I * X  # conj of the linear error kernel σ(x) for real x
    sigma_c = -n / b + (sp.exp(b * n) - 1) / b**2 - sum(sw[j] * (sp.exp(b * (j + 1)) - sp.exp(b * j)) / b for j in range(n))
    return (K_r - K_ralg) / n + sigma_c / (sp.I * X * n)


def _pair_moment(k: int, i: int, j: int) -> Fraction:
    """``∫_{i−1}^{i} ∫_{j−1}^{j} (σ − τ)^k dτ dσ`` exactly."""

    def F(s, t):
        return -Fraction(s - t) ** (k + 2) / ((k + 1) * (k + 2))

    return F(i, j) - F(i, j - 1) - F(i - 1, j) + F(i - 1, j - 1)


def _taylor(algorithm: Algorithm, count: int) -> tuple:
    """Taylor coefficients ``z_k`` of Z(x), k = 0 … count − 1, as ``(re, im)`` Fractions.

    Each kernel is ``Σ_k (ix)^k/k! m_k`` with ``m_k`` the integral of ``(σ − τ)^k``
    over its domain, exact rationals: ``K_r``: ``(−1)^k N^(k+3)/((k+1)(k+2)(k+3))``,
    ``k_ij``: the rectangle moments.
    """
    n = algorithm.samples
    sw, e = _exact_weights(n)
    sw = [_fraction(x) for x in sw]
    e = [[_fraction(x) for x in row] for row in e]
    out = []
    for k in range(count):
        sign = -1 if k % 2 else 1
        r = Fraction(sign * n ** (k + 3), (k + 1) * (k + 2) * (k + 3))
        r -= sum((e[i][j] * _pair_moment(k, i + 1, j + 1) for i in range(n) for j in range(n)), Fraction(0))
        # the linear error of the step turned by the attitude at its start: (−1)^(k+1) i^k μ_(k+1)/(k+1)!
        m = k + 1
        mu = Fraction(n ** (m + 2), (m + 1) * (m + 2)) - sum((sw[j] * Fraction((j + 1) ** (m + 1) - j ** (m + 1), m + 1) for j in range(n)), Fraction(0))
        z = (r / math.factorial(k) - sign * mu / math.factorial(m)) / n
        # times i^k: 1, i, −1, −i
        out.append({0: (z, Fraction(0)), 1: (Fraction(0), z), 2: (-z, Fraction(0)), 3: (Fraction(0), -z)}[k % 4])
    return tuple(out)


@dataclass(frozen=True)
class ScrollingKernel:
    """``Z(x)`` of an algorithm: ``e_r = (h²/2) Re((Â × conj B̂) Z(νh))`` (module docstring).

    Attributes
    ----------
    samples : int
        N.
    function : sympy.Expr
        Z in :data:`X`, closed form (complex).
    taylor_real, taylor_imag : tuple of Fraction
        Taylor coefficients of ``Re Z`` and ``Im Z`` at x = 0.
    """

    samples: int
    function: sp.Expr
    taylor_real: tuple
    taylor_imag: tuple

    @property
    def leading(self) -> tuple:
        """``(power, coefficient)`` of the leading term of ``Im Z`` (the in-phase sculling part) at small x."""
        for k, c in enumerate(self.taylor_imag):
            if c != 0:
                return k, c
        return None, Fraction(0)

    def switch(self, *, tolerance: float = 1e-12) -> float:
        """The x below which the Taylor polynomial replaces the closed form (which cancels at small x) [rad].

        Parameters
        ----------
        tolerance : float, keyword-only
            Relative accuracy wanted of the closed form above the switch.

        Returns
        -------
        float
        """
        leads = [next((k for k, c in enumerate(cs) if c != 0), None) for cs in (self.taylor_real, self.taylor_imag)]
        best = 1.5
        for lead, cs in zip(leads, (self.taylor_real, self.taylor_imag)):
            if lead is None:
                continue
            c = abs(float(cs[lead]))
            # terms of the closed form are O(N³/x²)-sized: accuracy about ε N³/(c x^(lead + 2))
            best = min(best, (2.0**-52 * self.samples**3 / (c * tolerance)) ** (1.0 / (lead + 2)))
        return max(best, 0.05)


#: Taylor terms kept: the polynomial serves below x ≈ 1.5 at most, where term 60 is below round-off for N ≤ 8.
TAYLOR_TERMS = 60


def scrolling_kernel(algorithm: Algorithm, *, terms: int = TAYLOR_TERMS) -> ScrollingKernel:
    """``Z(x)`` of the position algorithm of ``algorithm.samples`` samples.

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm; its N is the position algorithm's.
    terms : int, keyword-only
        Taylor coefficients kept [count].

    Returns
    -------
    ScrollingKernel

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm.
    ValueError
        For more than :data:`MAX_SAMPLES` samples.

    References
    ----------
    Savage (1998), part 2 (scrolling); module docstring for the derivation.

    Examples
    --------
    With one sample the scrolling error of in-phase sculling starts at the first power of x:

    >>> from strapdown.derivations.coning.registry import get
    >>> z = scrolling_kernel(get("one-sample"), terms=6)
    >>> z.leading
    (1, Fraction(-1, 12))
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    _check_samples(algorithm.samples)
    coeffs = _taylor(algorithm, int(terms))
    return ScrollingKernel(algorithm.samples, _closed_form(algorithm), tuple(c[0] for c in coeffs), tuple(c[1] for c in coeffs))
