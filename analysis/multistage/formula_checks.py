"""Printed formulas of Plotnikov (1999) against their derivations and the exact rotation.

Each check evaluates a formula as printed
(:mod:`strapdown.derivations.multistage.published`) and as derived
(:mod:`strapdown.derivations.multistage.tilt_quaternion`,
:mod:`strapdown.derivations.multistage.schuler`) on random attitudes and
compares both with an independent numerical truth (the quaternion of the
attitude, the exact rotation of the specific force).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import budget
from ..core import quaternion as quat
from ..core.cache import compiled
from ..core.validation import as_int
from .ship_angles import angles_to_quat
from .stages import tilt_quaternion

__all__ = ["FormulaChecks", "check_printed_formulas"]


@dataclass(frozen=True)
class FormulaChecks:
    """Largest deviations from the truth over the random samples.

    Attributes
    ----------
    samples : int
        Attitudes (and small rotations) drawn.
    package_tilt : float
        :func:`strapdown.analysis.multistage.stages.tilt_quaternion` against the true quaternion.
    printed_1_10 : float
        (1.10) as printed against the true quaternion.
    derived_1_10 : float
        (1.10) derived from (1.7)–(1.9) against the true quaternion.
    printed_cos_gamma : float
        ``cos γ = −n₂/h`` (1.9) as printed against cos γ.
    derived_cos_gamma : float
        ``cos γ = n₂/h`` against cos γ.
    printed_w3 : float
        ``W₃⁽¹⁾ = W₃ − gα − W₁β`` (3.7) as printed against the exact rotation [m/s²].
    derived_w3 : float
        The first-order expansion of :mod:`strapdown.derivations.multistage.schuler` against it [m/s²].
    printed_m11 : float
        ``M₁₁ = α − n₃ − n₁β`` (3.7) as printed against the exact ``−W₃⁽¹⁾/g`` [-].
    small_angle : float
        Size of the small rotations of the (3.7) checks [rad] (first-order terms
        are exact to about its square).
    """

    samples: int
    package_tilt: float
    printed_1_10: float
    derived_1_10: float
    printed_cos_gamma: float
    derived_cos_gamma: float
    printed_w3: float
    derived_w3: float
    printed_m11: float
    small_angle: float


def _tilt_build(which):
    def build():
        from ...derivations.multistage import published
        from ...derivations.multistage.tilt_quaternion import derive

        s = published.SYMBOLS
        if which == "printed":
            expr = tuple(published.PRINTED_TILT_QUATERNION_1_10) + (published.PRINTED_COS_GAMMA_1_9,)
        else:
            d = derive()
            expr = tuple(d.components) + (d.cos_gamma,)
        return (s.n1, s.n2, s.n3, s.h, s.n), expr

    return build


def _w3_build(which):
    def build():
        from ...derivations.multistage import published
        from ...derivations.multistage.schuler import SYMBOLS, derive

        p = published.SYMBOLS
        if which == "printed":
            return (p.W1, p.W3, p.g, p.alpha, p.beta), (published.PRINTED_W3_3_7, published.PRINTED_M11_3_7)
        w3 = derive().W1[2]  # g (n₃ − α + n₁β) in the functions of t of the linearisation
        sub = {SYMBOLS.n1: p.W1 / p.g, SYMBOLS.n3: p.W3 / p.g, SYMBOLS.alpha: p.alpha, SYMBOLS.beta: p.beta, SYMBOLS.g: p.g}
        return (p.W1, p.W3, p.g, p.alpha, p.beta), (w3.subs(sub),)

    return build


def check_printed_formulas(*, samples: int = 500, small_angle: float = 1e-3, rng=None, limits: budget.Limits | None = None) -> FormulaChecks:
    """Evaluate (1.9), (1.10) and (3.7) as printed and as derived against the truth.

    Parameters
    ----------
    samples : int
        Number of random attitudes (ψ = 0, ``|θ|``, ``|γ|`` ≤ 0.6 rad) and of small rotations.
    small_angle : float
        Bound of the small error angles (α, β, χ) of the (3.7) check [rad].
    rng : numpy.random.Generator, int, SeedSequence or None
        Source of the samples.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    FormulaChecks

    Raises
    ------
    ValueError
        For ``samples`` below 1 or beyond ``limits``.

    References
    ----------
    Plotnikov (1999), eqs. (1.7)–(1.10), (3.7).
    """
    n_samples = as_int(samples, "samples", minimum=1)
    budget.check(budget.arrays(n_samples, what=f"`samples` = {n_samples:.3g} random attitudes", copies=150.0), limits)
    gen = np.random.default_rng(rng)
    ang = gen.uniform([0.0, -0.6, -0.6], [0.0, 0.6, 0.6], size=(n_samples, 3))
    mu = angles_to_quat(ang[:, 0], ang[:, 1], ang[:, 2])
    n = quat.rotate(quat.conjugate(mu), np.array([0.0, 1.0, 0.0]))  # (1.8) with g = 1
    h = np.hypot(n[:, 1], n[:, 2])
    nn = np.linalg.norm(n, axis=-1)
    args = (n[:, 0], n[:, 1], n[:, 2], h, nn)
    *printed, printed_cos = compiled("multistage:published:tilt-quaternion-1.9-1.10:v1", _tilt_build("printed"))(*args)
    *derived, derived_cos = compiled("multistage:tilt-quaternion:derived-1.9-1.10:v1", _tilt_build("derived"))(*args)
    printed, derived = np.stack(printed, axis=-1), np.stack(derived, axis=-1)
    cos_g = np.cos(ang[:, 2])
    # (3.7): the frame η(1) turned from η by small (α, β, χ) about the axes 1, 2, 3.
    small = gen.uniform(-small_angle, small_angle, size=(n_samples, 3))
    w = np.column_stack([gen.uniform(-20.0, 20.0, n_samples), np.full(n_samples, 9.81), gen.uniform(-20.0, 20.0, n_samples)])
    d = quat.multiply(quat.multiply(quat.rotvec_to_quat(small[:, 0:1] * [1, 0, 0]), quat.rotvec_to_quat(small[:, 1:2] * [0, 1, 0])), quat.rotvec_to_quat(small[:, 2:3] * [0, 0, 1]))
    w1 = quat.rotate(quat.conjugate(d), w)
    cargs = (w[:, 0], w[:, 2], 9.81, small[:, 0], small[:, 1])
    w3_printed, m11_printed = compiled("multistage:published:w3-m11-3.7:v1", _w3_build("printed"))(*cargs)
    (w3_derived,) = compiled("multistage:schuler:w3-first-order:v1", _w3_build("derived"))(*cargs)
    return FormulaChecks(
        samples=n_samples,
        package_tilt=float(np.abs(tilt_quaternion(n) - mu).max()),
        printed_1_10=float(np.abs(printed - mu).max()),
        derived_1_10=float(np.abs(derived - mu).max()),
        printed_cos_gamma=float(np.abs(printed_cos - cos_g).max()),
        derived_cos_gamma=float(np.abs(derived_cos - cos_g).max()),
        printed_w3=float(np.abs(w3_printed - w1[:, 2]).max()),
        derived_w3=float(np.abs(w3_derived - w1[:, 2]).max()),
        printed_m11=float(np.abs(m11_printed - (-w1[:, 2] / 9.81)).max()),
        small_angle=float(small_angle),
    )
