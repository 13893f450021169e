"""
Algorithms tuned to an environment, across the band
===================================================

The package's qualification example (a MEMS IMU in a rotorcraft bay) and
algorithms tuned to it: the mean drift is affine in an algorithm's lag sums,
the sensors included, so N-sample algorithms can null it
(:func:`~strapdown.analysis.vibration.tuning.tune`; ``strapdown design-coning``).
Through the environment's sensors, a coning line of 1 deg/s rate swept in frequency: the
tuned algorithms (dashed) trade accuracy away from the environment's content
for zero mean drift on it; the dotted line is the sensor part alone.

Report figure ``vibration-tuned-band.png`` (50 frequencies, as in the quick
report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG, RAD_PER_S_TO_DEG_PER_H
from strapdown.analysis.vibration.environment import load_environment
from strapdown.analysis.vibration.examples import QUALIFICATION
from strapdown.analysis.vibration.tuning import drift_across_band, tune
from strapdown.derivations.coning.drift import optimal_coning_algorithm
from strapdown.derivations.coning.registry import get

h = 1e-3
environment = load_environment(QUALIFICATION)
tuned2, tuned3 = tune(environment, 2, h, name="tuned-2"), tune(environment, 3, h, name="tuned-3")
for t in (tuned2, tuned3):
    print(f"{t.algorithm.name}: {', '.join(f'c{k} = {v:.8g}' for k, v in t.coefficients.items())} ({'nulled' if t.nulled else 'minimised'})")

freq = np.geomspace(5.0, 400.0, 50)
compare = [get("two-sample"), tuned2.algorithm, optimal_coning_algorithm(3), tuned3.algorithm]
band = drift_across_band(compare, environment, h, freq, rate_amplitude=1.0 * DEG)
fig, ax = plt.subplots(figsize=(7.2, 4.6), layout="constrained")
for name, v, style in zip(band.names, band.total, ["C0-", "C0--", "C1-", "C1--"]):
    ax.loglog(freq, np.abs(v) * RAD_PER_S_TO_DEG_PER_H, style, label=name)
ax.loglog(freq, np.abs(band.sensor) * RAD_PER_S_TO_DEG_PER_H, "k:", label="sensor part alone")
ax.set_xlabel("frequency of a coning line of 1 deg/s rate [Hz]")
ax.set_ylabel("|drift| [deg/h], qualification sensors")
ax.legend(loc="lower right", fontsize=7)
plt.show()
