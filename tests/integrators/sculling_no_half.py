"""Savage's per-sample recursion with sculling, written without the rotation term 1/2 alpha x nu."""

import numpy as np

from strapdown.analysis.coning.integrators.interface import Integrator


def _run(gyro, samples_per_step, accel):
    n = samples_per_step
    rot, vel = [], []
    last_a = np.zeros(3)
    last_b = np.zeros(3)
    for k in range(0, gyro.shape[0], n):
        alpha, beta, nu, gamma = np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)
        for d, db in zip(gyro[k : k + n], accel[k : k + n]):
            read_a = alpha + last_a / 6.0
            read_b = nu + last_b / 6.0
            beta = beta + 0.5 * np.cross(read_a, d)
            gamma = gamma + 0.5 * (np.cross(read_a, db) + np.cross(read_b, d))
            alpha, nu, last_a, last_b = alpha + d, nu + db, d, db
        rot.append(alpha + beta)
        vel.append(nu + gamma)  # the rotation term 0.5 * cross(alpha, nu) is missing
    return np.array(rot), np.array(vel)


integrate = Integrator(_run, velocity=True, name="sculling without the rotation term")
