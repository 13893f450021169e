"""Symbolic series of coning (rotation-vector) and sculling algorithms.

Modules
-------
algorithms
    An algorithm as exact data (:class:`Algorithm`, :class:`Term`) and TOML files.
registry
    The published algorithms, each with its source.
polynomial_fit
    Polynomial-fit algorithms (ω fitted through the N increments).
graded
    Series graded by weight, with parts computed on demand (any ring).
magnus
    The exact rotation-vector increment as a Lie series, weight by weight.
series
    Component polynomials: the algorithm series and the local error to any weight.
drift
    Drift under regular precession to any weight, structure functions, coning
    drift in closed form, optimal coning.
leading_drift
    The leading drift term two ways (mid-step projection, full coefficient); coning limits.
series_summary
    The series of each algorithm in the shape a reader needs (order, weights, factored drift).
printed_checks
    Table 2, eq. (2.4) and the structure functions as printed against the derivations.
formula_one
    Assignments of the Table 1 constants to cross products (formula (1) of Budennyi et al.).
published
    The printed tables and formulas of the coning papers and published algorithm
    figures, with their sources (reference data).
"""
