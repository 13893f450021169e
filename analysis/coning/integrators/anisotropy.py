"""An integrator that treats the axes differently, described as it is: each axis's correction and its coning drift.

A rotation-equivariant integrator corrects every axis alike; flight code that
applies its coning term to one axis only, or drops an increment component,
does not.  From the full tensors of :func:`~.identification.identify`
(``L``, and ``H`` whose entry ``H[(i,u),(j,v)]_w`` is the coefficient of
``p_(i,u) p_(j,v)`` in output w) this module says, for a cone about each
body axis ``e_k``, what the integrator computes.

Classical coning about ``e_k`` (half-cone angle α, rate ω, samples of h) has
increments ``p_j = r_j + a e_k`` with a radial part ``r_j`` of amplitude
``ρ = 2α sin(ωh/2)`` turning by ``ωh`` per sample in the plane of
``(u, v)`` (``(u, v, e_k)`` right-handed) and an axial part ``a = O(α²)``.
To order α² the step error along the cone axis comes from the linear part
acting on the axial increment and from the bilinear part acting on two radial
increments; averaged over the cone's phase, ``H`` contributes along ``e_k``

    ρ² Σ_{i<j} [ c^k_ij sin((j−i)ωh) + s^k_ij cos((j−i)ωh) ] + ρ² Σ_j s^k_jj,

    c^k_ij = ½ (H[(i,u),(j,v)] − H[(i,v),(j,u)])·e_k,
    s^k_ij = ½ (H[(i,u),(j,u)] + H[(i,v),(j,v)])·e_k.

The antisymmetric part ``c^k`` is exactly the coning term of an isotropic
algorithm: the cone about ``e_k`` sees the algorithm ``P + Σ c^k_ij p_i × p_j``
(:attr:`AxisCorrection.algorithm`), whose drift has the closed form of
:func:`strapdown.derivations.coning.drift.coning_drift`.  The symmetric part
adds, along the cone axis ``−e_k`` of the verification's motion (exact minus
integrator), ``4 sin²(ωh/2) Σ s^k_ij cos((j−i)ωh) / (N ωh)`` to the drift
coefficient ``D = u/(α² ω)``.  Both need the linear part to be ``P`` on every
axis (``L_j = I`` for j = 1 … N, zero elsewhere); otherwise the axial
increment itself is mis-counted and the axis has no α² closed form (its drift
is still simulated, :func:`~.verification.coning_drift_check` with ``axis``).

Public API
----------
:data:`AXES`, :class:`AxisCorrection`, :class:`Isotropy`, :func:`axis_corrections`.

References
----------
Lebedev & Panov (1989), eq. (2.1) (classical coning), section 4.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ....derivations.coning.algorithms import Algorithm, Term
from ..drift_theory import coning_drift, coning_drift_function
from .identification import Identification

__all__ = ["AXES", "AxisCorrection", "Isotropy", "axis_corrections"]

#: Names of the body axes.
AXES = ("x", "y", "z")
#: (u, v) completing each axis k to a right-handed triad (u, v, e_k).
_PLANE = {0: (1, 2), 1: (2, 0), 2: (0, 1)}


def _check(check) -> dict:
    points = [{"x": p.x, "closed_form": p.closed_form, "simulated": p.simulated, "relative_difference": p.relative_difference if p.resolved else None} for p in check.points]
    return {"holds": check.holds, "largest_difference": check.largest_difference, "points": points}


def _text(f: Fraction) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


@dataclass(frozen=True)
class AxisCorrection:
    """What the integrator computes under a cone about one body axis.

    Attributes
    ----------
    axis : int
        k: 0, 1, 2 for x, y, z.
    algorithm : Algorithm
        ``P + Σ c^k_ij p_i × p_j``: the isotropic algorithm the cone sees (module docstring).
    symmetric : dict
        ``{(i, j): s^k_ij}`` (i ≤ j), nonzero entries, Fractions.
    linear : dict
        ``{j: L_j[k, k]}``: how the axial increment of each sample is counted (nonzero entries).
    linear_is_sum : bool
        Every ``L_j`` is the identity for j = 1 … N and zero elsewhere (all
        axes): the α² closed form applies.
    """

    axis: int
    algorithm: Algorithm
    symmetric: dict
    linear: dict
    linear_is_sum: bool

    @property
    def name(self) -> str:
        """``"x"``, ``"y"`` or ``"z"``."""
        return AXES[self.axis]

    @property
    def terms(self) -> dict:
        """``{"i,j": "p/q"}`` of the coning term the cone sees."""
        return {f"{i},{j}": _text(c) for (i, j), c in self.algorithm.pairwise.items()}

    def drift_function(self):
        """``D_k(ωh)``, the closed-form drift coefficient (``u = α² ω D_k``), or None without an α² closed form.

        Returns
        -------
        callable or None
            ``D_k(x)`` of a float or an array ``x = ωh`` [rad].
        """
        if not self.linear_is_sum:
            return None
        iso = coning_drift_function(self.algorithm)
        n = self.algorithm.samples
        sym = dict(self.symmetric)

        def d(x):
            total = iso(x)
            if sym:
                extra = sum(float(s) * np.cos((j - i) * x) for (i, j), s in sym.items())
                total = total + 4 * np.sin(x / 2) ** 2 * extra / (n * x)
            return total

        return d

    def drift(self):
        """The closed form of the antisymmetric part as ``derive coning-drift`` gives it (None with a symmetric part or without P).

        Returns
        -------
        strapdown.derivations.coning.drift.ConingDrift or None
        """
        if not self.linear_is_sum or self.symmetric:
            return None
        return coning_drift(self.algorithm)


def axis_corrections(identification: Identification, name: str | None = None) -> tuple:
    """The correction each body axis's cone sees (module docstring).

    Parameters
    ----------
    identification : Identification
        With its tensors.
    name : str, optional
        Stem of the algorithms' names (default: the integrator's).

    Returns
    -------
    tuple of AxisCorrection
        For x, y and z.

    Raises
    ------
    TypeError
        If ``identification`` is not an :class:`~.identification.Identification`.

    References
    ----------
    Lebedev & Panov (1989), eq. (2.1).
    """
    if not isinstance(identification, Identification):
        raise TypeError(f"Expected `identification` to be an Identification, got {type(identification).__name__}")
    ident = identification
    n = ident.samples
    lin = ident.linear_tensor
    expected = {(j, u, u): Fraction(1) for j in range(1, n + 1) for u in range(3)}
    is_sum = lin == expected
    quad = ident.quadratic_tensor
    out = []
    for k in range(3):
        u, v = _PLANE[k]
        anti: dict = {}
        sym: dict = {}
        for (i, a, j, b, w), c in quad.items():
            if w != k:
                continue
            if i == j and a == b and a in (u, v):  # the square of one radial component
                sym[(i, i)] = sym.get((i, i), Fraction(0)) + c / 2
            elif i < j:
                if (a, b) == (u, v):
                    anti[(i, j)] = anti.get((i, j), Fraction(0)) + c / 2
                elif (a, b) == (v, u):
                    anti[(i, j)] = anti.get((i, j), Fraction(0)) - c / 2
                elif a == b and a in (u, v):
                    sym[(i, j)] = sym.get((i, j), Fraction(0)) + c / 2
        terms = tuple(Term(c, key) for key, c in sorted(anti.items()) if c)
        alg = Algorithm(
            f"{name or ident.name} (cone about {AXES[k]})",
            n,
            terms,
            description=f"the coning term that a cone about the {AXES[k]} axis sees in {ident.name!r}",
            reference="identified by strapdown identify (full bilinear form)",
        )
        out.append(AxisCorrection(k, alg, {key: s for key, s in sorted(sym.items()) if s}, {j: c for (j, w, a), c in sorted(lin.items()) if w == k and a == k}, is_sum))
    return tuple(out)


@dataclass(frozen=True)
class Isotropy:
    """Whether the integrator treats every axis alike; if not, what each axis's cone sees, and its drift.

    Attributes
    ----------
    holds : bool
        Every measured entry is isotropic within its uncertainty
        (:attr:`~.identification.Identification.isotropic`).
    largest_departure : float
        The largest departure of an entry from the isotropic pattern [dimensionless].
    corrections : tuple of AxisCorrection
        Per axis x, y, z (empty when the integrator is isotropic).
    checks : tuple
        Per axis, the integrator's simulated drift against the axis's closed
        form (:class:`~.verification.Check`), or None (not verified, or no
        closed form).
    simulated : tuple
        Per axis, the simulated drift coefficients ``D = u/(α² ω)`` at the
        check's ωh (a tuple of (ωh, D) pairs), or None.
    """

    holds: bool
    largest_departure: float
    corrections: tuple = ()
    checks: tuple = ()
    simulated: tuple = ()

    def summary(self) -> str:
        """One line.

        Returns
        -------
        str
        """
        if self.holds:
            return "every axis alike: each tensor entry is the isotropic one within its uncertainty"
        return f"NO: entries depart from the isotropic pattern by up to {self.largest_departure:.3g}; described per axis below"

    def as_dict(self) -> dict:
        """JSON-able verdict.

        Returns
        -------
        dict
        """
        per_axis = {}
        for k, c in enumerate(self.corrections):
            drift = c.drift()
            check = self.checks[k] if k < len(self.checks) else None
            sim = self.simulated[k] if k < len(self.simulated) else None
            per_axis[c.name] = {
                "terms": c.terms,
                "symmetric_terms": {f"{i},{j}": _text(v) for (i, j), v in c.symmetric.items()},
                "axial_linear": {str(j): _text(v) for j, v in c.linear.items()},
                "linear_is_sum": c.linear_is_sum,
                "coning_drift_order": None if drift is None else drift.order,
                "coefficient": None if drift is None else _text(drift.coefficient),
                "closed_form": c.drift_function() is not None,
                "check": None if check is None else _check(check),
                "simulated": None if sim is None else [{"x": x, "simulated": d} for x, d in sim],
            }
        return {"holds": self.holds, "largest_departure": self.largest_departure, "per_axis": per_axis, "summary": self.summary()}
