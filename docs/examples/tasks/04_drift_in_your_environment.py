r"""
The drift in your environment
=============================

A pure cone and ideal sensors are the textbook case. Your IMU sees a spectrum
of angular vibration with lines from rotors and engines, and its gyro and
accelerometer outputs pass through analog anti-aliasing filters, digital
low-pass filters and decimation before the algorithm sees them. The package
takes that environment as a TOML file (:doc:`../environment-files`) and gives
the mean drift of any algorithm in it, in closed form, in two parts: what the
sensors' filters do to the motion (pseudo-coning: a drift even an exact
algorithm would have) and the algorithm's own residual on what it is fed.

At the command line::

    strapdown environment-drift --algorithm two-sample --environment my-imu.toml --sample-interval 1e-3
    strapdown design-coning --samples 2 --environment my-imu.toml --sample-interval 1e-3
    strapdown environment-rates --environment my-imu.toml --budget-deg-per-h 0.5

A designer who has a linear random-vibration specification of the structure
(breakpoints in g²/Hz) and an IMU mount, rather than the IMU's own spectra,
gets the environment from them (:doc:`../mount-files`)::

    strapdown mount-environment --profile airframe.toml --mount mount.toml --out my-imu.toml --sample-interval 1e-3

This page writes a small environment, checks the closed form against a
simulation that shares nothing with it, and then runs the package's example of
a MEMS IMU in a rotorcraft bay.
"""

import tempfile
from pathlib import Path

import numpy as np

from strapdown.analysis.core.units import deg_per_h
from strapdown.analysis.vibration.drift import environment_drift
from strapdown.analysis.vibration.environment import load_environment
from strapdown.analysis.vibration.examples import QUALIFICATION
from strapdown.analysis.vibration.simulation import filtered_coning_check
from strapdown.analysis.vibration.tuning import tune
from strapdown.derivations.coning.registry import get

h = 1e-3  # algorithm sample interval [s]: a 1 kHz algorithm

# %%
# One coning line through a gyro filter
# -------------------------------------
# 1° of coning at 10 Hz, seen by gyros behind a first-order 100 Hz analog
# low-pass filter.
path = Path(tempfile.mkdtemp()) / "my-imu.toml"
path.write_text(
    """name = "coning 10 Hz through a 100 Hz gyro filter"
[[line]]
freq_hz = 10.0
half_angle_deg = 1.0
[gyro]
filter = "lowpass1"
cutoff_hz = 100.0
""",
    encoding="utf-8",
)
environment = load_environment(path)
for name in ("two-sample", "optimal-3"):
    d = environment_drift(get(name), environment, h)
    print(f"{name:>10}: |drift| {deg_per_h(d.magnitude):.4f} deg/h; about the cone axis z: sensor part {deg_per_h(d.sensor):+.4f} + algorithm part {deg_per_h(d.algorithm_part):+.2e} deg/h")

# %%
# The filter passes the rate with a gain ``|H| < 1``, so the sensed motion cones
# less than the true one (with the same filter on every axis only ``|H|²`` counts,
# not its phase: the sensed coning is ``|H|²`` times the true one, and a resonant
# filter with ``|H| > 1`` makes the sensor part negative); the difference is the
# same for every algorithm, and here it is
# four orders of magnitude above the two-sample algorithm's own residual. A
# better coning algorithm does not help: only a wider filter, or an algorithm
# tuned to this filter (below), does.
#
# An independent check
# --------------------
# DOP853 integrates the true attitude, the filter in continuous time and the
# attitude the filtered gyros sense, together; the algorithm then runs on the
# filtered increments (:func:`~strapdown.analysis.vibration.simulation.filtered_coning_check`).
# No closed form enters it.
check = filtered_coning_check(get("two-sample"), environment.gyro, h, freq_hz=10.0, half_angle=np.radians(1.0), periods=1, rtol=1e-11)
d = environment_drift(get("two-sample"), environment, h)
print(f"sensor part: closed form {deg_per_h(d.sensor):.6f} deg/h, DOP853 {deg_per_h(check.sensor_drift):.6f} deg/h ({check.sensor_drift / d.sensor - 1:+.1e})")
print(f"total:       closed form {deg_per_h(d.total):.6f} deg/h, DOP853 {deg_per_h(check.total_drift):.6f} deg/h")

# %%
# The closed form is second order in the cone angle; the difference is of
# relative order α², a few times 10⁻⁴ here.
#
# A tuned algorithm
# -----------------
# The mean drift is affine in an algorithm's lag sums, the sensors included, so
# a two-sample algorithm can be tuned to null it — the filter's pseudo-coning
# as well as its own residual (``strapdown design-coning``):
tuned = tune(environment, 2, h)
print(f"tuned coefficient {tuned.coefficients}, nulled: {tuned.nulled}")
print(f"|drift|: tuned {deg_per_h(np.linalg.norm(tuned.drift)):.2e} deg/h, classical {tuned.classical.name} {deg_per_h(np.linalg.norm(tuned.classical_drift)):.4f} deg/h")

# %%
# A MEMS IMU in a rotorcraft bay
# ------------------------------
# The package ships a larger example (:data:`~strapdown.analysis.vibration.examples.QUALIFICATION`):
# rotor lines over a qualification random-vibration spectrum, second-order
# anti-aliasing filters, digital low-pass filters at the sensor rate and
# decimation by 4. The drift is a vector in body axes, quoted by its
# magnitude; it comes line by line and band by band. The main rotor cones about
# z, the tail rotor about y: a projection on one axis would hide the other.
qualification = load_environment(QUALIFICATION)
print(qualification.description)
for name in ("two-sample", "optimal-3", "ignagni-1996-5"):
    d = environment_drift(get(name), qualification, h)
    sensor = deg_per_h(np.linalg.norm(d.sensor_vector))
    print(f"{name:>15}: |drift| {deg_per_h(d.magnitude):.5f} deg/h, vector {np.round(deg_per_h(d.total_vector), 5)} deg/h, |sensor part| {sensor:.5f}")
d = environment_drift(get("two-sample"), qualification, h)
for p in d.parts:
    band = f"{p.band[0]:g} Hz" if p.band[0] == p.band[1] else f"{p.band[0]:g}–{p.band[1]:g} Hz"
    print(f"  {p.label:>32} ({band}): sensor part {np.round(deg_per_h(p.sensor), 5)}, two-sample {np.round(deg_per_h(p.algorithm), 6)} deg/h (body axes)")

# %%
# Here too the filters, not the algorithm, set the drift. The gallery page
# :doc:`../gallery/coning/plot_vibration_pseudo_coning` shows the pseudo-coning
# of common MEMS filter settings against frequency, and
# :doc:`../gallery/coning/plot_vibration_rates` the sample rate each algorithm
# needs in this environment for a drift budget.
