"""Convergence of the stage integrator: halving the step divides the error by 4 (second order).

The splitting recursion of :mod:`strapdown.analysis.multistage.stage_recursion` is
second order in the step h.  :func:`step_convergence` runs the cascade on the
same scenario with a sequence of steps and measures the difference of each run
from the finest one at the common grid points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import montecarlo
from ..core.validation import positive
from .stages import plotnikov_1999_stages, simulate
from .trajectory import Scenario

__all__ = ["ConvergenceStudy", "step_convergence"]


@dataclass(frozen=True)
class ConvergenceStudy:
    """Result of :func:`step_convergence`.

    Attributes
    ----------
    steps : tuple of float
        Steps [s], coarse to fine; the last is the reference.
    composite_difference : tuple of float
        Largest ``|Δν⁺|`` (all stages) of each coarser run from the reference.
    angle_difference : tuple of float
        Largest ``|Δ(angle error)|`` [rad] of each coarser run from the reference.
    ratios : tuple of float
        ``composite_difference[i] / composite_difference[i + 1]`` (about 4 for second order).
    """

    steps: tuple
    composite_difference: tuple
    angle_difference: tuple
    ratios: tuple


def step_convergence(scenario: Scenario | None = None, steps=(0.08, 0.04, 0.02, 0.01), *, stages=None, rng=None) -> ConvergenceStudy:
    """Differences of runs with decreasing steps from the finest run.

    Parameters
    ----------
    scenario : Scenario, optional
        Default: the first 1250 s of section 5 (rocking and acceleration included).
    steps : sequence of float
        Steps [s], decreasing, each an integer multiple of the last.
    stages : sequence of Stage, optional
        Default :func:`strapdown.analysis.multistage.stages.plotnikov_1999_stages`.
    rng : numpy.random.Generator, int, SeedSequence or None
        Sensor-noise source (the same for every run).

    Returns
    -------
    ConvergenceStudy

    Raises
    ------
    ValueError
        If the steps do not decrease or are not multiples of the finest.
    """
    sc = Scenario(duration=1250.0) if scenario is None else scenario
    steps = tuple(positive(h, "steps") for h in steps)
    if len(steps) < 3 or any(b >= a for a, b in zip(steps, steps[1:])):
        raise ValueError(f"Expected at least three decreasing `steps`, got {steps}")
    strides = [h / steps[-1] for h in steps]
    if any(abs(s - round(s)) > 1e-9 for s in strides):
        raise ValueError(f"Expected every step to be a multiple of the finest {steps[-1]:g} s, got {steps}")
    stages = plotnikov_1999_stages(sc.gravity, sc.earth_radius) if stages is None else stages
    root = montecarlo.root_seed_sequence(rng)
    runs = [simulate(sc, stages, step=h, rng=root) for h in steps]
    ref = runs[-1]
    dq, de = [], []
    for s, run in zip(strides[:-1], runs[:-1]):
        k = int(round(s))
        dq.append(float(np.abs(run.composite - ref.composite[:, ::k]).max()))
        de.append(float(np.abs(run.errors - ref.errors[:, ::k]).max()))
    ratios = tuple(a / b for a, b in zip(dq, dq[1:]))
    return ConvergenceStudy(steps, tuple(dq), tuple(de), ratios)
