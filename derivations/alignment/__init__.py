"""Symbolic derivations for the self-alignment of the whole system.

Modules
-------
analytic_gains
    Gains of the linearised analytic self-alignment (gyro, accelerometer and rocking terms).
"""
