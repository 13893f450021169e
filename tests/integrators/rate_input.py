"""The two-sample algorithm written on rate samples (mean rate of each sample, 400 Hz)."""

import numpy as np

from strapdown.analysis.coning.integrators.interface import Integrator

H = 1.0 / 400.0


def _run(rates, samples_per_step):
    w = rates.reshape(-1, 2, 3)
    return H * (w[:, 0] + w[:, 1]) + 2.0 / 3.0 * H * H * np.cross(w[:, 0], w[:, 1])


integrate = Integrator(_run, input="rate", sample_interval=H, name="two-sample on rates")
