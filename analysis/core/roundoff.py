"""Round-off floor of a simulated drift rate in float64.

A parallel computation compares an algorithm's attitude with the exact
attitude of a closed-form motion.  Both are computed in float64 from angles
that grow linearly in time (νt, μt), so both carry round-off that a
least-squares slope reads as a drift of about ``ε_mach · (|ν| + |μ|)``
(``ε_mach = 2.2·10⁻¹⁶``), whatever the sample interval and the length of the
run.  A simulated drift below that floor is round-off, not the algorithm's
drift: for a sixth-order algorithm under 10 Hz coning the truncation drift
falls below it once h is below about 2.5·10⁻⁴ s.

The floor was measured (``benchmarks/bench_budget.py`` prints the table) with
registry algorithms at sample intervals where their truncation drift is many
orders of magnitude smaller: the simulated drift settles at 0.07–0.9 times
``ε_mach (|ν| + |μ|)`` for coning and for ε = 0.5, from 2 500 to 5·10⁶ steps,
independent of h and of the duration.  :func:`drift_floor` returns the bound
with factor 1.
"""

from __future__ import annotations

import numpy as np

from .validation import as_float

__all__ = ["EPSILON", "drift_floor"]

#: Unit round-off of float64 (``numpy.finfo(float).eps``).
EPSILON = float(np.finfo(float).eps)


def drift_floor(spin_rate, precession_rate) -> float:
    """Round-off floor of a drift rate simulated in float64 [rad/s].

    Parameters
    ----------
    spin_rate : float
        Spin rate ν of the motion [rad/s].
    precession_rate : float
        Precession rate μ = εν of the motion [rad/s].

    Returns
    -------
    float
        ``ε_mach (|ν| + |μ|)`` [rad/s]: a simulated drift below it is not resolved.

    Examples
    --------
    >>> from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H
    >>> f"{drift_floor(2 * np.pi * 10, -2 * np.pi * 10) * RAD_PER_S_TO_DEG_PER_H:.3g} deg/h"  # 10 Hz coning
    '5.76e-09 deg/h'
    """
    nu = as_float(spin_rate, "spin_rate")
    mu = as_float(precession_rate, "precession_rate")
    return EPSILON * (abs(nu) + abs(mu))
