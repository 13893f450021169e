"""
Where the bounds hold: known stable tilts
=========================================

Latitude × rocking standard deviation (both axes equal). Colour: log10 of
the Monte Carlo rms over the bound (14) (top) and (15) (bottom); ×: the bound
fails (the whole 95 % interval above it), ·: it holds (the whole interval
below it), blank: undecided
(:func:`~strapdown.analysis.gyrocompass.bound_sweep.validity_map`, control
variates). At zero stable tilt (left) the bounds fail by the second-order
excess of the error; with stable tilts (15) fails wholesale.

Report figure ``azimuth-validity-known.png`` (the quick report's 5 × 5 grid
and 20 000 samples per cell).
"""

import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import rad
from strapdown.analysis.gyrocompass.bound_sweep import validity_map

latitudes, sigmas = rad(np.array([0.0, 20.0, 45.0, 70.0, 80.0])), rad(np.array([0.01, 0.1, 1.0, 3.0, 10.0]))
groups = {
    "normal, β0=γ0=0": dict(model="normal"),
    "normal, β0=2°, γ0=−2°": dict(model="normal", beta0=rad(2.0), gamma0=rad(-2.0)),
    "sine, β0=2°, γ0=−2°": dict(model="sine", beta0=rad(2.0), gamma0=rad(-2.0)),
}
seeds = np.random.SeedSequence(1).spawn(len(groups))
maps = {name: validity_map(latitudes, sigmas, n_samples=20_000, rng=seed, control_degree=4, **fields) for (name, fields), seed in zip(groups.items(), seeds)}

norm = mcolors.TwoSlopeNorm(vmin=-0.3, vcenter=0.0, vmax=0.3)  # a factor of two either way
fig, axes = plt.subplots(2, len(maps), figsize=(12.5, 7.0), layout="constrained")
for j, (name, m) in enumerate(maps.items()):
    print(f"{name}: (14) fails in {int(m.fails14.sum())} of {m.ratio14.size} cells, (15) in {int(m.fails15.sum())}")
    for i, (ratio, holds, fails, bound) in enumerate(((m.ratio14, m.holds14, m.fails14, "(14)"), (m.ratio15, m.holds15, m.fails15, "(15)"))):
        ax = axes[i, j]
        im = ax.pcolormesh(np.arange(len(m.sigmas) + 1), np.arange(len(m.latitudes) + 1), np.clip(np.log10(ratio), -0.3, 0.3), cmap="RdBu_r", norm=norm)
        yy, xx = np.nonzero(fails)
        ax.plot(xx + 0.5, yy + 0.5, "kx", ms=4)
        yy, xx = np.nonzero(holds)
        ax.plot(xx + 0.5, yy + 0.5, "k.", ms=2)
        ax.set_xticks(np.arange(len(m.sigmas)) + 0.5, [f"{s * D:.3g}" for s in m.sigmas], fontsize=7)
        ax.set_yticks(np.arange(len(m.latitudes)) + 0.5, [f"{v * D:.3g}" for v in m.latitudes], fontsize=7)
        ax.set_title(f"{name}:\nMC rms / {bound}", fontsize=8)
        ax.set_xlabel("rocking σ [deg]")
        ax.set_ylabel("latitude [deg]")
fig.colorbar(im, ax=axes, label="log10(MC rms / bound); ×: fails, ·: holds")
plt.show()
