"""
Sculling error of the velocity algorithms
=========================================

Classical sculling: angular vibration θ₀ sin νt about body x, specific force
A sin νt along body y. The exact apparent velocity rectifies ``A J₁(θ₀)``
along z; the velocity algorithm of each coning algorithm is its dual
extension. The curves are the relative rectification error against νh to
first order in θ₀A, exact in νh
(:func:`~strapdown.analysis.coning.papers.published_check.sculling_error_curve`;
the fitted slope in brackets); the crosses are the simulator
(:func:`~strapdown.analysis.coning.papers.published_check.sculling_simulation_checks`).
The slopes, the powers of νh of the sculling error, are the coning-drift
orders m of the same algorithms (Ignagni's 1998 duality).

Report figure ``published-algorithms-sculling.png`` (the full report's 30
points per curve, the quick report's three simulator checks).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.papers.published_check import sculling_error_curve, sculling_simulation_checks

algorithms = ("one-sample", "savage-1+1", "two-sample", "miller-3", "compressed-3", "ignagni-1996-1", "ignagni-1996-2",
              "ignagni-1996-5", "compressed-4", "ignagni-1996-6", "compressed-5", "polynomial-4")  # fmt: skip
curves = sculling_error_curve(algorithms, np.geomspace(0.02, 1.0, 30))
points = sculling_simulation_checks((("savage-1+1", 0.1), ("two-sample", 0.2), ("miller-3", 0.3)), cycles=20)
for p in points:
    print(f"{p.algorithm}, νh = {p.nu_h:g}: theory {p.theory:.6e}, simulated {p.simulated:.6e} m/s² ({p.relative_difference:+.1e})")

fig, ax = plt.subplots(figsize=(7, 4.6), layout="constrained")
for k, c in enumerate(curves):
    ax.loglog(c.nu_h, np.abs(c.relative), ("-", "--", ":")[k // 10], lw=1.2, label=f"{c.algorithm} ({c.slope:.1f})")
for p in points:
    ax.loglog([p.nu_h], [abs(p.simulated_relative)], "kx", ms=6)
ax.set_xlabel("ν h [rad]")
ax.set_ylabel("|rectification error| / A J₁(θ₀)")
ax.set_title("Sculling error of the dual extensions (× : simulator)")
ax.set_ylim(1e-22, 10)
ax.legend(fontsize=6, ncol=2, loc="lower right")
plt.show()
