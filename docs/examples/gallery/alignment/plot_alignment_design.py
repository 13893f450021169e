"""
Admissible rocking for an azimuth budget, per alignment method
==============================================================

The designer's answer for the whole system: for a 0.3° azimuth budget, the
largest rocking amplitude against frequency for each alignment method, by
the rms (solid) and by 95 % of the trials (dashed)
(:func:`~strapdown.analysis.alignment.design.admissible_rocking`). The
analytic method's curve is its first-order theory; the inertial and Kalman
curves are Monte Carlo root searches with common random numbers, with the
interval of the rms amplitude as a band, and circles are independent Monte
Carlo checks (:func:`~strapdown.analysis.alignment.design.design_check`).
The dotted curve is the paper's tilt channel. The task page
:doc:`../../tasks/06_alignment_design` walks through the same design.

Report figure ``azimuth-alignment-design.png`` (two frequencies, 16 trials
and a loose tolerance, as in the quick report; the full report runs six
frequencies).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.design import admissible_rocking, design_check
from strapdown.analysis.alignment.fine import Disturbance
from strapdown.analysis.alignment.studies import DESIGN_SCENARIO, NAVIGATION_GRADE, kalman_options
from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import rad
from strapdown.analysis.gyrocompass.admissible_rocking import admissible_amplitude

scenario, sensors, budget = DESIGN_SCENARIO, NAVIGATION_GRADE, rad(0.3)
freqs = np.geomspace(0.05, 0.4, 2)
n_trials = {"analytic": 8, "inertial": 32, "kalman": 16}
seeds = iter(np.random.SeedSequence(1).spawn(12))
designs, checks = [], []
for method in ("analytic", "inertial", "kalman"):
    for rocking in ("sine", "narrowband"):
        options = kalman_options(scenario, sensors, disturbance=Disturbance("shaping", 0.01)) if method == "kalman" else None
        d = admissible_rocking(method, budget, scenario, freqs, sensors, rocking=rocking, options=options, n_trials=n_trials[method], rtol=0.3, rng=next(seeds))
        designs.append(d)
        print(f"{method:>8}, {rocking:>10}: admissible amplitude " + ", ".join(f"{a * D:.3g}°" for a in d.amplitude) + " at " + ", ".join(f"{f:.3g}" for f in freqs) + " Hz")
        if method != "analytic":
            checks.append((d, design_check(d, scenario, sensors, indices=(0, -1), options=options, n_trials=16, rng=next(seeds))))
tilt = {r: admissible_amplitude(budget, scenario.latitude, scenario.duration, freqs, rocking=r, sample_rate=scenario.sample_rate) for r in ("sine", "narrowband")}

colours = {"analytic": "C3", "inertial": "C0", "kalman": "C2"}
fig, axes = plt.subplots(1, 2, figsize=(11, 4.0), sharey=True, layout="constrained")
for ax, rocking in zip(axes, ("sine", "narrowband")):
    for d in (d for d in designs if d.rocking == rocking):
        c = colours[d.method]
        ax.loglog(d.frequency, np.where(d.amplitude > 0, d.amplitude, np.nan) * D, "-", color=c, label=f"{d.method}, rms")
        ax.loglog(d.frequency, np.where(d.amplitude_percentile > 0, d.amplitude_percentile, np.nan) * D, "--", color=c, label=f"{d.method}, 95 %")
        if d.method != "analytic":
            ax.fill_between(d.frequency, d.amplitude_ci[:, 0] * D, d.amplitude_ci[:, 1] * D, color=c, alpha=0.15, lw=0)
    ax.loglog(freqs, tilt[rocking].amplitude * D, ":", color="0.4", label="tilt channel only (paper), rms")
    for d, points in checks:
        if d.rocking == rocking:
            ax.plot([p.frequency for p in points], [p.amplitude * D for p in points], "o", color=colours[d.method], ms=5, mfc="none")
    ax.set_title(f"{rocking} rocking" + (", envelope over phase (analytic)" if rocking == "sine" else ", ζ = 0.1"), fontsize=9)
    ax.set_xlabel("rocking frequency [Hz]")
axes[0].set_ylabel("admissible amplitude [deg]")
axes[0].set_ylim(1e-4, 40.0)
axes[1].legend(fontsize=6, loc="center right")
plt.show()
