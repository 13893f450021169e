"""ArduPilot's delta-angle accumulator (AP_InertialSensor backend) written again from its description.

One accumulator holds the angle and its coning corrections together: per sample,
``delta_coning = 1/2 (acc + last_delta / 6) x delta``, ``acc += delta + delta_coning``,
``last_delta = delta``; the attitude task reads ``acc`` and clears it; ``last_delta``
carries over.  The correction reads the accumulator as it stands, corrections included:
the same bilinear part as Savage's recursion, plus terms of degree three.
"""

import numpy as np


class Accumulator:
    def reset(self):
        self.acc = np.zeros(3)
        self.last = np.zeros(3)

    def update(self, delta):
        coning = 0.5 * np.cross(self.acc + self.last / 6.0, delta)
        self.acc = self.acc + delta + coning
        self.last = delta

    def output(self):
        out, self.acc = self.acc, np.zeros(3)
        return out


integrate = Accumulator
