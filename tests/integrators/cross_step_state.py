"""Savage's 1 + 1 correction with the previous increment kept in the object across steps (not cleared by output)."""

import numpy as np


class OnePlusOne:
    def reset(self):
        self.previous = np.zeros(3)
        self.angle = np.zeros(3)

    def update(self, gyro):
        self.angle = self.angle + gyro + np.cross(self.previous, gyro) / 12.0
        self.previous = gyro

    def output(self):
        out, self.angle = self.angle, np.zeros(3)
        return out


integrate = OnePlusOne
