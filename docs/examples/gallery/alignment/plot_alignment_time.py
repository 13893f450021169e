"""
Time to align, per sensor grade and under rocking
=================================================

Left: the fine-alignment filter's own azimuth σ (filterpy) at rest against
time for three grades, with each grade's bias floor (dotted) and the time to
align, after which σ stays within 10 % of the floor (dots)
(:func:`~strapdown.analysis.alignment.design_studies.grade_study`). Right: the
navigation grade under narrow-band rocking, the block 1 m from the rocking
centre, the filter carrying the rocking's shaping states or treating the
lever-arm velocity as noise
(:func:`~strapdown.analysis.alignment.design_studies.rocking_design_study`).

Report figure ``alignment-design-time.png`` (two rocking amplitudes, as in the
quick report).
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.design_studies import grade_study, rocking_design_study
from strapdown.analysis.alignment.sensor_models import GRADES
from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import rad

curves = grade_study(GRADES[:3], duration=4000.0)
rocking = rocking_design_study(rad(np.array([0.5, 2.0])))
for c in curves:
    when = f"{c.time_to_align:.0f} s" if math.isfinite(c.time_to_align) else f"beyond the {c.times[-1]:.0f} s shown"
    print(f"{c.grade}: floor {c.floor * D:.3g}°, time to align {when}")

fig, ax = plt.subplots(1, 2, figsize=(9.0, 3.6), layout="constrained")
for k, c in enumerate(curves):
    ax[0].loglog(c.times, c.sigma * D, "-", color=f"C{k}", label=c.grade)
    ax[0].axhline(c.floor * D, color=f"C{k}", lw=0.8, ls=":")
    if math.isfinite(c.time_to_align):
        ax[0].plot([c.time_to_align], [1.1 * c.floor * D], "o", color=f"C{k}", ms=4)
ax[0].set_xlabel("alignment time [s]")
ax[0].set_ylabel("azimuth σ [°]")
ax[0].set_title("Kalman alignment at rest, per grade")
ax[0].legend(loc="upper right", fontsize=7)
for k, kind in enumerate(("shaping", "white")):
    rows = [r for r in rocking if r.kind == kind]
    ax[1].plot([r.sigma * D for r in rows], [r.time_to_align for r in rows], "o-", color=f"C{k + 3}", label="rocking states" if kind == "shaping" else "rocking as noise")
ax[1].set_xlabel("tilt rocking σ [°] (narrow-band, 8 s)")
ax[1].set_ylabel("time to 1.1 × floor [s]")
ax[1].set_title("navigation grade under rocking")
ax[1].legend(loc="upper left", fontsize=7)
plt.show()
