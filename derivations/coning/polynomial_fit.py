"""Polynomial-fit coning algorithms: ω fitted by a polynomial through the N increments.

Fit ``ω(t) = Σ_{k<N} a_k t^k`` on the step ``[0, N h]`` so that its integral
over every sample interval is the measured increment ``p_j``, and take the
second-order (Bortz) term of the rotation vector of that rate exactly:

    Δφ ≈ P + ½ ∫₀^H α(t) × ω(t) dt,      α(t) = ∫₀ᵗ ω.

With ``a = M⁻¹ p`` the term is bilinear, ``Σ_{i<j} c_ij p_i × p_j``, with exact
rational ``c_ij``.  N = 2 gives the two-sample ``2/3 p₁ × p₂``; N = 3 gives
``33/80 p₁ × p₃ + 57/80 (p₁ × p₂ + p₂ × p₃)``, Ignagni's (1990) Algorithm D.

References
----------
Jordan (1969), "An accurate strapdown direction cosine algorithm", NASA TN D-5384
(the polynomial-fit construction); Ignagni (1990), Algorithm D.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import sympy as sp

from .algorithms import Algorithm, Term

__all__ = ["polynomial_fit_coefficients", "polynomial_fit_algorithm"]


@cache
def polynomial_fit_coefficients(samples: int) -> dict:
    """Coefficients ``{(i, j): c_ij}`` (i < j) of the N-sample polynomial-fit algorithm.

    Parameters
    ----------
    samples : int
        N ≥ 2 (the fitted polynomial has degree N − 1).

    Returns
    -------
    dict
        ``{(i, j): Fraction}`` with ``Σ c_ij p_i × p_j`` the coning term (h = 1; the
        coefficients are scale-free).

    Raises
    ------
    ValueError
        If ``samples`` < 2.

    Examples
    --------
    >>> polynomial_fit_coefficients(2)
    {(1, 2): Fraction(2, 3)}
    """
    if isinstance(samples, bool) or not isinstance(samples, int) or samples < 2:
        raise ValueError(f"Expected `samples` to be an integer >= 2, got {samples!r}")
    n = samples
    # p_j = Σ_k a_k ((j)^{k+1} − (j−1)^{k+1})/(k+1):  p = M a
    m = sp.Matrix(n, n, lambda j, k: sp.Rational((j + 1) ** (k + 1) - j ** (k + 1), k + 1))
    inv = m.inv()  # a_k = Σ_i inv[k, i] p_i
    # ½ ∫₀^N α × ω dt = Σ_{k<l} C_kl a_k × a_l
    coeff = {}
    for k in range(n):
        for l in range(k + 1, n):
            coeff[(k, l)] = sp.Rational(1, 2) * sp.Integer(n) ** (k + l + 2) / (k + l + 2) * (sp.Rational(1, k + 1) - sp.Rational(1, l + 1))
    out = {}
    for i in range(n):
        for j in range(i + 1, n):
            c = sum((ckl * (inv[k, i] * inv[l, j] - inv[k, j] * inv[l, i]) for (k, l), ckl in coeff.items()), sp.Integer(0))  # exact: a Rational
            if c != 0:
                out[(i + 1, j + 1)] = Fraction(int(c.p), int(c.q))
    return out


def polynomial_fit_algorithm(samples: int, *, name: str | None = None, reference: str = "") -> Algorithm:
    """The N-sample polynomial-fit algorithm as an :class:`Algorithm`.

    Parameters
    ----------
    samples : int
        N ≥ 2.
    name : str, optional
        Registry name (default ``"polynomial-N"``).
    reference : str, optional
        Source text (default: the construction).

    Returns
    -------
    Algorithm
    """
    terms = tuple(Term(c, pair) for pair, c in polynomial_fit_coefficients(samples).items())
    return Algorithm(
        name or f"polynomial-{samples}",
        samples,
        terms,
        f"{samples}-sample polynomial fit: ω of degree {samples - 1} through the increments, exact second-order term",
        reference or "Jordan (1969) construction; coefficients derived (polynomial fit of degree N − 1)",
    )
