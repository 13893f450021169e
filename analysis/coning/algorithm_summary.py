"""What one needs to know about an algorithm at a glance: terms, window, consistency, order, source.

:func:`summarize` backs ``strapdown algorithms show``; :func:`summaries` backs
``strapdown algorithms list``.  The local-error order comes from the symbolic
series (:func:`strapdown.derivations.coning.series.local_error`), cross-step
algorithms (indices ≤ 0) included.  :func:`cross_step_local_exponent` measures
the same order numerically, on a tumbling motion with no symmetry (the exponent
of the one-step error ``|Δφ_exact − Δφ_alg|`` against the step, whose window
starts ``history`` samples before the step): an independent check of the series.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ...derivations.coning import series as S
from ...derivations.coning.algorithms import Algorithm, second_order_defect
from ..core import quaternion as quat
from .evaluation import increment
from .local_error import TumblingMotion

__all__ = ["AlgorithmSummary", "summarize", "cross_step_local_exponent"]


@dataclass(frozen=True)
class AlgorithmSummary:
    """An algorithm's data and properties, ready to print.

    Attributes
    ----------
    name : str
        Registry (or file) name.
    samples : int
        N, samples per step.
    history : int
        Samples read before the step (0: within the step).
    window : int
        Rows ``p_{1−history} … p_N`` the algorithm takes.
    terms : tuple of (Fraction, str)
        Each nonlinear term: exact coefficient and the product it multiplies.
    second_order_defect : Fraction
        ``Σ c_ij (j − i) − N³/12`` (zero: the second-order condition holds).
    order : int or None
        Order ρ: local error O(h^(ρ+1)); None when it vanishes through h⁷.
    description : str
        One line.
    reference : str
        Source: author, year, equation or table.
    """

    name: str
    samples: int
    history: int
    window: int
    terms: tuple
    second_order_defect: Fraction
    order: int | None
    description: str
    reference: str

    def as_dict(self) -> dict:
        """JSON-able form (fractions as strings such as ``"27/40"``)."""
        return {
            "name": self.name,
            "samples": self.samples,
            "history": self.history,
            "window": self.window,
            "terms": [{"coefficient": str(c), "product": p} for c, p in self.terms],
            "second_order_defect": str(self.second_order_defect),
            "order": self.order,
            "description": self.description,
            "reference": self.reference,
        }


def _product(term) -> str:
    text = str(term)
    return text.split(" ", 1)[1]


def cross_step_local_exponent(algorithm: Algorithm, *, steps=(0.2, 0.1, 0.05), times=(0.3, 1.1, 2.4)) -> float:
    """Mean exponent of the one-step error against H on :class:`TumblingMotion` (works with any history).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    steps : sequence of float, keyword-only
        Steps H [s].
    times : sequence of float, keyword-only
        Middles of the step [s].

    Returns
    -------
    float
        ``d log|δφ| / d log H`` (ρ + 1 for an algorithm of order ρ).
    """
    motion = TumblingMotion()
    n, hist = algorithm.samples, algorithm.history
    exps = []
    for t_mid in times:
        errs = []
        for big_h in steps:
            h = big_h / n
            t0 = t_mid - 0.5 * big_h
            p = motion.increments(t0 - hist * h, h, algorithm.window)
            exact = quat.quat_to_rotvec(quat.multiply(quat.conjugate(motion.attitude(t0)), motion.attitude(t0 + big_h)), validate=False)
            errs.append(np.linalg.norm(exact - increment(algorithm, p)))
        exps.append(np.polyfit(np.log(steps), np.log(errs), 1)[0])
    return float(np.mean(exps))


def summarize(algorithm: Algorithm) -> AlgorithmSummary:
    """Summary of ``algorithm`` (see :class:`AlgorithmSummary`).

    Parameters
    ----------
    algorithm : Algorithm
        Any algorithm (registry, TOML file, constructed).

    Returns
    -------
    AlgorithmSummary

    Raises
    ------
    TypeError
        If ``algorithm`` is not an :class:`Algorithm`.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> s = summarize(get("savage-1+1"))
    >>> (s.samples, s.history, s.order, str(s.second_order_defect))
    (1, 1, 3, '0')
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    order = S.local_error(algorithm).order
    return AlgorithmSummary(
        algorithm.name,
        algorithm.samples,
        algorithm.history,
        algorithm.window,
        tuple((t.coefficient, _product(t)) for t in algorithm.terms),
        second_order_defect(algorithm),
        order,
        algorithm.description,
        algorithm.reference,
    )
