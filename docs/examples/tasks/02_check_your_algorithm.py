"""
Check your own algorithm
========================

An algorithm in your flight code is a set of coefficients of cross products
of gyro increments. Written as an algorithm file (:doc:`../algorithm-files`),
it gets everything a registry algorithm gets: the second-order condition, its
orders (:doc:`../concepts/04_three_orders`), the exact local-error series, the
coning drift in closed form with the range where it holds, the velocity
algorithm by dual extension, and runs against the exact solution.

At the command line the same checks are::

    strapdown algorithms show --algorithm-file my-3-sample.toml
    strapdown derive coning-drift --algorithm-file my-3-sample.toml
    strapdown drift --algorithm-file my-3-sample.toml --half-angle-deg 1 \\
        --freq-hz 10 --sample-interval 0.0025 --duration 20

Here they are in Python, on a three-sample algorithm and on the same file with
one coefficient moved to the wrong pair — the kind of slip that survives code
review. If your algorithm exists only as code, :doc:`03_check_your_integrator`
recovers its coefficients first.
"""

import tempfile
from pathlib import Path

import numpy as np

from strapdown.analysis.coning.algorithm_summary import summarize
from strapdown.analysis.coning.coning_validity import coning_case
from strapdown.analysis.coning.drift_theory import coning_drift, coning_drift_rate
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.sculling_motion import ScullingMotion, rectification_error
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core.units import deg_per_h, rad
from strapdown.derivations.coning.algorithms import SecondOrderConditionError, load_toml
from strapdown.derivations.coning.drift import lag_sums
from strapdown.derivations.coning.registry import get, names

folder = Path(tempfile.mkdtemp())
(folder / "my-3-sample.toml").write_text(
    """name = "my-3-sample"
samples = 3
description = "three samples per step, as coded in the attitude task"
[cross]
"1,2" = "27/40"
"2,3" = "27/40"
"1,3" = "9/20"
""",
    encoding="utf-8",
)

# %%
# What the file describes
# -----------------------
mine = load_toml(folder / "my-3-sample.toml")
s = summarize(mine)
print(f"{s.name}: N = {s.samples}, window {s.window}, terms:")
for c, product in s.terms:
    print(f"  {c} {product}")
print(f"second-order defect Σ c_ij (j − i) − N³/12 = {s.second_order_defect}")
print(f"accuracy order ρ = {s.accuracy_order}: local error O(h^{s.local_error_order}) in a general motion")
print(f"coning-drift order m = {s.coning_drift_order}: drift c α² ω (ωh)^{s.coning_drift_order} under classical coning")

# %%
# Its coning drift in closed form
# -------------------------------
# Under classical coning (half-cone angle α, rate ω) the drift along the cone
# axis is ``u = α² ω D(ωh) + O(α⁴)``, with ``D`` in closed form, exact in ωh;
# its leading term ``c α² ω (ωh)^m`` gives the coning-drift order m.
# Algorithms with the same lag sums ``k_l = Σ_{j−i=l} c_ij`` have the same
# coning drift; the registry says which published algorithms this one matches
# under coning.
d = coning_drift(mine)
print(f"D(x) = {d.function}")
print(f"u = {d.coefficient} α² ω (ωh)^{d.order} + …   (lag sums {tuple(str(k) for k in d.lag_sums)})")
twins = [n for n in names(library=True) if get(n).samples == mine.samples and lag_sums(get(n)) == lag_sums(mine)]
print("registry algorithms with the same lag sums:", ", ".join(twins))

# %%
# And against the exact solution
# ------------------------------
# 1° of coning at 10 Hz on a 400 Hz gyro (``--half-angle-deg 1`` at the command
# line: the regular precession with ε = −1 and nutation α). The closed form is
# at order α²; the simulation has every order, and so has the exact drift of
# :func:`~strapdown.analysis.coning.coning_validity.coning_case` (one step in
# extended precision, no series), which also gives the next term in α and how
# far the leading term is from the drift.
coning = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=rad(1.0))
run = simulate(mine, coning, sample_interval=1 / 400, duration=20.0, engine="numpy")
u = coning_drift_rate(mine, cone_angle=coning.nutation, nu=coning.nu, sample_interval=1 / 400)
case = coning_case(mine, cone_angle=coning.nutation, nu=coning.nu, sample_interval=1 / 400)
print(f"simulated {deg_per_h(run.drift_rate):.4e} deg/h, exact {deg_per_h(case.exact):.4e} deg/h, closed form {deg_per_h(u):.4e} deg/h")
print(f"leading term {deg_per_h(case.leading):.4e} deg/h ({case.ratio:.4f} of the exact drift), next term in α {deg_per_h(case.next_term):+.2e} deg/h")
print(f"the leading term is within {case.range.tolerance:.0%} of the drift up to α = {np.degrees(case.range.half_angle_limits[0]):.3g}° at ωh = {case.omega_h:.3g} rad")

# %%
# The velocity algorithm that goes with it is its dual extension; under 10 Hz
# sculling (1 mrad, 1 m/s²) on a 200 Hz accelerometer it rectifies
sculling = ScullingMotion(1e-3, 1.0, 2 * np.pi * 10)
e = rectification_error(mine, sculling, sample_interval=1 / 200)
print(f"rectification error {e.rate:+.3e} m/s² ({e.relative:+.2e} of the rectified {e.exact_rate:.2e} m/s²)")

# %%
# One coefficient on the wrong pair
# ---------------------------------
# The same file with the lag-2 coefficient and one lag-1 coefficient swapped.
# The loader refuses it and says why: the algorithm no longer reproduces the
# ``H³/12 ω × ω'`` term that every consistent algorithm has.
(folder / "slipped.toml").write_text(
    """name = "slipped"
samples = 3
[cross]
"1,2" = "9/20"
"2,3" = "27/40"
"1,3" = "27/40"
""",
    encoding="utf-8",
)
try:
    load_toml(folder / "slipped.toml")
except SecondOrderConditionError as error:
    print("refused:", str(error).replace(str(folder), "<folder>"))

# %%
# Accepted on purpose (``allow_inconsistent=True``, ``--allow-inconsistent`` at
# the command line), it shows what the slip costs: its local error starts two
# orders lower, and under the same coning it drifts many orders of magnitude
# more.
slipped = summarize(load_toml(folder / "slipped.toml", allow_inconsistent=True))
print(f"accuracy order ρ = {slipped.accuracy_order}: local error O(h^{slipped.local_error_order}); coning-drift order m = {slipped.coning_drift_order}")
run = simulate(load_toml(folder / "slipped.toml", allow_inconsistent=True), coning, sample_interval=1 / 400, duration=20.0, engine="numpy")
print(f"simulated drift {deg_per_h(run.drift_rate):.4e} deg/h")
