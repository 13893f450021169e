r"""
From your flight log to your drift budget
=========================================

The vibration environment of the other pages is a TOML file typed by hand. The
log that measures it is on the designer's desk: this page goes from a recorded
log to the environment file, the drift of each algorithm in it, the algorithms
replayed on the log itself, and the noise of a static stretch. At the command
line::

    strapdown log environment flight.npz --out flight-env.toml --figure flight-env.png
    strapdown environment-drift --algorithm two-sample --environment flight-env.toml --sample-interval 1e-3
    strapdown log coning flight.npz --algorithm two-sample --algorithm miller-3 --algorithm ignagni-1996-5
    strapdown log allan bench-static.npz --out my-imu.toml

The build of this site has no network and a real log cannot be shipped with
it, so the log here is synthetic, with a known truth: half a minute at 1 kHz of
a rotor's 1° coning line at 10 Hz, a coning band from the airframe, and white
sensor noise. Its format is :doc:`../recorded-logs`.
"""

import math
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.alignment.sensor_models import SensorSpec, simulate_sensor_errors
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.core.units import DEG_PER_RAD, deg_per_h
from strapdown.analysis.logs.environment_estimate import estimate_environment, write_environment
from strapdown.analysis.logs.imu_log import ImuLog
from strapdown.analysis.logs.native import read_log, write_log
from strapdown.analysis.logs.replay import replay
from strapdown.analysis.logs.sensor_file import read_sensor_file, write_sensor_file
from strapdown.analysis.logs.static_noise import static_noise
from strapdown.analysis.vibration.drift import environment_drift
from strapdown.analysis.vibration.environment import load_environment
from strapdown.derivations.coning.registry import get

h, n = 1e-3, 30_000
rng = np.random.default_rng(2026)
folder = Path(tempfile.mkdtemp())

# %%
# A synthetic flight log
# ----------------------
# Exact increments of each part: the cone in closed form (the regular
# precession of Lebedev & Panov 1989), the band drawn on the record's own
# frequency grid (x Gaussian between 40 and 150 Hz, y a quarter period ahead:
# a coning band), the noise white.
dtheta = RegularPrecession(-1.0, 2 * math.pi * 10.0, math.radians(1.0)).grid_increments(h, 0, n)
f = np.arange(n // 2 + 1) / (n * h)
band = (f >= 40.0) & (f <= 150.0)
c = np.where(band, math.sqrt(5e-6 / (n * h)) * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size)), 0.0)
w = 2 * math.pi * np.maximum(f, 1e-12)
b = c * (1.0 - np.exp(-1j * w * h)) / (1j * w) * np.exp(1j * w * h)
dtheta[:, 0] += np.fft.irfft(b, n) * n / 2
dtheta[:, 1] += np.fft.irfft(1j * b, n) * n / 2
dtheta += 1e-4 * math.sqrt(h) * rng.standard_normal((n, 3))
dv = 0.02 * math.sqrt(h) * rng.standard_normal((n, 3)) + [0.0, 0.0, -9.80665 * h]
write_log(folder / "flight.npz", ImuLog(h * np.arange(1, n + 1), dtheta, dv))
log = read_log(folder / "flight.npz")

# %%
# The environment the log measured
# --------------------------------
# Lines are told from the band by Thomson's F-test over blocks of the record: a
# line keeps its amplitude and phase from block to block, a band does not, so
# pure band noise yields a line with probability at most 10⁻³. The band is the
# Welch estimate of the rest, with χ² intervals. Both are turned from
# increments back into the rate and specific force whose increments they are.
est = estimate_environment(log)
print(f"Nyquist frequency {est.nyquist:g} Hz: nothing above it is seen (it would be folded below it)")
lo, hi = est.auto_factors()
print(f"Welch: {est.welch_segments} segments, {est.dof:.0f} degrees of freedom, a PSD value within ×[{lo:.2f}, {hi:.2f}] (95 %)")
for ln in est.lines:
    a = np.abs(ln.amplitude[:3]) * DEG_PER_RAD
    phase = np.angle(ln.amplitude[:3]) * DEG_PER_RAD
    print(f"line {ln.frequency:.4f} Hz: rate amplitudes {np.round(a, 3)} deg/s, phases {np.round(phase, 1)} deg (y a quarter period ahead of x: coning)")
print(f"band rms, rate: {np.round(est.band_rms()[:3] * DEG_PER_RAD, 3)} deg/s")

fig, ax = plt.subplots(figsize=(7, 3.5))
for k, name in enumerate("xyz"):
    ax.loglog(est.frequency, np.real(est.density[:, k, k]) * DEG_PER_RAD**2, linewidth=0.8, label=f"ω{name}")
