"""Symbolic series of coning (rotation-vector) and sculling algorithms.

Modules
-------
algorithms
    An algorithm as exact data (:class:`Algorithm`, :class:`Term`) and TOML files.
registry
    The published algorithms, each with its source.
polynomial_fit
    Polynomial-fit algorithms (ω fitted through the N increments).
published
    Published figures of the domain, as reference data with their source.
series
    The exact rotation-vector increment and the algorithm error series.
drift
    Asymptotic drift under regular precession, structure functions, optimal coning.
"""
