"""The Bortz rotation-vector equation, dphi = dalpha + 1/2 phi x dalpha + (1/12) phi x (phi x dalpha),
integrated sample by sample (Euler, increments as dalpha) over each step."""

import numpy as np


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, samples_per_step, 3)
    phi = np.zeros((p.shape[0], 3))
    for j in range(samples_per_step):
        d = p[:, j]
        phi = phi + d + 0.5 * np.cross(phi, d) + np.cross(phi, np.cross(phi, d)) / 12.0
    return phi
