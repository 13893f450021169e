"""Coning and sculling algorithms: evaluation, motions with exact solutions, simulation, drift.

Modules
-------
evaluation
    One evaluator of an algorithm (as data) on real or dual increments.
precession
    Regular precession and its dual analogue, with exact attitude and velocity
    (Lebedev & Panov 1989, §4).
sculling_motion
    Classical sculling (angular and linear vibration) with its exact solution,
    and the rectification error of an algorithm's dual extension.
simulator
    Parallel computation: an algorithm run beside the exact solution
    (cross-step algorithms included).
algorithm_summary
    An algorithm at a glance: terms, window, second-order defect, order, source.
published_check
    Published figures of the algorithm library beside our exact and simulated values.
kernels
    Fused compiled simulator kernels generated from an algorithm's terms (numba).
streaming
    Drift fit and error statistics from running sums (memory independent of the run).
batch
    Batches over arrays of ε, ν, ϑ, h in one call.
local_error
    One-step local error on a motion with no symmetry (tumbling motion).
drift_theory
    Asymptotic drift and accumulated error from the symbolic one-step series
    (with the composition of the steps, summed to a truncation error); coning
    drift in closed form as compiled functions.
exact_drift
    The exact drift under regular precession or classical coning from one step
    in extended precision: the reference for the series, with no series.
coning_validity
    Where the leading coning term is the drift: the next term in α and the
    range of α and ωh where the leading term is within a tolerance of the exact drift.
frequency_response
    Coning drift against ωh for several algorithms, with simulator checks.
computational_load
    Operation counts, the largest step for a drift budget and the computational
    load (Budennyi, Kalinovsky, Panov et al., eq. (6)).
budennyi_table3, budennyi_loads
    Table 3 (drift u*, u_a) and Tables 4–5 (loads) of Budennyi, Kalinovsky, Panov et al.
formula_one
    Evidence for the reconstruction of their formula (1) and Table 1 (Tables 2–3).
lebedev_panov_table
    The table of Lebedev & Panov (1989), section 6: runs, convergence, asymptotic theory.
order_study
    Observed orders of the drift and of the local error.
drift_crosscheck
    u*/u_a over a grid of steps.
biquaternion_checks
    The printed (1.12) and (4.7) of Lebedev & Panov (1989) against the package.
"""
