"""The two-sample coning term applied to the z component only (an attitude task that corrects yaw alone)."""


def integrate(gyro, samples_per_step):
    p = gyro.reshape(-1, 2, 3)
    out = p[:, 0] + p[:, 1]
    out[:, 2] += 2.0 / 3.0 * (p[:, 0, 0] * p[:, 1, 1] - p[:, 0, 1] * p[:, 1, 0])
    return out
