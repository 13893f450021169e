"""The printed biquaternion formulas of Lebedev & Panov (1989) against the package.

* (1.12), the unit biquaternion Λ + sM of a dual vector Φ = φ + sφ°, and the
  unit condition printed after it, against the dual extension of the
  rotation-vector map (:func:`strapdown.analysis.core.quaternion.rotvec_to_quat`
  on :class:`strapdown.analysis.core.dual.Dual` arguments: forward-mode
  differentiation of the real map);
* (4.7), U_I(t) of the dual regular precession, against ``2 R ∘ Q̄`` of the
  biquaternion (4.4)–(4.5) (:meth:`strapdown.analysis.coning.precession.RegularPrecession.biquaternion`).

The printed formulas are the SymPy expressions of
:mod:`strapdown.derivations.coning.published`, lambdified here.

References
----------
Lebedev & Panov (1989), eqs. (1.3), (1.12), (4.4)–(4.7).
"""

from __future__ import annotations

from functools import cache
from typing import NamedTuple

import numpy as np
import sympy as sp
from sympy.printing.numpy import NumPyPrinter

from ....derivations.coning import published as P
from ...core import quaternion as quat
from ...core.dual import Dual
from ...core.units import rad
from ..precession import RegularPrecession

__all__ = ["PrintedFormulaChecks", "printed_formula_checks", "CHECK_POINTS", "CHECK_TIMES", "CHECK_SPAN", "CHECK_MOTION"]


class PrintedFormulaChecks(NamedTuple):
    """Largest residuals of the printed (1.12) and (4.7) on random points.

    Attributes
    ----------
    unit_condition_plus : float
        max ``|λ·μ|`` (= λ0μ0 + λ1μ1 + λ2μ2 + λ3μ3, the dual part of ``|Λ|² = 1``) of the package's biquaternion.
    unit_condition_printed : float
        max ``|λ0μ0 − λ1μ1 − λ2μ2 − λ3μ3|`` of the same biquaternion: the condition as printed.
    mu0_error : float
        max ``|μ0 printed − μ0|``.
    mu_vec_error_printed : float
        max ``|μ_i printed − μ_i|``.
    mu_vec_error_fixed : float
        max ``|μ_i − μ_i|`` with the sign of the second term of the printed μ_i flipped.
    u_inertial_error : float
        max ``|U_I printed − 2 R ∘ Q̄|`` [m/s], reading the garbled Λ° of (4.7) as ν°.
    points : int
        Random dual vectors on which (1.12) and its condition are checked.
    times : int
        Random times at which (4.7) is checked.
    time_span : float
        The times lie in ``[0, time_span]`` [s].
    motion : RegularPrecession
        The dual regular precession of the (4.7) check.
    """

    unit_condition_plus: float
    unit_condition_printed: float
    mu0_error: float
    mu_vec_error_printed: float
    mu_vec_error_fixed: float
    u_inertial_error: float
    points: int
    times: int
    time_span: float
    motion: RegularPrecession


def _lambdify(args, expr):
    """NumPy function of ``expr`` that evaluates its factors in the order they are written."""
    return sp.lambdify(args, expr, printer=NumPyPrinter({"order": "none"}))


@cache
def _printed_1_12():
    args = P.PHI + P.PHI_DUAL
    return _lambdify(args, P.EQ_1_12.mu[0]), tuple(_lambdify(args, m) for m in P.EQ_1_12.mu[1:])


@cache
def _printed_condition():
    lam, mu = P.CONDITION_SYMBOLS
    return _lambdify(lam + mu, P.EQ_1_12.condition)


@cache
def _printed_4_7():
    t, eps, nu, nut, nu_d, nut_d, lam_d = P.EQ_4_7_SYMBOLS
    read = [sp.sympify(c).subs(lam_d, nu_d) for c in P.EQ_4_7]  # the garbled Λ° read as ν°
    return tuple(_lambdify((t, eps, nu, nut, nu_d, nut_d), c) for c in read)


#: Sizes of the checks of :func:`printed_formula_checks`: dual vectors, times, and their span [s].
CHECK_POINTS, CHECK_TIMES, CHECK_SPAN = 200, 50, 100.0
#: The dual precession of the (4.7) check: variant 2 of Lebedev & Panov (1989), section 6, at ε = 0.5.
CHECK_MOTION = RegularPrecession(0.5, 2 * np.pi, rad(10.0), 10.0, 100.0)


def printed_formula_checks(rng=None) -> PrintedFormulaChecks:
    """Evaluate the printed (1.12), its unit condition and (4.7) against the package.

    (1.12) is checked on :data:`CHECK_POINTS` random dual vectors, (4.7) at
    :data:`CHECK_TIMES` random times in [0, :data:`CHECK_SPAN`] s of the dual
    precession :data:`CHECK_MOTION` (ε = 0.5, ν = 2π s⁻¹, ϑ = 10°, ν° = 10 m/s²,
    ϑ° = 100 m/s: variant 2 of section 6).

    Parameters
    ----------
    rng : numpy.random.Generator, int or None
        Source of the random points (one stream, drawn in that order); None: fresh entropy.

    Returns
    -------
    PrintedFormulaChecks

    References
    ----------
    Lebedev & Panov (1989), eqs. (1.12), (4.7).

    Examples
    --------
    >>> c = printed_formula_checks(0)
    >>> c.unit_condition_plus < 1e-14 < 0.1 < c.unit_condition_printed
    True
    """
    rng = np.random.default_rng(rng)
    phi = rng.normal(size=(CHECK_POINTS, 3))
    phi_d = rng.normal(size=(CHECK_POINTS, 3))
    theta = quat.rotvec_to_quat(Dual(phi, phi_d))
    lam, mu = theta.re, theta.du
    mu0_printed, mui_printed = _printed_1_12()
    args = tuple(phi.T) + tuple(phi_d.T)
    mu_p = np.stack([mu0_printed(*args)] + [f(*args) for f in mui_printed], axis=-1)
    cond_plus = np.abs(np.sum(lam * mu, axis=-1)).max()
    cond_printed = np.abs(_printed_condition()(*lam.T, *mu.T)).max()
    mu_vec_err = np.abs(mu_p[:, 1:] - mu[:, 1:]).max()
    mu0_err = np.abs(mu_p[:, 0] - mu[:, 0]).max()
    # μ_i with the sign of the second term of the printed form flipped
    n = np.linalg.norm(phi, axis=-1)
    pd = np.sum(phi * phi_d, axis=-1)
    mui_fixed = (np.sin(n / 2) / n)[:, None] * phi_d + (n**-2 * (0.5 * np.cos(n / 2) - np.sin(n / 2) / n) * pd)[:, None] * phi
    mu_vec_fixed_err = np.abs(mui_fixed - mu[:, 1:]).max()
    motion = CHECK_MOTION
    t = rng.uniform(0, CHECK_SPAN, CHECK_TIMES)
    p = motion.biquaternion(t)
    u_i = 2 * quat.multiply(p.du, quat.conjugate(p.re))
    args = (motion.eps, motion.nu, motion.nutation, motion.nu_dual, motion.nutation_dual)
    printed = np.stack([np.broadcast_to(f(t, *args), t.shape) for f in _printed_4_7()], axis=-1)
    u_i_err = np.abs(u_i - printed).max()
    return PrintedFormulaChecks(float(cond_plus), float(cond_printed), float(mu0_err), float(mu_vec_err), float(mu_vec_fixed_err), float(u_i_err),
                                CHECK_POINTS, CHECK_TIMES, CHECK_SPAN, motion)  # fmt: skip
