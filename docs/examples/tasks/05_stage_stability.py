"""
Stage stability and Schuler tuning
==================================

A corrected attitude stage of Plotnikov (1999) integrates the gyros and pulls
its horizontal attitude toward the tilt the accelerometers see, with a
position gain k [1/s] and an integral gain l [1/s²]. Linearised, its tilt
channel is the loop ``s² + Ks + L`` with ``K = kc/2``, ``L = lc/2`` — a
complementary filter: the gyros pass through the high-pass
``H_g = s²/(s² + Ks + L)``, the accelerometer tilt through the low-pass
``H_a = (Ks + L)/(s² + Ks + L)``.

The designer's questions, in order: which gains give the loop I want; does
the nonlinear stage behave like its loop; how does a Schuler-tuned stage
answer sensor errors. At the command line::

    strapdown stability --natural-frequency-rad-s 0.01 --damping 0.7
    strapdown stability --schuler --accel-m-s2 20 --accel-duration 20
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.cache import derived
from strapdown.analysis.multistage.gain_design import check_design, check_error_budget, design_gains, schuler_error_budget, schuler_gains
from strapdown.analysis.multistage.tilt_loop import complementary_filter, responses
from strapdown.derivations.multistage.schuler import derive

# %%
# Gains from a requested loop
# ---------------------------
# ω_n = 0.01 rad/s and ζ = 0.7 for a stage that levels on the whole-angle
# accelerometer quaternion (1.4) (``reference="pure"``, c = 2). The loop is a
# python-control system; its poles and damping come from ``control.damp``.
gains = design_gains(0.01, 0.7, reference="pure")
loop = gains.loop()
wn, zeta, poles = loop.damp()
print(f"k = {gains.k:.5g} 1/s, l = {gains.l:.5g} 1/s², c = {gains.c:g}")
print(f"poles {', '.join(f'{p.real:.4g}{p.imag:+.4g}j' for p in poles)} 1/s, ω_n = {wn[0]:.4g} rad/s, ζ = {zeta[0]:.3g}: {loop.stability}")

# %%
# Does the stage behave like its loop?
# ------------------------------------
# The stage recursion (nonlinear, quaternions, compiled) started level on a
# body pitched by 0.01 rad, against the loop's prediction, ``−0.01 H_g`` as a
# step response from python-control. The difference is second order in the
# tilt.
check = check_design(gains, tilt=0.01, duration=1500.0, step=1.0)
print(f"largest difference between the stage and its loop: {check.max_difference:.1e} rad")

t = np.linspace(0.0, 1500.0, 751)
resp = responses(loop, t)
omega = np.logspace(-4, 0, 300)
filt = complementary_filter(loop, omega)
fig, axes = plt.subplots(1, 3, figsize=(12, 3.6), layout="constrained")
axes[0].plot(check.time, check.simulated, lw=1.2, label="stage recursion")
axes[0].plot(check.time[::40], check.predicted[::40], "o", ms=3, label="loop: −0.01 H_g step")
axes[0].set(title="pitch error from a 0.01 rad tilt", xlabel="t [s]", ylabel="[rad]")
axes[0].legend(fontsize=7)
axes[1].plot(t, resp.accel_step)
axes[1].set(title="tilt error per m/s² of acceleration", xlabel="t [s]", ylabel="[rad per m/s²]")
axes[2].loglog(filt.omega, filt.gyro_magnitude, label="gyros: high-pass H_g")
axes[2].loglog(filt.omega, filt.accel_magnitude, label="accelerometers: low-pass H_a")
axes[2].set(title="the stage as a complementary filter", xlabel="ω [rad/s]", ylim=(1e-4, 3))
axes[2].legend(fontsize=7)
plt.show()

# %%
# Schuler tuning
# --------------
# With ``k = 0`` and ``l = g/R`` (for (1.4)) the integral path turns the frame
# by exactly the transport rate: the tilt error no longer depends on the
# horizontal acceleration. The linearised transfer function from acceleration
# to tilt error, derived symbolically from the stage equations, vanishes
# identically at those gains (Plotnikov 1999, (3.11)):
schuler = derived("multistage:schuler:v1", derive)
print("E(s)/A(s) =", schuler.tf_accel)
print("at k = 0, l = g/R:", schuler.schuler_residual)

# %%
# The price is a marginally stable loop: poles on the imaginary axis at the
# Schuler frequency, so errors present at the switch persist as undamped
# oscillations with the 84-minute Schuler period. Against an acceleration the
# accelerometers *do* sense, the tuned loop has no tilt error; the damped loop
# above does.
tuned = schuler_gains(reference="pure").loop()
print(f"Schuler-tuned loop: poles {', '.join(f'{abs(p.real):.1g}{p.imag:+.5g}j' for p in tuned.poles())} 1/s: {tuned.stability}, period {tuned.schuler_period / 60:.2f} min")
for name, lp in (("Schuler-tuned", tuned), ("damped, ω_n = 0.01", loop)):
    print(f"{name:>18}: peak tilt error after 20 m/s² for 20 s = {lp.peak_tilt_error(20.0, 20.0):.3e} rad")

# %%
# The Schuler error budget
# ------------------------
# What the tuned stage does with constant sensor errors, in closed form, checked
# against the stage recursion: gyro drift d = (10⁻⁷, 2·10⁻⁸, −10⁻⁷) rad/s and
# accelerometer bias b = (10⁻³, 0, −2·10⁻³) m/s² (level axes north, up, east).
# The pitch oscillates at the Schuler period about ``b₁/g`` with the drift's
# amplitude ``d₃/Ω_s``; the yaw grows as ``d₂ t``.
budget = schuler_error_budget((1e-7, 2e-8, -1e-7), (1e-3, 0.0, -2e-3))
budget_check = check_error_budget(budget, duration=6000.0, step=2.0)
drift_amplitude, bias_amplitude = budget.pitch_amplitudes
print(f"pitch amplitudes: drift {drift_amplitude:.3e} rad, bias {bias_amplitude:.3e} rad")
print(f"closed form against the simulation: {budget_check.max_difference:.1e} rad on errors up to {budget_check.scale:.2e} rad")

fig, ax = plt.subplots(figsize=(7, 3.6), layout="constrained")
for i, label in ((1, "Δθ (pitch)"), (2, "Δγ (roll)"), (0, "Δψ (yaw)")):
    line = ax.plot(budget_check.time, budget_check.simulated[:, i], lw=1.2, label=f"{label}, stage recursion")[0]
    ax.plot(budget_check.time[::60], budget_check.predicted[::60, i], "o", ms=3, color=line.get_color(), label=f"{label}, closed form")
ax.set(title="Schuler-tuned stage: constant drift and bias", xlabel="t [s]", ylabel="error [rad]")
ax.legend(fontsize=7)
plt.show()
