"""An integrator that imports a module from its own directory (the two-sample algorithm)."""

import numpy as np
from sibling_coefficients import TWO_SAMPLE


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, 2, 3)
    return p[:, 0] + p[:, 1] + TWO_SAMPLE * np.cross(p[:, 0], p[:, 1])
