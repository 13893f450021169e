"""Corrected multistage attitude systems (Plotnikov 1999): stages, truth model, control analysis.

Modules
-------
ship_angles
    Yaw, pitch and roll (Krylov angles) and the attitude quaternion, eqs. (1.7), (3.6).
earth
    The spherical rotating Earth: frames, position, gravitation, the specific force of a moving point.
sensors
    Gyro and accelerometer errors and the sampled sensor record.
trajectory
    The section-5 scenario: the true motion, its sampling, the residual check of the truth model.
stage_recursion
    The time-stepping recursion of one stage: compiled (numba) and the plain-Python reference.
stages
    The corrected attitude stages and their cascade, simulated.
composition
    The composite attitude (2.6): the stage-1 corrections cancel; the yaw study.
decay_rates
    Exponential decay rates of the first-variant stage: exact, at rest, guaranteed, simulated.
tilt_loop
    python-control analysis of a stage loop: poles, damping, root loci, responses, Bode data.
response_grid
    The time grid of a pulse response, and its size bounded before the loop is built.
gain_design
    Gains from a requested loop, Schuler tuning, bumpless switch, the Schuler error budget.
readings
    The readings of section 5 the text leaves open, run side by side; the loops of the printed gains.
sensor_statistics
    Monte Carlo over sensor errors: percentiles of the peak errors per stage.
formula_checks
    Printed formulas against their derivations and the exact rotation.
step_convergence
    Second-order convergence of the stage integrator.
"""
