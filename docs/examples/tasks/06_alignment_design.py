"""
Alignment design: how much rocking an azimuth budget allows
===========================================================

A strapdown system aligns itself on a base that rocks — a ship at its
mooring, a vehicle with its engine running. Hrechka & Koroliov bound the
azimuth error through the tilt channel and leave open the designer's
question: for an azimuth budget, how much rocking is admissible, at which
frequencies, with which alignment method?

The package answers for the whole system — the rocking in the gyros and the
accelerometers, the lever arm, the sensor errors — and for each method:
``analytic`` (formula (2) on averaged outputs), ``inertial`` (inertial-frame
coarse alignment) and ``kalman`` (fine alignment). At the command line::

    strapdown azimuth-design --budget-deg 0.3 --lat-deg 60 --averaging-time 120 --rocking sine
    strapdown align --method inertial --lat-deg 60 --rocking sine --amplitude-deg 5 --period 10 --trials 64 --seed 1

The first is the tilt channel of the paper; the second runs the whole system
at one rocking and checks it against its theory.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.design import admissible_rocking, design_check
from strapdown.analysis.alignment.studies import DESIGN_SCENARIO, NAVIGATION_GRADE
from strapdown.analysis.core.units import deg, deg_per_h, rad
from strapdown.analysis.gyrocompass.admissible_rocking import admissible_amplitude

# %%
# The set-up
# ----------
# Latitude 60°, two minutes of alignment at 10 Hz, the inertial block 1 m above
# the rocking centre and 0.5 m, 0.3 m off it, navigation-grade sensors; rocking
# on the two tilt axes; a budget of 0.3° on the azimuth error.
scenario, sensors = DESIGN_SCENARIO, NAVIGATION_GRADE
budget = rad(0.3)
frequencies = np.geomspace(0.05, 0.4, 4)  # rocking frequencies [Hz]
print(f"latitude {deg(scenario.latitude):g}°, T = {scenario.duration:g} s at {scenario.sample_rate:g} Hz, lever arm {scenario.lever_arm} m")
print(f"gyro bias σ {deg_per_h(sensors.gyro_bias_sigma):g} deg/h, accelerometer bias σ {sensors.accel_bias_sigma:g} m/s²")

# %%
# The admissible amplitude against frequency
# ------------------------------------------
# For the analytic method the first-order theory gives it directly. For the
# inertial-frame method the amplitude is found by a root search on a Monte
# Carlo with common random numbers (here 32 trials per frequency and a loose
# tolerance, to keep the page quick; the report runs more). The curve of the
# paper's tilt channel — gyros at the stable attitude, the rocking seen by the
# accelerometers only — is the reference.
designs = {}
for method, trials in (("analytic", 0), ("inertial", 32)):
    for rocking in ("sine", "narrowband"):
        designs[method, rocking] = admissible_rocking(method, budget, scenario, frequencies, sensors, rocking=rocking, n_trials=max(trials, 8), rtol=0.3, rng=2)
tilt_channel = {r: admissible_amplitude(budget, scenario.latitude, scenario.duration, frequencies, rocking=r, sample_rate=scenario.sample_rate) for r in ("sine", "narrowband")}

print(f"{'method':>10} {'rocking':>11} {'floor':>8}  admissible amplitude [deg] at " + ", ".join(f"{f:.3g}" for f in frequencies) + " Hz")
for (method, rocking), d in designs.items():
    print(f"{method:>10} {rocking:>11} {deg(d.floor):7.3f}°  " + "  ".join(f"{a:8.3g}" for a in deg(d.amplitude)))
for rocking, t in tilt_channel.items():
    print(f"{'tilt only':>10} {rocking:>11} {'':>8}  " + "  ".join(f"{a:8.3g}" for a in deg(t.amplitude)))

# %%
# The floor is the azimuth error with no rocking at all, set by the sensors;
# where it exceeds the budget no rocking is admissible. Two things stand out:
#
# * the **analytic** method admits arc-seconds of rocking: averaged gyro
#   outputs carry the rocking rates, which dwarf the Earth rate it measures;
# * the **inertial-frame** method admits degrees, in the range of the tilt
#   channel of the paper — but not the same curve: the lever arm and the
#   rocking in the gyros change it.
fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharey=True, layout="constrained")
for ax, rocking in zip(axes, ("sine", "narrowband")):
    for (method, r), d in designs.items():
        if r == rocking:
            ax.loglog(d.frequency, np.where(d.amplitude > 0, deg(d.amplitude), np.nan), "o-", label=f"{method}, rms")
    ax.loglog(frequencies, deg(tilt_channel[rocking].amplitude), ":", color="0.4", label="tilt channel only (paper)")
    ax.set(title=f"{rocking} rocking", xlabel="rocking frequency [Hz]")
    ax.legend(fontsize=7)
axes[0].set_ylabel("admissible amplitude [deg]")
plt.show()

# %%
# An independent check
# --------------------
# At the admissible amplitude of the lowest frequency, a fresh Monte Carlo
# (new streams, more trials) should find the rms azimuth error at the budget,
# within its interval.
d = designs["inertial", "narrowband"]
(point,) = design_check(d, scenario, sensors, indices=(0,), n_trials=64, rng=3)
lo, hi = point.result.rms_ci
print(f"{point.frequency:.3g} Hz, amplitude {deg(point.amplitude):.3g}°: rms {deg(point.result.rms):.3f}° (95 % interval {deg(lo):.3f}–{deg(hi):.3f}°), budget {deg(budget):g}°")
