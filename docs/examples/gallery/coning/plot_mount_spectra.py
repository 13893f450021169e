"""
The IMU's spectra through its mount
===================================

A linear random-vibration profile of an airframe rack (breakpoints in g²/Hz and
slopes in dB/octave, :func:`~strapdown.analysis.vibration.profile.load_profile`)
at the base of a 1 kg IMU block on four elastomer isolators
(:func:`~strapdown.analysis.vibration.mount.load_mount`). The mount's transfer
matrix gives the IMU's cross-spectral density
(:func:`~strapdown.analysis.vibration.mount_response.output_density`): above,
the specific force against the base profile; below, the angular rates and the
quadrature spectra between two rate axes, the part that cones. Grey lines: the
mount's natural frequencies.

Report figure ``mount-spectra.png``.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG, STANDARD_GRAVITY
from strapdown.analysis.vibration.examples import AIRFRAME_PROFILE, ISOLATED_MOUNT
from strapdown.analysis.vibration.mount import load_mount
from strapdown.analysis.vibration.mount_response import output_density
from strapdown.analysis.vibration.profile import load_profile

excitation = load_profile(AIRFRAME_PROFILE)
mount = load_mount(ISOLATED_MOUNT)
for i, mode in enumerate(mount.modes()):
    print(f"mode {i + 1}: {mode.frequency:6.2f} Hz, damping {mode.damping_ratio:.3f}, {mode.description}")

f = np.geomspace(*excitation.band, 300)
g = output_density(mount, excitation, f)
fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.2, 6.6), sharex=True, layout="constrained")
top.loglog(f, excitation.linear[0].at(f) / STANDARD_GRAVITY**2, "k--", label="base acceleration, each axis")
for i, axis in enumerate("xyz"):
    top.loglog(f, np.real(g[:, 3 + i, 3 + i]) / STANDARD_GRAVITY**2, label=f"IMU specific force {axis}")
    bottom.loglog(f, np.real(g[:, i, i]) / DEG**2, label=f"IMU angular rate {axis}")
for (a, b), style in zip(((0, 1), (1, 2), (2, 0)), ("k-", "k--", "k:")):
    bottom.loglog(f, np.abs(np.imag(g[:, a, b])) / DEG**2, style, lw=0.9, label=f"|quadrature| ω{'xyz'[a]}–ω{'xyz'[b]}")
top.set_ylabel("density [g²/Hz]")
top.set_ylim(1e-7, 1e0)
bottom.set_ylabel("density [(deg/s)²/Hz]")
bottom.set_ylim(1e-6, 1e3)
bottom.set_xlabel("frequency [Hz]")
for ax in (top, bottom):
    ax.legend(loc="lower left", fontsize=7)
    for mode in mount.modes():
        ax.axvline(mode.frequency, color="0.75", lw=0.6, zorder=0)
plt.show()
