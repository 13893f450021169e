"""
GNSS-aided alignment in motion
==============================

A car at 10 m/s weaving its heading ±A with a 40 s period, its trajectory
exact over the WGS-84 ellipsoid; a tactical-grade IMU, which cannot
gyrocompass at rest; a closed-loop 15-state filter fusing 1 Hz GNSS velocity
and position from a 3° azimuth prior. Left: the time until the filter's
azimuth σ is within 0.5°, against the peak lateral acceleration of the weave;
right: the azimuth σ after 180 s
(:func:`~strapdown.analysis.alignment.design_studies.manoeuvre_study`). A
straight drive leaves the azimuth as unobservable as at rest.

Report figure ``alignment-design-motion.png`` (three weave amplitudes, as in
the quick report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.design_studies import manoeuvre_study
from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import rad

rows = manoeuvre_study(rad(np.array([0.0, 5.0, 20.0])))
for r in rows:
    when = f"{r.time_to_align:.0f} s" if np.isfinite(r.time_to_align) else "not within 180 s"
    print(f"weave ±{r.amplitude * D:.3g}°: peak lateral acceleration {r.lateral_acceleration:.3g} m/s², time to align {when}, σ_ψ after 180 s {r.sigma_end * D:.3g}°")

a = np.array([r.lateral_acceleration for r in rows])
t = np.array([r.time_to_align for r in rows])
s = np.array([r.sigma_end for r in rows]) * D
finite = np.isfinite(t)
fig, ax = plt.subplots(1, 2, figsize=(8.6, 3.4), layout="constrained")
ax[0].plot(a[finite], t[finite], "o-", color="C0")
ax[0].set_xlabel("peak lateral acceleration of the weave [m/s²]")
ax[0].set_ylabel("time to σ_ψ ≤ 0.5° [s]")
ax[0].set_title("GNSS-aided alignment: time to align")
ax[1].semilogy(a, s, "s-", color="C1")
ax[1].set_xlabel("peak lateral acceleration [m/s²]")
ax[1].set_ylabel("σ_ψ after 180 s [°]")
ax[1].set_title("azimuth after 180 s")
plt.show()
