"""The two-sample algorithm in single precision (as microcontroller code computes it); the same code in double."""

import numpy as np


def _two_sample(gyro, dtype):
    p = gyro.reshape(-1, 2, 3).astype(dtype)
    return (p[:, 0] + p[:, 1] + dtype(2.0 / 3.0) * np.cross(p[:, 0], p[:, 1])).astype(float)


def integrate(gyro, samples_per_step):
    return _two_sample(gyro, np.float32)


def integrate_float64(gyro, samples_per_step):
    return _two_sample(gyro, np.float64)
