"""Symbolic derivations for the gyrocompass tilt channel (Hrechka & Koroliov).

Modules
-------
azimuth_error
    Taylor parts (5)–(10), bounds (14)–(15), second-order bias and mean-square error.
published
    The paper's printed formulas and claims, as reference data.
"""