for ln in est.lines:
    ax.axvline(ln.frequency, color="k", linestyle=":", linewidth=0.8)
ax.set_xlabel("frequency [Hz]")
ax.set_ylabel("rate PSD [(deg/s)²/Hz]")
ax.set_title("band with the line removed (dotted: the line)", fontsize=9)
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# The environment file and the drift budget
# -----------------------------------------
# The file holds the line and the band and no sensor filter: whatever filtered
# the signal before it was logged is already in the samples. Every command
# that takes an environment reads it as it is. The closed form then gives the
# mean drift of each algorithm at the log's rate:
path = write_environment(folder / "flight-env.toml", est)
env = load_environment(path)
for name in ("two-sample", "miller-3", "ignagni-1996-5"):
    d = environment_drift(get(name), env, h)
    print(f"{name:>15}: drift {deg_per_h(d.total):+.2e} deg/h along the coning axis")

# %%
# The line alone gives the two-sample algorithm about 0.001 deg/h; the band
# about as much again. Against a budget of 10⁻³ deg/h the two-sample algorithm
# at 1 kHz fails and the three-sample ones pass with orders to spare.
#
# The algorithms on the log itself
# --------------------------------
# Replayed on the recorded increments, each algorithm's corrections (its terms
# beyond the plain sum of the increments) add up to a mean correction rate.
# The drifts of two algorithms differ by the rotation between the attitudes
# they compute — no model enters — and the closed form in the estimated
# environment predicts that difference:
names = ("two-sample", "miller-3", "ignagni-1996-5")
r = replay(log, [get(x) for x in names])
base = environment_drift(get(names[0]), env, h)
axis = base.coning_axis  # signed values along the coning axis, as environment-drift gives them
for i, name in enumerate(names):
    rate = deg_per_h(r.algorithms[i].rate @ axis)
    if i == 0:
        print(f"{name:>15}: correction rate {rate:+.4f} deg/h along the coning axis")
        continue
    diff = deg_per_h(r.drift_difference(i, 0) @ axis)
    pred = deg_per_h(environment_drift(get(name), env, h).total - base.total)
    print(f"{name:>15}: correction rate {rate:+.4f} deg/h; drift minus two-sample's {diff:+.2e} deg/h on the log, {pred:+.2e} by the closed form")

# %%
# The corrections of the three-sample algorithms are twice those of the
# two-sample one — their steps are longer, and their compositions miss more —
# while their drifts differ by a thousandth of a degree per hour: a difference
# of correction rates is a difference of drifts only between algorithms of one
# step length. On the log and by the closed form the differences agree to the
# scatter a short record of a random band allows: the closed form gives the
# mean drift, the log what the attitudes really did in these thirty seconds,
# in which the band's part is itself random (on a twenty-second record of the
# same motion the two part by a factor of three).
#
# The noise of a static stretch
# -----------------------------
# ``log allan`` reads ARW, bias instability and rate random walk off the Allan
# deviation of a static stretch, each with the χ² interval of the point it is
# read at, and writes them as the sensor file ``align`` and the alignment
# toolkit take. A synthetic two-hour bench log of a MEMS-grade IMU at 1 Hz (a
# 95 % interval misses its truth one time in twenty; the package's tests check
# the coverage over repeated logs):
gyro = SensorSpec(0.2 / 60.0 * math.pi / 180, 3.0 / 3600 * math.pi / 180, 0.0, flicker_band=(0.05, 1e4))
accel = SensorSpec(0.05 / 60.0, 2e-4, 0.0, flicker_band=(0.05, 1e4))
m = 7_200
g_err = simulate_sensor_errors(gyro, n_trials=1, n_samples=m, dt=1.0, rng=1)
a_err = simulate_sensor_errors(accel, n_trials=1, n_samples=m, dt=1.0, rng=2)
static = ImuLog(np.arange(1.0, m + 1), g_err.increments[0], a_err.increments[0] + [0.0, 0.0, -9.80665])
noise = static_noise(static)
sheet = read_sensor_file(write_sensor_file(folder / "my-imu.toml", noise, name="bench IMU"))
for key, value in sheet.intervals.items():
    print(f"{key:>24}: {getattr(getattr(sheet.sheet, key.split('.')[0]), key.split('.')[1]):.3e}  95 % interval [{value[0]:.3e}, {value[1]:.3e}] (SI)")
print(f"true: gyro ARW {gyro.random_walk:.3e}, bias instability {gyro.bias_instability:.3e}; accel VRW {accel.random_walk:.3e}, bias instability {accel.bias_instability:.3e}")
