"""
The azimuth error against the bounds (14) and (15)
==================================================

Hrechka & Koroliov bound the mean-square azimuth error of a gyrocompass on a
rocking base by (14), and at zero stable tilt by (15),
``δ ≤ tan φ √Dξ``. The Monte Carlo distribution of the error at three
configurations (normal and sinusoidal rocking, with and without stable tilts)
against the bounds and its own rms
(:func:`~strapdown.analysis.gyrocompass.studies.run_cases` on
:data:`~strapdown.analysis.gyrocompass.studies.DISTRIBUTION_CASES`): at large
rocking and high latitude the error exceeds both — they are first-order
estimates, not bounds.

Report figure ``azimuth-distribution.png`` (200 000 samples per case, as in
the quick report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.gyrocompass.studies import DISTRIBUTION_CASES, run_cases

results = run_cases(DISTRIBUTION_CASES, n_samples=200_000, rng=np.random.SeedSequence(1))
fig, axes = plt.subplots(1, len(results), figsize=(11, 3.4), layout="constrained")
for ax, v in zip(axes, results):
    c, mc = v.case, v.mc
    lo, hi = mc.result.rms_ci
    print(f"{c.model}, φ = {c.latitude * D:.3g}°, σ = {c.sigma * D:.3g}°: MC rms {mc.result.rms * D:.4f}° ({lo * D:.4f}–{hi * D:.4f}), (14) {mc.bound14 * D:.4f}°, (15) {mc.bound15 * D:.4f}°")
    edges, counts, _, _ = mc.result.histogram
    k = 40  # merge bins for display
    m = counts[: len(counts) // k * k].reshape(-1, k).sum(axis=1)
    e = edges[::k][: len(m) + 1] * D
    ax.stairs(m / (m.sum() * (e[1] - e[0])), e, fill=True, color="0.7", label="Monte Carlo")
    for value, style, name in ((mc.result.rms, "-", "MC rms"), (mc.bound14, "--", "bound (14)"), (mc.bound15, ":", "bound (15)")):
        ax.axvline(value * D, color="k", ls=style, label=name)
        ax.axvline(-value * D, color="k", ls=style)
    lim = 3.2 * mc.result.rms * D
    ax.set_xlim(-lim, lim)
    ax.set_title(f"{c.model}, φ={c.latitude * D:.3g}°, β0={c.beta0 * D:.3g}°, γ0={c.gamma0 * D:.3g}°, σ={c.sigma * D:.3g}°", fontsize=8)
    ax.set_xlabel("azimuth error α − α* [deg]")
axes[0].set_ylabel("density [1/deg]")
axes[0].legend(loc="upper left", fontsize=7)
plt.show()
