"""The coning papers reproduced: their tables and printed formulas, computed by the library.

The general coning library (:mod:`strapdown.analysis.coning`: motions,
simulator, kernels, drift theory, frequency response, computational load)
knows nothing of any paper's table.  The modules here set it to the
conditions of a paper, run it, and put the result beside the printed numbers
of :mod:`strapdown.derivations.coning.published`, which are compared, never
used as inputs.  Imports run one way: these modules use the library, the
library never imports them; the reports and ``strapdown reproduce`` read them.

Modules
-------
budennyi_table3
    Table 3 of Budennyi, Kalinovsky, Panov et al.: simulated drift u* and
    asymptotic drift u_a of the five algorithms.
budennyi_loads
    Their Tables 4–5: the computational load for a drift budget.
formula_one
    Evidence for the reconstruction of their formula (1) and Table 1 (Tables 2–3).
lebedev_panov_table
    The table of Lebedev & Panov (1989), section 6: runs, convergence, asymptotic theory.
lebedev_panov_dot_term
    The dot-product term of their sixth-order algorithm (2.2), as printed.
biquaternion_checks
    Their printed (1.12) and (4.7) against the package.
published_check
    Published figures of the algorithm library (Ignagni, Savage, PSINS):
    coefficients, coning-error coefficients, orders, sculling error.
"""
