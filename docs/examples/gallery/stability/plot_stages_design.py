"""
Designed stages: simulation against the loop
============================================

Gains from a requested loop, ω_n = 0.01 rad/s and ζ = 0.3, 0.7, 1
(:func:`~strapdown.analysis.multistage.gain_design.design_gains`), for the
whole-angle accelerometer quaternion (1.4) with c = 2 and the half-angle one
(1.10) with c = 1. Each stage is started level on a body pitched by 0.01 rad
and simulated by the stage recursion; the markers are the loop's prediction,
the step response of ``H_g`` from python-control
(:func:`~strapdown.analysis.multistage.gain_design.check_design`).

Report figure ``stability-design.png`` (the quick report's step of 1 s).
"""

import matplotlib.pyplot as plt

from strapdown.analysis.multistage.gain_design import check_design, design_gains, largest_design_difference

checks = [check_design(design_gains(1e-2, zeta, reference=ref), duration=1500.0, step=1.0) for ref in ("pure", "tilt") for zeta in (0.3, 0.7, 1.0)]
print(f"largest difference between a stage and its loop: {largest_design_difference(checks):.1e} rad")

fig, axes = plt.subplots(1, 2, figsize=(12, 3.6), sharey=True, layout="constrained")
for ax, ref in zip(axes, ("pure", "tilt")):
    for c in (c for c in checks if c.gains.reference == ref):
        line = ax.plot(c.time, c.simulated, lw=1.2, label=f"ζ = {c.gains.damping:.1g} simulated")[0]
        ax.plot(c.time[::40], c.predicted[::40], "o", ms=3, color=line.get_color(), label=f"ζ = {c.gains.damping:.1g} loop (H_g)")
    ax.set_title(f"designed stage, ω_n = 0.01 rad/s, {'(1.4), c = 2' if ref == 'pure' else '(1.10), c = 1'}")
    ax.set_xlabel("t [s]")
    ax.legend(fontsize=6)
axes[0].set_ylabel("pitch error [rad]")
plt.show()
