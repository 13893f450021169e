"""A quaternion integrator with the two-sample coning correction applied to each step's rotation vector."""

import numpy as np

from strapdown.analysis.coning.integrators.interface import Integrator


def _run(gyro, samples_per_step):
    p = gyro.reshape(-1, 2, 3)
    phi = p[:, 0] + p[:, 1] + 2.0 / 3.0 * np.cross(p[:, 0], p[:, 1])
    q = np.array([1.0, 0.0, 0.0, 0.0])
    out = []
    for v in phi:
        a = np.linalg.norm(v)
        dq = np.concatenate([[np.cos(a / 2)], (np.sin(a / 2) / a if a > 0 else 0.5) * v])
        w0, x0, y0, z0 = q
        w1, x1, y1, z1 = dq
        q = np.array(
            [
                w0 * w1 - x0 * x1 - y0 * y1 - z0 * z1,
                w0 * x1 + x0 * w1 + y0 * z1 - z0 * y1,
                w0 * y1 - x0 * z1 + y0 * w1 + z0 * x1,
                w0 * z1 + x0 * y1 - y0 * x1 + z0 * w1,
            ]
        )
        out.append(q)
    return np.array(out)


integrate = Integrator(_run, output="quaternion", name="quaternion, two-sample correction")
