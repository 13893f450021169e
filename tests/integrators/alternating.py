"""A coning coefficient that alternates every step of the record: 2/3 on even steps, 3/5 on odd ones."""

import numpy as np


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, 2, 3)
    c = np.where(np.arange(p.shape[0]) % 2 == 0, 2.0 / 3.0, 3.0 / 5.0)[:, None]
    return p[:, 0] + p[:, 1] + c * np.cross(p[:, 0], p[:, 1])
