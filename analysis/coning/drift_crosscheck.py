"""The asymptotic drift u_a against the simulated drift u*, over a grid of steps.

For each algorithm and motion, the ratio u*/u_a of the parallel computation
(:func:`strapdown.analysis.coning.simulator.simulate`) to the leading term of
the drift series (:func:`strapdown.analysis.coning.drift_theory.asymptotic_drift`)
tends to 1 as H → 0; the next drift term is two weights higher, so
``|u*/u_a − 1|`` falls by about 4 per halving of H.

References
----------
Budennyi, Kalinovsky, Panov et al. (Part 2), eq. (3), Table 3.
Lebedev & Panov (1989), eq. (5.3).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...derivations.coning.registry import get, names
from ..core.validation import positive
from .drift_theory import asymptotic_drift, asymptotic_order
from .precession import RegularPrecession
from .simulator import simulate

__all__ = ["DriftRatios", "drift_ratios"]


class DriftRatios(NamedTuple):
    """u*/u_a of one algorithm under one motion, against the step.

    Attributes
    ----------
    algorithm : str
        Algorithm name.
    eps : float
        ε of the motion.
    order : int
        ρ of the drift at the motion.
    steps : ndarray
        Steps H [s].
    ratios : ndarray
        u*/u_a at each step.
    """

    algorithm: str
    eps: float
    order: int
    steps: np.ndarray
    ratios: np.ndarray

    @property
    def deviations(self) -> np.ndarray:
        """``|u*/u_a − 1|`` at each step."""
        return np.abs(self.ratios - 1)


def drift_ratios(motions, *, steps=(0.04, 0.02, 0.01, 0.005), duration: float = 8.0, algorithms=None, engine: str = "auto") -> tuple:
    """u*/u_a for every algorithm and motion over a grid of steps.

    Parameters
    ----------
    motions : sequence of RegularPrecession
        The motions (4.1).
    steps : sequence of float, keyword-only
        Steps H [s].
    duration : float, keyword-only
        Length of each simulated run [s].
    algorithms : sequence of str or Algorithm, keyword-only, optional
        Default: the whole registry.
    engine : {"auto", "numpy", "compiled"}, keyword-only
        Simulator engine (:func:`strapdown.analysis.coning.simulator.simulate`);
        ``"numpy"`` compiles nothing, the right choice for a few short runs on a
        cold cache.

    Returns
    -------
    tuple of DriftRatios
        Motion by motion, algorithm by algorithm.

    Raises
    ------
    TypeError
        If a motion is not a :class:`RegularPrecession`.
    """
    duration = positive(duration, "duration")
    big_h = np.array([positive(H, "steps") for H in steps])
    algs = [get(a) if isinstance(a, str) else a for a in (algorithms if algorithms is not None else names())]
    out = []
    for motion in motions:
        if not isinstance(motion, RegularPrecession):
            raise TypeError(f"Expected each of `motions` to be a RegularPrecession, got {type(motion).__name__}")
        for alg in algs:
            ratios = []
            for H in big_h:
                r = simulate(alg, motion, H / alg.samples, duration, engine=engine)
                ua = float(asymptotic_drift(alg, eps=motion.eps, nu=motion.nu, nutation=motion.nutation, step=H))
                ratios.append(float(np.linalg.norm(r.drift)) / ua)
            out.append(DriftRatios(alg.name, motion.eps, int(asymptotic_order(alg, motion.eps, motion.nutation)), big_h, np.array(ratios)))
    return tuple(out)
