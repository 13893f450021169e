"""Miller's three-sample algorithm written with one product fewer: the two adjacent pairs through
p2 x (p3 - p1) = p1 x p2 + p2 x p3.  Expanded it is Miller's 27/40 p1 x p2 + 9/20 p1 x p3 + 27/40 p2 x p3."""

import numpy as np


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, 3, 3)
    p1, p2, p3 = p[:, 0], p[:, 1], p[:, 2]
    total = p1 + p2 + p3
    # 27/40 (p1 x p2 + p2 x p3) + 9/20 p1 x p3, written through p2 x (p3 - p1) = p2 x p3 + p1 x p2
    return total + 27.0 / 40.0 * np.cross(p2, p3 - p1) + 9.0 / 20.0 * np.cross(p1, p3)
