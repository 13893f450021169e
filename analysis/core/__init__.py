"""Shared numerical core: quaternions, dual numbers, validation, units, Monte Carlo, verdicts, quadrature, quantiles, Kalman adapter.

Modules
-------
quaternion
    Hamilton products, rotation vectors and the angle maps on ``(..., 4)`` arrays.
dual
    Dual numbers ``x + s x°`` as a numpy array type (forward-mode derivatives).
validation
    The one place where arguments are checked; messages name the argument.
units
    Every unit factor (degrees, deg/h, ...) used at the edges of the package.
montecarlo
    Chunked, reproducible Monte Carlo of a scalar error (``SeedSequence.spawn``).
verdicts
    "yes", "no" or "not resolved: N more trials needed": every verdict a test
    (TOST or one-sided) against a named margin, with its interval.
quadrature
    Integrals of smooth or oscillatory vector functions (composite Gauss–Legendre, halved to a tolerance).
quantiles
    Quantiles of Monte Carlo errors as order statistics, with their 95 % intervals.
kalman
    Thin adapter over filterpy, the only module that imports it.
budget
    Work estimates of the hot paths: a request is refused before it starts if it exceeds a limit.
progress
    Progress bars on stderr, shown only when stderr is a terminal.
roundoff
    The float64 round-off floor of a simulated drift rate.
blocks
    Elementwise array expressions evaluated in cache-sized blocks (the same bits, fewer passes over memory).
"""
