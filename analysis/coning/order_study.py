"""Observed orders of convergence: of the drift under regular precession, and of the local error.

* :func:`drift_orders`: the constant drift rate of each algorithm against the
  step H on log–log axes; the slope of the least-squares line is the order of
  the drift.
* :func:`local_error_exponents`: the exponent of the one-step error ``|δφ|``
  against H on a motion with no symmetry
  (:class:`strapdown.analysis.coning.local_error.TumblingMotion`): an algorithm
  of order ρ gives ρ + 1.  Regular precession has ``|ω|`` constant, which hides
  errors of dot-product terms; :func:`dot_term_study` uses the tumbling motion
  to test the dot-product term of the sixth-order algorithm (2.2).

References
----------
Lebedev & Panov (1989), eqs. (2.2), (2.4).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ...derivations.coning.registry import get, names
from ..core.validation import positive
from .local_error import TumblingMotion, local_error
from .precession import RegularPrecession
from .simulator import simulate

__all__ = ["DriftOrder", "drift_orders", "LocalErrorExponents", "local_error_exponents", "DotTermStudy", "dot_term_study"]


class DriftOrder(NamedTuple):
    """The drift of one algorithm against the step.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    steps : ndarray
        Steps H [s].
    drifts : ndarray
        Constant drift rate at each step [rad/s].
    slope : float
        Slope of the least-squares line of log drift against log H: the observed order.
    """

    algorithm: str
    steps: np.ndarray
    drifts: np.ndarray
    slope: float


def drift_orders(motion: RegularPrecession, *, steps=(0.16, 0.08, 0.04, 0.02), duration: float = 20.0, algorithms=None) -> tuple:
    """Drift rate against the step for each algorithm under ``motion``, with the fitted order.

    Parameters
    ----------
    motion : RegularPrecession
        The motion (4.1).
    steps : sequence of float, keyword-only
        Steps H [s] (h = H / N for each algorithm).
    duration : float, keyword-only
        Length of each run [s].
    algorithms : sequence of str or Algorithm, keyword-only, optional
        Default: the whole registry.

    Returns
    -------
    tuple of DriftOrder
        In the order of ``algorithms``.

    Raises
    ------
    TypeError
        If ``motion`` is not a :class:`RegularPrecession`.
    """
    if not isinstance(motion, RegularPrecession):
        raise TypeError(f"Expected `motion` to be a RegularPrecession, got {type(motion).__name__}")
    duration = positive(duration, "duration")
    big_h = np.array([positive(H, "steps") for H in steps])
    out = []
    for alg in (get(a) if isinstance(a, str) else a for a in (algorithms if algorithms is not None else names())):
        drifts = np.array([float(np.linalg.norm(simulate(alg, motion, H / alg.samples, duration).drift, axis=-1)) for H in big_h])
        out.append(DriftOrder(alg.name, big_h, drifts, float(np.polyfit(np.log(big_h), np.log(drifts), 1)[0])))
    return tuple(out)


class LocalErrorExponents(NamedTuple):
    """The observed exponent of the local error of one algorithm at several instants.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    exponents : tuple of float
        Slope of log ``|δφ|`` against log H at each instant (ρ + 1 for order ρ).
    """

    algorithm: str
    exponents: tuple

    @property
    def local_order(self) -> int:
        """The mean exponent rounded: ρ + 1 for an algorithm of order ρ."""
        return round(sum(self.exponents) / len(self.exponents))

    @property
    def order(self) -> int:
        """The (global) order ρ: :attr:`local_order` − 1."""
        return self.local_order - 1


class DotTermStudy(NamedTuple):
    """Local-error exponents of (2.2) at orders 2, 4, 6, and of order 6 without its dot-product term.

    Attributes
    ----------
    rows : tuple of LocalErrorExponents
        ``lebedev-panov-2``, ``-4``, ``-6`` and ``lebedev-panov-6 without (p2·p3) term``.
    """

    rows: tuple

    @property
    def printed(self) -> LocalErrorExponents:
        """(2.2) of order 6 as printed, with its dot-product term."""
        return self.rows[2]

    @property
    def without_dot(self) -> LocalErrorExponents:
        """(2.2) of order 6 without the ``(p2·p3)`` part of its last term."""
        return self.rows[3]

    @property
    def printed_is_sixth_order(self) -> bool:
        """True when the printed form has a local error O(H⁷): the order the paper states."""
        return self.printed.order == 6


def local_error_exponents(algorithm: Algorithm, *, motion: TumblingMotion | None = None, times=(0.3, 1.1, 2.4), steps=(0.2, 0.1, 0.05)) -> LocalErrorExponents:
    """Exponent of the one-step error ``|δφ|`` against H, at each of ``times``.

    Parameters
    ----------
    algorithm : Algorithm
        Rotation-vector algorithm.
    motion : TumblingMotion, keyword-only, optional
        Default ``TumblingMotion()``.
    times : sequence of float, keyword-only
        Middles of the steps [s].
    steps : sequence of float, keyword-only
        Steps H [s].

    Returns
    -------
    LocalErrorExponents
    """
    motion = motion or TumblingMotion()
    big_h = np.array(steps, dtype=float)
    exps = []
    for t in times:
        e = np.array([np.linalg.norm(local_error(algorithm, motion, t, H)) for H in big_h])
        exps.append(float(np.polyfit(np.log(big_h), np.log(e), 1)[0]))
    return LocalErrorExponents(algorithm.name, tuple(exps))


def dot_term_study(**kwargs) -> DotTermStudy:
    """Local-error exponents of (2.2) at orders 2, 4, 6, and of order 6 without its dot-product term.

    The last term of (2.2), ``−64/45 (1 − p2·p3) p2 × p3``, carries a dot
    product; removing its ``(p2·p3)`` part tests whether the printed form is
    the sixth-order one.

    Parameters
    ----------
    **kwargs
        Passed to :func:`local_error_exponents` (``motion``, ``times``, ``steps``).

    Returns
    -------
    DotTermStudy

    References
    ----------
    Lebedev & Panov (1989), eq. (2.2).
    """
    printed = get("lebedev-panov-6")
    no_dot = Algorithm("lebedev-panov-6 without (p2·p3) term", 4, tuple(t for t in printed.terms if not t.dots))
    return DotTermStudy(tuple(local_error_exponents(alg, **kwargs) for alg in (get("lebedev-panov-2"), get("lebedev-panov-4"), printed, no_dot)))
