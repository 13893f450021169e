"""
Regular precession and classical coning
=======================================

Two ways of describing the test motion appear in the sources, and the package
uses both.

**Regular precession** (Lebedev & Panov 1989, eq. (4.1)): the body spins at
the rate ν about its own z axis while that axis precesses at the rate μ = εν
about an axis n fixed in I, at the nutation angle ϑ. The body rate is

.. math::

   \\omega(t) = \\nu\\,(\\varepsilon \\sin\\vartheta \\sin\\nu t,\\;
   \\varepsilon \\sin\\vartheta \\cos\\nu t,\\; 1 + \\varepsilon\\cos\\vartheta).

Its three parameters (ε, ν, ϑ) are the arguments ``eps``, ``nu``,
``nutation`` of :class:`~strapdown.analysis.coning.precession.RegularPrecession`
and the options ``--eps``, ``--freq-hz``, ``--nutation-deg`` of
``strapdown drift``. Budennyi, Kalinovsky, Panov et al. run their Table 3 at
ε = −1 and ε = 0.5.

**Classical coning** (Ignagni, Savage and most of the literature): a body
axis describes a cone of half-angle α at the coning rate ω. Its body rate has
a transverse part of amplitude ``ω sin α`` turning at ω and a constant axial
part ``ω (1 − cos α)``.

Classical coning **is** the regular precession with ε = −1, ϑ = α, ν = ω: the
spin and the precession cancel except for the small axial rate. The cone axis
(the direction of the mean angular velocity of the body in I) is −n.
``strapdown drift`` takes either description: ``--eps`` and ``--nutation-deg``
for a regular precession, or ``--half-angle-deg`` for classical coning (with
``--freq-hz`` the coning frequency), and quotes a coning drift along the cone
axis.
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.coning.drift_theory import asymptotic_drift, asymptotic_order, coning_drift_rate
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.units import deg_per_h
from strapdown.derivations.coning.registry import get

alpha, f = np.radians(1.0), 10.0
omega = 2 * np.pi * f
coning = RegularPrecession(eps=-1.0, nu=omega, nutation=alpha)

# %%
# The body rate of ε = −1 is the classical coning rate
# ----------------------------------------------------
t = np.linspace(0.0, 1 / f, 200, endpoint=False)  # one coning period
rate = coning.omega(t)
transverse = np.linalg.norm(rate[:, :2], axis=1)
print(f"transverse amplitude: {transverse.min():.6f} … {transverse.max():.6f} rad/s   (ω sin α = {omega * np.sin(alpha):.6f})")
print(f"axial rate:           {rate[:, 2].min():.3e} … {rate[:, 2].max():.3e} rad/s   (ω (1 − cos α) = {omega * (1 - np.cos(alpha)):.3e})")

# %%
# The body's z axis stays at the angle α from the precession axis n while it
# goes round it once per period. The mean angular velocity of the body in I,
# ``−ω (1 − cos α) n``, points the other way: that is the cone axis along which
# the package quotes a coning drift.
attitude = quat.multiply(quat.conjugate(coning.attitude(0.0)), coning.attitude(t))  # a run started at Λ(0) = 1
z_in_I = quat.rotate(attitude, np.array([0.0, 0.0, 1.0]))
n = coning.precession_axis()
angle = np.degrees(np.arccos(np.clip(z_in_I @ n, -1.0, 1.0)))
print(f"angle between the body z axis and n: {angle.min():.9f}° … {angle.max():.9f}°")
mean_rate = quat.rotate(attitude, rate).mean(axis=0)
print(f"mean angular velocity in I: {mean_rate @ n:+.4e} n rad/s   (−ω (1 − cos α) = {-omega * (1 - np.cos(alpha)):+.4e})")

# %%
# The same drift, described either way
# ------------------------------------
# The closed form of the coning drift takes the classical parameters (α, ω, h);
# the asymptotic drift of the regular precession takes (ε, ν, ϑ, H). The first
# keeps every power of ωh at order α², the second the leading power of H at
# every order in ϑ; at a small angle and ωh they agree to within what each
# leaves out:
algorithm = get("two-sample")
h = 1 / 400
u_coning = coning_drift_rate(algorithm, cone_angle=alpha, nu=omega, sample_interval=h)
u_precession = asymptotic_drift(algorithm, eps=-1.0, nu=omega, nutation=alpha, step=algorithm.samples * h)
print(f"closed form (α, ω, h):          {deg_per_h(u_coning):.5e} deg/h")
print(f"precession series (ε, ν, ϑ, H): {deg_per_h(u_precession):.5e} deg/h   ({u_precession / u_coning - 1:+.1%})")

# %%
# ε = 0.5 is a different motion
# -----------------------------
# The other case of Table 3, ε = 0.5, spins and precesses in the same sense:
# the body rate is large along the body z axis. It has less symmetry than
# coning, and an algorithm whose H⁴ drift cancels under coning (drift order 6
# there) has drift order 4 at ε = 0.5 (see :doc:`04_three_orders`).
precession = RegularPrecession(eps=0.5, nu=omega, nutation=alpha)
for name in ("panov-4s-3", "panov-4s-1"):
    a = get(name)
    print(f"{name}: drift order {int(asymptotic_order(a, -1.0, alpha))} under coning, {int(asymptotic_order(a, 0.5, alpha))} at ε = 0.5")

fig, axes = plt.subplots(1, 2, figsize=(9, 3.4), sharex=True, layout="constrained")
for ax, motion, title in ((axes[0], coning, "classical coning: ε = −1, ϑ = α = 1°"), (axes[1], precession, "regular precession: ε = 0.5, ϑ = 1°")):
    w = motion.omega(t)
    for k, label in enumerate(("ω₁", "ω₂", "ω₃")):
        ax.plot(t * 1e3, w[:, k], label=label)
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("t [ms]")
    ax.legend(fontsize=8)
axes[0].set_ylabel("body rate [rad/s]")
plt.show()
