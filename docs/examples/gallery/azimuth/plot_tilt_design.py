"""
Admissible rocking in the tilt channel
======================================

The designer's answer in the paper's setting (the rocking reaches the
accelerometers, not the gyros): the largest rocking amplitude against
frequency for three azimuth budgets, by the rms (solid) and by 95 % of the
errors (dashed), at latitude 60° with the tilts averaged over 60 s at 10 Hz
(:func:`~strapdown.analysis.gyrocompass.admissible_rocking.admissible_amplitude`;
``strapdown azimuth-design``). For the sine the curves are the envelope over
phase; the grey line is the exact phase, jagged where whole periods fit in
the averaging time. Black dots: an independent Monte Carlo at the
admissible amplitudes (:func:`~strapdown.analysis.gyrocompass.studies.tilt_design_check`).

Report figure ``azimuth-design.png`` (16 frequencies and 400 trials per
check, as in the quick report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import rad
from strapdown.analysis.gyrocompass.admissible_rocking import admissible_amplitude
from strapdown.analysis.gyrocompass.studies import tilt_design_check

latitude, averaging = rad(60.0), 60.0
freqs = np.geomspace(0.02, 1.0, 16)
curves = {(kind, b): admissible_amplitude(rad(b), latitude, averaging, freqs, rocking=kind, damping=0.1) for kind in ("narrowband", "sine") for b in (0.05, 0.1, 0.5)}
exact_sine = admissible_amplitude(rad(0.1), latitude, averaging, freqs, rocking="sine", envelope=False)
check = tilt_design_check(rad(0.1), latitude, averaging, freqs, n_trials=400, check=(0, len(freqs) // 2, -1), rng=np.random.SeedSequence(1))
for f, a, r in zip(check.frequencies, check.amplitudes, check.results):
    print(f"narrow-band check at {f:.3g} Hz, amplitude {a * D:.3g}°: Monte Carlo rms {r.rms * D:.4f}° ({r.rms_ci[0] * D:.4f}–{r.rms_ci[1] * D:.4f}) for a 0.1° budget")

fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
for ax, kind in zip(axes, ("narrowband", "sine")):
    for b, colour in zip((0.05, 0.1, 0.5), ("C0", "C1", "C2")):
        d = curves[(kind, b)]
        ax.loglog(freqs, d.amplitude * D, color=colour, label=f"budget {b:g}°, rms")
        ax.loglog(freqs, d.amplitude_percentile * D, color=colour, ls="--", label=f"budget {b:g}°, {d.level:.0%} of |Δ|")
    ax.set_xlabel("rocking frequency [Hz]")
    ax.set_ylabel("admissible amplitude [deg]")
    ax.set_title(f"{kind}: φ = 60°, T = 60 s, 10 Hz" + (", ζ = 0.1" if kind == "narrowband" else ", envelope over phase"), fontsize=9)
axes[1].loglog(freqs, exact_sine.amplitude * D, color="0.6", lw=0.8, label="budget 0.1°, exact phase (jagged)")
axes[0].plot(check.frequencies, check.amplitudes * D, "ko", ms=4, label="Monte Carlo check")
for ax in axes:
    ax.legend(fontsize=6)
plt.show()
