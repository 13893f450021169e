"""Gyrocompass azimuth error on a rocking base (Hrechka & Koroliov), and self-alignment of the whole system.

Tilt channel (the paper's setting)
----------------------------------
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

Whole system
------------
earth
    Earth rate and normal gravity (WGS-84), NED.
tilt_attitude
    The attitude in the paper's angles (ψ, β, γ) and its kinematics.
base_motion
    Rocking in three axes as smooth random functions (sine, sum of sines, narrow-band, white).
imu
    Kinematically consistent gyro and accelerometer increments with lever arm and sensor errors.
preintegration
    Epoch increments (coning and sculling compensated).
alignment_kernels
    Compiled loops of the self-alignment Monte Carlo (sensor increments, preintegration, the filter's epochs).
alignment_estimate
    What an alignment method returns.
analytic_alignment
    Formula (2) with the averaged outputs and the estimates (16), or levelled.
inertial_alignment
    Inertial-frame (coarse) alignment: Wahba's problem on integrated specific force.
fine_alignment
    Kalman fine alignment with NEES and NIS, and the rocking model it assumes.
alignment_theory
    First-order theory of every error term; the Kalman filter's own prediction.
alignment_monte_carlo
    Monte Carlo of each method against its theory.
alignment_design
    The admissible rocking amplitude against frequency for each method.
alignment_studies
    The whole-system studies of the report.
"""
