"""
Asymptotic drift against simulated drift
========================================

The asymptotic drift u_a — the leading term of the drift series, the figure
the papers print — against the drift u* of the simulation, for every
algorithm of the source papers, as the step shrinks
(:func:`~strapdown.analysis.coning.drift_crosscheck.drift_ratios`). The
relative difference falls by about four per halving of H: the next term of
the series is two powers of H higher. The legend gives ``u_a ∝ H^ρ``, ρ the
drift order at the motion. ϑ = 10°, f = 10 Hz.

Report figure ``derivations-ua-vs-ustar.png`` (the quick report's steps).
Numpy engine.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.drift_crosscheck import drift_ratios
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.core.units import rad

motions = [RegularPrecession(eps, 2 * math.pi * 10.0, rad(10.0)) for eps in (-1.0, 0.5)]
steps = np.array([0.02, 0.01, 0.005])
ratios = drift_ratios(motions, steps=steps, duration=8.0, engine="numpy")

fig, axes = plt.subplots(1, 2, figsize=(9, 3.8), sharey=True, layout="constrained")
for ax, eps in zip(axes, (-1.0, 0.5)):
    for r in (r for r in ratios if r.eps == eps):
        ax.loglog(r.steps * 1e3, np.maximum(r.deviations, 1e-8), "o-", ms=3, label=f"{r.algorithm} ($H^{r.order}$)")
    s = np.array([steps[0], steps[-1]])
    ax.loglog(s * 1e3, 0.3 * (s / s[0]) ** 2, "k--", lw=0.8, label="slope 2")
    ax.set_title(f"ε = {eps:g}, ϑ = 10°, f = 10 Hz")
    ax.set_xlabel("step H [ms]")
    ax.set_xticks(steps * 1e3, [f"{h * 1e3:g}" for h in steps])
    ax.xaxis.set_minor_formatter(plt.NullFormatter())
axes[0].set_ylabel("|u*/u_a − 1|")
axes[1].legend(fontsize=6, loc="lower right")
plt.show()

for r in ratios:
    print(f"ε = {r.eps:+g} {r.algorithm:>16}: |u*/u_a − 1| = " + ", ".join(f"{d:.1e}" for d in r.deviations))
