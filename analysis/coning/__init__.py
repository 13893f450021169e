"""Coning and sculling algorithms: evaluation, motions with exact solutions, simulation, drift.

Modules
-------
evaluation
    One evaluator of an algorithm (as data) on real or dual increments.
precession
    Regular precession and its dual analogue, with exact attitude and velocity
    (Lebedev & Panov 1989, §4).
simulator
    Parallel computation: an algorithm run beside the exact solution.
kernels
    Fused compiled simulator kernels generated from an algorithm's terms (numba).
streaming
    Drift fit and error statistics from running sums (memory independent of the run).
batch
    Batches over arrays of ε, ν, ϑ, h in one call.
local_error
    One-step local error on a motion with no symmetry (tumbling motion).
drift_theory
    Asymptotic drift and accumulated error from the symbolic one-step series.
sampling_design
    Sampling rate for a drift budget and the computational load
    (Budennyi, Kalinovsky, Panov et al., Tables 4–5).
"""
