"""
Coning per mode band of an IMU mount
====================================

The mean coning drift of four algorithms at h = 1 ms in the environment an
airframe profile makes through the example IMU mount
(:func:`~strapdown.analysis.vibration.mount_response.mount_environment`,
:func:`~strapdown.analysis.vibration.mount_response.mount_drift`), split into the
bands around the mount's modes (between the geometric means of adjacent
natural frequencies), as magnitudes of the drift vectors, with the true coning
rate of each band beside them. The command line gives the same table:
``strapdown mount-environment --profile P --mount M --sample-interval 1e-3``.

Report figure ``mount-coning-by-mode.png``.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H
from strapdown.analysis.vibration.examples import AIRFRAME_PROFILE, ISOLATED_MOUNT
from strapdown.analysis.vibration.mount import load_mount
from strapdown.analysis.vibration.mount_response import mount_drift, mount_environment
from strapdown.analysis.vibration.profile import load_profile
from strapdown.derivations.coning.registry import get

h = 1e-3
response = mount_environment(load_mount(ISOLATED_MOUNT), load_profile(AIRFRAME_PROFILE))
algorithms = [get(n) for n in ("one-sample", "two-sample", "optimal-3", "ignagni-1996-5")]
d = mount_drift(algorithms, response, h)
for a, total in zip(algorithms, d.total_coning):
    print(f"{a.name:>15}: drift {np.round(total * RAD_PER_S_TO_DEG_PER_H, 6)} deg/h, |u| = {np.linalg.norm(total) * RAD_PER_S_TO_DEG_PER_H:.4g} deg/h")

x = np.arange(len(d.bands))
width = 0.8 / (len(algorithms) + 1)
fig, ax = plt.subplots(figsize=(7.2, 4.0), layout="constrained")
ax.bar(x - 0.4 + width / 2, np.linalg.norm(d.true_coning, axis=1) * RAD_PER_S_TO_DEG_PER_H, width, color="0.6", label="true coning rate")
for i, a in enumerate(algorithms):
    ax.bar(x - 0.4 + width * (i + 1.5), np.linalg.norm(d.coning[i], axis=1) * RAD_PER_S_TO_DEG_PER_H, width, label=a.name)
ax.set_yscale("log")
ax.set_xticks(x, [f"{b.low:.0f}–{b.high:.0f} Hz\nmode {', '.join(str(m + 1) for m in b.modes)}" for b in d.bands], fontsize=7)
ax.set_ylabel("|coning drift| per band [deg/h], h = 1 ms")
ax.legend(loc="upper right", fontsize=7, ncol=2)
plt.show()
