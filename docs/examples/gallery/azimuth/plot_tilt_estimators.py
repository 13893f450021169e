"""
Estimating the stable tilts: sample means against a Kalman filter
=================================================================

The tilts β0, γ0 that enter the azimuth formula are estimated from the
rocking accelerometers, by the sample means (16) of the paper or by a Kalman
filter that models the rocking
(:func:`~strapdown.analysis.gyrocompass.tilt_estimation.compare_estimators`).
Left: the rms alignment error against the averaging time for three rocking
models (latitude 60°, σ = 1° on both axes, 10 Hz). Right: the mean NEES of
the filter's β̂0, inside the 95 % band when the filter is consistent.

Report figure ``azimuth-estimators.png`` (150 trials, as in the quick report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import rad
from strapdown.analysis.gyrocompass.rocking import GaussianRocking, NarrowbandRocking, SineRocking
from strapdown.analysis.gyrocompass.tilt_estimation import compare_estimators

times = np.array([0.1, 0.5, 1.0, 2.0, 4.0, 8.0, 15.0, 30.0, 60.0, 120.0])
s = rad(1.0)
models = {"sine (period 8 s)": SineRocking(s, s, 8.0, 8.0), "narrowband (8 s, ζ=0.1)": NarrowbandRocking(s, s, 8.0, 0.1), "normal (white)": GaussianRocking(s, s)}
seeds = np.random.SeedSequence(1).spawn(len(models))
results = {name: compare_estimators(rad(60.0), m, dt=0.1, averaging_times=times, n_trials=150, rng=np.random.default_rng(seed)) for (name, m), seed in zip(models.items(), seeds)}

fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
for (name, c), colour in zip(results.items(), ("C0", "C1", "C2")):
    ax.loglog(c.times, c.rms_mean * D, "-o", color=colour, ms=3, label=f"sample mean (16), {name}")
    ax.loglog(c.times, c.rms_kalman * D, "--s", color=colour, ms=3, label=f"Kalman filter, {name}")
    ax2.semilogx(c.times, c.nees_mean, "-o", color=colour, ms=3, label=name)
    print(f"{name}: rms at 30 s, sample mean {c.rms_mean[7] * D:.4f}°, Kalman {c.rms_kalman[7] * D:.4f}°")
lo, hi = next(iter(results.values())).nees_band
ax2.axhspan(lo, hi, color="0.85", label="95 % band (consistent)")
ax.set_xlabel("averaging time [s]")
ax.set_ylabel("rms alignment error Δ [deg]")
ax.set_title("latitude 60°, σ = 1° on both axes, 10 Hz")
ax.legend(fontsize=6)
ax2.set_xlabel("averaging time [s]")
ax2.set_ylabel("mean NEES of β̂0 (1 dof)")
ax2.legend(fontsize=6)
plt.show()
