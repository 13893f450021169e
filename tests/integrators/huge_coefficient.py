"""A coning coefficient of 10^6 (a units slip: microradians taken for radians)."""

import numpy as np


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, 2, 3)
    return p[:, 0] + p[:, 1] + 1e6 * np.cross(p[:, 0], p[:, 1])
