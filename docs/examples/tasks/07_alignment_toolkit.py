r"""
Alignment: what can be observed, which method, how long
=======================================================

Before choosing an alignment method an engineer asks what the measurements
can tell at all, how the methods compare on the same data, how long a grade
of IMU takes, and what a recorded log gives. The package answers each
(:mod:`strapdown.analysis.alignment`; at the command line)::

    strapdown observability --lat-deg 45
    strapdown align --method kalman --lat-deg 45 --trials 64 --seed 1
    strapdown align --method compass --lat-deg 45 --log my-imu.npz

The log format is in :doc:`../recorded-logs`. Angles are printed in degrees;
the library works in radians.
"""

import math

from strapdown.analysis.alignment.design_studies import grade_study, methods_study
from strapdown.analysis.alignment.fine import FilterTuning
from strapdown.analysis.alignment.observability import BodyRotation, multi_position_problem, observability, stationary_problem
from strapdown.analysis.alignment.sensor_models import GRADES
from strapdown.analysis.core.units import DEG_PER_RAD as D
from strapdown.analysis.core.units import deg_per_h, rad
from strapdown.analysis.logs.alignment import align_log
from strapdown.analysis.logs.examples import example_log

latitude = rad(45.0)

# %%
# What zero-velocity measurements can observe
# -------------------------------------------
# The twelve-state error model of a navigator at rest (attitude, velocity, gyro
# and accelerometer biases), observed through zero velocity: its rank, and the
# directions it cannot see, in words.
at_rest = observability(stationary_problem(latitude, duration=300.0))
print(f"at rest: rank {at_rest.rank} of {at_rest.dim}")
for d in at_rest.unobservable:
    print(f"  cannot tell apart: {d.text}")

# %%
# These are the three classical pairs (Bar-Itzhack & Berman 1988): each tilt
# against an accelerometer bias, and the azimuth against the east gyro bias.
# They set floors no method at rest can beat: ∇/g on the tilts,
# ε_E/(Ω cos φ) on the azimuth. Turning the block about the vertical halfway
# through makes the rank full: given time, every bias can be told from the
# attitude. The rank is not the degree of observability: after 300 s the
# filter may still have learned little of a state that is observable in rank.
turned = observability(multi_position_problem(latitude, [BodyRotation(150.0, "z", rad(90.0))], 300.0))
print(f"turned 90° at 150 s: rank {turned.rank} of {turned.dim}, {len(turned.unobservable)} unobservable directions")
little = [turned.labels[turned.names.index(n)] for n in turned.little_learned(0.9)]
print(f"  learned little within 300 s (σ over the prior ≥ 0.9): {', '.join(little) or 'none'}")

# %%
# The methods on the same trials
# ------------------------------
# Navigation-grade sensors, 300 s at rest; every method on the same records
# (:func:`~strapdown.analysis.alignment.design_studies.methods_study`, eight
# trials here — the report runs 96). Each trial's *floor* is the azimuth error
# its own biases leave. A residual of zero mean proves nothing; a method has
# reached the floor when the rms of its residual is at most the floor's rms
# (:func:`~strapdown.analysis.alignment.comparison.floor_reached`, a one-sided
# test). Eight trials rarely decide, and the verdict says how many more would:
study = methods_study(n_trials=8, rng=1)
print(f"{'method':>15} {'azimuth rms':>12} {'residual rms':>13}  floor reached")
for r in study.rows:
    print(f"{r.method:>15} {r.error.rms * D:10.3f}° {r.residual.rms * D:11.4f}°  {r.floor_reached}")

# %%
# How long a grade takes
# ----------------------
# The fine filter's own azimuth σ at rest (its covariance, no Monte Carlo) for
# three grades of the package's illustrative data sheets, against the floor
# of the grade: the *time to align* is when σ comes within 10 % of it.
for c in grade_study(GRADES[:3], latitude=latitude, duration=4000.0):
    when = f"{c.time_to_align:.0f} s" if math.isfinite(c.time_to_align) else f"more than {c.times[-1]:.0f} s"
    print(f"{c.grade:>13}: floor {c.floor * D:.4f}°, time to align {when}")

# %%
# A recorded log
# --------------
# The package ships four minutes of a simulated navigation-grade IMU on a
# rocking base, its truth in the file's metadata
# (:func:`~strapdown.analysis.logs.examples.example_log`). Each method
# aligns it once; the analytic method assumes the gyros see the Earth rate
# only, and the rocking they see spoils it.
log = example_log()
nav = next(g for g in GRADES if g.name == "navigation")
tuning = FilterTuning(epoch=0.1, gyro_bias=nav.gyro.turn_on_bias, accel_bias=nav.accel.turn_on_bias, gyro_noise=nav.gyro.random_walk, accel_noise=nav.accel.random_walk, measurement_noise=0.02)
print(f"{log.n_samples} samples at {1 / log.dt:.0f} Hz; gyro turn-on bias of the grade {deg_per_h(nav.gyro.turn_on_bias):g} deg/h")
for method in ("analytic", "inertial", "kalman", "compass"):
    r = align_log(log, log.metadata["latitude"], method=method, tuning=tuning, rng=5)
    sigma = "" if r.heading_sigma is None else f", filter σ {r.heading_sigma * D:.3f}°"
    print(f"{method:>9}: heading {r.heading * D:.4f}°, error against the truth {r.heading_error * D:+.4f}°{sigma}")
