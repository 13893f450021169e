"""
The sample interval h and the step H
====================================

A rotation-vector algorithm with N samples takes N gyro increments
``p_1 … p_N`` and returns one rotation-vector increment. Two intervals are
involved, and the papers use both:

* ``h`` — the **sample interval**, between two gyro increments (the gyro data
  rate is 1/h);
* ``H = N h`` — the **step** of the algorithm, between two attitude updates.

The public arguments say which one they mean: ``sample_interval`` is h,
``step`` is H. The multistage stages of Plotnikov (1999) take one sample per
step, so there ``h = H`` and the argument is ``step``.

Quoting a result against the wrong one is an easy slip: where the drift goes
as H⁴ (drift order 4, :doc:`04_three_orders`), a factor N in the interval is a
factor N⁴ in the drift.
"""

import numpy as np

from strapdown.analysis.coning.drift_theory import asymptotic_drift, coning_drift, coning_drift_rate
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core.units import deg_per_h
from strapdown.derivations.coning.registry import get

# %%
# Table 3 of Budennyi, Kalinovsky, Panov et al. quotes the four-sample
# algorithms at ``H = 0.01 s``: the gyro delivers an increment every
# ``h = H / 4 = 2.5 ms``. The simulator takes h, the asymptotic drift takes H.
algorithm = get("panov-4s-1")
N = algorithm.samples
H = 0.01
h = H / N
coning = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))

run = simulate(algorithm, coning, sample_interval=h, duration=20.0)
u_a = asymptotic_drift(algorithm, eps=coning.eps, nu=coning.nu, nutation=coning.nutation, step=H)
print(f"N = {N}, H = {H} s, h = {h} s")
print(f"simulated drift u*   = {deg_per_h(run.drift_rate):.3f} deg/h   (sample_interval = h)")
print(f"asymptotic drift u_a = {deg_per_h(u_a):.3f} deg/h   (step = H)")

# %%
# Passing H where h is meant runs the algorithm on a gyro four times slower.
# Where the leading term of a drift of order 4 dominates that costs a factor
# 4⁴ = 256; here ``ωH`` becomes 2.5 rad, beyond that regime, and the factor is
# still two orders of magnitude:
wrong = simulate(algorithm, coning, sample_interval=H, duration=20.0)
print(f"sample_interval = H by mistake: {deg_per_h(wrong.drift_rate):.1f} deg/h, {wrong.drift_rate / run.drift_rate:.0f} times too much")

# %%
# Coefficients per h and per H
# ----------------------------
# The closed-form coning drift is written in the sample interval,
# :math:`u = c\,\alpha^2\omega(\omega h)^m`, because algorithms are compared at
# the same gyro data rate. Tables of the literature often write it in the step,
# :math:`u = c_H\,\alpha^2\omega(\omega H)^m` with :math:`c_H = c/N^m`. Both
# are exact fractions:
for name in ("two-sample", "miller-3", "panov-4s-1"):
    d = coning_drift(get(name))
    print(f"{name:>11}: N = {d.samples}, coning-drift order m = {d.order}, c = {d.coefficient}, c_H = {d.step_coefficient}")

# %%
# Same data rate, different steps
# -------------------------------
# At one gyro rate, 400 Hz (h = 2.5 ms), under 1° of coning at 10 Hz, the
# drift depends on the coning-drift order m and the coefficient c together;
# the number of samples alone says little (``panov-4s-1`` has m = 4 with a
# large coefficient, ``miller-3`` m = 6):
for name in ("two-sample", "miller-3", "panov-4s-1"):
    alg = get(name)
    u = coning_drift_rate(alg, cone_angle=np.radians(1.0), nu=2 * np.pi * 10, sample_interval=h)
    print(f"{name:>11}: H = {alg.samples * h * 1e3:4.1f} ms, u = {deg_per_h(u):.3e} deg/h")
