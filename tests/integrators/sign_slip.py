"""The two-sample algorithm with the cross product's operands swapped: p2 x p1 instead of p1 x p2."""

import numpy as np


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, 2, 3)
    return p[:, 0] + p[:, 1] + 2.0 / 3.0 * np.cross(p[:, 1], p[:, 0])
