"""
Integrators in the wild
=======================

Integrators as code, identified as exact algorithms
(:func:`~strapdown.analysis.coning.integrators.assessment.assess`; ``strapdown
identify``): the per-sample recursion of flight code (Savage's form), the same
recursion with its previous α one sample older, a quaternion composed per
sample with no coning term, and two peers, pyins's strapdown loop and
smsfusion's ``StrapdownINS`` (the ``peers`` extra). Lines: the closed-form
coning drift ``|D(ωh)|`` of each identified algorithm (``u = α² ω D``);
markers: the integrator's own simulated drift, extrapolated to α → 0, where
the round-off floor resolves it. pyins falls on Savage's recursion (dashed on
solid), smsfusion on the composition without coning term: per sample they are
the same algorithms.

Report figure ``integrators-in-the-wild.png``.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.drift_theory import coning_drift_function
from strapdown.analysis.coning.integrators.assessment import assess
from strapdown.analysis.coning.integrators.peers import pyins_integrator, smsfusion_ins
from strapdown.analysis.coning.integrators.recursions import quaternion_composition, recursion

h = 1.0 / 400.0
cases = [
    ("Savage's recursion, N = 4", recursion(), 4),
    ("previous α older, N = 4", recursion(alpha_lag=2), 4),
    ("quaternion composition, N = 4", quaternion_composition(), 4),
    ("pyins (Savage's 1 + 1)", pyins_integrator(sample_interval=h), 1),
    ("smsfusion StrapdownINS", smsfusion_ins(sample_interval=h), 1),
]
curves = []
for label, integrator, n in cases:
    a = assess(integrator, n)
    curves.append((label, a))
    c = a.coning
    drift = "no coning drift" if c is None else f"u = {c.coefficient.numerator}/{c.coefficient.denominator} α²ω(ωh)^{c.order} (coning-drift order {c.order})"
    print(f"{label}: terms {a.identification.terms}, accuracy order ρ = {a.order}, {drift}, simulation agrees: {a.check.holds}")

grid = np.geomspace(0.05, 2.5, 120)
fig, ax = plt.subplots(figsize=(7.5, 4.8), layout="constrained")
styles = (("-", "o", 6), ("-", "o", 6), ("-", "o", 6), ("--", "s", 9), ("--", "s", 9))  # the peers dashed: they fall on the recursions' lines
for k, ((label, a), (line, marker, size)) in enumerate(zip(curves, styles)):
    colour = plt.get_cmap("tab10")(k)
    d = np.abs(np.asarray(coning_drift_function(a.algorithm)(grid), dtype=float))
    ax.loglog(grid, d, line, color=colour, lw=1.3, label=label)
    if a.check is not None:
        points = a.check.resolved
        ax.loglog([p.x for p in points], [abs(p.simulated) for p in points], marker, color=colour, ms=size, mfc="none")
ax.set_xlabel("ωh: coning rate × sample interval [rad]")
ax.set_ylabel("|D(ωh)| = |u| / (α² ω)")
ax.set_title("Identified integrators: closed form (lines) and their own simulation (markers)", fontsize=10)
ax.legend(fontsize=7, loc="lower right")
plt.show()
