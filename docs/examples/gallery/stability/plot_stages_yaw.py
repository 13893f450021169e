"""
The yaw through the composition of stages
=========================================

Every correction of stage 1 cancels in the composite ``ν₁ ∘ ν`` of
Plotnikov's (2.6) (derived symbolically in
:mod:`strapdown.derivations.multistage.composition`): the composite's yaw
follows the gyros. With stage 1 correcting the horizontal components 1 and 3
(left) neither yaw error grows; with stage 1 correcting all four components
(right) its own yaw is pulled toward zero while the true yaw grows with the
Earth's rotation, and the composite keeps the gyro yaw
(:func:`~strapdown.analysis.multistage.composition.yaw_study`).

Report figure ``stability-yaw.png`` (2000 s, as in the quick report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.multistage.composition import yaw_study
from strapdown.analysis.multistage.trajectory import Scenario
from strapdown.derivations.multistage.published import PAPER, PRINTED_GAINS

study = yaw_study(Scenario(duration=2000.0), step=0.2, rng=np.random.SeedSequence(1))
for r in study.readings:
    print(f"stage 1 on components {r.components}: peak yaw after stage 1 {r.stage1_peak:.2e} rad, after two stages {r.two_stage_peak:.2e} rad")

fig, axes = plt.subplots(1, 2, figsize=(12, 3.8), layout="constrained")
for ax, r in zip(axes, study.readings):
    ax.plot(r.series_time, r.series_stage1, lw=0.9, label="after stage 1")
    ax.plot(r.series_time, r.series_two_stage, lw=0.9, label="after two stages")
    ax.axhline(PAPER.yaw_stage1.value, color="C0", ls=":", lw=0.8, label="paper: stage 1")
    ax.axhline(PAPER.yaw_two_stage.value, color="C1", ls=":", lw=0.8, label="paper: two stages")
    ax.axvline(PRINTED_GAINS.switch_time, color="0.6", lw=0.6)
    ax.set_title("stage 1 corrects " + ("components 1, 3" if r.components == (1, 3) else "all four components"))
    ax.set_xlabel("t [s]")
    ax.set_ylabel("Δψ [rad]")
    ax.legend(fontsize=6)
plt.show()
