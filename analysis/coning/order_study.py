"""Observed orders of convergence: of the drift under regular precession, and of the local error.

* :func:`drift_orders`: the constant drift rate of each algorithm against the
  step H on log–log axes; the slope of the least-squares line is the order of
  the drift.
* :func:`local_error_exponents`: the exponent of the one-step error ``|δφ|``
  against H on a motion with no symmetry
  (:class:`strapdown.analysis.coning.local_error.TumblingMotion`): an algorithm
  of order ρ gives ρ + 1.  Regular precession has ``|ω|`` constant, which hides
  errors of dot-product terms; the tumbling motion does not
  (:mod:`strapdown.analysis.coning.papers.lebedev_panov_dot_term` uses it on
  the printed sixth-order algorithm (2.2)).

References
----------
Lebedev & Panov (1989), eq. (2.4).
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

__all__ = ["DriftOrder", "drift_orders", "LocalErrorExponents", "local_error_exponents"]


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


def drift_orders(motion: RegularPrecession, *, steps=(0.16, 0.08, 0.04, 0.02), duration: float = 20.0, algorithms=None, engine: str = "auto") -> tuple:
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
    engine : {"auto", "numpy", "compiled"}, keyword-only
        Simulator engine (:func:`strapdown.analysis.coning.simulator.simulate`);
        ``"numpy"`` compiles nothing, the right choice for a few short runs on a
        cold cache.

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
        drifts = np.array([float(np.linalg.norm(simulate(alg, motion, H / alg.samples, duration, engine=engine).drift, axis=-1)) for H in big_h])
        out.append(DriftOrder(alg.name, big_h, drifts, float(np.polyfit(np.log(big_h), np.log(drifts), 1)[0])))
    return tuple(out)


class LocalErrorExponents(NamedTuple):
    """The observed exponent of the local error of one algorithm at several instants.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    exponents : tuple of float
        Slope of log ``|δφ|`` against log H at each instant (ρ + 1 for accuracy order ρ).
    """

    algorithm: str
    exponents: tuple

    @property
    def local_error_order(self) -> int:
        """The observed local-error order: the mean exponent rounded, ρ + 1 for accuracy order ρ."""
        return round(sum(self.exponents) / len(self.exponents))

    @property
    def accuracy_order(self) -> int:
        """The observed accuracy order ρ: :attr:`local_error_order` − 1 (package docstring, "Orders")."""
        return self.local_error_order - 1


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
