"""
Where the bounds hold: correlated rocking and the estimates (16)
================================================================

With narrow-band rocking the tilts are estimated by the sample means (16)
over 30 s at 10 Hz, and the error is the alignment error Δ of those means.
Top: Δ against (14) evaluated at the variance of the mean, the bound that
applies to it. Bottom: against (14) with the sample variances, the paper's
prescription after (16), which bounds the instantaneous error and overstates
the error of the estimate
(:func:`~strapdown.analysis.gyrocompass.bound_sweep.validity_map` with
``estimate="sample-mean"``).

Report figure ``azimuth-validity-correlation.png`` (the quick report's 5 × 5
grid and 20 000 records per cell).
"""

import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import rad
from strapdown.analysis.gyrocompass.bound_sweep import validity_map

latitudes, sigmas = rad(np.array([0.0, 20.0, 45.0, 70.0, 80.0])), rad(np.array([0.01, 0.1, 1.0, 3.0, 10.0]))
groups = {
    "narrowband τc=6.4 s, (16) over 30 s": dict(model="narrowband", period=8.0, damping=0.2, estimate="sample-mean", averaging_time=30.0),
    "narrowband τc=64 s, (16) over 30 s": dict(model="narrowband", period=8.0, damping=0.02, estimate="sample-mean", averaging_time=30.0),
}
seeds = np.random.SeedSequence(2).spawn(len(groups))
maps = {name: validity_map(latitudes, sigmas, n_samples=20_000, rng=seed, control_degree=4, **fields) for (name, fields), seed in zip(groups.items(), seeds)}

norm = mcolors.TwoSlopeNorm(vmin=-0.3, vcenter=0.0, vmax=0.3)
fig, axes = plt.subplots(2, len(maps), figsize=(9.5, 7.0), layout="constrained")
for j, (name, m) in enumerate(maps.items()):
    print(f"{name}: largest rms Δ / (14) at the variance of the mean {np.nanmax(m.ratio14):.3g}, with the sample variances {np.nanmax(m.plugin_ratio14):.3g}")
    for i, (ratio, label) in enumerate(((m.ratio14, "rms Δ / (14) at the variance of the mean"), (m.plugin_ratio14, "rms Δ / (14) with the sample variances of (16)"))):
        ax = axes[i, j]
        im = ax.pcolormesh(np.arange(len(m.sigmas) + 1), np.arange(len(m.latitudes) + 1), np.clip(np.log10(ratio), -0.3, 0.3), cmap="RdBu_r", norm=norm)
        if i == 0:
            yy, xx = np.nonzero(m.fails14)
            ax.plot(xx + 0.5, yy + 0.5, "kx", ms=4)
            yy, xx = np.nonzero(m.holds14)
            ax.plot(xx + 0.5, yy + 0.5, "k.", ms=2)
        ax.set_xticks(np.arange(len(m.sigmas)) + 0.5, [f"{s * D:.3g}" for s in m.sigmas], fontsize=7)
        ax.set_yticks(np.arange(len(m.latitudes)) + 0.5, [f"{v * D:.3g}" for v in m.latitudes], fontsize=7)
        ax.set_title(f"{name}:\n{label}", fontsize=8)
        ax.set_xlabel("rocking σ [deg]")
        ax.set_ylabel("latitude [deg]")
fig.colorbar(im, ax=axes, label="log10(rms alignment error / bound)")
plt.show()
