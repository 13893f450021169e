"""
Data-sheet sensors and their Allan deviation
============================================

Gyros modelled as a data sheet specifies them — turn-on bias, angle random
walk N, bias instability B (flicker noise, as a sum of Gauss–Markov processes
over its band), rate random walk K — for four illustrative grades
(:data:`~strapdown.analysis.alignment.sensor_models.GRADES`): the data sheet's
Allan deviation (lines) and, for one grade, the overlapping Allan deviation of
a simulated record measured by ``allantools`` with 95 % intervals
(:func:`~strapdown.analysis.alignment.design_studies.allan_study`).

Report figure ``alignment-design-allan.png`` (2¹⁵ samples at 10 Hz, as in the
quick report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.design_studies import allan_study
from strapdown.analysis.alignment.sensor_models import GRADES
from strapdown.analysis.core.units import deg_per_h

study = allan_study(GRADES[3], n_samples=2**15, rng=np.random.SeedSequence(1))
print(f"{study.grade}: the data sheet's curve inside the measured 95 % interval at {study.inside} of {study.expected.size} averaging times")
f, s = study.fit, study.spec
print(f"read back: ARW {f.random_walk / s.random_walk:.3f} × the data sheet, bias instability {f.bias_instability / s.bias_instability:.3f} ×")

tau = np.geomspace(0.1, 1e5, 200)
fig, ax = plt.subplots(figsize=(6.8, 4.0), layout="constrained")
for k, g in enumerate(GRADES):
    ax.loglog(tau, deg_per_h(np.sqrt(g.gyro.allan_variance(tau))), "-", lw=1.0, color=f"C{k}", label=f"{g.name} (data sheet)")
m = study.measured
ax.errorbar(m.taus, deg_per_h(m.adev), yerr=[deg_per_h(m.adev - m.low), deg_per_h(m.high - m.adev)], fmt="o", ms=3, color="k", label=f"{study.grade}: simulated, 95 % CI")
ax.set_xlabel("averaging time τ [s]")
ax.set_ylabel("Allan deviation [deg/h]")
ax.set_title("gyro Allan deviation: data sheet and simulated sensor")
ax.legend(loc="lower left", fontsize=7)
plt.show()
