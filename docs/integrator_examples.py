"""Integrators written the ways `strapdown identify` accepts them (see docs/integrators.md).

    strapdown identify --integrator docs/integrator_examples.py:two_sample --samples-per-step 2
    strapdown identify --integrator docs/integrator_examples.py:PerSample --samples-per-step 4
    strapdown identify --integrator docs/integrator_examples.py:per_sample_quaternion --samples-per-step 3
    strapdown identify --integrator docs/integrator_examples.py:savage_with_sculling --samples-per-step 1
"""

import numpy as np

from strapdown.analysis.coning.integrators.interface import Integrator


def two_sample(gyro, samples_per_step):
    """A plain function: one rotation vector per step, ``p1 + p2 + (2/3) p1 × p2``."""
    if samples_per_step != 2:
        raise ValueError(f"two_sample takes 2 samples per step, got {samples_per_step}")
    p = gyro.reshape(-1, 2, 3)
    return p[:, 0] + p[:, 1] + 2.0 / 3.0 * np.cross(p[:, 0], p[:, 1])


class PerSample:
    """A stateful object, one sample per ``update``, as flight code is written (Savage's recursion)."""

    def reset(self):
        self.alpha = np.zeros(3)
        self.beta = np.zeros(3)
        self.last = np.zeros(3)

    def update(self, gyro):
        self.beta = self.beta + 0.5 * np.cross(self.alpha + self.last / 6.0, gyro)
        self.alpha = self.alpha + gyro
        self.last = gyro

    def output(self):
        out = self.alpha + self.beta
        self.alpha = np.zeros(3)
        self.beta = np.zeros(3)
        return out


def _compose(gyro, samples_per_step):
    """Attitude after every step: the exact rotation of each sample composed, no coning term."""
    q = np.array([1.0, 0.0, 0.0, 0.0])
    out = []
    for k, p in enumerate(gyro):
        angle = np.linalg.norm(p)
        half = 0.5 * angle
        s = 0.5 if angle == 0 else np.sin(half) / angle
        dq = np.array([np.cos(half), *(s * p)])
        q = np.array(
            [
                q[0] * dq[0] - q[1] * dq[1] - q[2] * dq[2] - q[3] * dq[3],
                q[0] * dq[1] + q[1] * dq[0] + q[2] * dq[3] - q[3] * dq[2],
                q[0] * dq[2] - q[1] * dq[3] + q[2] * dq[0] + q[3] * dq[1],
                q[0] * dq[3] + q[1] * dq[2] - q[2] * dq[1] + q[3] * dq[0],
            ]
        )
        if (k + 1) % samples_per_step == 0:
            out.append(q)
    return np.array(out)


#: An attitude-output integrator: the attitude quaternion after each step, declared by ``output``.
per_sample_quaternion = Integrator(_compose, output="quaternion", name="quaternion per sample")


def _savage(gyro, samples_per_step, accel):
    """Savage's "1 + 1": coning ``p + (1/12) p_prev × p``, sculling ``b + ½ p × b + (p_prev × b + b_prev × p)/12``."""
    if samples_per_step != 1:
        raise ValueError(f"savage_with_sculling takes 1 sample per step, got {samples_per_step}")
    p_prev = np.vstack([np.zeros((1, 3)), gyro[:-1]])
    b_prev = np.vstack([np.zeros((1, 3)), accel[:-1]])
    rotation = gyro + np.cross(p_prev, gyro) / 12.0
    velocity = accel + 0.5 * np.cross(gyro, accel) + (np.cross(p_prev, accel) + np.cross(b_prev, gyro)) / 12.0
    return rotation, velocity


#: A coning and sculling integrator: takes accelerometer increments, returns (rotation vectors, velocity increments).
savage_with_sculling = Integrator(_savage, velocity=True, name="Savage 1 + 1 with sculling")
