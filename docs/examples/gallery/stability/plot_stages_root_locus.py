"""
Poles and root loci of the stage loops
======================================

The linearised tilt channel of a stage, ``s² + Ks + L``, as python-control
systems: the root locus over the position gain k at three integral gains (the
stage-1 and stage-2 gains of Plotnikov's section 5, and Schuler tuning), and
over the integral gain l at two position gains
(:func:`~strapdown.analysis.multistage.tilt_loop.root_locus_k`,
:func:`~strapdown.analysis.multistage.tilt_loop.root_locus_l`). Crosses: the
poles of the section-5 loops
(:func:`~strapdown.analysis.multistage.readings.section5_loops`).

Report figure ``stability-root-locus.png``.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.multistage.readings import section5_loops
from strapdown.analysis.multistage.tilt_loop import StageLoop, root_locus_k, root_locus_l
from strapdown.derivations.multistage.published import PRINTED_GAINS

g, r = 9.81, 6.371e6
loops = section5_loops(g, r)
for named in loops:
    wn, zeta, poles = named.loop.damp()
    print(f"{named.label}: poles {', '.join(f'{p.real:.3g}{p.imag:+.3g}j' for p in poles)}, ζ = {zeta[0] + 0.0:.3g}, {named.loop.stability}")

fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), layout="constrained")
ks = np.concatenate([[0.0], np.logspace(-4, -0.5, 120)])
for l, colour in [(PRINTED_GAINS.stage1[1], "C0"), (PRINTED_GAINS.stage2_before[1], "C1"), (StageLoop.schuler(g, r).l, "C2")]:
    loci = root_locus_k(l, ks).loci
    axes[0].plot(loci.real.ravel(), loci.imag.ravel(), ".", ms=2, color=colour, label=f"l = {l:.3g} s⁻², k from 0 to 0.3")
ls = np.concatenate([[0.0], np.logspace(-7, -3, 120)])
for k, colour in [(PRINTED_GAINS.stage1[0], "C3"), (PRINTED_GAINS.stage2_before[0], "C4")]:
    loci = root_locus_l(k, ls).loci
    axes[1].plot(loci.real.ravel(), loci.imag.ravel(), ".", ms=2, color=colour, label=f"k = {k:g} s⁻¹, l from 0 to 1e-3")
for named in loops:
    p = named.loop.poles()
    for ax in axes:
        ax.plot(p.real, p.imag, "x", ms=7, mew=1.5, color="k")
axes[0].set_title("root locus over k (× : poles of the section-5 loops)")
axes[1].set_title("root locus over l")
for ax in axes:
    ax.set_xlabel("Re s [1/s]")
    ax.set_ylabel("Im s [1/s]")
    ax.legend(loc="lower left", fontsize=7)
axes[0].set_xlim(-0.03, 0.002)
axes[0].set_ylim(-0.015, 0.015)
axes[1].set_xlim(-0.02, 0.002)
axes[1].set_ylim(-0.03, 0.03)
plt.show()
