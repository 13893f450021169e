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
local_error
    One-step local error on a motion with no symmetry (tumbling motion).
drift_theory
    Asymptotic drift and accumulated error from the symbolic one-step series.
sampling_design
    Sampling rate for a drift budget and the computational load
    (Budennyi, Kalinovsky, Panov et al., Tables 4–5).
"""
