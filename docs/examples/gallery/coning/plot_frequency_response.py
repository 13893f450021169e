"""
Coning drift against frequency, every algorithm
===============================================

Under classical coning (half-cone angle α, rate ω, sample interval h) the
drift of any algorithm is ``u = α² ω D(ωh) + O(α⁴)`` with ``D`` exact in ωh
(:func:`strapdown.derivations.coning.drift.coning_drift`). On log–log axes
``|D|`` is the algorithm's error-versus-frequency response; markers are the
simulator at three points, where it runs and the drift is above the round-off
of the run (:func:`~strapdown.analysis.coning.frequency_response.coning_frequency_response`).
Solid: the published algorithms of the registry; dashed: the optimal coning
class derived by the package. The legend gives the leading term ``c·x^m`` of
each ``D(x)``, m the coning-drift order.

Report figure ``frequency-response-coning.png`` (80 points per curve, as in
the quick report). Numpy engine.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.frequency_response import coning_frequency_response
from strapdown.derivations.coning.drift import optimal_coning_algorithm
from strapdown.derivations.coning.registry import get, names

published = names(library=True)
algorithms = [get(n) for n in published] + [optimal_coning_algorithm(n, history=k) for n, k in ((4, 0), (5, 0), (6, 0), (1, 1))]
response = coning_frequency_response(algorithms, np.geomspace(1e-2, math.pi / 2, 80), check_omega_h=(0.25, 0.5, 1.0), engine="numpy")
print(f"{len(response.simulated_checks)} points simulated; largest relative difference from the closed form {response.largest_relative_difference:.1e}")

panels = (
    ("papers: Lebedev & Panov (1989), Budennyi et al.", lambda a: a.startswith(("lebedev-panov", "panov-4s"))),
    ("cross-step: Savage 1 + 1, Ignagni (1996)", lambda a: a.startswith(("savage", "ignagni-1996")) or a.endswith("1+1")),
    ("optimal class: compressed, derived", lambda a: a.startswith(("compressed", "optimal-coning"))),
    ("within one step: Miller, Ignagni (1990), polynomial fits", lambda a: True),
)
fig, axes = plt.subplots(2, 2, figsize=(11, 8.5), sharex=True, sharey=True, layout="constrained")
groups = [[] for _ in panels]
for r in response.responses:
    groups[next(k for k, (_, test) in enumerate(panels) if test(r.algorithm.name))].append(r)
for ax, (title, _), rows in zip(axes.ravel(), panels, groups):
    for k, r in enumerate(rows):
        colour = plt.get_cmap("tab10")(k % 10)
        style = "-" if r.algorithm.name in published else "--"
        c = r.coefficient
        ax.loglog(r.omega_h, np.abs(r.drift), style, color=colour, lw=1.2, label=f"{r.algorithm.name} ({c.numerator}/{c.denominator}·x^{r.order})")
        sims = r.simulated_checks
        if sims:
            ax.loglog([s.omega_h for s in sims], [abs(s.simulated_coefficient) for s in sims], "o", color=colour, ms=4, mfc="none")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
for ax in axes[-1]:
    ax.set_xlabel("ωh: coning rate × sample interval [rad]")
for ax in axes[:, 0]:
    ax.set_ylabel("|D(ωh)| = |u| / (α² ω)")
axes[0, 0].set_ylim(1e-30, 1.0)
fig.suptitle("Coning drift against frequency (lines: closed form, dashed: derived; circles: simulator)")
plt.show()
