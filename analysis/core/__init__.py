"""Shared numerical core: quaternions, dual numbers, validation, units, Monte Carlo, repeated draws, Kalman adapter.

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
memo
    A bounded memo of arrays (least recently used out past a memory bound).
repeated_draws
    Normal draws repeated from the same generator state (common random numbers), served from memory.
kalman
    Thin adapter over filterpy, the only module that imports it.
budget
    Work estimates of the hot paths: a request is refused before it starts if it exceeds a limit.
progress
    Progress bars on stderr, shown only when stderr is a terminal.
roundoff
    The float64 round-off floor of a simulated drift rate.
"""
