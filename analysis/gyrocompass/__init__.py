"""Gyrocompass azimuth error on a rocking base (Hrechka & Koroliov).

Modules
-------
rocking
    Rocking models: Gaussian, sinusoidal, narrow-band; exact statistics of their means.
azimuth
    Azimuth error kernel, bounds (14)–(15), Monte Carlo and second-order theory.
bound_sweep
    Sweeps over latitude and rocking: where bounds (14) and (15) hold.
admissible_rocking
    The admissible rocking amplitude for an azimuth budget.
tilt_estimation
    Stable-tilt estimation: the sample mean (16) against a Kalman filter.
"""
