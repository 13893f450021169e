"""Symbolic derivations for gyrocompass alignment (Hrechka & Koroliov).

Modules
-------
azimuth_error
    Taylor parts (5)–(10), bounds (14)–(15), second-order bias and mean-square error.
alignment_error
    Gains of the linearised analytic self-alignment (gyro, accelerometer and rocking terms).
published
    The paper's printed formulas and claims, as reference data.
"""
