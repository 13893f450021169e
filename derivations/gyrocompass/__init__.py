"""Symbolic derivations for gyrocompass alignment (Hrechka & Koroliov).

Modules
-------
azimuth_error
    Taylor parts (5)–(10), bounds (14)–(15), second-order bias and mean-square error.
"""
