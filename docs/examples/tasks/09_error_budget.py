r"""
An error budget for your IMU
============================

A designer's deliverable is an error budget: for a given IMU, environment,
sample rate and algorithm, how large the attitude, velocity and horizontal
position errors are after a minute, ten minutes and an hour, and which source
dominates. The package runs the linear navigation error model once per source
(every error of the data sheet, the algorithms' residuals in the environment,
the alignment's own noise), from the initial condition the alignment leaves,
and adds them up. Fixed errors are signed; random ones are 1σ; the total is
the root sum square.

At the command line::

    strapdown budget --imu my-imu.toml --lat-deg 45 --duration-s 3600 --alignment analytic
    strapdown budget --imu my-imu.toml --environment my-bay.toml --algorithm two-sample --lat-deg 45 --duration-s 3600 --json

The IMU file holds the data sheet in body axes (at rest and level, body x
points along the heading)::

    sample_rate_hz = 200.0
    [gyro]
    bias_deg_per_h = [0.0, 0.0, 0.0]      # fixed, signed
    turn_on_bias_deg_per_h = 1.0          # 1σ per axis
    arw_deg_per_rt_h = 0.05
    bias_instability_deg_per_h = 0.5
    [accel]
    bias_ug = [100.0, 0.0, 0.0]
    vrw_m_s_per_rt_h = 0.06

(every key of :mod:`strapdown.analysis.navigation.imu_file`). This page
builds the budget of the two example IMUs, and checks the model's Schuler
response against the textbook formula.
"""

import math

from strapdown.analysis.navigation.error_budget import error_budget
from strapdown.analysis.navigation.error_model import Site
from strapdown.analysis.navigation.imu_file import ImuSpec, TriadErrors, example_imu

site = Site(math.radians(45.0), heading=0.0)

# %%
# The textbook check: a north accelerometer bias
# -----------------------------------------------
# Without alignment, 100 µg along body x (north) gives the north position
# error ``(b/ω_s²)(1 − cos ω_s t)``, ``ω_s² = g/R`` (the Schuler period, 84.4 min).
b = 100e-6 * 9.80665
ws = math.sqrt(site.gravity / 6371000.0)
half = math.pi / ws
r = error_budget(ImuSpec("bias only", 100.0, accel=TriadErrors(bias=[b, 0.0, 0.0])), site, half, report_times=[half / 2])
for t in r.report_times:
    model = r.line("accel bias").mean[r.index(t), 6]
    print(f"t = {t / 60:5.1f} min: budget {model:8.2f} m, textbook {b / ws**2 * (1 - math.cos(ws * t)):8.2f} m")

# %%
# A tactical-grade IMU, aligned by the analytic method
# -----------------------------------------------------
# The alignment ties the tilts to the horizontal accelerometer biases and the
# heading to the east gyro bias, so those errors largely cancel at first; what
# the alignment cannot tell apart from its noise is its own line.
tactical = error_budget(example_imu("tactical"), site, 3600.0, alignment="analytic")
print(f"{'source':<26}{'1 min':>12}{'10 min':>12}{'1 h':>12}   horizontal position [m]")
for line in tactical.lines:
    print(f"{line.name:<26}" + "".join(f"{float(line.position[tactical.index(t)]):>12.4g}" for t in tactical.report_times))
print(f"{'total':<26}" + "".join(f"{float(tactical.total.position[tactical.index(t)]):>12.4g}" for t in tactical.report_times))
print("dominant source at one hour:", tactical.dominant("position"))

# %%
# An industrial MEMS IMU
# ----------------------
# Its gyros cannot find north (a bias of 50 °/h against an Earth rate of
# 15 °/h), so this budget starts without alignment: the gyro turn-on bias
# dominates within minutes.
mems = error_budget(example_imu("mems"), site, 600.0, alignment="none", report_times=[60.0, 300.0])
for t in mems.report_times:
    i = mems.index(t)
    print(f"t = {t:5.0f} s: total {float(mems.total.position[i]):10.4g} m, {float(mems.total.velocity[i]):8.4g} m/s; dominant {mems.dominant('position', t)}")
