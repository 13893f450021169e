r"""
The sign of errors
==================

An error has a sign, and the package gives it one convention per kind of
error (package docstring of :mod:`strapdown.analysis`, "Errors").

**Errors of an algorithm** against the exact motion (coning, sculling) are
*exact minus algorithm*, on the symbolic side and the numeric side alike:

.. math::

   \delta\varphi = \Delta\varphi_{\mathrm{exact}} - \Delta\varphi_{\mathrm{algorithm}},
   \qquad
   \Lambda_{\mathrm{true}} = \exp(\delta\varphi_I)\circ\Lambda_{\mathrm{computed}},
   \qquad
   \Delta W = W_{\mathrm{true}} - W_{\mathrm{computed}}.

The first is the local error of one step; the second defines the attitude
error :math:`\delta\varphi_I`, the rotation vector of
:math:`\Lambda_{\mathrm{true}}\circ\bar\Lambda_{\mathrm{computed}}` with
components in frame I; the third the apparent-velocity errors (in E or I). A
drift is the slope of these errors and keeps their sign. Under coning,
**u > 0 means that the computed attitude lags the coning rotation**; a
rectification (sculling) error is positive when the algorithm under-rectifies.

**Errors of an estimator** against the truth (the corrected attitude stages,
the alignment filters) are *estimate minus truth*, as for any estimator.

This page checks the first convention three independent ways on one case:
the two-sample algorithm under 1° of coning at 10 Hz.
"""

import numpy as np

from strapdown.analysis.coning.drift_theory import coning_drift_rate
from strapdown.analysis.coning.evaluation import increment
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.sculling_motion import ScullingMotion, rectification_error
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.units import deg_per_h
from strapdown.derivations.coning.registry import get

algorithm = get("two-sample")
alpha, f, h = np.radians(1.0), 10.0, 1 / 400  # half-cone angle [rad], coning frequency [Hz], sample interval [s]
omega = 2 * np.pi * f
coning = RegularPrecession(eps=-1.0, nu=omega, nutation=alpha)  # classical coning (next pages)

# %%
# One step: the local error is exact minus algorithm
# --------------------------------------------------
# Over one step ``[0, H]``, ``H = 2h``, the exact rotation vector is that of
# ``Λ̄(0) ∘ Λ(H)``; the algorithm builds its own from the two gyro increments
# ``p_j = ∫ω dt`` of the step.
H = algorithm.samples * h
p = coning.grid_increments(h, 0, algorithm.samples)  # shape (2, 3): p_1, p_2
exact = quat.quat_to_rotvec(quat.multiply(quat.conjugate(coning.attitude(0.0)), coning.attitude(H)))
computed = increment(algorithm, p)
local_error = exact - computed
print("δφ = Δφ_exact − Δφ_algorithm =", local_error, "rad")

# %%
# A run: the attitude error and its drift
# ---------------------------------------
# The simulator runs the algorithm beside the exact solution and returns
# ``δφ_I = rotvec(Λ_true ∘ Λ̄_computed)`` after every step, and its
# least-squares slope (the drift vector, frame I). The run starts at
# ``Λ(0) = 1``, so its true attitude is ``P̄(0) ∘ P(t)`` with ``P`` the closed-form
# solution of the motion. The cone axis is found here from the motion alone: it
# is the direction of the mean angular velocity of the body seen in I,
# ``⟨Λ ∘ ω ∘ Λ̄⟩``, over one coning period.
run = simulate(algorithm, coning, sample_interval=h, duration=20.0)
t = np.linspace(0.0, 2 * np.pi / omega, 4096, endpoint=False)
true_attitude = quat.multiply(quat.conjugate(coning.attitude(0.0)), coning.attitude(t))
mean_rate = quat.rotate(true_attitude, coning.omega(t)).mean(axis=0)
cone_axis = mean_rate / np.linalg.norm(mean_rate)
u_simulated = run.drift @ cone_axis
print(f"cone axis in I: {np.round(cone_axis, 6)}")
print(f"simulated drift along the cone axis: u = {deg_per_h(u_simulated):+.4e} deg/h")

# %%
# The closed form of the coning drift, ``u = α² ω D(ωh)``
# (:func:`~strapdown.analysis.coning.drift_theory.coning_drift_rate`), has the
# same sign and value: positive, so the two-sample algorithm lags the cone.
u_theory = coning_drift_rate(algorithm, cone_angle=alpha, nu=omega, sample_interval=h)
print(f"closed form:                         u = {deg_per_h(u_theory):+.4e} deg/h")
print(f"relative difference: {u_simulated / u_theory - 1:+.1e}  (the α⁴ term and the finite run)")

# %%
# The error rotation carries the computed attitude onto the true one:
# ``Λ_true = exp(δφ_I) ∘ Λ_computed``. At the end of the run the computed
# attitude has turned less about the cone axis than the body did.
steps = run.steps
print(f"after {steps} steps the computed attitude is behind by {run.attitude_error[-1] @ cone_axis:.3e} rad about the cone axis")

# %%
# Velocity: the rectification error
# ---------------------------------
# Under classical sculling (angular vibration about one body axis, linear
# vibration along another) the velocity algorithm of the package, the dual
# extension of the coning algorithm (see :doc:`06_dual_extension`), rectifies
# a constant specific force. The error is the rate of ``W_I,true − W_I,computed``:
# positive when the algorithm under-rectifies.
sculling = ScullingMotion(1e-3, 1.0, 2 * np.pi * 10)  # 1 mrad about x, 1 m/s² along y, 10 Hz
e = rectification_error(algorithm, sculling, sample_interval=0.005)
print(f"exact rectified acceleration {e.exact_rate:.6e} m/s², error rate {e.rate:+.3e} m/s² (relative {e.relative:+.2e})")

# %%
# The simulator (velocity run) measures the same rate as the slope of
# ``ΔW_I = W_I,true − W_I,computed`` along ``e_r × e_a`` (here the z axis).
velocity_run = simulate(algorithm, sculling, sample_interval=0.005, duration=10.0, velocity=True)
print(f"simulated error rate: {velocity_run.velocity_error_rate[2]:+.3e} m/s²")
