"""Corrected multistage attitude systems (Plotnikov 1999): stages, trajectory, control analysis.

Modules
-------
ship_angles
    Yaw, pitch and roll (Krylov angles) and the attitude quaternion, eqs. (1.7), (3.6).
trajectory
    The section-5 scenario: motion, sensor data and sensor errors.
stages
    The corrected attitude stages and their cascade, simulated.
convergence
    Exponential convergence rates of a stage: exact, at rest, guaranteed, simulated.
stage_control
    python-control analysis of a stage loop: poles, damping, root loci, responses.
"""
