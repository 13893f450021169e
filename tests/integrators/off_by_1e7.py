"""A coefficient of 2/3 + 1e-7 (a constant typed with too few digits, then 'corrected')."""

import numpy as np

C = 2.0 / 3.0 + 1e-7


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, 2, 3)
    return p[:, 0] + p[:, 1] + C * np.cross(p[:, 0], p[:, 1])
