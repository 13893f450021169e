"""
Sample rate for a drift budget in an environment
================================================

Budennyi et al.'s Tables 4–5 in a vibration environment
(:func:`~strapdown.analysis.vibration.rate_design.rate_design`; ``strapdown
environment-rates``): for the package's qualification example, the worst
drift of each algorithm against the algorithm's sample rate, over the
environment with every frequency scaled by 1 ± a margin (so that a tuning
that needs the frequencies exactly is not admitted), against a budget of
0.5 deg/h. Tuned algorithms (dashed) are re-tuned at every rate; the dotted
line is the sensor part, which depends on the rate through the digital
filters running at the sensor rate.

Report figure ``vibration-rates.png`` (8 rates, as in the quick report).
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import NullFormatter

from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H, rad_per_s
from strapdown.analysis.vibration.environment import load_environment
from strapdown.analysis.vibration.examples import QUALIFICATION
from strapdown.analysis.vibration.rate_design import rate_design
from strapdown.derivations.coning.registry import get

budget_deg_per_h = 0.5
environment = load_environment(QUALIFICATION)
design = rate_design(environment, rad_per_s(budget_deg_per_h), algorithms=[get(n) for n in ("two-sample", "optimal-3", "ignagni-1996-5")], tuned=((2, 0), (3, 0)), rates=np.geomspace(100.0, 5000.0, 8))
for r in design.rows:
    print(f"{r.algorithm:>15}: " + ("no rate in the range" if r.sample_rate is None else f"lowest rate {r.sample_rate:.4g} Hz, load {r.load / 1e3:.4g} kop/s"))

fig, ax = plt.subplots(figsize=(7.2, 4.4), layout="constrained")
for row, curve in zip(design.rows, design.curves):
    ax.loglog(design.rates, curve * RAD_PER_S_TO_DEG_PER_H, "--" if row.tuned else "-", marker=".", label=row.algorithm)
ax.loglog(design.rates, design.sensor * RAD_PER_S_TO_DEG_PER_H, "k:", label="sensor part")
ax.axhline(budget_deg_per_h, color="r", lw=0.8, label="budget")
ax.xaxis.set_minor_formatter(NullFormatter())
ax.set_xlabel("algorithm sample rate 1/h [Hz]")
ax.set_ylabel("worst |drift| [deg/h] (±margin)")
ax.legend(loc="upper right", fontsize=7)
plt.show()
