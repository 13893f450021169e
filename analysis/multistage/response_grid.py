"""The time grid of a tilt-loop pulse response: fine enough for the peak, with the pulse's end on a sample.

The response of a linear loop to a piecewise-constant input is exact on any
uniform grid (zero-order hold), so the grid only has to resolve the peak: a
step of at most a twentieth of the pulse, a fifth of the fastest time
constant and a two-thousandth of the horizon, but no finer than ``horizon /
max_points``; the step is then shortened so that a whole number of steps
spans the pulse.  :func:`pulse_grid` gives that grid;
:func:`largest_sample_count` bounds its size from the pulse and the horizon
alone, whatever the loop, so that a request can be refused before the loop is
even built (numpy only: no python-control).

Public API: :class:`PulseGrid`, :func:`pulse_grid`, :func:`largest_sample_count`,
:data:`MAX_POINTS`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

__all__ = ["MAX_POINTS", "PulseGrid", "pulse_grid", "largest_sample_count"]

#: Number of samples a pulse response aims at (more only for a pulse short against the horizon).
MAX_POINTS = 20_000


class PulseGrid(NamedTuple):
    """A uniform grid ``t_k = k · step``, k = 0 … samples − 1.

    Attributes
    ----------
    step : float
        Time step [s].
    hold : int
        Steps that span the pulse (its end is sample ``hold``) [count].
    samples : float
        Samples of the grid up to the horizon [count] (a float: it may be huge).
    """

    step: float
    hold: int
    samples: float


def pulse_grid(duration: float, end: float, fastest: float, max_points: int = MAX_POINTS) -> PulseGrid:
    """The grid of a pulse of ``duration`` seconds seen until ``end``.

    Parameters
    ----------
    duration : float
        Length T of the pulse [s], > 0 (validated by the caller).
    end : float
        Horizon [s], >= ``duration``.
    fastest : float
        Largest pole magnitude of the loop [1/s] (0 for none).
    max_points : int
        Number of samples the grid aims at [count].

    Returns
    -------
    PulseGrid

    Examples
    --------
    >>> g = pulse_grid(20.0, 10_147.0, 0.0012)
    >>> g.hold, g.samples
    (20, 10148.0)
    """
    dt = min(duration / 20.0, 0.2 / fastest if fastest > 0 else math.inf, end / 2000.0)
    dt = max(dt, end / max_points)
    hold = max(1, math.ceil(duration / dt))
    dt = duration / hold
    return PulseGrid(dt, hold, math.ceil(end / dt) + 1.0)


def largest_sample_count(duration: float, end: float, max_points: int = MAX_POINTS) -> float:
    """An upper bound of ``pulse_grid(duration, end, fastest, max_points).samples`` for every loop.

    The step before shortening is at least ``end / max_points``; shortening
    at most halves it when the pulse is longer than that step, and otherwise
    makes it the pulse itself.

    Parameters
    ----------
    duration : float
        Length T of the pulse [s], > 0.
    end : float
        Horizon [s], >= ``duration``.
    max_points : int
        Number of samples the grid aims at [count].

    Returns
    -------
    float
        Samples [count].

    Examples
    --------
    >>> largest_sample_count(20.0, 3e9)
    150000001.0
    """
    return max(2.0 * max_points, math.ceil(end / duration)) + 1.0
