"""
Computational load against the coning frequency
===============================================

Tables 4–5 of Budennyi, Kalinovsky, Panov et al. extended in frequency: the
load (operations per second, a multiplication counted as five additions) of
each algorithm run at the largest step that its asymptotic drift allows for
the budget [u] = 10⁻³ deg/h, at ϑ = 1°
(:func:`~strapdown.analysis.coning.papers.budennyi_loads.load_curves`).

The step follows the paper's rule, the leading term of the drift series. For
an algorithm whose leading term does not dominate at that step —
``optimal-3`` under coning (ε = −1), where the α⁴ term leads (drift order 4)
but the α² term (coning-drift order 6) is the drift — the rule places the step
too long; the task page :doc:`../../tasks/01_algorithm_and_rate` shows the
check by simulation that finds it.

Report figure ``derivations-load-vs-frequency.png`` (the quick report's 12
frequencies).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.papers import budennyi_loads
from strapdown.analysis.core.units import rad
from strapdown.derivations.coning.published import BUDENNYI_CONDITIONS

conditions = BUDENNYI_CONDITIONS
budget, _ = budennyi_loads.required_drifts()
algorithms = tuple(f"panov-4s-{k}" for k in range(1, 6)) + ("optimal-3", "lebedev-panov-6")
frequencies = np.geomspace(10, 4000, 12)
curves = budennyi_loads.load_curves(frequencies, eps_values=conditions.eps, nutation=rad(conditions.nutation_deg), required_drift=budget, algorithms=algorithms)

fig, axes = plt.subplots(1, 2, figsize=(9, 3.8), sharey=True, layout="constrained")
for ax, eps in zip(axes, conditions.eps):
    for curve in (k for k in curves if k.eps == eps):
        ax.loglog(curve.frequencies, curve.loads / 1e6, label=curve.algorithm)
    ax.set_title(f"[u] = {conditions.required_drift_deg_per_h[0]:g} deg/h, ϑ = {conditions.nutation_deg:g}°, ε = {eps:g}")
    ax.set_xlabel("f [Hz]")
axes[0].set_ylabel("load β [million op/s]")
axes[1].legend(fontsize=6)
plt.show()
