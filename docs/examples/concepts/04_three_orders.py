r"""
Three orders
============

"A fourth-order algorithm" can mean three different things, and for the
coning-optimised algorithms of the literature they differ. The package keeps
them apart and names each:

**Local-error order ρ** — a property of the algorithm alone. Over one step the
error of the rotation-vector increment is :math:`O(h^{\rho+1})` for a *general*
motion (:func:`~strapdown.derivations.coning.series.local_error`; the ``order``
column of ``strapdown algorithms list``).

**Coning-drift order m** — under classical coning (half-cone angle α, rate ω)
the drift is

.. math::

   u = c\,\alpha^2\,\omega\,(\omega h)^m + O(\alpha^4),

and m is the power of ωh of the leading α² term
(:func:`~strapdown.derivations.coning.drift.coning_drift`; ``strapdown derive
coning-drift``). Coning-optimised algorithms raise m far above ρ.

**Drift order at a motion** — the power of the step in the drift actually seen
at a given motion, every power of the angle included: :math:`u_a = K H^{\rho}`
with the leading nonvanishing term of the drift series
(:func:`~strapdown.analysis.coning.drift_theory.asymptotic_order`; the "drift
order" that ``strapdown drift`` prints). At a finite cone angle the α⁴ term
has its own, lower power of ωh; below some sample rate it wins.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.algorithm_summary import cross_step_local_exponent
from strapdown.analysis.coning.batch import simulate_batch
from strapdown.analysis.coning.drift_theory import asymptotic_order, coning_drift, coning_drift_rate, drift_series
from strapdown.analysis.core.roundoff import drift_floor
from strapdown.derivations.coning.registry import get
from strapdown.derivations.coning.series import local_error

# %%
# The three orders of a few algorithms
# ------------------------------------
# The drift order is taken at 1° of coning (ε = −1) and at a regular precession
# with ε = 0.5, both with a 1° nutation angle.
names = ["one-sample", "two-sample", "savage-1+1", "miller-3", "compressed-4", "ignagni-1996-6", "panov-4s-3", "lebedev-panov-6"]
print(f"{'algorithm':>16}  N  prev  local-error ρ  coning-drift m  drift order: coning 1°, ε = 0.5")
for name in names:
    a = get(name)
    rho = local_error(a).order
    m = coning_drift(a).order
    cone = int(asymptotic_order(a, -1.0, np.radians(1.0)))
    precession = int(asymptotic_order(a, 0.5, np.radians(1.0)))
    print(f"{name:>16}  {a.samples}  {a.history:>4}  {rho:>12}  {m:>14}  {cone:>18}, {precession}")

# %%
# Reading the table:
#
# * ``panov-4s-3`` is of local-error order 4, but its fourth-order drift
#   cancels under coning (a symmetry of the motion), so under coning it drifts
#   at order 6 in the step; under a precession with ε = 0.5 it is fourth order
#   again.
# * The coning-optimised algorithms (``compressed-4``, ``ignagni-1996-6``) have
#   a local-error order of only 3 — they are *less* accurate than two-sample
#   for a general motion — and a coning-drift order of 8 or 10. At 1° their
#   drift order is nevertheless 4: the α⁴ term, of order 4 in ``ωh``.
#
# The local-error order can be measured without the series: on a tumbling
# motion with no symmetry, the one-step error falls as ``H^(ρ+1)``
# (:func:`~strapdown.analysis.coning.algorithm_summary.cross_step_local_exponent`).
for name in ("two-sample", "compressed-4", "lebedev-panov-6"):
    print(f"{name:>16}: measured exponent {cross_step_local_exponent(get(name)):.2f}, series ρ + 1 = {local_error(get(name)).order + 1}")

# %%
# Where the coning-drift order stops describing the drift
# -------------------------------------------------------
# ``compressed-4`` under 10 Hz coning, simulated over 20 s at eight gyro rates
# (the ``numpy`` engine of the simulator, which needs no compilation), against
# the α² closed form (slope m = 8) and the drift series summed through weight 9
# (every power of α). At α = 1° the simulation follows the series, whose α⁴
# term has slope 4, over the whole range. At α = 0.1° the closed form holds
# until the α⁴ term takes over, which happens only where the drift has
# nearly reached the round-off floor of a float64 run. (At the lowest rates the
# series, truncated at weight 9, falls a little short of the simulation.)
algorithm = get("compressed-4")
omega = 2 * np.pi * 10.0
h = np.geomspace(1 / 100, 1 / 2000, 8)
floor = drift_floor(omega, -omega)

fig, ax = plt.subplots(figsize=(7, 4.6), layout="constrained")
print(f"{'α':>5} {'gyro rate':>10} {'simulated':>10} {'series':>10} {'α² form':>10}  [rad/s]")
for alpha_deg, colour in ((1.0, "C0"), (0.1, "C1")):
    alpha = np.radians(alpha_deg)
    simulated = simulate_batch(algorithm, -1.0, omega, alpha, h, 20.0, engine="numpy").drift_rate
    closed = coning_drift_rate(algorithm, cone_angle=alpha, nu=omega, sample_interval=h)
    series = drift_series(algorithm, eps=-1.0, nu=omega, nutation=alpha, step=algorithm.samples * h, max_weight=9)
    resolved = simulated > 10 * floor
    ax.loglog(1 / h, closed, "--", color=colour, label=f"α = {alpha_deg:g}°: α² closed form (slope {coning_drift(algorithm).order})")
    ax.loglog(1 / h, series, "-", color=colour, lw=0.8, label=f"α = {alpha_deg:g}°: drift series, all powers of α")
    ax.loglog(1 / h[resolved], simulated[resolved], "o", color=colour, mfc="none", label=f"α = {alpha_deg:g}°: simulated (above 10× the floor)")
    for k in range(h.size):
        print(f"{alpha_deg:4g}° {1 / h[k]:7.1f} Hz {simulated[k]:10.3e} {series[k]:10.3e} {closed[k]:10.3e}")
ax.axhline(floor, color="0.5", lw=0.8, ls=":", label="round-off floor of a float64 run")
ax.set_xlabel("gyro rate 1/h [Hz]")
ax.set_ylabel("drift along the cone axis [rad/s]")
ax.set_title("compressed-4 under 10 Hz coning")
ax.legend(fontsize=7, loc="lower left")
plt.show()

# %%
# What to quote
# -------------
# Quote the local-error order for a general motion, the coning-drift order
# with its coefficient for small cone angles, and check at the actual angle
# and rate which term of the drift series leads before extrapolating with
# either. The task page :doc:`../tasks/01_algorithm_and_rate` does this for a
# budget.
