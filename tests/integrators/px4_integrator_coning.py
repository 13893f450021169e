"""PX4's IntegratorConing (vehicle_imu, 2021-2023) written again from its description, in single precision.

What PX4's class does, per gyro sample (a rate ``val`` [rad/s] and its interval ``dt``):
the increment is the trapezoid ``delta_alpha = (val + last_val) dt / 2``; the coning
term is ``beta += 1/2 (last_alpha + last_delta_alpha / 6) x delta_alpha``, where
``last_alpha`` is the accumulated angle *before* the previous sample was added; then
``last_delta_alpha = delta_alpha``, ``last_alpha = alpha``, ``alpha += delta_alpha``.
Reading the integral returns ``alpha + beta`` and clears ``alpha``, ``beta`` and
``last_alpha``; ``last_val`` and ``last_delta_alpha`` carry over.  All in float32.
"""

import numpy as np

DT = 0.001
F = np.float32


class IntegratorConing:
    def reset(self):
        self.alpha = np.zeros(3, F)
        self.beta = np.zeros(3, F)
        self.last_alpha = np.zeros(3, F)
        self.last_delta_alpha = np.zeros(3, F)
        self.last_val = np.zeros(3, F)

    def update(self, rate):
        val = rate.astype(F)
        delta_alpha = (val + self.last_val) * F(DT) * F(0.5)
        self.last_val = val
        self.beta = self.beta + np.cross(self.last_alpha + self.last_delta_alpha * F(1.0 / 6.0), delta_alpha) * F(0.5)
        self.last_delta_alpha = delta_alpha
        self.last_alpha = self.alpha
        self.alpha = self.alpha + delta_alpha

    def output(self):
        integral = (self.alpha + self.beta).astype(float)
        self.alpha = np.zeros(3, F)
        self.beta = np.zeros(3, F)
        self.last_alpha = np.zeros(3, F)
        return integral


# the gyro gives rates: the adapter hands it the mean rate of each sample at DT
from strapdown.analysis.coning.integrators.adapters import stateful  # noqa: E402

integrate = stateful(IntegratorConing, input="rate", sample_interval=DT, name="PX4 IntegratorConing (float32)")
