"""
Sensor noise against alignment time
===================================

The rms azimuth error of the three alignment methods with white sensor noise
only (angle random walk 0.003 deg/√h, velocity random walk 0.03 m/s/√h,
latitude 45°), against the alignment time, with the analytic method's
first-order theory, which falls as 1/√T
(:func:`~strapdown.analysis.alignment.studies.noise_study`). Error bars: the
95 % intervals of the Monte Carlo.

Report figure ``azimuth-alignment-noise.png`` (two alignment times and 32
trials, as in the quick report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.studies import noise_study
from strapdown.analysis.core.units import DEG_PER_RAD as D

rows = noise_study([30.0, 120.0], n_trials=32, rng=np.random.SeedSequence(1))
names = {"analytic": "analytic (2)+(16)", "inertial": "inertial frame", "kalman": "Kalman"}
for r in rows:
    print(f"T = {r.duration:g} s: theory {r.theory * D:.4f}°, " + ", ".join(f"{names[m]} {v.result.rms * D:.4f}°" for m, v in r.results.items()))

T = np.array([r.duration for r in rows])
fig, ax = plt.subplots(figsize=(5.6, 3.8), layout="constrained")
ax.loglog(T, [r.theory * D for r in rows], "k-", label="analytic theory ∝ 1/√T")
for m, marker in zip(rows[0].results, ("o", "s", "^")):
    y = np.array([r.results[m].result.rms for r in rows]) * D
    lo = np.array([r.results[m].result.rms_ci[0] for r in rows]) * D
    hi = np.array([r.results[m].result.rms_ci[1] for r in rows]) * D
    ax.errorbar(T, y, yerr=[y - lo, hi - y], fmt=marker, ms=4, capsize=2, label=f"{names[m]} (MC)")
ax.set_xlabel("alignment time T [s]")
ax.set_ylabel("rms azimuth error [deg]")
ax.legend(fontsize=7)
plt.show()
