"""
The stage as a complementary filter
===================================

A corrected stage passes the gyro-integrated attitude through the high-pass
``H_g = s²/(s² + ks + l)`` and the accelerometer tilt through the low-pass
``H_a = (ks + l)/(s² + ks + l)``, with ``H_g + H_a = 1``
(:func:`~strapdown.analysis.multistage.tilt_loop.complementary_filter`). Two
section-5 loops; the grey line is the Schuler frequency √(g/R).

Report figure ``stability-bode.png``.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core import units
from strapdown.analysis.multistage.readings import section5_loops
from strapdown.analysis.multistage.tilt_loop import complementary_filter

g, r = 9.81, 6.371e6
loops = section5_loops(g, r)
omega = np.logspace(-5, 0, 400)
fig, axes = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True, layout="constrained")
for named in (loops[0], loops[2]):
    f = complementary_filter(named.loop, omega)
    short = named.label.split(" (")[0]
    line = axes[0].loglog(f.omega, f.gyro_magnitude, "-", label=f"gyro high-pass H_g, {short}")[0]
    axes[1].semilogx(f.omega, units.deg(f.gyro_phase), "-", color=line.get_color())
    axes[0].loglog(f.omega, f.accel_magnitude, "--", color=line.get_color(), label=f"accelerometer low-pass H_a, {short}")
    axes[1].semilogx(f.omega, units.deg(f.accel_phase), "--", color=line.get_color())
    print(f"{short}: largest |H_g + H_a − 1| on the grid {f.max_sum_error:.1e}")
axes[0].axvline(np.sqrt(g / r), color="0.5", lw=0.8)
axes[0].set_ylim(1e-4, 3)
axes[0].set_ylabel("|H|")
axes[1].set_ylabel("phase [deg]")
axes[1].set_xlabel("ω [rad/s] (grey: Schuler frequency)")
axes[0].legend(fontsize=6)
plt.show()
