r"""
The dual extension: velocity from attitude
==========================================

Lebedev & Panov (1989) treat attitude and apparent velocity together with dual
numbers :math:`x + s\,x^\circ`, :math:`s^2 = 0`. By the transfer principle
(Kotelnikov–Study) a formula valid for real arguments stays valid for dual
ones, and

.. math::

   f(x + s\,x^\circ) = f(x) + s\,f'(x)\,x^\circ :

the dual extension of a real formula is forward-mode differentiation.

The package uses this once and everywhere. :class:`~strapdown.analysis.core.dual.Dual`
is an array type that numpy ufuncs accept, so every routine written with
ordinary numpy operations evaluates its own dual extension when handed a
``Dual``. In particular:

* the **velocity (sculling) algorithm** is the coning algorithm evaluated on
  dual increments :math:`q_j = p_j + s\,b_j` (gyro and accelerometer
  increments), eq. (2.5) — no second formula is written;
* the **dual regular precession** (4.2)–(4.3) is the real one evaluated at the
  dual parameters :math:`\nu + s\,\nu^\circ`, :math:`\vartheta + s\,\vartheta^\circ`:
  its dual part is the apparent acceleration;
* the **biquaternion** :math:`\theta = \Lambda + s M` of a dual rotation vector,
  (1.12), is the dual extension of the real map from rotation vector to
  quaternion.
"""

import numpy as np

from strapdown.analysis.coning.evaluation import increment
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.dual import Dual
from strapdown.derivations.coning.registry import get

# %%
# Dual numbers differentiate
# --------------------------
x = Dual(0.5, 1.0)
y = np.sin(x) * np.exp(x)
print(f"f(0.5) = {y.re:.12f}, dual part {y.du:.12f}, f'(0.5) = {np.exp(0.5) * (np.sin(0.5) + np.cos(0.5)):.12f}")

# %%
# The velocity algorithm is the coning algorithm on dual increments
# -----------------------------------------------------------------
# The two-sample algorithm is ``Δφ = p₁ + p₂ + ⅔ p₁ × p₂``. Handed dual
# increments it returns ``ΔΦ = Δφ + s Δφ°`` whose dual part is
# ``b₁ + b₂ + ⅔ (p₁ × b₂ + b₁ × p₂)`` — the bilinear part of the classical
# sculling correction, with no velocity formula written anywhere.
rng = np.random.default_rng(0)
p = rng.normal(scale=1e-3, size=(2, 3))  # gyro increments [rad]
b = rng.normal(scale=1e-2, size=(2, 3))  # accelerometer increments [m/s]
algorithm = get("two-sample")
dual_increment = increment(algorithm, Dual(p, b))
by_hand = b[0] + b[1] + 2 / 3 * (np.cross(p[0], b[1]) + np.cross(b[0], p[1]))
print("Δφ  =", dual_increment.re)
print("Δφ° =", dual_increment.du)
print("largest difference from the hand-written sculling term:", np.abs(dual_increment.du - by_hand).max())

# %%
# The dual motion: its dual part is the acceleration
# --------------------------------------------------
# The regular precession with dual parts ν° [m/s²] and ϑ° [m/s] has the
# apparent acceleration as the dual part of its body rate. Checked against a
# finite-difference derivative of the *real* body rate, which uses no dual
# arithmetic at all:
nu, theta, nu_dual, theta_dual = 2 * np.pi, np.radians(10.0), 1.0, 0.5
motion = RegularPrecession(eps=-1.0, nu=nu, nutation=theta, nu_dual=nu_dual, nutation_dual=theta_dual)
t = np.linspace(0.0, 2.0, 7)
d = 1e-6
d_nu = (RegularPrecession(-1.0, nu + d, theta).omega(t) - RegularPrecession(-1.0, nu - d, theta).omega(t)) / (2 * d)
d_theta = (RegularPrecession(-1.0, nu, theta + d).omega(t) - RegularPrecession(-1.0, nu, theta - d).omega(t)) / (2 * d)
print("largest |a − (∂ω/∂ν ν° + ∂ω/∂ϑ ϑ°)| [m/s²]:", np.abs(motion.accel(t) - (d_nu * nu_dual + d_theta * theta_dual)).max())

# %%
# The biquaternion of a dual rotation vector
# ------------------------------------------
# The real map φ → Λ(φ), evaluated on ``Φ = φ + s φ°``, gives the unit
# biquaternion ``θ = Λ + s M`` of (1.12). Its dual part is the derivative of Λ
# along φ°, and the unit condition holds to round-off: ``Λ · M = 0`` (the dual
# part of ``|Λ|² = 1``). The errata page of the report lists the signs that the
# paper prints wrong in (1.12); this evaluation needs none of them.
phi, phi_dual = np.array([0.3, -0.2, 0.5]), np.array([1.0, 2.0, -0.5])
theta_bq = quat.rotvec_to_quat(Dual(phi, phi_dual))
numeric = (quat.rotvec_to_quat(phi + d * phi_dual) - quat.rotvec_to_quat(phi - d * phi_dual)) / (2 * d)
print("M =", theta_bq.du)
print("largest |M − dΛ/dφ · φ°|:", np.abs(theta_bq.du - numeric).max(), "  Λ · M =", float(theta_bq.re @ theta_bq.du))

# %%
# A velocity run
# --------------
# The simulator integrates attitude and apparent velocity together when asked
# (``velocity=True``): biquaternion steps from the dual increments, against the
# closed-form biquaternion of the motion (4.4)–(4.5). Here the dual motion
# above (ν = 2π s⁻¹, ϑ = 10°, ν° = 1 m/s², ϑ° = 0.5 m/s), 10 s on a 400 Hz
# gyro, with the algorithms of accuracy order 4 and 6 of Lebedev & Panov
# (1989), eq. (2.2); the numpy engine of the simulator needs no compilation for
# a run this short.
for name in ("lebedev-panov-4", "lebedev-panov-6"):
    run = simulate(get(name), motion, sample_interval=0.0025, duration=10.0, velocity=True, engine="numpy")
    print(f"{name}: |ΔW_E| = {run.final_dw_body:.3e} m/s, |ΔW_I| = {run.final_dw_inertial:.3e} m/s after {run.time[-1]:g} s")
