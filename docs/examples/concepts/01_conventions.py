r"""
Conventions: quaternions, frames, rotation vectors, units
=========================================================

The package states its conventions once, in the docstring of
:mod:`strapdown.analysis`, and every module follows them. This page shows each
one at work, so that a number printed by the package can be read without
guessing.

* **Quaternions** are scalar first, ``(q0, q1, q2, q3)``, stored as arrays of
  shape ``(..., 4)``; the product ∘ is Hamilton's (:math:`i\circ j = k`).
* **Vectors** are arrays of shape ``(..., 3)``. Leading axes are batch or time.
* **Frames**: E is the body frame, I the reference (inertial) frame. The
  attitude quaternion Λ maps E to I and obeys the kinematic equation with the
  body rate ω resolved in E:

  .. math::

     v_I = \Lambda\circ v_E\circ\bar\Lambda, \qquad 2\dot\Lambda = \Lambda\circ\omega.

* **Rotation vectors** φ give
  :math:`\Lambda = (\cos\tfrac{|\varphi|}{2},\ \sin\tfrac{|\varphi|}{2}\,\varphi/|\varphi|)`.
* **Units** are SI, angles in radians; degrees and deg/h appear only at the
  command line and in the reports, through :mod:`strapdown.analysis.core.units`.
"""

import numpy as np

from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core import units

# %%
# Hamilton's product, scalar first
# --------------------------------
# The unit quaternions i and j multiply to k, and in the other order to −k.
i = np.array([0.0, 1.0, 0.0, 0.0])
j = np.array([0.0, 0.0, 1.0, 0.0])
print("i ∘ j =", quat.multiply(i, j))
print("j ∘ i =", quat.multiply(j, i))

# %%
# The attitude maps the body frame E to the reference frame I
# -----------------------------------------------------------
# A body turned by 90° about the common z axis: its x axis (in E) points along
# the y axis of I. The rotation vector of that attitude is ``(0, 0, π/2)``.
attitude = quat.rotvec_to_quat(np.array([0.0, 0.0, np.pi / 2]))
print("Λ =", np.round(attitude, 6))
print("body x axis seen in I:", np.round(quat.rotate(attitude, np.array([1.0, 0.0, 0.0])), 12))
print("rotation vector of Λ:", quat.quat_to_rotvec(attitude))

# %%
# Every routine takes leading batch axes: here 1000 random rotation vectors go
# to quaternions and back in one call.
rng = np.random.default_rng(1)
phi = rng.uniform(-1.0, 1.0, size=(1000, 3))
q = quat.rotvec_to_quat(phi)
print("shapes:", phi.shape, "->", q.shape)
print("largest round-trip error [rad]:", np.abs(quat.quat_to_rotvec(q) - phi).max())

# %%
# The kinematic equation 2Λ' = Λ ∘ ω, with ω in the body frame
# -------------------------------------------------------------
# The test motions of the package come with their exact attitude. For the
# regular precession of Lebedev & Panov (1989), eq. (4.1), a centred difference
# of the exact attitude satisfies the kinematic equation with the body rate on
# the right of the product, as it should when ω is resolved in E.
motion = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))
t, dt = 0.0123, 1e-6
lhs = 2 * (motion.attitude(t + dt) - motion.attitude(t - dt)) / (2 * dt)
right = quat.multiply(motion.attitude(t), quat.vector_to_quat(motion.omega(t)))
left = quat.multiply(quat.vector_to_quat(motion.omega(t)), motion.attitude(t))
print("|2Λ' − Λ∘ω| =", np.abs(lhs - right).max(), "  (ω resolved in E)")
print("|2Λ' − ω∘Λ| =", np.abs(lhs - left).max(), "  (the other order: not the convention)")

# %%
# Units at the edges only
# -----------------------
# Inside the library a rate is in rad/s and an angle in radians. The factors
# live in one module; the command line and the reports convert with them.
print(f"1 deg = {units.rad(1.0):.10f} rad")
print(f"1e-6 rad/s = {units.deg_per_h(1e-6):.6f} deg/h")
print(f"0.1 deg/h = {units.rad_per_s(0.1):.6e} rad/s")
