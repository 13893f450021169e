"""What one needs to know about an algorithm at a glance: terms, window, consistency, orders, source.

:func:`summarize` backs ``strapdown algorithms show``; :func:`summaries` backs
``strapdown algorithms list``.  The accuracy order ρ (local error O(h^(ρ+1)),
local-error order ρ + 1) comes from the symbolic series
(:func:`strapdown.derivations.coning.series.local_error`), the coning-drift order
m (drift ∝ α² ω (ωh)^m under classical coning) from the closed form
(:func:`strapdown.derivations.coning.drift.coning_drift`), cross-step algorithms
(indices ≤ 0) included.  :func:`cross_step_local_exponent` measures
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
from ..core.cache import derived
from .drift_theory import algorithm_key, coning_drift
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
    accuracy_order : int or None
        ρ: local error O(h^(ρ+1)) in a general motion; None when it vanishes through h⁷.
    coning_drift_order : int or None
        m: under classical coning the drift is ``c α² ω (ωh)^m``; None if the
        closed form finds no finite order.
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
    accuracy_order: int | None
    coning_drift_order: int | None
    description: str
    reference: str

    @property
    def local_error_order(self) -> int | None:
        """ρ + 1: the power of h of the leading local error."""
        return None if self.accuracy_order is None else self.accuracy_order + 1

    def as_dict(self) -> dict:
        """JSON-able form (fractions as strings such as ``"27/40"``)."""
        return {
            "name": self.name,
            "samples": self.samples,
            "history": self.history,
            "window": self.window,
            "terms": [{"coefficient": str(c), "product": p} for c, p in self.terms],
            "second_order_defect": str(self.second_order_defect),
            "accuracy_order": self.accuracy_order,
            "local_error_order": self.local_error_order,
            "coning_drift_order": self.coning_drift_order,
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
        ``d log|δφ| / d log H``: the local-error order ρ + 1 of an algorithm of accuracy order ρ.
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
    >>> (s.samples, s.history, s.accuracy_order, s.coning_drift_order, str(s.second_order_defect))
    (1, 1, 3, 4, '0')
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    order = derived(f"coning:local-error-order:v1:{algorithm_key(algorithm)}", lambda: S.local_error(algorithm).order)
    try:
        coning = coning_drift(algorithm).order
    except ValueError:  # no finite order through (ωh)^60
        coning = None
    return AlgorithmSummary(
        algorithm.name,
        algorithm.samples,
        algorithm.history,
        algorithm.window,
        tuple((t.coefficient, _product(t)) for t in algorithm.terms),
        second_order_defect(algorithm),
        order,
        coning,
        algorithm.description,
        algorithm.reference,
    )
