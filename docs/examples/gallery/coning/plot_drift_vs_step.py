"""
Drift against the step: the observed orders
===========================================

The constant drift of every algorithm of the source papers against the step
H, under coning (ε = −1) and a regular precession with ε = 0.5, at the
conditions of Lebedev & Panov (1989) (ν = 2π s⁻¹, ϑ = 10°). The fitted slope
on log–log axes is the observed order, an estimate of the drift order at that
motion
(:func:`~strapdown.analysis.coning.order_study.drift_orders`; see
:doc:`../../concepts/04_three_orders`).

Report figure ``algorithms-drift-vs-step.png`` (the quick report's three
steps; the full report adds H = 0.02 s). Numpy engine.
"""

import math

import matplotlib.pyplot as plt

from strapdown.analysis.coning.order_study import drift_orders
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.core.units import deg_per_h, rad

steps = (0.16, 0.08, 0.04)
fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True, layout="constrained")
for ax, eps in zip(axes, (-1.0, 0.5)):
    study = drift_orders(RegularPrecession(eps, 2 * math.pi, rad(10.0)), steps=steps, engine="numpy")
    for r in study:
        ax.loglog(r.steps, deg_per_h(r.drifts), "o-", ms=3, label=f"{r.algorithm} ({r.slope:.2f})")
    print(f"ε = {eps:g}: " + ", ".join(f"{r.algorithm} {r.slope:.2f}" for r in study))
    ax.set_xlabel("step H [s]")
    ax.set_title(f"ε = {eps:g} (ν = 2π s⁻¹, ϑ = 10°); fitted slope in brackets", fontsize=10)
    ax.set_ylim(top=ax.get_ylim()[1] * 300)
    ax.legend(fontsize=6, loc="upper left", ncol=2)
axes[0].set_ylabel("constant drift [deg/h]")
plt.show()
