"""Gyrocompass azimuth error on a rocking base: the tilt channel of Hrechka & Koroliov.

The paper's setting: the azimuth from two horizontal gyros by formula (2), the
stable tilts estimated from the accelerometers by the sample means (16), the
rocking in the tilts.  The whole system (rocking in every sensor, sensor errors,
three alignment methods) is :mod:`strapdown.analysis.alignment`, which builds on
this package.

rocking
    Tilt rocking models: Gaussian, sinusoidal, narrow-band; exact statistics of their means.
azimuth
    Azimuth error kernel, bounds (14)–(15), Monte Carlo and second-order theory.
bound_sweep
    Sweeps over latitude and rocking: where bounds (14) and (15) hold.
admissible_rocking
    The admissible rocking amplitude for an azimuth budget (tilt channel).
tilt_estimation
    Stable-tilt estimation: the sample mean (16) against a Kalman filter.
finite_sample
    Finite-sample statistics of (16): effective sample size, variance bias, intervals, averaging needed.
formula_checks
    The printed formulas against the derivation.
error_distribution
    Percentiles of errors made of random-phase sinusoids and Gaussian noise.
studies
    The tilt-channel studies of the report.
"""
