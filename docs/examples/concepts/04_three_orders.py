r"""
Three orders
============

"A fourth-order algorithm" can mean three different things, and for the
coning-optimised algorithms of the literature they differ. The package names
each one once, and uses the name alike in the library (the attributes of its
results), the command line and its JSON keys, this site and the reports (the
package docstring, section "Orders", :mod:`strapdown.analysis`).

Every order is read off a **weight**: the power of h of a term of the local
error, or of ν and H of a term ``d_w ν^w H^(w−1)`` of the drift series.
``--max-order K`` keeps the weights through K.

**Accuracy order ρ** (``accuracy_order``) — a property of the algorithm
alone. Over one step the error of the rotation-vector increment is
:math:`O(h^{\rho+1})` for a *general* motion, so the error over a fixed time
is :math:`O(h^{\rho})`: the ρ of Table 2 of Budennyi, Kalinovsky, Panov et al.
The same fact named by the weight of the leading local error is the
**local-error order ρ + 1** (``local_error_order``)
(:func:`~strapdown.derivations.coning.series.local_error`; ``strapdown
algorithms list``, ``strapdown derive local-error``).

**Coning-drift order m** (``coning_drift_order``) — under classical coning
(half-cone angle α, rate ω) the drift is

.. math::

   u = c\,\alpha^2\,\omega\,(\omega h)^m + O(\alpha^4),

and m is the power of ωh of the leading α² term
(:func:`~strapdown.derivations.coning.drift.coning_drift`; ``strapdown derive
coning-drift``). m ≥ ρ, and coning-optimised algorithms raise m far above ρ.

**Drift order at a motion** (``drift_order``) — the power of H of the leading
term of the drift actually seen at a given motion, every power of the angle
included: its weight minus one, :math:`u_a = K H^{\rho}` with the ρ of Table 3
of the same paper
(:func:`~strapdown.analysis.coning.drift_theory.asymptotic_order`; the "drift
order" that ``strapdown drift`` prints). At a finite cone angle the α⁴ term
has its own power of ωh, lower than m for the coning-optimised algorithms: the
drift order then lies below m.

An **observed** order is an exponent measured by halving h: of the one-step
error (it estimates ρ + 1) or of a simulated drift (it estimates the drift
order at that motion, where the leading term dominates).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.algorithm_summary import cross_step_local_exponent, summarize
from strapdown.analysis.coning.batch import simulate_batch
from strapdown.analysis.coning.coning_validity import next_coning_term
from strapdown.analysis.coning.drift_theory import asymptotic_order, coning_drift, coning_drift_rate
from strapdown.analysis.coning.exact_drift import exact_coning_drift
from strapdown.analysis.core.roundoff import drift_floor
from strapdown.derivations.coning.registry import get

# %%
# The orders of a few algorithms
# ------------------------------
# :func:`~strapdown.analysis.coning.algorithm_summary.summarize` gives the
# accuracy, local-error and coning-drift orders (the columns of ``strapdown
# algorithms list``); the drift order is taken at 1° of coning (ε = −1) and at
# a regular precession with ε = 0.5, both with a 1° nutation angle.
names = ["one-sample", "two-sample", "savage-1+1", "miller-3", "panov-4s-3", "lebedev-panov-6", "compressed-4", "ignagni-1996-5", "ignagni-1996-6"]
print(f"{'':>16}  {'':>1}  {'':>4}  {'accuracy':>8}  {'local-error':>11}  {'coning-drift':>12}  drift order")
print(f"{'algorithm':>16}  N  prev  {'ρ':>8}  {'ρ + 1':>11}  {'m':>12}  coning 1°, ε = 0.5")
for name in names:
    a = get(name)
    s = summarize(a)
    cone = int(asymptotic_order(a, -1.0, np.radians(1.0)))
    precession = int(asymptotic_order(a, 0.5, np.radians(1.0)))
    print(f"{name:>16}  {a.samples}  {a.history:>4}  {s.accuracy_order:>8}  {s.local_error_order:>11}  {s.coning_drift_order:>12}  {cone:>9}, {precession}")

# %%
# Reading the table:
#
# * For the classical algorithms (``one-sample``, ``two-sample``) the three
#   coincide: m = ρ, and the drift order is ρ at both motions.
# * ``panov-4s-3`` has accuracy order 4, but its H⁴ drift cancels under coning
#   (a symmetry of the motion): its coning-drift order is 6, and so is its
#   drift order under coning; under a precession with ε = 0.5 its drift order
#   is 4 again.
# * The coning-optimised algorithms (``compressed-4``, Ignagni's) have an
#   accuracy order of only 3 — they are *less* accurate than ``two-sample``
#   for a general motion — and a coning-drift order of 8 or 10. At 1° their
#   drift order is nevertheless 4: the α⁴ term, of power 4 in ``ωh``, leads.
#   ``miller-3`` (m = 6) does the same.
#
# The local-error order can be observed without the series: on a tumbling
# motion with no symmetry, the one-step error falls as ``h^(ρ+1)`` when h is
# halved
# (:func:`~strapdown.analysis.coning.algorithm_summary.cross_step_local_exponent`).
for name in ("two-sample", "compressed-4", "lebedev-panov-6"):
    a = get(name)
    print(f"{name:>16}: observed exponent {cross_step_local_exponent(a):.2f}, local-error order ρ + 1 = {summarize(a).local_error_order}")

# %%
# Where the coning-drift order stops describing the drift
# -------------------------------------------------------
# ``compressed-4`` under 10 Hz coning, simulated over 20 s at gyro rates from
# 100 Hz to 3.2 kHz, each twice the one before (the ``numpy`` engine of the
# simulator, which needs no compilation). Beside the simulation: the α² closed
# form (slope m = 8), the leading α⁴ term
# (:func:`~strapdown.analysis.coning.coning_validity.next_coning_term`, slope
# 4) and the exact drift, every order in α and ωh
# (:func:`~strapdown.analysis.coning.exact_drift.exact_coning_drift`: one step
# in extended precision, no series, no simulation).
algorithm = get("compressed-4")
omega = 2 * np.pi * 10.0
h = 1 / (100.0 * 2.0 ** np.arange(6))
floor = drift_floor(omega, -omega)
m = coning_drift(algorithm).order
quartic = next_coning_term(algorithm)
print(f"α² term: c = {coning_drift(algorithm).coefficient}, m = {m}; α⁴ term: c₄ = {quartic.coefficient}, power {quartic.order}")

fig, ax = plt.subplots(figsize=(7, 4.6), layout="constrained")
print(f"{'α':>5} {'gyro rate':>10} {'simulated':>10} {'exact':>10} {'α² form':>10} {'α⁴ term':>10}  [rad/s]")
observed = {}
for alpha_deg, colour in ((1.0, "C0"), (0.1, "C1")):
    alpha = np.radians(alpha_deg)
    simulated = simulate_batch(algorithm, -1.0, omega, alpha, h, 20.0, engine="numpy").drift_rate
    exact = np.array([exact_coning_drift(algorithm, cone_angle=alpha, nu=omega, sample_interval=x) for x in h])
    closed = coning_drift_rate(algorithm, cone_angle=alpha, nu=omega, sample_interval=h)
    fourth = np.array([quartic.value(alpha, omega, x) for x in h])
    resolved = simulated > 10 * floor
    ax.loglog(1 / h, np.abs(exact), "-", color=colour, lw=1.2, label=f"α = {alpha_deg:g}°: exact drift")
    ax.loglog(1 / h, closed, "--", color=colour, lw=0.8, label=f"α = {alpha_deg:g}°: α² closed form (slope {m})")
    ax.loglog(1 / h, np.abs(fourth), ":", color=colour, lw=0.8, label=f"α = {alpha_deg:g}°: α⁴ term (slope {quartic.order})")
    ax.loglog(1 / h[resolved], simulated[resolved], "o", color=colour, mfc="none", label=f"α = {alpha_deg:g}°: simulated (above 10× the floor)")
    for k in range(h.size):
        print(f"{alpha_deg:4g}° {1 / h[k]:7.0f} Hz {simulated[k]:10.3e} {exact[k]:10.3e} {closed[k]:10.3e} {fourth[k]:10.3e}")
    both = resolved[:-1] & resolved[1:]
    observed[alpha_deg] = [(1 / h[k], 1 / h[k + 1], np.log2(simulated[k] / simulated[k + 1])) for k in np.flatnonzero(both)]
ax.axhline(floor, color="0.5", lw=0.8, ls=":", label="round-off floor of a float64 run")
ax.set_xlabel("gyro rate 1/h [Hz]")
ax.set_ylabel("drift along the cone axis [rad/s]")
ax.set_title("compressed-4 under 10 Hz coning")
ax.legend(fontsize=7, loc="lower left")
plt.show()

# %%
# The observed order of the drift, from each halving of h where both runs are
# resolved, beside the coning-drift order and the drift order at 1°:
for alpha_deg, rows in observed.items():
    print(f"α = {alpha_deg:g}°: " + ", ".join(f"{a:.0f}→{b:.0f} Hz: {p:.2f}" for a, b, p in rows))
print(f"coning-drift order m = {m}; drift order at 1°: {int(asymptotic_order(algorithm, -1.0, np.radians(1.0)))}")

# %%
# At α = 1° the simulation follows the exact drift at every rate; the α² term
# alone understates it even at 100 Hz and is below the α⁴ term from 200 Hz on,
# and as h falls the observed order settles on 4, the drift order at this
# angle. At α = 0.1° the α⁴ term is a hundred times smaller: the α² term, of
# slope m = 8, is the drift (the observed order is close to 8) until the two
# meet, which happens only where the drift has nearly reached the round-off
# floor of a float64 run.
#
# What to quote
# -------------
# Quote the accuracy order for a general motion, the coning-drift order with
# its coefficient for small cone angles, and check at the actual angle and
# rate which term leads (``strapdown derive coning-drift`` gives the range
# where the leading term holds; ``strapdown drift`` the drift order there)
# before extrapolating with either. The task page
# :doc:`../tasks/01_algorithm_and_rate` does this for a budget.
