"""Symbolic series of coning (rotation-vector) and sculling algorithms.

Modules
-------
algorithms
    An algorithm as exact data (:class:`Algorithm`, :class:`Term`) and TOML files.
registry
    The published algorithms, each with its source.
graded
    Series graded by weight, with parts computed on demand (any ring).
magnus
    The exact rotation-vector increment as a Lie series, weight by weight.
series
    Component polynomials: the algorithm series and the local error to any weight.
drift
    Drift under regular precession to any weight, structure functions, coning
    drift in closed form, optimal coning.
"""
