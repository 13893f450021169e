"""
Step and impulse responses of the stage loops
=============================================

The tilt error of three section-5 loops of Plotnikov (1999) after a step and
an impulse of horizontal acceleration, and after a step of gyro drift
(:func:`~strapdown.analysis.multistage.tilt_loop.responses`, python-control's
responses of the loop's transfer functions).

Report figure ``stability-responses.png``.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.multistage.readings import section5_loops
from strapdown.analysis.multistage.tilt_loop import responses

loops = section5_loops(9.81, 6.371e6)
t = np.linspace(0.0, 3000.0, 1501)
fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), layout="constrained")
for named in (loops[0], loops[2], loops[3]):
    resp = responses(named.loop, t)
    axes[0].plot(t, resp.accel_step, label=named.label)
    axes[1].plot(t, resp.accel_impulse, label=named.label)
    axes[2].plot(t, resp.drift_step, label=named.label)
    print(f"{named.label}: tilt error per m/s² of acceleration at 3000 s {resp.accel_step[-1]:.3e} rad")
axes[0].set_title("tilt error, acceleration step\n[rad per m/s²]")
axes[1].set_title("tilt error, acceleration impulse\n[rad per m/s]")
axes[2].set_title("tilt error, drift step\n[rad per rad/s]")
for ax in axes:
    ax.set_xlabel("t [s]")
axes[0].legend(fontsize=6)
plt.show()
