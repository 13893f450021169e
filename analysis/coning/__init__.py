"""Coning and sculling algorithms: evaluation, motions with exact solutions, simulation, drift.

The general tool.  The reproductions of the papers' tables and printed
formulas that validate it live apart, in :mod:`strapdown.analysis.coning.papers`
(they import this library; it never imports them).  The algorithms in a vibration
environment (sensor filters, spectra, mean drift, tuning, sample rate) are the
domain :mod:`strapdown.analysis.vibration`, built on this one.

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
    An algorithm at a glance: terms, window, second-order defect, orders, source.
kernels
    Fused compiled simulator kernels generated from an algorithm's terms (numba),
    and the chunked run of a batch of points through them.
streaming
    Drift fit and error statistics from running sums (memory independent of the run).
long_run
    One run of any length at constant memory: the drift fit, the error
    statistics and the periodic error over windows of the series.
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
order_study
    Observed orders of the drift and of the local error.
drift_crosscheck
    u*/u_a over a grid of steps.
papers
    The papers' tables and printed formulas reproduced (subpackage).
"""
