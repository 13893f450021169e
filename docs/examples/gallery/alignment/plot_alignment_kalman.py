"""
Consistency of the Kalman fine alignment
========================================

The mean normalised estimation error squared (NEES) and innovation squared
(NIS) of the fine-alignment filter, per degree of freedom, against time, at
rest and under narrow-band rocking with a lever arm (the filter carrying
shaping states for the rocking). A consistent filter stays inside the 95 %
band of the chi-square law of its Monte Carlo
(:func:`~strapdown.analysis.alignment.monte_carlo.alignment_monte_carlo`,
``method="kalman"``).

Report figure ``azimuth-alignment-kalman.png`` (32 trials, as in the quick
report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.base_motion import NarrowbandMotion
from strapdown.analysis.alignment.imu import Scenario
from strapdown.analysis.alignment.monte_carlo import alignment_monte_carlo
from strapdown.analysis.alignment.studies import NAVIGATION_GRADE, kalman_options
from strapdown.analysis.core.units import rad

still = Scenario(rad(60.0), heading=rad(30.0), sample_rate=10.0, duration=120.0)
rocking = Scenario(rad(60.0), heading=rad(30.0), motion=NarrowbandMotion(rad(np.array([0.5, 1.0, 1.0])), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=120.0)
seeds = np.random.SeedSequence(1).spawn(2)
cases = []
for (label, scenario), seed in zip((("at rest", still), ("narrow-band rocking, lever arm, shaping states", rocking)), seeds):
    mc = alignment_monte_carlo(scenario, NAVIGATION_GRADE, method="kalman", n_trials=32, rng=seed, options=kalman_options(scenario, NAVIGATION_GRADE))
    k = mc.kalman
    inside = np.mean((k.nees >= k.nees_band[0]) & (k.nees <= k.nees_band[1]))
    print(f"{label}: NEES inside its band at {inside:.0%} of the epochs shown")
    cases.append((label, mc))

fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.6), layout="constrained")
for (label, mc), colour in zip(cases, ("C0", "C1")):
    k = mc.kalman
    a1.semilogx(k.times, k.nees / k.dim, "-o", color=colour, ms=3, label=label)
    a1.axhspan(k.nees_band[0] / k.dim, k.nees_band[1] / k.dim, color=colour, alpha=0.15)
    a2.semilogx(k.times, k.nis / k.meas_dim, "-o", color=colour, ms=3, label=label)
    a2.axhspan(k.nis_band[0] / k.meas_dim, k.nis_band[1] / k.meas_dim, color=colour, alpha=0.15)
a1.set_ylabel("mean NEES / dof")
a2.set_ylabel("mean NIS / dof")
for a in (a1, a2):
    a.set_xlabel("time [s]")
    a.legend(fontsize=7)
plt.show()
