"""
Section 5 of Plotnikov (1999): one and two stages
=================================================

The example of section 5 on a consistent truth model over the rotating Earth
(:class:`~strapdown.analysis.multistage.trajectory.Scenario`): 1000 s at
rest, rocking with a decaying envelope, then 20 m/s² for 20 s, the gains of
stage 2 switched to Schuler tuning at 600 s. Errors are Krylov-angle
differences, estimate minus truth, after stage 1 and after the two stages
(:func:`~strapdown.analysis.multistage.stages.simulate`). Dotted: the values
the paper prints.

Report figure ``stability-scenario.png`` (the quick report's step of 0.2 s).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.multistage.stages import simulate
from strapdown.analysis.multistage.trajectory import Scenario
from strapdown.derivations.multistage.published import PAPER, PRINTED_GAINS

scenario = Scenario()
result = simulate(scenario, step=0.2, rng=np.random.SeedSequence(1))
stage1, two_stages = result.peaks()
print(f"peak pitch error: stage 1 {stage1.pitch:.3e} rad, two stages {two_stages.pitch:.3e} rad "
      f"(paper: {PAPER.stage1_pitch_peak.value:.1e}, ≤ {PAPER.two_stage_pitch_bound.value:.1e})")  # fmt: skip

fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True, layout="constrained")
for i, label in enumerate(["Δψ (yaw)", "Δθ (pitch)", "Δγ (roll)"]):
    axes[i].plot(result.time, result.errors[0, :, i], lw=0.8, label="after stage 1")
    axes[i].plot(result.time, result.errors[1, :, i], lw=0.8, label="after two stages")
    axes[i].set_ylabel(f"{label} [rad]")
    for t in (PRINTED_GAINS.switch_time, scenario.accel_start):
        axes[i].axvline(t, color="0.6", lw=0.6)
axes[1].axhline(PAPER.stage1_pitch_peak.value, color="C0", ls=":", lw=0.8, label="paper: stage-1 peak")
axes[1].axhline(PAPER.two_stage_pitch_bound.value, color="C1", ls=":", lw=0.8, label="paper: two-stage bound")
axes[1].axhline(-PAPER.two_stage_pitch_bound.value, color="C1", ls=":", lw=0.8)
axes[1].set_ylim(-0.06, 0.12)
axes[0].legend(fontsize=7, loc="lower right")
axes[1].legend(fontsize=7, loc="upper right")
axes[2].set_xlabel("t [s] (grey: gain switch at 600 s, start of the acceleration)")
plt.show()
