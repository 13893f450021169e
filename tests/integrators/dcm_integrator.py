"""A direction-cosine-matrix integrator: C <- C (I + sin|p|/|p| [p x] + (1 - cos|p|)/|p|^2 [p x]^2) per sample."""

import numpy as np

from strapdown.analysis.coning.integrators.interface import Integrator


def _skew(v):
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _run(gyro, samples_per_step):
    c = np.eye(3)
    out = []
    for k, p in enumerate(gyro):
        a = np.linalg.norm(p)
        s = _skew(p)
        if a > 0:
            c = c @ (np.eye(3) + np.sin(a) / a * s + (1 - np.cos(a)) / a**2 * s @ s)
        if (k + 1) % samples_per_step == 0:
            out.append(c.copy())
    return np.array(out)


integrate = Integrator(_run, output="dcm", name="DCM per sample")
