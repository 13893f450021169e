"""The two-sample algorithm on increments clipped at 0.01 rad per component (a sensor's range)."""

import numpy as np


def integrate(gyro, samples_per_step):
    p = np.clip(gyro, -0.01, 0.01).reshape(-1, 2, 3)
    return p[:, 0] + p[:, 1] + 2.0 / 3.0 * np.cross(p[:, 0], p[:, 1])
