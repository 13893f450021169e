"""
The Schuler error budget
========================

Left: a Schuler-tuned stage with a constant gyro drift and accelerometer bias,
simulated by the stage recursion against the closed form of
:class:`~strapdown.analysis.multistage.gain_design.SchulerErrorBudget`
(:func:`~strapdown.analysis.multistage.gain_design.check_error_budget`).
Right: the two-stage pitch error of Plotnikov's section 5 after the switch to
Schuler tuning at 600 s, against the budget of the horizontal centripetal
acceleration that no accelerometer senses
(:func:`~strapdown.analysis.multistage.gain_design.section5_budget`).

Report figure ``stability-budget.png`` (the quick report's steps: 2 s for the
budget check, 0.2 s for section 5).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.multistage.gain_design import check_error_budget, schuler_error_budget, section5_budget
from strapdown.analysis.multistage.stages import simulate
from strapdown.analysis.multistage.trajectory import Scenario
from strapdown.derivations.multistage.published import PRINTED_GAINS

budget = schuler_error_budget((1e-7, 2e-8, -1e-7), (1e-3, 0.0, -2e-3))
check = check_error_budget(budget, duration=6000.0, step=2.0)
print(f"closed form against the simulation: {check.max_difference:.1e} rad on errors up to {check.scale:.2e} rad")

scenario = Scenario()
result = simulate(scenario, step=0.2, rng=np.random.SeedSequence(1))
predicted = section5_budget(scenario).errors(result.time)
after = result.time >= PRINTED_GAINS.switch_time
print(f"section 5, two-stage pitch after the switch: peak {np.abs(result.errors[1, after, 1]).max():.3e} rad, budget {np.abs(predicted[after, 1]).max():.3e} rad")

fig, axes = plt.subplots(1, 2, figsize=(12, 3.8), layout="constrained")
for i, label in ((1, "Δθ"), (2, "Δγ"), (0, "Δψ")):
    line = axes[0].plot(check.time, check.simulated[:, i], lw=1.2, label=f"{label} simulated")[0]
    axes[0].plot(check.time[::50], check.predicted[::50, i], "o", ms=3, color=line.get_color(), label=f"{label} closed form")
axes[0].set_title("Schuler-tuned stage, constant drift and bias")
axes[0].set_xlabel("t [s]")
axes[0].set_ylabel("error [rad]")
axes[0].legend(fontsize=6)
axes[1].plot(result.time, result.errors[1, :, 1], lw=0.8, label="Δθ after two stages (simulated)")
axes[1].plot(result.time[after], predicted[after, 1], "--", lw=1.2, label="budget: b₁/g − (Ω²R sin φ cos φ/g)(1 − cos Ω_s τ)")
axes[1].set_title("section 5: two-stage pitch error")
axes[1].set_xlabel("t [s]")
axes[1].legend(fontsize=6, loc="upper right")
plt.show()
